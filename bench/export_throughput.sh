#!/usr/bin/env bash
# Export throughput: `crtforge export` (all presets x the six SPIRV-Cross targets, which the
# alternative can also produce) against the obvious alternative a user would script, measured in
# the same run on the same machine:
#   per variant: glslangValidator -V, spirv-opt -O, spirv-val, then spirv-cross once per text target.
# Prints medians of N runs and the ratios (baseline time / crtforge time), cold and warm cache.
#
# usage: bench/export_throughput.sh [runs=5]      (after scripts/build.sh)
set -euo pipefail
cd "$(dirname "$0")/.."
RUNS="${1:-5}"
CRTFORGE=build/crtforge
for tool in glslangValidator spirv-opt spirv-val spirv-cross; do
  command -v "$tool" >/dev/null || { echo "bench: $tool missing (apt-get install glslang-tools spirv-tools spirv-cross)" >&2; exit 2; }
done
[[ -x $CRTFORGE ]] || { echo "bench: build crtforge first (scripts/build.sh)" >&2; exit 2; }

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mapfile -t presets < <($CRTFORGE list presets)
TARGETS=spirv,glsl450,glsl330,glsles300,hlsl50,hlsl60

# The shell loop gets the same GLSL 450 crtforge compiles (assembled outside the timed region).
mkdir -p "$work/src"
for p in "${presets[@]}"; do $CRTFORGE assemble --preset "$p" > "$work/src/$p.frag"; done
cp templates/fullscreen.vert "$work/src/fullscreen.vert"

now_ns() { date +%s%N; }

shell_loop() {
  local out="$work/loop"; rm -rf "$out"; mkdir -p "$out"
  glslangValidator -V -S vert "$work/src/fullscreen.vert" -o "$out/vert.spv" >/dev/null
  for p in "${presets[@]}"; do
    glslangValidator -V -S frag "$work/src/$p.frag" -o "$out/$p.raw.spv" >/dev/null
    spirv-opt -O "$out/$p.raw.spv" -o "$out/$p.spv"
    spirv-val "$out/$p.spv"
    for s in vert "$p"; do
      spirv-cross "$out/$s.spv" --version 450 --no-es --output "$out/$s.450.glsl"
      spirv-cross "$out/$s.spv" --version 330 --no-es --output "$out/$s.330.glsl"
      spirv-cross "$out/$s.spv" --version 300 --es --output "$out/$s.300es.glsl"
      spirv-cross "$out/$s.spv" --hlsl --shader-model 50 --output "$out/$s.50.hlsl"
      spirv-cross "$out/$s.spv" --hlsl --shader-model 60 --output "$out/$s.60.hlsl"
    done
  done
}

time_ms() {  # time_ms <command...>: wall milliseconds of one run
  local t0 t1; t0=$(now_ns); "$@" >/dev/null; t1=$(now_ns)
  echo $(( (t1 - t0) / 1000000 ))
}

median() { sort -n | awk '{a[NR]=$1} END {print (NR%2) ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2}'; }

loop_ms=(); cold_ms=(); warm_ms=()
for ((i = 0; i < RUNS; i++)); do
  loop_ms+=("$(time_ms shell_loop)")
  rm -rf "$work/cache" "$work/export"
  cold_ms+=("$(time_ms $CRTFORGE --cache-dir "$work/cache" export -q --target "$TARGETS" --out "$work/export")")
  warm_ms+=("$(time_ms $CRTFORGE --cache-dir "$work/cache" export -q --target "$TARGETS" --out "$work/export")")
done
loop=$(printf '%s\n' "${loop_ms[@]}" | median)
cold=$(printf '%s\n' "${cold_ms[@]}" | median)
warm=$(printf '%s\n' "${warm_ms[@]}" | median)
n=${#presets[@]}
echo "export throughput: ${n} presets x 6 targets, median of ${RUNS} runs"
printf '  %-44s %8s ms\n' "baseline: shell loop (glslang/spirv-opt/val/cross)" "$loop"
printf '  %-44s %8s ms   %6.1fx faster\n' "crtforge export, cold cache" "$cold" "$(awk -v a="$loop" -v b="$cold" 'BEGIN{print a/(b>0?b:1)}')"
printf '  %-44s %8s ms   %6.1fx faster\n' "crtforge export, warm cache" "$warm" "$(awk -v a="$loop" -v b="$warm" 'BEGIN{print a/(b>0?b:1)}')"
