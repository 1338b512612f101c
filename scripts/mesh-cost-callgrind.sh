#!/usr/bin/env bash
# Instructions per input face (topology, analysis) and per patch
# (evaluation) of whole generated meshes, counted by callgrind (reproducible
# on a noisy machine), as a Markdown table with its header line.
#
#   bash scripts/mesh-cost-callgrind.sh [FACES ...]   (default 10000 100000)
#
# Runs `mesh/examples/cost_probe.rs KIND FACES` under
# `valgrind --tool=callgrind` for the `regular` torus and the `features` mix
# (poles, EG caps, a Catmull-Clark cap; caps to depth 3) and reads the
# inclusive counts of `Topology::new`, `SurfacePlan::new` and
# `Evaluator::evaluate`.
set -euo pipefail
cd "$(dirname "$0")/.."
command -v valgrind >/dev/null || { echo "needs valgrind (apt-get install valgrind)" >&2; exit 1; }
sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(10000 100000)
cargo build --release -p capdiv-mesh --example cost_probe >/dev/null 2>&1
exe=target/release/examples/cost_probe
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
BENCH_LOAD=${BENCH_LOAD:-"n/a (instruction counts)"} python3 scripts/bench-table.py header "Whole meshes, instructions (callgrind, \`bash scripts/mesh-cost-callgrind.sh\`), f64"
echo
echo "| mesh | faces | topology (instr/face) | analysis (instr/face) | evaluation (instr/patch) | patches |"
echo "|---|---:|---:|---:|---:|---:|"
for kind in regular features; do
    for faces in "${sizes[@]}"; do
        out=$tmp/cg.$kind.$faces
        printed=$(valgrind --tool=callgrind --callgrind-out-file="$out" "$exe" "$kind" "$faces" 2>/dev/null)
        callgrind_annotate --inclusive=yes "$out" 2>/dev/null | python3 -c '
import re, sys
kind, printed = sys.argv[1], sys.argv[2]
m = re.match(r"\S+: (\d+) faces, (\d+) patches", printed)
faces, patches = int(m.group(1)), int(m.group(2))
got = {}
for line in sys.stdin:
    m = re.match(r"\s*([\d,]+)\s.*capdiv_mesh::(topology::Topology::new|plan::SurfacePlan::new|evaluate::Evaluator<R>::evaluate)\b", line)
    if m and m.group(2) not in got:
        got[m.group(2)] = int(m.group(1).replace(",", ""))
t = got.get("topology::Topology::new", float("nan")) / faces
a = got.get("plan::SurfacePlan::new", float("nan")) / faces
e = got.get("evaluate::Evaluator<R>::evaluate", float("nan")) / patches
print(f"| {kind} | {faces:,} | {t:,.0f} | {a:,.0f} | {e:,.0f} | {patches:,} |")
' "$kind" "$printed"
    done
done
