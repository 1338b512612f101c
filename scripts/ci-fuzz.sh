#!/usr/bin/env bash
# Bounded fuzzing for CI: builds the cargo-fuzz targets in fuzz/
# and runs each for a short time on its committed seed corpus. Fails on any
# crash, panic, timeout or out-of-memory.
#
#   bash scripts/ci-fuzz.sh              # FUZZ_TOTAL=100 s shared by the targets
#   FUZZ_SECONDS=60 bash scripts/ci-fuzz.sh   # 60 s per target instead
#   bash scripts/ci-fuzz.sh obj_mesh     # some targets only
#
# The targets are every [[bin]] of fuzz/Cargo.toml (a new target is picked up
# without editing this script). Installs the nightly toolchain (minimal
# profile) and cargo-fuzz if missing. Built without a sanitizer (`-s none`):
# the kernel forbids unsafe code, and libFuzzer still catches panics, aborts
# and stack overflows; Miri (scripts/ci-miri.sh) covers the dependencies'
# unsafe code. New inputs go to a scratch directory, the committed corpus is
# only read. Honours CARGO_TARGET_DIR (default fuzz/target).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD

if [ "$#" -gt 0 ]; then
    TARGETS=("$@")
else
    mapfile -t TARGETS < <(awk '/^\[\[bin\]\]/ { bin = 1; next }
        /^\[/ { bin = 0 }
        bin && /^name *=/ { gsub(/.*= *"|".*/, ""); print }' fuzz/Cargo.toml)
fi
[ "${#TARGETS[@]}" -gt 0 ] || { echo "ci-fuzz: no targets in fuzz/Cargo.toml"; exit 1; }
SECONDS_EACH=${FUZZ_SECONDS:-$(( ${FUZZ_TOTAL:-100} / ${#TARGETS[@]} ))}
[ "$SECONDS_EACH" -ge 5 ] || SECONDS_EACH=5

if ! rustup toolchain list | grep -q '^nightly'; then
    rustup toolchain install nightly --profile minimal
fi
if ! cargo fuzz --version >/dev/null 2>&1; then
    cargo install cargo-fuzz --locked
fi

start=$(date +%s)
(cd fuzz && cargo fmt --check)
target_dir=${CARGO_TARGET_DIR:-$root/fuzz/target}
# Every target (cargo fuzz build takes at most one name).
(cd fuzz && cargo +nightly fuzz build -s none --target-dir "$target_dir")
built=$(date +%s)
bin=$target_dir/x86_64-unknown-linux-gnu/release
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
status=0
for t in "${TARGETS[@]}"; do
    mkdir -p "$scratch/$t/corpus" "$scratch/$t/run"
    echo "== fuzz $t (${SECONDS_EACH} s)"
    # Run from a scratch directory: -jobs writes fuzz-0.log to the cwd.
    if ! (cd "$scratch/$t/run" && "$bin/$t" "$scratch/$t/corpus" "$root/fuzz/corpus/$t" \
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
end=$(date +%s)
echo "ci-fuzz: ${#TARGETS[@]} targets, build $(( built - start )) s, fuzzing $(( end - built )) s"
exit "$status"
