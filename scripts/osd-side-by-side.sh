#!/usr/bin/env bash
# capdiv's analysis (SurfacePlan::for_mesh, depth 4) side by side with
# OpenSubdiv 3.5's (TopologyRefinerFactory::Create + RefineAdaptive to level 4
# + PatchTableFactory::Create + PatchMap) on the same tagged meshes: prints
# markdown tables of
#   1. wall-clock ns per input face, median of repeated batches on both sides
#      (mesh/benches/osd_side_by_side.rs and its helper osd/osd_bench.cpp);
#   2. patches per input face, in total and by level;
#   3. instructions per input face under callgrind, counted only inside the
#      analysis on both sides (--toggle-collect), for meshes of about 10^4
#      faces (steady on a loaded machine, unlike the wall clock);
#   4. with perf installed, the functions where capdiv's analysis of the 10^5
#      face torus spends its time.
#
# Needs libosd-dev, g++ and valgrind (apt-get install libosd-dev g++ valgrind).
# Usage: scripts/osd-side-by-side.sh [--no-callgrind] [--no-perf]
set -euo pipefail
cd "$(dirname "$0")/.."

callgrind=1
perf=1
for a in "$@"; do
    case "$a" in
    --no-callgrind) callgrind=0 ;;
    --no-perf) perf=0 ;;
    *) echo "unknown option $a" >&2; exit 2 ;;
    esac
done

bin=$(cargo bench -p capdiv-mesh --bench osd_side_by_side --no-run 2>&1 |
    sed -n 's/.*Executable .*(\(.*osd_side_by_side-[^)]*\)).*/\1/p' | tail -1)
[ -x "$bin" ] || { echo "could not build the bench" >&2; exit 1; }

echo "Machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'),"\
    "load average at start $(cut -d' ' -f1-3 /proc/loadavg)"
echo

"$bin"

if [ "$callgrind" = 1 ]; then
    command -v valgrind >/dev/null || { echo "valgrind not installed" >&2; exit 1; }
    tmp=$(mktemp -d)
    trap 'rm -rf "$tmp"' EXIT
    echo
    echo "### Instructions per input face (callgrind, analysis only)"
    echo
    echo "| mesh | faces | capdiv instr/face | OSD instr/face | capdiv / OSD |"
    echo "|---|--:|--:|--:|--:|"
    collected() { sed -n 's/.*Collected : \([0-9]*\).*/\1/p' "$1" | tail -1; }
    for mesh in torus-features-1e4 grid-1e4 feature-mix-1e4 icosphere-1280 hand; do
        prep=$("$bin" --prepare "$mesh")
        helper=$(sed -n 's/^helper //p' <<<"$prep")
        job=$(sed -n 's/^job //p' <<<"$prep")
        faces=$(sed -n 's/^faces //p' <<<"$prep")
        valgrind --tool=callgrind --toggle-collect=capdiv_analyse \
            --callgrind-out-file="$tmp/capdiv.out" "$bin" --once "$mesh" \
            >/dev/null 2>"$tmp/capdiv.err"
        valgrind --tool=callgrind --toggle-collect=analyse \
            --callgrind-out-file="$tmp/osd.out" "$helper" --once "$job" \
            >/dev/null 2>"$tmp/osd.err"
        c=$(collected "$tmp/capdiv.err")
        o=$(collected "$tmp/osd.err")
        awk -v m="$mesh" -v f="$faces" -v c="$c" -v o="$o" \
            'BEGIN { printf "| %s | %d | %.0f | %.0f | %.2f |\n", m, f, c / f, o / f, c / o }'
    done
fi

if [ "$perf" = 1 ] && command -v perf >/dev/null; then
    data=$(mktemp)
    # One list item per perf line: its percentages and the symbol, generic
    # parameters of BTreeMap's search elided.
    tidy() {
        sed 's/[ -]*$//; s/^ */- /; s/\[\.\] *//; s/<impl alloc::collections::btree::node::NodeRef<.*>>::/NodeRef::/'
    }
    echo
    echo "### Where capdiv's analysis of torus-features-1e5 spends its time (perf, share of samples)"
    echo
    if perf record -q -o "$data" -F 499 --call-graph dwarf,16384 "$bin" --once torus-features-1e5 \
        >/dev/null 2>&1; then
        echo "Self time, top functions:"
        echo
        perf report -i "$data" --no-children --sort symbol --stdio -g none 2>/dev/null |
            grep -v '^#' | grep -v '^$' | awk 'NR <= 8' | tidy
        echo
        echo "Including callees (first column; self second), capdiv's functions:"
        echo
        perf report -i "$data" --children --sort symbol --stdio -g none 2>/dev/null |
            grep 'capdiv_mesh::' | awk 'NR <= 8' | tidy
    else
        echo "(perf record failed: kernel.perf_event_paranoid?)"
    fi
    rm -f "$data"
fi
echo
echo "Load average at end $(cut -d' ' -f1-3 /proc/loadavg)"
