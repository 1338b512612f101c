#!/usr/bin/env bash
# Lists the panic paths left in the firmware's release build, for when the
# link-time check (the unlinkable panic handler) fails: builds with
# the diagnosis feature `linkable-panic`, disassembles, and prints every call
# into core's panic functions with the function it sits in and the nearest
# source line the debug info gives (inlined code: an approximation).
#
#   scripts/panic-paths.sh [TARGET] [extra cargo args...]
set -euo pipefail
cd "$(dirname "$0")/../firmware"
target=${1:-thumbv7em-none-eabihf}
shift || true
cargo build -q --release --target "$target" --features linkable-panic "$@"
bin="$(rustc --print sysroot)/lib/rustlib/x86_64-unknown-linux-gnu/bin"
elf="target/$target/release/capdiv-firmware"
dis=$(mktemp)
trap 'rm -f "$dis"' EXIT
"$bin/llvm-objdump" -d -l -C --no-show-raw-insn "$elf" > "$dis"
python3 - "$dis" <<'PY'
import re, sys
func = line = None
hits = []
for l in open(sys.argv[1]):
    m = re.match(r"^[0-9a-f]+ <(.*)>:$", l)
    if m:
        func = m.group(1)
        continue
    if l.startswith("; /"):
        line = l[2:].strip()
        continue
    m = re.search(r"\tbl?(\.w)?\s+0x[0-9a-f]+ <(core::panicking::[a-z_]+|core::slice::index::[a-z_]+|core::option::unwrap_failed|core::result::unwrap_failed)", l)
    if m and func and not func.startswith(("core::panicking", "core::slice::index")):
        hits.append((func, m.group(2), line))
for f, callee, src in hits:
    print(callee, "in", f[:100])
    print("    near", src)
print(len(hits), "panic call(s)")
sys.exit(1 if hits else 0)
PY
