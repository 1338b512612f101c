#!/usr/bin/env bash
# `capdiv surface --format step` checked by OpenCascade, for CI and by hand.
# Installs cadquery-ocp (PyPI, pinned) in a virtual environment
# ($STEP_VENV, default ~/.cache/capdiv/step-venv), then:
#   1. builds the CLI (release profile) and writes the demo meshes
#      (`capdiv demo`) and the generated ones (scripts/exchange/meshes.py:
#      an open tube, a bowl with a pole, an open box with extraordinary
#      points, an icosahedron, a sphere with triangle-fan poles);
#   2. per mesh: `capdiv surface --format step` (keeping the summary: counts,
#      shell, capdiv's own Gauss-quadrature volume) and `--format json` (the
#      patches and caps);
#   3. scripts/exchange/check_step.py on each: STEPControl_Reader reads it,
#      BRepCheck_Analyzer finds it valid, faces/edges/vertices as written,
#      every patch face equals capdiv's patch (1e-9 of the size), hole fills
#      ruled to a cap's limit point; closed: a solid without free edges whose
#      GProp volume is capdiv's (1e-9 relative, f32 1e-6); open: free edges on
#      the input's boundary limit curve and covering it.
# Env: STEP_DEPTH (default 4; the hand runs one less); STEP_SCREENSHOT=path.png
# renders the mushroom's file as OpenCascade reads it (scripts/exchange/
# render_step.py; docs/img/step-occ.png is STEP_DEPTH=3). Prints its run time
# and `N passed, N failed`. `bash scripts/ci-step.sh --install` only
# installs (CI prefetches with it).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
start=$(date +%s)
step() { echo "== step: $* ($(( $(date +%s) - start )) s)"; }

step "tools"
venv=${STEP_VENV:-${HOME:-/tmp}/.cache/capdiv/step-venv}
[ -x "$venv/bin/python" ] || python3 -m venv "$venv"
"$venv/bin/pip" install --quiet --disable-pip-version-check cadquery-ocp==8.0.1.1.0
py="$venv/bin/python"
[ "${1:-}" != --install ] || exit 0

step "build the CLI"
cargo build --quiet --release -p capdiv-cli
bin="${CARGO_TARGET_DIR:-$root/target}/release/capdiv"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$bin" demo --out "$work/demo" >/dev/null
python3 scripts/exchange/meshes.py "$work/gen"
depth=${STEP_DEPTH:-4}

# name  file  depth  extra options  (open meshes: checked against their OBJ's boundary)
cases=(
  "cube $work/demo/cube.json $depth"
  "globe $work/demo/globe.json $depth"
  "mushroom $work/demo/mushroom.json $depth"
  "rounded-cube $work/demo/rounded-cube.json $depth"
  "two-beam-corner $work/demo/two-beam-corner.json $depth"
  "hand $work/demo/hand.json $(( depth > 1 ? depth - 1 : 1 ))"
  "icosahedron $work/gen/icosahedron.obj $depth"
  "pole-sphere $work/gen/pole-sphere.obj $depth"
  "tube $work/gen/tube.obj $depth"
  "bowl $work/gen/bowl.obj $depth"
  "open-box $work/gen/open-box.obj $depth"
  "globe-f32 $work/demo/globe.json $depth --precision f32"
  "cube-cc $work/demo/cube.json $depth --scheme catmull-clark"
)

step "capdiv surface --format step|json, check_step.py"
passed=0
failed=0
for c in "${cases[@]}"; do
  read -r name file d extra <<< "$c"
  # shellcheck disable=SC2086 # extra options split on purpose
  "$bin" surface --depth "$d" $extra --format step -o "$work/$name.step" "$file" 2> "$work/$name.log"
  # shellcheck disable=SC2086
  "$bin" surface --depth "$d" $extra --format json -o "$work/$name.json" "$file" 2> /dev/null
  args=("$work/$name.step" "$work/$name.json" "$work/$name.log")
  case "$file" in *.obj) args+=(--mesh "$file") ;; esac
  case "$extra" in *f32*) args+=(--f32) ;; esac
  if "$py" scripts/exchange/check_step.py "${args[@]}"; then
    passed=$(( passed + 1 ))
  else
    failed=$(( failed + 1 ))
    sed -n '/^  step/p' "$work/$name.log"
  fi
done

step "check_step.py rejects broken files"
# The cube's file with one face dropped from its shell, and with one interior
# control point of the first patch's surface moved by 1e-6: both must fail.
python3 - "$work/cube.step" "$work/broken" <<'PY'
import re, sys
text = open(sys.argv[1]).read()
shell = re.search(r"CLOSED_SHELL\('',\((#\d+),", text)
open(sys.argv[2] + "-face.step", "w").write(text.replace(shell[0], shell[0][: -len(shell[1]) - 1]))
surface = re.search(r"B_SPLINE_SURFACE_WITH_KNOTS\('',\d,\d,\(\((?:#\d+,)+#\d+\),\(#\d+,(#\d+),", text)
point = re.search("\n" + surface[1] + r"=CARTESIAN_POINT\('',\(([^,]+),", text)
x = float(point[1].replace("E", "e")) + 1e-6
moved = point[0].replace(point[1], repr(x).replace("e", "E"), 1)
open(sys.argv[2] + "-point.step", "w").write(text.replace(point[0], moved))
PY
for broken in face point; do
  if "$py" scripts/exchange/check_step.py "$work/broken-$broken.step" "$work/cube.json" "$work/cube.log"; then
    echo "check_step.py accepted broken-$broken.step"
    failed=$(( failed + 1 ))
  else
    passed=$(( passed + 1 ))
  fi
done

if [ -n "${STEP_SCREENSHOT:-}" ]; then
  step "render the mushroom"
  "$py" scripts/exchange/render_step.py "$work/mushroom.step" "$STEP_SCREENSHOT" 800 600 2>&1 | grep -v WARN
fi

step "done"
echo "ci-step: $(( $(date +%s) - start )) s"
echo "step: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
