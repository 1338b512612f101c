#!/usr/bin/env bash
# The C firmware checks, for CI and by hand. Installs what it needs
# on a fresh Debian machine, then:
#   1. capi/include/capdiv.h is what cbindgen generates from capi/src (capi/header);
#   2. fmt and clippy of capi/, capi/header/ and embedded-tests/ with the test;
#   3. the C ABI's staticlib for thumbv7em-none-eabihf and thumbv6m-none-eabi
#      and the C firmware linked against it (cfirmware/, Debian's
#      arm-none-eabi-gcc): the link fails if a panic path is left in any call of
#      the header (the panic handler calls an undefined symbol); a negative
#      control builds the staticlib with overflow checks and requires that link
#      to fail;
#   4. embedded-tests/tests/c_firmware_qemu.rs: both images under QEMU, and
#      main.c as a host program (cc, the host staticlib, -Wl,--gc-sections),
#      every number against the f64 kernel;
#   5. the C firmware's sizes against cfirmware/size-budget.txt.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
start=$(date +%s)
step() { echo "== cfirmware: $* ($(( $(date +%s) - start )) s)"; }

step "toolchain pieces"
for t in thumbv7em-none-eabihf thumbv6m-none-eabi; do
  rustup target list --installed | grep -qx "$t" || rustup target add "$t"
done
missing=()
command -v arm-none-eabi-gcc >/dev/null || missing+=(gcc-arm-none-eabi binutils-arm-none-eabi)
command -v qemu-system-arm >/dev/null || missing+=(qemu-system-arm)
command -v make >/dev/null || missing+=(make)
command -v cc >/dev/null || missing+=(gcc)
if [ ${#missing[@]} -gt 0 ]; then
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
arm-none-eabi-gcc --version | head -1
qemu-system-arm --version | head -1

# The own-workspace crates use their own target directories.
unset CARGO_TARGET_DIR RUSTFLAGS CARGO_BUILD_TARGET

step "header: capi/include/capdiv.h is current (cbindgen)"
cargo run -q --manifest-path capi/header/Cargo.toml -- --check

step "fmt + clippy: capi"
(cd capi && cargo fmt --check && cargo clippy -q --release --all-targets -- -D warnings)
step "fmt + clippy: capi/header"
(cd capi/header && cargo fmt --check && cargo clippy -q --all-targets -- -D warnings)
(cd capi && cargo clippy -q --release --target thumbv6m-none-eabi -- -D warnings)
step "fmt + clippy: embedded-tests with the C firmware test"
(cd embedded-tests && cargo fmt --check && cargo clippy -q --release --all-targets --features cfirmware -- -D warnings)

step "staticlibs and C firmware (M4, M0): the link is the panic check"
make -s -C cfirmware clean
make -s -C cfirmware all

step "negative control: a staticlib with panic paths (overflow checks) must not link"
probe=$(mktemp -d)
trap 'rm -rf "$probe"' EXIT
(cd capi && CARGO_PROFILE_RELEASE_OVERFLOW_CHECKS=true \
  cargo build -q --release --target thumbv6m-none-eabi --target-dir "$probe/target")
if (cd cfirmware && arm-none-eabi-gcc -mcpu=cortex-m0 -mthumb -mfloat-abi=soft -std=c11 -Os \
      -ffreestanding -ffunction-sections -fdata-sections -DCFW_M0 -nostdlib -Wl,--gc-sections \
      -Wl,-z,noexecstack -T microbit.ld -o "$probe/probe.elf" main.c startup.c semihost.c \
      "$probe/target/thumbv6m-none-eabi/release/libcapdiv_capi.a" -lgcc) 2>"$probe/ld.txt"; then
  echo "the panic check is broken: a staticlib with panic paths linked" >&2
  exit 1
fi
grep -q "undefined reference to .capdiv_panic_path_linked" "$probe/ld.txt" || {
  echo "the probe link failed for another reason:" >&2
  cat "$probe/ld.txt" >&2
  exit 1
}
echo "probe link failed as it must: $(grep -c 'undefined reference to .capdiv_panic_path_linked' "$probe/ld.txt") panic call site(s)"

step "C firmware under QEMU and as a host program against the f64 kernel"
(cd embedded-tests && cargo test -q --release --features cfirmware --test c_firmware_qemu)

step "sizes"
bash cfirmware/size-report.sh

step "done"
