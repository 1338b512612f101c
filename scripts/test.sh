#!/usr/bin/env bash
# The whole test suite (the README's test command): host tests of every crate,
# the kernel with the micromath backend, then the embedded checks (firmware
# under QEMU, WASM under node, size budgets), which install what they need.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo test --workspace --release
cargo test -p capdiv --release --features micromath --test micromath
if [ -f scripts/ci-embedded.sh ]; then
  bash scripts/ci-embedded.sh
fi
