#!/usr/bin/env bash
# The browser viewer's checks, for CI and by hand. Installs what it
# needs on a fresh Debian machine (chromium and node from apt, the wasm32
# target, playwright-core by `npm ci`), then:
#   1. fmt, clippy and host tests of the WASM crate (viewer/wasm, own workspace);
#   2. its release build for wasm32-unknown-unknown, copied to viewer/build/
#      where the page loads it (viewer/build.sh; not in git);
#   3. viewer/test/viewer.test.mjs: the page served from loopback, driven in
#      headless chromium (WebGL through SwiftShader): loads with no console
#      error, shows the surface, every shading changes the image, broken files
#      show a message, an empty surface is an error, a mesh far from the
#      origin is framed as at the origin, a control-point drag changes the
#      surface, the edited mesh and the surface save as OBJ, scheme and depth
#      re-plan, the up toggle, highlight lines anti-aliased on a tall object,
#      highlight lines spaced relative to the view through a zoom; prints the
#      edit-to-surface times per sample.
# Prints its run time.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
start=$(date +%s)
step() { echo "== viewer: $* ($(( $(date +%s) - start )) s)"; }

step "toolchain pieces"
rustup target list --installed | grep -qx wasm32-unknown-unknown || rustup target add wasm32-unknown-unknown
. "$root/scripts/browser-tools.sh"

# The own-workspace crate uses its own target directory.
unset CARGO_TARGET_DIR RUSTFLAGS CARGO_BUILD_TARGET

step "viewer/wasm: fmt, clippy, host tests"
(cd viewer/wasm && cargo fmt --check && cargo clippy --all-targets -- -D warnings && cargo test --quiet)

step "viewer/wasm: wasm32 release build -> viewer/build/"
bash viewer/build.sh
ls -l viewer/build/capdiv_viewer.wasm

step "viewer/test: npm ci"
(cd viewer/test && npm ci --no-audit --no-fund --loglevel=error)

step "viewer/test: the page in headless chromium"
(cd viewer/test && node --test-reporter=spec viewer.test.mjs)

step "done"
echo "ci-viewer: $(( $(date +%s) - start )) s"
