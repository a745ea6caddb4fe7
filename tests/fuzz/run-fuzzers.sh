#!/usr/bin/env bash
# Builds the libFuzzer harnesses of the readers in build-fuzz (clang, ASan + UBSan, assertions on) and
# runs each for a bounded number of seconds from its checked-in seed corpus, with its dictionary, JOBS
# at a time (the CI's 2 cores: about 6 minutes to build from nothing, 2 minutes to run).
# A crash, a sanitizer finding, a leak, a timeout or an input past the memory limit fails the script;
# libFuzzer leaves the input as build-fuzz/findings/<harness>/crash-… (reproduce: run the harness on it).
#
#   FUZZ_SECONDS   seconds per harness (default 60)
#   FUZZ_MAX_LEN   longest input in bytes (default 4096)
#   JOBS           parallel build jobs and harnesses run at once (default 2)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build="$root/build-fuzz"
seconds=${FUZZ_SECONDS:-60}
max_len=${FUZZ_MAX_LEN:-4096}
harnesses=(cycle_spec gcode_program force_log plan_report)

launcher=()
if command -v ccache > /dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
mkdir -p "$build"
cmake -S "$root" -B "$build" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g" \
  -DFEEDPLAN_BUILD_FUZZERS=ON -DFEEDPLAN_BUILD_TESTS=OFF -DFEEDPLAN_BUILD_BENCH=OFF "${launcher[@]}" > "$build/configure.log" 2>&1 \
  || { cat "$build/configure.log"; exit 1; }
cmake --build "$build" -j "${JOBS:-2}" --target "${harnesses[@]/#/fuzz_}"

export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:allocator_may_return_null=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}

# Runs one harness; its verdict goes to <work>/verdict, its output to <work>/log.txt.
run_one() {
  local name=$1 dir="$root/tests/fuzz/$1" work="$build/findings/$1"
  rm -rf "$work" && mkdir -p "$work/corpus"
  local dictionary=()
  if [[ -f "$dir/$name.dict" ]]; then dictionary=(-dict="$dir/$name.dict"); fi
  # New inputs go to a scratch corpus: the checked-in seeds stay as they are.
  if "$build/tests/fuzz/fuzz_$name" "$work/corpus" "$dir/corpus" "${dictionary[@]}" -max_total_time="$seconds" \
       -max_len="$max_len" -rss_limit_mb=2048 -malloc_limit_mb=1024 -timeout=10 -print_final_stats=1 \
       -artifact_prefix="$work/" > "$work/log.txt" 2>&1; then
    local runs
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$work/log.txt")
    echo "fuzz $name: ${runs:-?} executions in $seconds s, no crash" > "$work/verdict"
  else
    echo "fuzz $name: FAILED; input and log in $work" > "$work/verdict"
  fi
}

# JOBS harnesses at a time (each is one process).
running=0
for name in "${harnesses[@]}"; do
  run_one "$name" &
  running=$((running + 1))
  if ((running >= ${JOBS:-2})); then wait -n; running=$((running - 1)); fi
done
wait

failed=()
for name in "${harnesses[@]}"; do
  cat "$build/findings/$name/verdict"
  if grep -q FAILED "$build/findings/$name/verdict"; then
    tail -n 60 "$build/findings/$name/log.txt"
    failed+=("$name")
  fi
done
if ((${#failed[@]} > 0)); then
  echo "fuzzers that found a problem: ${failed[*]}"
  exit 1
fi
