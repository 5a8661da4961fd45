#!/usr/bin/env bash
# Fuzzes crtforge's input surfaces with libFuzzer (docs/fuzzing.md):
#   scripts/fuzz.sh [SECONDS_PER_TARGET] [TARGET...]
# Installs Debian's clang if missing, builds the fuzz targets into build-fuzz/ (clang, AddressSanitizer
# and UndefinedBehaviorSanitizer), replays every committed regression, then fuzzes each target for
# SECONDS_PER_TARGET (default 20) starting from a copy of its committed corpus. Exits non-zero on
# any crash, sanitizer report, leak, timeout or out-of-memory, naming the input that caused it.
# CRTFORGE_FUZZ_RUNS=N runs each target for N executions instead of a time.
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=${1:-20}
shift || true
all_targets=(stage_spec preset wgsl_emitter wgsl_valid image_reader)
targets=("$@")
((${#targets[@]})) || targets=("${all_targets[@]}")
if ! [[ $seconds =~ ^[1-9][0-9]*$ ]]; then
  echo "usage: scripts/fuzz.sh [SECONDS_PER_TARGET] [TARGET...]  (targets: ${all_targets[*]})" >&2
  exit 2
fi

# Longest input each target is given: a few times its largest seed.
declare -A max_len=([stage_spec]=4096 [preset]=4096 [wgsl_emitter]=8192 [wgsl_valid]=8192 [image_reader]=2048)
declare -A dict=([stage_spec]=fuzz/dict/toml.dict [preset]=fuzz/dict/toml.dict)
# Seconds one input may take. The image reader's is longer: under AddressSanitizer OpenImageIO's
# large scratch buffers cost up to a thousand times what they do in a plain build (10 s measured
# for an input a plain build reads in 9 ms).
declare -A timeout=([image_reader]=30)
for target in "${targets[@]}"; do
  if [[ -z ${max_len[$target]:-} ]]; then
    echo "crtforge fuzz: no target '$target' (targets: ${all_targets[*]})" >&2
    exit 2
  fi
done

# clang 16 rather than Debian 12's default 14: clang 14 lacks C++20's capture of structured bindings
# in lambdas, which crtforge's sources use.
CLANG_VERSION=16
source scripts/apt-packages.sh
mapfile -t missing < <(missing_apt_packages clang-$CLANG_VERSION libclang-rt-$CLANG_VERSION-dev)
install_apt_packages "crtforge fuzz" "${missing[@]}"

build=build-fuzz
jobs=$(nproc 2>/dev/null || echo 2)
# -O1 with line tables only, as libFuzzer's documentation suggests: quicker to build than -O2 -g, and
# assertions stay on.
cmake -S . -B "$build" -DCMAKE_CXX_COMPILER="$(command -v "clang++-$CLANG_VERSION")" -DCRTFORGE_FUZZ=ON \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only" \
  -DBUILD_TESTING=OFF >/dev/null
# Progress lines are noise in CI logs; warnings and errors still show.
cmake --build "$build" --target fuzz_all -j "$jobs" 2>&1 | { grep -vE '^\[ *[0-9]+%\]' || true; }

export LSAN_OPTIONS="suppressions=$PWD/fuzz/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1"
for symbolizer in "llvm-symbolizer-$CLANG_VERSION" llvm-symbolizer; do
  if command -v "$symbolizer" >/dev/null 2>&1; then
    export ASAN_SYMBOLIZER_PATH
    ASAN_SYMBOLIZER_PATH=$(command -v "$symbolizer")
    break
  fi
done

failed=()
summary=()
for target in "${targets[@]}"; do
  binary="$build/fuzz/fuzz_$target"
  run="$build/fuzz-run/$target"
  rm -rf "$run"
  mkdir -p "$run/corpus" "$run/artifacts"

  # Every input that ever crashed this target must stay fixed.
  mapfile -t regressions < <(find "fuzz/regressions/$target" -type f 2>/dev/null | sort)
  if ((${#regressions[@]})) && ! "$binary" "${regressions[@]}" >"$run/regressions.log" 2>&1; then
    echo "crtforge fuzz: $target: a committed regression fails again; log: $run/regressions.log" >&2
    grep -E "^Running: |ERROR|runtime error|SUMMARY" "$run/regressions.log" | tail -5 >&2 || true
    failed+=("$target")
    summary+=("$(printf '%-14s %12s %10s  %s' "$target" - - "regression fails")")
    continue
  fi

  # A copy of the committed corpus, so new inputs never land in fuzz/corpus.
  cp "fuzz/corpus/$target"/* "$run/corpus/"
  if [[ -n ${CRTFORGE_FUZZ_RUNS:-} ]]; then limit=(-runs="$CRTFORGE_FUZZ_RUNS"); else limit=(-max_total_time="$seconds"); fi
  options=("${limit[@]}" -max_len="${max_len[$target]}" -timeout="${timeout[$target]:-10}" -rss_limit_mb=2048
           -print_final_stats=1 -artifact_prefix="$run/artifacts/")
  if [[ -n ${dict[$target]:-} ]]; then options+=(-dict="${dict[$target]}"); fi
  status=0
  "$binary" "${options[@]}" "$run/corpus" >"$run/fuzz.log" 2>&1 || status=$?

  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$run/fuzz.log" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$run/fuzz.log" | tail -1)
  if ((status != 0)); then
    failed+=("$target")
    crash=$(sed -n 's/.*Test unit written to \(.*\)$/\1/p' "$run/fuzz.log" | tail -1)
    echo "crtforge fuzz: $target FAILED (exit $status): ${crash:-no input saved}; log: $run/fuzz.log" >&2
    grep -E "ERROR|runtime error|SUMMARY" "$run/fuzz.log" | head -5 >&2 || true
    summary+=("$(printf '%-14s %12s %10s  %s' "$target" "${execs:--}" "${rate:--}" "FAILED: ${crash:-see $run/fuzz.log}")")
  else
    summary+=("$(printf '%-14s %12s %10s  %s' "$target" "${execs:--}" "${rate:--}" ok)")
  fi
done

if [[ -n ${CRTFORGE_FUZZ_RUNS:-} ]]; then echo "crtforge fuzz: $CRTFORGE_FUZZ_RUNS runs per target"
else echo "crtforge fuzz: $seconds s per target"; fi
printf '%-14s %12s %10s  %s\n' target executions exec/s result
printf '%s\n' "${summary[@]}"
if ((${#failed[@]})); then
  echo "crtforge fuzz: failed: ${failed[*]} (keep each crashing input in fuzz/regressions/<target>/ once fixed)" >&2
  exit 1
fi
