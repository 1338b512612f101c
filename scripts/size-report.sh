#!/usr/bin/env bash
# Size report and budgets. Builds the firmware (release profile:
# opt-level "s", LTO, f32) for several feature sets and targets, reads
# .text/.rodata/.data/.bss with llvm-size, runs each image under QEMU for its
# stack high-water mark (the firmware paints its stack and reports the mark),
# builds the WASM module for its size, prints a markdown table (also written
# to target/size-report.md) and fails when a figure exceeds its budget in
# scripts/size-budget.txt (or has none).
#
# Needs: the thumbv7em-none-eabihf, thumbv6m-none-eabi and wasm32-unknown-unknown
# targets, rustup's llvm-tools, qemu-system-arm (scripts/ci-embedded.sh
# installs them).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
budgets="$root/scripts/size-budget.txt"
out="$root/target/size-report.md"
mkdir -p "$root/target"
llvm_size="$(rustc --print sysroot)/lib/rustlib/x86_64-unknown-linux-gnu/bin/llvm-size"
[ -x "$llvm_size" ] || { echo "llvm-size missing: rustup component add llvm-tools" >&2; exit 1; }

(cd "$root/embedded-tests" && cargo build -q --release --bin defmt-decode)
decode="$root/embedded-tests/target/release/defmt-decode"

# name | target | features | QEMU machine | QEMU cpu
configs=(
  "m4-c2ps|thumbv7em-none-eabihf|c2ps|mps2-an386|cortex-m4"
  "m4-eg|thumbv7em-none-eabihf|eg|mps2-an386|cortex-m4"
  "m4-c2ps-eg|thumbv7em-none-eabihf|c2ps,eg|mps2-an386|cortex-m4"
  "m0-c2ps|thumbv6m-none-eabi|c2ps|microbit|"
  "m0-eg|thumbv6m-none-eabi|eg|microbit|"
  "m0-c2ps-stream|thumbv6m-none-eabi|c2ps-stream|microbit|"
)

declare -A figure
rows=()
for c in "${configs[@]}"; do
  IFS='|' read -r name target features machine cpu <<<"$c"
  (cd "$root/firmware" && cargo build -q --release --target "$target" --no-default-features --features "$features")
  elf="$root/firmware/target/$target/release/capdiv-firmware"
  # llvm-size -A: "section size addr" per line.
  read -r text rodata data bss < <("$llvm_size" -A "$elf" | awk '
    $1==".text"{t=$2} $1==".rodata"{r=$2} $1==".data"{d=$2} $1==".bss"{b=$2}
    END{print t+0, r+0, d+0, b+0}')
  log=$(mktemp)
  qemu=(qemu-system-arm -machine "$machine")
  [ -n "$cpu" ] && qemu+=(-cpu "$cpu")
  qemu+=(-nographic -monitor none -serial none -semihosting-config enable=on,target=native -kernel "$elf")
  # 300 s: the streaming build takes ~7 s of CPU (depth 12 in soft-float),
  # much longer in wall time on a shared machine.
  if ! timeout 300 "${qemu[@]}" >"$log"; then
    echo "$name: the firmware failed or hung under QEMU" >&2
    "$decode" "$elf" "$log" >&2 || true
    exit 1
  fi
  decoded=$("$decode" "$elf" "$log")
  rm -f "$log"
  grep -qx "done true" <<<"$decoded" || { echo "$name: run did not succeed:" >&2; echo "$decoded" >&2; exit 1; }
  stack=$(awk '$1=="stack"{print $2}' <<<"$decoded")
  figure[$name.text]=$text
  figure[$name.rodata]=$rodata
  figure[$name.data]=$data
  figure[$name.bss]=$bss
  figure[$name.stack]=$stack
  # Streaming C²PS: its RAM, .bss plus stack, must stay within 8 KiB.
  [ "$name" = m0-c2ps-stream ] && figure[$name.ram]=$((bss + stack))
  # Both schemes in one f32 firmware: .text + .rodata under 32 KiB.
  [ "$name" = m4-c2ps-eg ] && figure[$name.flash]=$((text + rodata))
  rows+=("| $name | $target | $features | $text | $rodata | $data | $bss | $stack |")
done

(cd "$root/capi-wasm" && cargo build -q --release)
wasm_bytes=$(stat -c %s "$root/capi-wasm/target/wasm32-unknown-unknown/release/capdiv_capi_wasm.wasm")
figure[wasm.bytes]=$wasm_bytes

{
  echo "| build | target | features | .text | .rodata | .data | .bss | stack high-water |"
  echo "|---|---|---|---:|---:|---:|---:|---:|"
  printf '%s\n' "${rows[@]}"
  echo
  echo "| WASM module (C²PS + EG C ABI, wasm32-unknown-unknown, opt-level \"s\") | bytes |"
  echo "|---|---:|"
  echo "| capdiv_capi_wasm.wasm | $wasm_bytes |"
  echo
  echo "All sizes in bytes. Firmware: release profile (opt-level \"s\", LTO, one codegen unit), f32;"
  echo "m4 = Cortex-M4F on QEMU mps2-an386, m0 = Cortex-M0 on QEMU microbit. .bss holds the nets"
  echo "(C²PS: valence 6 refined 6 times on m4, 3 times on m0; EG: one subdivision, n ≤ 10;"
  echo "c2ps-stream: valence 6 streamed to depth 12, the PolarStream<f32, 12> state)."
  echo "Stack: deepest use of the painted stack over the whole run."
} | tee "$out"

# Budgets: "<build>.<figure> <max bytes>" per line; # comments.
fail=0
declare -A seen
while read -r key max _; do
  [[ -z "$key" || "$key" == \#* ]] && continue
  seen[$key]=1
  value=${figure[$key]:-}
  if [ -z "$value" ]; then
    echo "BUDGET: $key has a budget but no measured figure" >&2
    fail=1
  elif [ "$value" -gt "$max" ]; then
    echo "BUDGET EXCEEDED: $key = $value > $max" >&2
    fail=1
  fi
done <"$budgets"
for key in "${!figure[@]}"; do
  if [ -z "${seen[$key]:-}" ]; then
    echo "BUDGET: $key = ${figure[$key]} has no budget in scripts/size-budget.txt" >&2
    fail=1
  fi
done
if [ "$fail" -ne 0 ]; then
  echo "size budgets: FAILED" >&2
  exit 1
fi
echo "size budgets: all ${#figure[@]} figures within budget"
