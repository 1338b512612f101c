#!/usr/bin/env bash
# The whole job — mesh in, positions and unit normals out on a 5x5 grid of
# (u, v) per ptex face — side by side with OpenSubdiv 3.5 (Far, CPU, one
# thread), f64 and f32. Prints markdown:
#   1. per mesh, wall clock (median of repeated runs on both sides): each
#      stage per input face or per sample, the whole job, re-evaluation after
#      the vertices move, capdiv's welded OBJ tessellation, f32 normals
#      against f64 (mesh/benches/osd_whole_job.rs and its helper
#      osd/osd_bench.cpp --whole);
#   2. instructions per input face under callgrind, counted only inside the
#      whole job on both sides (--toggle-collect), for meshes of about 10^4
#      faces (steady on a loaded machine, unlike the wall clock), with each
#      stage's share (callgrind_annotate --inclusive);
#   3. where the instructions of capdiv's whole job on one of them go (its
#      top functions, self cost).
#
# Needs libosd-dev, g++ and valgrind (apt-get install libosd-dev g++ valgrind).
# Usage: scripts/osd-whole-job.sh [--no-wall] [--no-callgrind] [--no-trim] [--only NAME,NAME]
# (--no-trim: glibc's heap trimming and mmap threshold fixed for both sides'
# processes, so that neither faults its heap in again on every timed run;
# see "Four more runs" in docs/benchmarks.md)
# (meshes of mesh/benches/osd_whole_job.rs; default: the 300x300 torus, the
# 9·10^4-face torus with extraordinary points and the three 10^4-face meshes).
set -euo pipefail
cd "$(dirname "$0")/.."

wall=1
callgrind=1
only=torus-300x300,torus-ev-9e4,torus-100x100,torus-ev-1e4,torus-features-1e4
while [ $# -gt 0 ]; do
    case "$1" in
    --no-wall) wall=0 ;;
    --no-callgrind) callgrind=0 ;;
    --no-trim) export GLIBC_TUNABLES=glibc.malloc.trim_threshold=4000000000:glibc.malloc.mmap_threshold=4000000000 ;;
    --only) only=$2; shift ;;
    *) echo "unknown option $1" >&2; exit 2 ;;
    esac
    shift
done

bin=$(nice cargo bench -p capdiv-mesh --bench osd_whole_job --no-run 2>&1 |
    sed -n 's/.*Executable .*(\(.*osd_whole_job-[^)]*\)).*/\1/p' | tail -1)
[ -x "$bin" ] || { echo "could not build the bench" >&2; exit 1; }

echo "Machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'),"\
    "load average at start $(cut -d' ' -f1-3 /proc/loadavg)${GLIBC_TUNABLES:+, GLIBC_TUNABLES=$GLIBC_TUNABLES}"
echo

if [ "$wall" = 1 ]; then
    "$bin" --only "$only"
fi

if [ "$callgrind" = 1 ]; then
    command -v valgrind >/dev/null || { echo "valgrind not installed" >&2; exit 1; }
    tmp=$(mktemp -d)
    trap 'rm -rf "$tmp"' EXIT
    collected() { sed -n 's/.*Collected : \([0-9]*\).*/\1/p' "$1" | tail -1; }
    # Inclusive instructions of the functions matching $2 (first match).
    inclusive() {
        callgrind_annotate --inclusive=yes --threshold=100 "$1" 2>/dev/null |
            grep -E "$2" | awk 'NR == 1 { gsub(",", "", $1); print $1 }'
    }
    echo
    echo "### Instructions per input face (callgrind, whole job only)"
    echo
    echo "Stages: analysis (OSD: Create + RefineAdaptive + PatchTable + PatchMap;"\
        "capdiv: \`SurfacePlan::for_mesh\`), stencils (OSD: stencil tables; capdiv:"\
        "\`Evaluator::new\`), points (OSD: \`UpdateValues\`; capdiv: \`evaluate\` without"\
        "its sink), sampling (OSD: FindPatch + EvaluateBasis + sums; capdiv: the sink)"\
        "per sample. \"OSD with PrimvarRefiner\": the refined points from"\
        "\`PrimvarRefiner::Interpolate\` level by level and the local points from the"\
        "patch table's stencils, instead of stencil tables."
    echo
    echo "Re-evaluation is not run under callgrind; its column adds the stages it"\
        "repeats: points (OSD) or patches (capdiv) + samples per face × sampling."
    echo
    echo "| mesh | precision | OSD instr/face | OSD with PrimvarRefiner | capdiv instr/face |"\
        "OSD / capdiv | OSD with PrimvarRefiner / capdiv |"\
        "OSD analysis / stencils / points per face, sampling per sample |"\
        "capdiv analysis / \`Evaluator::new\` / patches per face, sampling per sample |"\
        "re-evaluation OSD / capdiv per face (OSD / capdiv) |"
    echo "|---|---|--:|--:|--:|--:|--:|---|---|---|"
    for mesh in torus-100x100 torus-ev-1e4 torus-features-1e4; do
        prep=$("$bin" --prepare "$mesh")
        helper=$(sed -n 's/^helper //p' <<<"$prep")
        job=$(sed -n 's/^job //p' <<<"$prep")
        faces=$(sed -n 's/^faces //p' <<<"$prep")
        for prec in f64 f32; do
            valgrind --tool=callgrind --toggle-collect="capdiv_whole_job_$prec" \
                --callgrind-out-file="$tmp/capdiv-$mesh-$prec.out" "$bin" --once "$mesh" "$prec" \
                >"$tmp/capdiv.txt" 2>"$tmp/capdiv.err"
            valgrind --tool=callgrind --toggle-collect="osd_whole_job_$prec" \
                --callgrind-out-file="$tmp/osd.out" "$helper" --whole-once "$job" "$prec" \
                >"$tmp/osd.txt" 2>"$tmp/osd.err"
            valgrind --tool=callgrind --toggle-collect="osd_whole_job_primvar_$prec" \
                --callgrind-out-file="$tmp/osd-primvar.out" "$helper" --whole-once "$job" "$prec" primvar \
                >/dev/null 2>"$tmp/osd-primvar.err"
            c=$(collected "$tmp/capdiv.err")
            op2=$(collected "$tmp/osd-primvar.err")
            o=$(collected "$tmp/osd.err")
            n=$(sed -n 's/^covered //p' "$tmp/osd.txt")
            real=$([ "$prec" = f64 ] && echo double || echo float)
            oa=$(inclusive "$tmp/osd.out" "analyseIn<$real>")
            os=$(inclusive "$tmp/osd.out" "buildStencils<$real>")
            op=$(inclusive "$tmp/osd.out" "computePoints<$real>")
            osa=$(inclusive "$tmp/osd.out" "samplePoints<$real>")
            cf="$tmp/capdiv-$mesh-$prec.out"
            ca=$(inclusive "$cf" ":capdiv_job_analyse ")
            cn=$(inclusive "$cf" "Evaluator<R>::new ")
            ce=$(inclusive "$cf" "osd_whole_job::evaluate_sampled ")
            cs=$(inclusive "$cf" "GridSink<R> as capdiv_mesh::evaluate::SurfaceSink<R>>::patch ")
            awk -v m="$mesh" -v p="$prec" -v f="$faces" -v n="$n" -v c="$c" -v o="$o" -v o2="$op2" \
                -v oa="$oa" -v os="$os" -v op="$op" -v osa="$osa" \
                -v ca="$ca" -v cn="${cn:-0}" -v ce="$ce" -v cs="$cs" 'BEGIN {
                printf "| %s | %s | %.0f | %.0f | %.0f | %.2f× | %.2f× | %.0f / %.0f / %.0f, %.0f |", \
                    m, p, o / f, o2 / f, c / f, o / c, o2 / c, oa / f, os / f, op / f, osa / n
                printf " %.0f / %.0f / %.0f, %.0f |", ca / f, cn / f, (ce - cs) / f, cs / n
                ro = op / f + osa / f; rc = (ce - cs) / f + cs / f
                printf " %.0f / %.0f (%.2f×) |\n", ro, rc, ro / rc
            }'
        done
    done
    echo
    echo "### Where capdiv's whole job (torus-ev-1e4, f64) spends its instructions (callgrind, self cost)"
    echo
    callgrind_annotate --threshold=95 "$tmp/capdiv-torus-ev-1e4-f64.out" 2>/dev/null |
        grep -E '^ *[0-9,]+ \(' | grep -v 'PROGRAM TOTALS' | awk 'NR <= 12' |
        sed -E 's/^ *([0-9,]+) \( *([0-9.]+%)\) +[^:]*:(.*) \[.*\]$/- \2 \1 `\3`/'
    echo
    echo "Including callees (the evaluation's parts):"
    echo
    callgrind_annotate --inclusive=yes --threshold=100 "$tmp/capdiv-torus-ev-1e4-f64.out" 2>/dev/null |
        grep -E '^ *[0-9,]+ \(' | grep -E 'capdiv(_mesh)?::|GridSink' | awk 'NR <= 10' |
        sed -E 's/^ *([0-9,]+) \( *([0-9.]+%)\) +[^:]*:(.*) \[.*\]$/- \2 \1 `\3`/'
    echo
    echo "### Where capdiv's analysis of torus-features-1e4 spends its instructions (callgrind, self cost)"
    echo
    valgrind --tool=callgrind --toggle-collect=capdiv_job_analyse \
        --callgrind-out-file="$tmp/analysis.out" "$bin" --once torus-features-1e4 f64 \
        >/dev/null 2>"$tmp/analysis.err"
    echo "$(collected "$tmp/analysis.err" | awk '{ printf "%.0f", $1 / 10000 }') instructions per face in all;"\
        "top functions:"
    echo
    callgrind_annotate --threshold=95 "$tmp/analysis.out" 2>/dev/null |
        grep -E '^ *[0-9,]+ \(' | grep -v 'PROGRAM TOTALS' | awk 'NR <= 12' |
        sed -E 's/^ *([0-9,]+) \( *([0-9.]+%)\) +[^:]*:(.*) \[.*\]$/- \2 \1 `\3`/'
    echo
    echo "Including callees:"
    echo
    callgrind_annotate --inclusive=yes --threshold=100 "$tmp/analysis.out" 2>/dev/null |
        grep -E '^ *[0-9,]+ \(' | grep -E 'capdiv_mesh::' | awk 'NR <= 12' |
        sed -E 's/^ *([0-9,]+) \( *([0-9.]+%)\) +[^:]*:(.*) \[.*\]$/- \2 \1 `\3`/'
    echo
    echo "### capdiv's welded OBJ, streamed as \`capdiv surface\` writes it (callgrind, f64, grid 4)"
    echo
    echo "| mesh | evaluating the patches | + sampling, weld and assembly | + OBJ text | sampling alone | weld and assembly ÷ evaluating and sampling |"
    echo "|---|--:|--:|--:|--:|--:|"
    for mesh in torus-ev-1e4 torus-features-1e4; do
        for f in capdiv_stream_evaluate capdiv_stream_count capdiv_stream_obj; do
            valgrind --tool=callgrind --toggle-collect=$f \
                --callgrind-out-file="$tmp/$mesh-$f.out" "$bin" --stream $mesh \
                >"$tmp/stream.txt" 2>"$tmp/$mesh-$f.err"
        done
        e=$(collected "$tmp/$mesh-capdiv_stream_evaluate.err")
        c=$(collected "$tmp/$mesh-capdiv_stream_count.err")
        o=$(collected "$tmp/$mesh-capdiv_stream_obj.err")
        s=$(inclusive "$tmp/$mesh-capdiv_stream_count.out" "sample::Raw<R>::push")
        faces=$(sed -n 's/^faces //p' "$tmp/stream.txt")
        awk -v m="$mesh" -v f="$faces" -v e="$e" -v c="$c" -v o="$o" -v s="$s" 'BEGIN {
            w = c - e - s
            printf "| %s | %.0f | %.0f | %.0f | %.0f | %.2f |\n", m, e / f, (c - e) / f, (o - c) / f, s / f, w / (e + s)
        }'
    done
    echo
    echo "Instructions per input face. Where the OBJ of torus-ev-1e4 spends them (self cost):"
    echo
    callgrind_annotate --threshold=95 "$tmp/torus-ev-1e4-capdiv_stream_obj.out" 2>/dev/null |
        grep -E '^ *[0-9,]+ \(' | grep -v 'PROGRAM TOTALS' | awk 'NR <= 10' |
        sed -E 's/^ *([0-9,]+) \( *([0-9.]+%)\) +[^:]*:(.*) \[.*\]$/- \2 \1 `\3`/'
fi
echo
echo "Load average at end $(cut -d' ' -f1-3 /proc/loadavg)"
