#!/usr/bin/env bash
# capdiv's exchange formats checked by their real clients, for CI and by hand.
# Installs what it needs on a fresh Debian machine (chromium, node and npm from
# apt; gltf-validator, three and playwright-core by `npm ci` in
# scripts/exchange/), then:
#   1. builds the CLI (release profile, as scripts/test.sh has just done) and writes the demo meshes
#      (`capdiv demo`) and a generated two-object OBJ;
#   2. `capdiv surface --format glb` and `--format gltf` of each, keeping the
#      counts capdiv reports writing;
#   3. scripts/exchange/gltf.test.mjs: the Khronos validator reports no error
#      and no warning on every file; three.js's GLTFLoader in headless
#      chromium loads each with the node, vertex and triangle counts capdiv
#      wrote, and renders a lit, non-blank picture.
# Env: EXCHANGE_SCREENSHOT=path.png saves the picture of the hand (docs/img/gltf-three.png).
# Prints its run time.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
start=$(date +%s)
step() { echo "== exchange: $* ($(( $(date +%s) - start )) s)"; }

step "tools"
. "$root/scripts/browser-tools.sh"
(cd scripts/exchange && npm ci --no-audit --no-fund --loglevel=error)

step "build the CLI"
cargo build --quiet --release -p capdiv-cli
bin="${CARGO_TARGET_DIR:-$root/target}/release/capdiv"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$bin" demo --out "$work/demo" >/dev/null
mkdir -p "$work/cases"
cases=()
for m in globe mushroom hand rounded-cube cube two-beam-corner; do
  cases+=("$work/demo/$m.json")
done
# Two named objects: a cube and a second one moved along x (a node each).
{
  echo "o first_cube"
  for p in "0 0 0" "1 0 0" "1 1 0" "0 1 0" "0 0 1" "1 0 1" "1 1 1" "0 1 1"; do echo "v $p"; done
  echo "f 1 4 3 2"; echo "f 5 6 7 8"; echo "f 1 2 6 5"; echo "f 2 3 7 6"; echo "f 3 4 8 7"; echo "f 4 1 5 8"
  echo "o second_cube"
  for p in "2 0 0" "3 0 0" "3 1 0" "2 1 0" "2 0 1" "3 0 1" "3 1 1" "2 1 1"; do echo "v $p"; done
  echo "f 9 12 11 10"; echo "f 13 14 15 16"; echo "f 9 10 14 13"; echo "f 10 11 15 14"; echo "f 11 12 16 15"; echo "f 12 9 13 16"
} > "$work/two-objects.obj"
cases+=("$work/two-objects.obj")
# A textured cube: each face on its own square of a 3x2 atlas (OBJ vt), so
# the files carry TEXCOORD_0 with seams along every edge.
{
  for p in "0 0 0" "1 0 0" "1 1 0" "0 1 0" "0 0 1" "1 0 1" "1 1 1" "0 1 1"; do echo "v $p"; done
  for f in 0 1 2 3 4 5; do
    x=$((f % 3)); y=$((f / 3))
    for c in "0 0" "1 0" "1 1" "0 1"; do
      set -- $c
      echo "vt $(echo "($x + $1) / 3" | bc -l) $(echo "($y + $2) / 2" | bc -l)"
    done
  done
  echo "f 1/1 4/2 3/3 2/4"; echo "f 5/5 6/6 7/7 8/8"; echo "f 1/9 2/10 6/11 5/12"
  echo "f 2/13 3/14 7/15 6/16"; echo "f 3/17 4/18 8/19 7/20"; echo "f 4/21 1/22 5/23 8/24"
} > "$work/textured-cube.obj"
cases+=("$work/textured-cube.obj")

step "capdiv surface --format glb|gltf"
for file in "${cases[@]}"; do
  name=$(basename "${file%.*}")
  for format in glb gltf; do
    "$bin" surface --depth 4 --grid 3 --format "$format" -o "$work/cases/$name.$format" "$file" \
      2> "$work/cases/$name.$format.log"
  done
  # `  gltf         N nodes, V vertices, T triangles` (singular for 1)
  sed -n 's/^  gltf *\([0-9]*\) nodes\{0,1\}, \([0-9]*\) vert[a-z]*, \([0-9]*\) triangles\{0,1\}$/\1 \2 \3/p' \
    "$work/cases/$name.glb.log" > "$work/cases/$name.expect"
  [ -s "$work/cases/$name.expect" ] || { echo "no gltf line for $name"; cat "$work/cases/$name.glb.log"; exit 1; }
done
echo "first_cube second_cube" >> "$work/cases/two-objects.expect"
# Third line: the meshes carry UVs.
printf '\nuv\n' >> "$work/cases/textured-cube.expect"

step "glTF: Khronos validator, three.js in headless chromium"
(cd scripts/exchange && EXCHANGE_DIR="$work/cases" EXCHANGE_SCREENSHOT="${EXCHANGE_SCREENSHOT:-}" node --test-reporter=spec gltf.test.mjs)

step "done"
echo "ci-exchange: $(( $(date +%s) - start )) s"
