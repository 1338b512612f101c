#!/usr/bin/env bash
# How `capdiv surface --format obj` (streamed, f64, to /dev/null) scales with
# the input: per benchmark mesh and setting, the patches made, CPU time
# (user + system) per input face and per output patch, wall clock, and peak
# resident memory (`/usr/bin/time -v`), one Markdown table row per run,
# printed as each run ends.
#
#   bash scripts/surface-scaling.sh [FACES...]        (default: 10000 100000)
#
# Meshes (mesh/examples/bench_mesh.rs): `mixed` (copies of a mushroom with
# two valence-12 poles, a rounded cube with eight valence-3 points and a
# valence-7 disk: quads, triangle fans, one open boundary per copy) and
# `triangles` (a torus of triangles, every vertex of valence 6: two
# whole-mesh refinement steps, then a cap at every vertex and face centre)
# and `features` (a quad torus with isolated valence-3 and -5 points,
# creases, corners and holes as tag lines: the adaptive refinement's mesh,
# not in the default KINDS).
# Settings: `default` (depth 4, tolerance 3e-3rel, grid 4, every core) and
# `depth 6` (`--depth 6 --tolerance none`: every cap 6 rings).
#
# Environment: KINDS (default "mixed triangles"), SETTINGS (default
# "default depth6"), NICE (default 1: runs under `nice`), OUT (a file the
# rows are appended to as well), EXTRA (more `capdiv surface` options for
# every run, e.g. "--max-patches 100000000").
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(10000 100000)
kinds=${KINDS:-mixed triangles}
settings=${SETTINGS:-default depth6}
prefix=()
[ "${NICE:-1}" = 1 ] && prefix=(nice)

cargo build -q --release -p capdiv-cli
cargo build -q --release -p capdiv-mesh --example bench_mesh
target=${CARGO_TARGET_DIR:-$root/target}
bin=$target/release/capdiv
gen=$target/release/examples/bench_mesh
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

row() {
  echo "$1"
  if [ -n "${OUT:-}" ]; then echo "$1" >>"$OUT"; fi
}

cpu=$(grep -m1 'model name' /proc/cpuinfo | sed 's/.*: //')
row "Measured $(date -u +%Y-%m-%d) on $(nproc) cores ($cpu), load average $(cut -d' ' -f1-3 /proc/loadavg), commit $(git rev-parse --short HEAD)."
row ""
row "| mesh | input faces | setting | rings per cap | patches | patches per face | CPU (s) | CPU per face (µs) | CPU per patch (µs) | wall (s) | peak RSS (MB) | weld table (vertices) |"
row "|---|--:|---|---|--:|--:|--:|--:|--:|--:|--:|--:|"
for kind in $kinds; do
  for n in "${sizes[@]}"; do
    mesh=$tmp/$kind-$n.obj
    "$gen" "$kind" "$n" >"$mesh"
    for s in $settings; do
      case $s in
        default) opts=() ;;
        depth6) opts=(--depth 6 --tolerance none) ;;
        *) echo "unknown setting $s" >&2; exit 2 ;;
      esac
      # shellcheck disable=SC2206 # EXTRA is split into options on purpose.
      opts+=(${EXTRA:-})
      log=$tmp/log
      /usr/bin/time -v "${prefix[@]}" "$bin" surface --format obj -o /dev/null "${opts[@]}" "$mesh" \
        >"$log" 2>&1
      faces=$(sed -n 's/^capdiv surface: .*vertices, \([0-9]*\) faces.*/\1/p' "$log")
      patches=$(sed -n 's/^  patches *\([0-9]*\) .*/\1/p' "$log")
      rings=$(sed -n 's/^  rings *\([0-9-]*\) per cap.*/\1/p' "$log")
      weld=$(sed -n 's/^  streamed *weld table at most \([0-9]*\) .*/\1/p' "$log")
      user=$(sed -n 's/^\tUser time (seconds): //p' "$log")
      sys=$(sed -n 's/^\tSystem time (seconds): //p' "$log")
      wall=$(sed -n 's/^\tElapsed (wall clock) time (h:mm:ss or m:ss): //p' "$log")
      rss=$(sed -n 's/^\tMaximum resident set size (kbytes): //p' "$log")
      row "$(python3 - "$kind" "$faces" "$s" "$rings" "$patches" "$user" "$sys" "$wall" "$rss" "$weld" <<'EOF'
import sys
kind, faces, s, rings, patches, user, sys_, wall, rss, weld = sys.argv[1:]
faces, patches = int(faces), int(patches)
cpu = float(user) + float(sys_)
parts = [float(x) for x in wall.split(":")]
secs = 0.0
for x in parts:
    secs = 60 * secs + x
setting = {"default": "default", "depth6": "--depth 6 --tolerance none"}[s]
print(f"| {kind} | {faces:,} | {setting} | {rings} | {patches:,} | {patches / faces:.2f} | "
      f"{cpu:.1f} | {cpu / faces * 1e6:.1f} | {cpu / patches * 1e6:.2f} | {secs:.1f} | "
      f"{int(rss) / 1024:.0f} | {int(weld):,} |")
EOF
)"
    done
  done
done
