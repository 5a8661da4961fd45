#!/usr/bin/env bash
# What proving a target costs: `crtforge validate --target T` (every preset: consumer compile checks
# plus every golden render) for each target, against the SPIR-V/Vulkan path measured in the same run.
# The cache is warm (one untimed run first), so this times the consumers, not glslang.
# Prints the median wall time of N runs per target and its ratio to spirv.
#
# usage: bench/validate_targets.sh [runs=3] [targets=spirv,glsl330,hlsl50,godot4,wgsl]   (after scripts/build.sh)
set -euo pipefail
cd "$(dirname "$0")/.."
RUNS="${1:-3}"
IFS=, read -r -a TARGETS <<< "${2:-spirv,glsl330,hlsl50,godot4,wgsl}"
CRTFORGE=build/crtforge
[[ -x $CRTFORGE ]] || { echo "bench: build crtforge first (scripts/build.sh)" >&2; exit 2; }
[[ " ${TARGETS[*]} " == *" spirv "* ]] || TARGETS=(spirv "${TARGETS[@]}")

now_ns() { date +%s%N; }
median() { printf '%s\n' "$@" | sort -n | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }

declare -A result
for t in "${TARGETS[@]}"; do
  $CRTFORGE validate --target "$t" -j 1 >/dev/null  # warm the cache and the page cache
  times=()
  for ((i = 0; i < RUNS; ++i)); do
    start=$(now_ns)
    $CRTFORGE validate --target "$t" -j 1 >/dev/null
    times+=($(( ($(now_ns) - start) / 1000000 )))
  done
  result[$t]=$(median "${times[@]}")
done
checks=$($CRTFORGE validate --target spirv -j 1 | tail -1 | sed -E 's/.*\(([0-9]+) checks.*/\1/')
printf '%-10s %10s %14s\n' target "median ms" "x spirv"
for t in "${TARGETS[@]}"; do
  awk -v t="$t" -v ms="${result[$t]}" -v base="${result[spirv]}" 'BEGIN { printf "%-10s %10d %14.2f\n", t, ms, ms / base }'
done
echo "($RUNS runs each, -j 1, warm cache; spirv = $checks checks)"
