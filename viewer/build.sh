#!/usr/bin/env bash
# Builds the viewer's WASM module and puts it where the page loads it
# (viewer/build/, not in git).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
(cd "$here/wasm" && cargo build --release --target wasm32-unknown-unknown)
mkdir -p "$here/build"
cp "${CARGO_TARGET_DIR:-$here/wasm/target}/wasm32-unknown-unknown/release/capdiv_viewer.wasm" "$here/build/"
