#!/usr/bin/env bash
# Sizes of the C firmware: .text/.rodata/.data/.bss of the images
# (m4, m0: every call of the header; m4-f32, m0-f32: the float calls only)
# (arm-none-eabi-size) and the stack high-water mark of a run under QEMU,
# as a markdown table (also written to cfirmware/build/size-report.md),
# checked against cfirmware/size-budget.txt. Run `make` first (or
# scripts/ci-cfirmware.sh, which does).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
budgets="$here/size-budget.txt"
out="$here/build/size-report.md"

# board | target | QEMU machine args
boards=(
  "m4|thumbv7em-none-eabihf|-machine mps2-an386 -cpu cortex-m4"
  "m0|thumbv6m-none-eabi|-machine microbit"
  "m4-f32|thumbv7em-none-eabihf|-machine mps2-an386 -cpu cortex-m4"
  "m0-f32|thumbv6m-none-eabi|-machine microbit"
)
declare -A figure
rows=()
for b in "${boards[@]}"; do
  IFS='|' read -r name target machine <<<"$b"
  elf="$here/build/$name/cfirmware.elf"
  [ -f "$elf" ] || { echo "$elf missing: run make in cfirmware/" >&2; exit 1; }
  read -r text rodata data bss < <(arm-none-eabi-size -A "$elf" | awk '
    $1==".vectors"||$1==".text"{t+=$2} $1==".rodata"{r=$2} $1==".data"{d=$2} $1==".bss"{b=$2}
    END{print t+0, r+0, d+0, b+0}')
  # shellcheck disable=SC2086
  log=$(timeout 60 qemu-system-arm $machine -nographic -monitor none -serial none \
    -chardev stdio,id=sh -semihosting-config enable=on,target=native,chardev=sh -kernel "$elf")
  grep -qx "done 0" <<<"$log" || { echo "$name: the run failed" >&2; exit 1; }
  stack=$(awk '$1=="stack"{print $2}' <<<"$log")
  figure[$name.text]=$text
  figure[$name.rodata]=$rodata
  figure[$name.data]=$data
  figure[$name.bss]=$bss
  figure[$name.stack]=$stack
  rows+=("| $name | $target | $text | $rodata | $data | $bss | $stack |")
done

mkdir -p "$here/build"
{
  echo "| C firmware | target | .text | .rodata | .data | .bss | stack high-water |"
  echo "|---|---|---:|---:|---:|---:|---:|"
  printf '%s\n' "${rows[@]}"
} | tee "$out"

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
    echo "BUDGET: $key = ${figure[$key]} has no budget in cfirmware/size-budget.txt" >&2
    fail=1
  fi
done
[ "$fail" -eq 0 ] || { echo "C firmware size budgets: FAILED" >&2; exit 1; }
echo "C firmware size budgets: all ${#figure[@]} figures within budget"
