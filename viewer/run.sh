#!/usr/bin/env bash
# Builds the WASM module and serves the viewer: bash viewer/run.sh [port]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
bash "$here/build.sh"
exec node "$here/serve.mjs" "${1:-8080}"
