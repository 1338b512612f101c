#!/usr/bin/env bash
# The kernel's (package capdiv) unit, integration and doc tests under Miri,
# bounded.
#
#   bash scripts/ci-miri.sh
#
# Installs nightly + miri + rust-src if missing, sets up Miri's sysroot,
# builds every test binary once, then runs them as two groups in parallel
# (the machine has 2 cores; the groups are balanced by measured run time).
# The tests reduce their sizes under cfg(miri) themselves (proptest cases,
# valences, levels, loop counts); a few are `#[cfg_attr(miri, ignore)]`
# with the reason in the attribute (see docs/verification.md, "Fuzzing and Miri").
# Exits non-zero on any UB report or test failure, or when a group exceeds
# MIRI_TIMEOUT seconds (default 900).
#
# libm's x86 sqrt is inline assembly, which Miri cannot run: the run enables
# libm's `force-soft-floats` (its portable, also correctly rounded sqrt).
# Uses its own target directory (CARGO_TARGET_DIR, default target/miri-ci)
# so that the two groups do not wait for each other's lock.
set -euo pipefail
cd "$(dirname "$0")/.."

if ! cargo +nightly miri --version >/dev/null 2>&1; then
    rustup toolchain install nightly --profile minimal --component miri,rust-src
fi
cargo +nightly miri setup >/dev/null

# Miri models the unspecified precision of std's cos/sin/exp/... with random
# errors of a few ulps; tests/trig.rs holds the kernel's root table to 4e-16
# of this platform's f64::cos/sin. Deterministic floats: the host's results.
export MIRIFLAGS="${MIRIFLAGS:-} -Zmiri-deterministic-floats"

start=$(date +%s)
base=${CARGO_TARGET_DIR:-$PWD/target/miri-ci}
features=(--features libm/force-soft-floats)

# Each test target lands in exactly one group; a test file added later
# lands in group B until it is placed here.
# Measured CPU under Miri (s): cc_cap ~150, eg_ring ~120, eg_in_place ~90,
# numeric_extremes ~80, eg_ring_exact ~40, the rest below 30 each.
group_a=(--lib --test cc_cap --test eg_in_place --test eg_step
    --test fuzz_regressions --test trig --test polar_outer)
group_b=()
for f in tests/*.rs; do
    t=$(basename "$f" .rs)
    case " ${group_a[*]} " in *" $t "*) continue ;; esac
    group_b+=(--test "$t")
done

run() {
    local name=$1 dir=$2
    shift 2
    local s
    s=$(date +%s)
    if CARGO_TARGET_DIR=$dir timeout "${MIRI_TIMEOUT:-900}" \
        cargo +nightly miri test -p capdiv "${features[@]}" "$@" -- ${MIRI_TEST_ARGS:-} >"$dir-$name.log" 2>&1; then
        echo "== miri group $name: ok in $(( $(date +%s) - s )) s"
    else
        echo "== miri group $name FAILED (exit $?) after $(( $(date +%s) - s )) s"
        grep -E -B5 -A30 'Undefined Behavior|panicked|FAILED|error(\[|:)' "$dir-$name.log" | head -120
        return 1
    fi
    grep -E '^test result|Running|Doc-tests' "$dir-$name.log" || true
}

# Build every test binary once, then give group B a copy of the target
# directory: two cargo processes on one directory would wait for each
# other's lock for the whole run.
mkdir -p "$base"
CARGO_TARGET_DIR="$base/a" cargo +nightly miri test -p capdiv "${features[@]}" \
    --tests --no-run >"$base/build.log" 2>&1 || { tail -40 "$base/build.log"; exit 1; }
rm -rf "$base/b"
cp -a "$base/a" "$base/b"
echo "== miri build: $(( $(date +%s) - start )) s"
status=0
run A "$base/a" "${group_a[@]}" &
pid_a=$!
{ run B "$base/b" "${group_b[@]}" && run doc "$base/b" --doc; } || status=1
wait "$pid_a" || status=1
echo "ci-miri: $(( $(date +%s) - start )) s"
exit "$status"
