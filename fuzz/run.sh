#!/usr/bin/env bash
# Builds the libFuzzer harnesses (clang, ASan + UBSan, in build-fuzzing/ unless BUILD_DIR is set) and runs
# each for SECONDS on its corpus (seeds from fuzz/make_corpus.sh), with libFuzzer's -timeout=10 (a hang)
# and leak detection. Findings go to BUILD_DIR/fuzz-artifacts/; the exit status is non-zero if any fuzzer
# found one. usage: fuzz/run.sh SECONDS [READER...]   (readers: yaml_model osim_model storage_file
# external_loads tool_setup mjcf_model bvh_file trc_file; default all)
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:?usage: fuzz/run.sh SECONDS [READER...]}
shift
readers=("$@")
((${#readers[@]})) || readers=(yaml_model osim_model storage_file external_loads tool_setup mjcf_model bvh_file trc_file)
build=${BUILD_DIR:-build-fuzzing}
cmake -S . -B "$build" -DCMAKE_CXX_COMPILER=clang++ -DSINEW_FUZZ=ON -DSINEW_BUILD_TESTS=OFF \
      -DSINEW_BUILD_BENCHMARKS=OFF -DSINEW_OPT_FLAGS=-O1 >/dev/null
cmake --build "$build" -j "$(nproc)" --target "${readers[@]/#/fuzz_}"
fuzz/make_corpus.sh "$build/fuzz-seeds" >/dev/null
mkdir -p "$build/fuzz-artifacts"
export ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
status=0
for reader in "${readers[@]}"; do
  mkdir -p "$build/fuzz-corpus/$reader"
  log="$build/fuzz-artifacts/$reader.log"
  if "$build/bin/fuzz_$reader" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=65536 \
       -print_final_stats=1 -artifact_prefix="$build/fuzz-artifacts/$reader-" \
       "$build/fuzz-corpus/$reader" "$build/fuzz-seeds/$reader" >"$log" 2>&1; then
    result=ok
  else
    result="FINDING (see $log)"
    status=1
  fi
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  echo "fuzz $reader: ${runs:-?} runs in ${seconds} s (${rate:-?} exec/s): $result"
done
exit $status
