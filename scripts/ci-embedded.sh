#!/usr/bin/env bash
# The embedded checks, for CI and by hand (called from
# scripts/test.sh, which .ci/run runs). Installs what it needs on a fresh
# machine, then:
#   1. the kernel for thumbv6m-none-eabi and, with `defmt`, thumbv7em-none-eabihf;
#   2. fmt and clippy of firmware/, capi-wasm/, embedded-tests/ (own workspaces);
#   3. the firmware's release builds (M4 and M0): they link only if no panic
#      path is left in the kernel API they reference (see firmware/src/main.rs);
#   4. embedded-tests: the firmware under QEMU (every logged number against
#      f64) and the WASM module under node (bit for bit against native);
#   5. the size report with its budgets (scripts/size-budget.txt).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
start=$(date +%s)
step() { echo "== embedded: $* ($(( $(date +%s) - start )) s)"; }

step "toolchain pieces"
for t in thumbv7em-none-eabihf thumbv6m-none-eabi wasm32-unknown-unknown; do
  rustup target list --installed | grep -qx "$t" || rustup target add "$t"
done
rustup component list --installed | grep -q '^llvm-tools' || rustup component add llvm-tools
if ! command -v qemu-system-arm >/dev/null; then
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends qemu-system-arm >/dev/null
fi
if ! command -v node >/dev/null; then
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends nodejs >/dev/null
fi
qemu-system-arm --version | head -1
node --version

step "kernel: thumbv6m-none-eabi, and the defmt feature on thumbv7em-none-eabihf"
cargo build -q -p capdiv --release --target thumbv6m-none-eabi
cargo build -q -p capdiv --release --target thumbv7em-none-eabihf --features defmt

for dir in firmware capi-wasm embedded-tests; do
  step "fmt + clippy: $dir"
  (cd "$dir" && cargo fmt --check && cargo clippy -q --release --all-targets -- -D warnings)
done
(cd firmware && cargo clippy -q --release --target thumbv6m-none-eabi -- -D warnings)

step "firmware release builds (link-time panic check of the kernel API)"
(cd firmware && cargo build -q --release --target thumbv7em-none-eabihf)
(cd firmware && cargo build -q --release --target thumbv6m-none-eabi)

step "firmware under QEMU, WASM under node"
(cd embedded-tests && cargo test --release)

step "size report and budgets"
bash scripts/size-report.sh

step "done"
