#!/usr/bin/env bash
# The kernel's unit, integration and doc tests under Miri (issue 10).
#
#   bash scripts/ci-miri.sh
#
# Installs nightly + miri + rust-src if missing, sets up Miri's sysroot, runs
# `cargo +nightly miri test -p capdiv` (sizes reduced under cfg(miri) in the
# tests themselves) and exits non-zero on any UB report or test failure, or
# when the run exceeds MIRI_TIMEOUT seconds (default 1200).
#
# libm's x86 sqrt is inline assembly, which Miri cannot run: the run enables
# libm's `force-soft-floats` (its portable, also correctly rounded sqrt).
set -euo pipefail
cd "$(dirname "$0")/.."

if ! cargo +nightly miri --version >/dev/null 2>&1; then
    rustup toolchain install nightly --profile minimal --component miri,rust-src
fi
cargo +nightly miri setup

timeout "${MIRI_TIMEOUT:-1200}" \
    cargo +nightly miri test -p capdiv --features libm/force-soft-floats "$@"
