#!/usr/bin/env bash
# Export throughput: `crtforge export` (all presets x the six SPIRV-Cross targets, which the
# alternative can also produce) against the obvious alternative a user would script, measured in
# the same run on the same machine:
#   per variant: glslangValidator -V, spirv-opt -O, spirv-val, then spirv-cross once per text target.
# Prints medians of N runs and the ratios (baseline time / crtforge time): against the loop run
# serially and 2-wide (crtforge uses 2 threads), cold cache, and warm into a fresh folder and into an
# up-to-date one.
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

# One preset through the tool chain, as a user's script would (the full-screen vertex shader is
# compiled once per loop, below).
one_preset() {  # one_preset <preset> <out dir>
  local p="$1" out="$2"
  glslangValidator -V -S frag "$work/src/$p.frag" -o "$out/$p.raw.spv" >/dev/null
  spirv-opt -O "$out/$p.raw.spv" -o "$out/$p.spv"
  spirv-val "$out/$p.spv"
  for s in vert "$p"; do
    spirv-cross "$out/$s.spv" --version 450 --no-es --output "$out/$s.$p.450.glsl"
    spirv-cross "$out/$s.spv" --version 330 --no-es --output "$out/$s.$p.330.glsl"
    spirv-cross "$out/$s.spv" --version 300 --es --output "$out/$s.$p.300es.glsl"
    spirv-cross "$out/$s.spv" --hlsl --shader-model 50 --output "$out/$s.$p.50.hlsl"
    spirv-cross "$out/$s.spv" --hlsl --shader-model 60 --output "$out/$s.$p.60.hlsl"
  done
}
export -f one_preset
export work

shell_loop() {  # shell_loop <parallel jobs>: the presets one after another, or N at a time
  local out="$work/loop"; rm -rf "$out"; mkdir -p "$out"
  glslangValidator -V -S vert "$work/src/fullscreen.vert" -o "$out/vert.spv" >/dev/null
  printf '%s\n' "${presets[@]}" | xargs -P "$1" -I{} bash -c 'one_preset "$1" "$2"' _ {} "$out"
}

time_ms() {  # time_ms <command...>: wall milliseconds of one run
  local t0 t1; t0=$(now_ns); "$@" >/dev/null; t1=$(now_ns)
  echo $(( (t1 - t0) / 1000000 ))
}

median() { sort -n | awk '{a[NR]=$1} END {print (NR%2) ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2}'; }

# crtforge export runs 2 worker threads: compare it with the loop run serially and 2-wide (like with
# like). Warm cache: into a fresh folder (everything written again) and into the folder of the run
# before (nothing needs writing) — both, since they differ by an order of magnitude.
loop_ms=(); loop2_ms=(); cold_ms=(); warm_fresh_ms=(); warm_same_ms=()
for ((i = 0; i < RUNS; i++)); do
  loop_ms+=("$(time_ms shell_loop 1)")
  loop2_ms+=("$(time_ms shell_loop 2)")
  rm -rf "$work/cache" "$work/export"
  cold_ms+=("$(time_ms $CRTFORGE --cache-dir "$work/cache" export -q --target "$TARGETS" --out "$work/export")")
  rm -rf "$work/export"
  warm_fresh_ms+=("$(time_ms $CRTFORGE --cache-dir "$work/cache" export -q --target "$TARGETS" --out "$work/export")")
  warm_same_ms+=("$(time_ms $CRTFORGE --cache-dir "$work/cache" export -q --target "$TARGETS" --out "$work/export")")
done
loop=$(printf '%s\n' "${loop_ms[@]}" | median)
loop2=$(printf '%s\n' "${loop2_ms[@]}" | median)
cold=$(printf '%s\n' "${cold_ms[@]}" | median)
warm_fresh=$(printf '%s\n' "${warm_fresh_ms[@]}" | median)
warm_same=$(printf '%s\n' "${warm_same_ms[@]}" | median)
n=${#presets[@]}
ratio() { awk -v a="$1" -v b="$2" 'BEGIN{printf "%.1f", a/(b>0?b:1)}'; }
echo "export throughput: ${n} presets x 6 targets, median of ${RUNS} runs, $(nproc) cores"
printf '  %-52s %8s ms\n' "baseline: shell loop, serial" "$loop"
printf '  %-52s %8s ms\n' "baseline: shell loop, 2 presets at a time (xargs -P 2)" "$loop2"
for row in "crtforge export, cold cache:$cold" "crtforge export, warm cache, fresh folder:$warm_fresh" \
           "crtforge export, warm cache, folder up to date:$warm_same"; do
  label=${row%%:*}; ms=${row##*:}
  printf '  %-52s %8s ms   %6sx vs serial   %6sx vs 2-wide\n' "$label" "$ms" "$(ratio "$loop" "$ms")" "$(ratio "$loop2" "$ms")"
done
