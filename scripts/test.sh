#!/usr/bin/env bash
# The whole test suite (the README's test command): host tests of every crate
# (capdiv-mesh's against OpenSubdiv, installed here when missing),
# the kernel with the micromath backend, then the checks that install what they
# need on a fresh machine:
#   ci-embedded.sh   Rust firmware under QEMU, WASM under node, size budgets
#   ci-stream.sh     streaming C²PS firmware on the Cortex-M0 (16 KiB RAM)
#   ci-cfirmware.sh  the C ABI staticlib, its cbindgen header, the C firmware under QEMU
#   ci-viewer.sh     the browser viewer in headless chromium (playwright-core)
#   ci-step.sh       STEP output read and checked by OpenCascade (cadquery-ocp)
#   ci-fuzz.sh       every cargo-fuzz target, bounded, on its committed corpus
#   ci-miri.sh       the kernel's tests under Miri (sizes reduced under cfg(miri))
set -euo pipefail
cd "$(dirname "$0")/.."
start=$(date +%s)
# OpenSubdiv (libosd-dev), the oracle of capdiv-mesh's tests (mesh/tests/osd).
if [ ! -d /usr/include/opensubdiv ]; then
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends libosd-dev >/dev/null
fi
if ! command -v g++ >/dev/null; then
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends g++ >/dev/null
fi
cargo test --workspace --release
cargo test -p capdiv --release --features micromath --test micromath
for check in embedded stream cfirmware viewer exchange step fuzz miri; do
  t0=$(date +%s)
  # Miri: each of its two parallel groups gets 25 minutes (about 8 measured
  # on an idle 2-core machine); a hang still fails.
  MIRI_TIMEOUT=${MIRI_TIMEOUT:-1500} bash "scripts/ci-$check.sh"
  echo "== ci-$check.sh took $(( $(date +%s) - t0 )) s (suite so far $(( $(date +%s) - start )) s)"
done
