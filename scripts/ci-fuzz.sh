#!/usr/bin/env bash
# Bounded fuzzing for CI (issue 10): builds the cargo-fuzz targets in fuzz/
# and runs each for a short time on its committed seed corpus. Fails on any
# crash, panic, timeout or out-of-memory.
#
#   bash scripts/ci-fuzz.sh            # 20 s per target (5 targets)
#   FUZZ_SECONDS=60 bash scripts/ci-fuzz.sh
#
# Installs the nightly toolchain (minimal profile) and cargo-fuzz if missing.
# Built without a sanitizer (`-s none`): the kernel forbids unsafe code, and
# libFuzzer still catches panics, aborts and stack overflows; Miri covers
# the dependencies' unsafe code. New inputs go to a scratch directory, the
# committed corpus is only read.
set -euo pipefail
cd "$(dirname "$0")/.."
SECONDS_EACH=${FUZZ_SECONDS:-20}
TARGETS=(cli_json rule_table obj_mesh kernel_polar kernel_eg_cc)

if ! rustup toolchain list | grep -q '^nightly'; then
    rustup toolchain install nightly --profile minimal
fi
if ! cargo fuzz --version >/dev/null 2>&1; then
    cargo install cargo-fuzz --locked
fi

cd fuzz
start=$(date +%s)
cargo +nightly fuzz build -s none
bin=target/x86_64-unknown-linux-gnu/release
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
status=0
for t in "${TARGETS[@]}"; do
    mkdir -p "$scratch/$t/corpus" "$scratch/$t/run"
    echo "== fuzz $t (${SECONDS_EACH} s)"
    # Run from a scratch directory: -jobs writes fuzz-0.log to the cwd.
    if ! (cd "$scratch/$t/run" && "$OLDPWD/$bin/$t" "$scratch/$t/corpus" "$OLDPWD/corpus/$t" \
        -jobs=1 -workers=1 -max_total_time="$SECONDS_EACH" -timeout=10 \
        -rss_limit_mb=4096 -print_final_stats=1 \
        -artifact_prefix="$scratch/$t/" >"$scratch/$t/log" 2>&1); then
        status=1
    fi
    log="$scratch/$t/run/fuzz-0.log"
    [ -f "$log" ] || log="$scratch/$t/log"
    grep -E '^stat::number_of_executed_units|^stat::average_exec_per_sec' "$log" || true
    if ls "$scratch/$t"/crash-* "$scratch/$t"/timeout-* "$scratch/$t"/oom-* >/dev/null 2>&1; then
        status=1
    fi
    if [ "$status" -ne 0 ]; then
        echo "!! $t failed:"
        grep -E -A20 'panicked|ERROR|SUMMARY' "$log" | head -60
        for a in "$scratch/$t"/crash-* "$scratch/$t"/timeout-* "$scratch/$t"/oom-*; do
            [ -f "$a" ] && { echo "artifact $(basename "$a") (base64):"; base64 -w0 "$a"; echo; }
        done
        break
    fi
done
echo "ci-fuzz: $(( $(date +%s) - start )) s"
exit "$status"
