#!/usr/bin/env bash
# Streaming C²PS checks that scripts/ci-embedded.sh does not cover:
# fmt and clippy of the firmware's `c2ps-stream` feature (thumbv6m), its
# release link with `api-check` (the link-time panic check of the whole
# streaming API, f32 and f64), and the Cortex-M0 run against the f64 kernel
# (embedded-tests/tests/stream_qemu.rs; ci-embedded.sh's `cargo test` runs
# it too). The kernel's own tests (tests/polar_stream.rs), the CLI's
# (cli/tests/patches_stream.rs) and the size row m0-c2ps-stream run with the
# rest of scripts/test.sh / scripts/size-report.sh; the fuzz target
# kernel_stream is picked up by scripts/ci-fuzz.sh.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
start=$(date +%s)
step() { echo "== stream: $* ($(( $(date +%s) - start )) s)"; }

step "toolchain pieces"
rustup target list --installed | grep -qx thumbv6m-none-eabi || rustup target add thumbv6m-none-eabi
if ! command -v qemu-system-arm >/dev/null; then
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends qemu-system-arm >/dev/null
fi

step "firmware c2ps-stream: fmt, clippy, release link (panic check)"
(cd firmware && cargo fmt --check \
  && cargo clippy -q --release --target thumbv6m-none-eabi --no-default-features \
       --features c2ps-stream,api-check -- -D warnings \
  && cargo build -q --release --target thumbv6m-none-eabi --no-default-features \
       --features c2ps-stream,api-check)

step "Cortex-M0 under QEMU vs the f64 kernel"
(cd embedded-tests && cargo test -q --release --test stream_qemu)

step "done"
