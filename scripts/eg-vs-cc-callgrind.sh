#!/usr/bin/env bash
# Instructions per step, EG against Catmull-Clark, counted by callgrind
# (reproducible on a noisy machine).
#
#   bash scripts/eg-vs-cc-callgrind.sh [REPS]
#
# Runs `benches/eg_vs_cc.rs --probe REPS PREC N` under
# `valgrind --tool=callgrind` for f64/f32 and n = 3, 5, reads the inclusive
# counts of its probe functions (each runs REPS steps on fresh copies made
# beforehand) and prints instructions per step — EG dense (`step`), EG
# through the Fourier rule (`step_fourier`), the kernel's CcCap,
# subdiv-kernels (`interpolate`, and its cheaper `interpolate_rows`) — and
# the ratios of each EG step to CcCap and to subdiv-kernels' cheaper path.
set -euo pipefail
cd "$(dirname "$0")/.."
reps=${1:-200}
command -v valgrind >/dev/null || { echo "needs valgrind (apt-get install valgrind)" >&2; exit 1; }
cargo bench --bench eg_vs_cc --no-run >/dev/null 2>&1
exe=$(cargo bench --bench eg_vs_cc --no-run --message-format=json 2>/dev/null |
    python3 -c 'import json,sys
for l in sys.stdin:
    m=json.loads(l)
    if m.get("reason")=="compiler-artifact" and m.get("executable") and m["target"]["name"]=="eg_vs_cc": print(m["executable"])')
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
printf '%-5s %2s %8s %8s %8s %8s %8s %7s %7s %7s %7s\n' prec n eg eg_four cc_cap sk sk_rows eg/cc four/cc eg/sk four/sk
for prec in f64 f32; do
    for n in 3 5; do
        out=$tmp/cg.$prec.$n
        valgrind --tool=callgrind --callgrind-out-file="$out" "$exe" --probe "$reps" "$prec" "$n" >/dev/null 2>&1
        callgrind_annotate --inclusive=yes "$out" 2>/dev/null | python3 -c '
import re, sys
reps, prec, n = int(sys.argv[1]), sys.argv[2], sys.argv[3]
got = {}
for line in sys.stdin:
    m = re.match(r"\s*([\d,]+)\s.*eg_vs_cc::(probe_eg_fourier|probe_eg|probe_cc|probe_sk_rows|probe_sk)\b", line)
    if m and m.group(2) not in got:
        got[m.group(2)] = int(m.group(1).replace(",", "")) / reps
eg, ef, cc, sk, skr = (got.get(k, float("nan")) for k in ("probe_eg", "probe_eg_fourier", "probe_cc", "probe_sk", "probe_sk_rows"))
print(f"{prec:<5} {n:>2} {eg:8.0f} {ef:8.0f} {cc:8.0f} {sk:8.0f} {skr:8.0f} {eg/cc:7.2f} {ef/cc:7.2f} {eg/skr:7.2f} {ef/skr:7.2f}")
' "$reps" "$prec" "$n"
    done
done
