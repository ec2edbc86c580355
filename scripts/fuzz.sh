#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/) with clang, ASan and UBSan in build-fuzz, then runs each one
# for SECONDS seconds over its seed corpus fuzz/corpus/<target>/ (new inputs go to
# build-fuzz/corpus/<target>/, the seeds in the repository stay as they are).
#
#   scripts/fuzz.sh [SECONDS] [TARGET...]      SECONDS defaults to $FUZZ_SECONDS, else 20
#
# Exits 1 when a target crashes, leaks, trips a sanitizer or hangs (the input is kept in
# build-fuzz/artifacts/), 77 when clang or libFuzzer is missing (ctest shows the test as skipped),
# 0 otherwise. A table of executions per target is printed at the end. docs/testing.md, "Fuzzing".
set -uo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
seconds=${1:-${FUZZ_SECONDS:-20}}
shift $(($# > 0 ? 1 : 0))
build=${FUZZ_BUILD:-$root/build-fuzz}
jobs=${JOBS:-$(nproc)}

cxx=$(command -v clang++-14 || command -v clang++ || true)
cc=$(command -v clang-14 || command -v clang || true)
if [[ -z $cxx || -z $cc ]]; then
  echo "fuzz: skipped: clang is not installed (scripts/setup.sh installs clang and libclang-rt-14-dev)"
  exit 77
fi
if ! echo 'extern "C" int LLVMFuzzerTestOneInput(const char*, unsigned long) { return 0; }' |
  "$cxx" -x c++ -fsanitize=fuzzer - -o /dev/null 2>/dev/null; then
  echo "fuzz: skipped: $cxx cannot link libFuzzer (install libclang-rt-14-dev)"
  exit 77
fi

if [[ ! -f $build/CMakeCache.txt ]]; then
  cmake -S "$root" -B "$build" -DSMQL_FUZZ=ON -DSMQL_BUILD_BENCH=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_C_COMPILER="$cc" -DCMAKE_CXX_COMPILER="$cxx" >/dev/null || exit 1
fi
cmake --build "$build" -j "$jobs" --target smql_fuzz >"$build/fuzz-build.log" 2>&1 || {
  tail -40 "$build/fuzz-build.log"
  echo "fuzz: the build failed ($build/fuzz-build.log)"
  exit 1
}

if (($# > 0)); then
  targets=("$@")
else
  targets=()
  for dir in "$root"/fuzz/corpus/*/; do targets+=("$(basename "$dir")"); done
fi

mkdir -p "$build/artifacts" "$build/logs"
failed=0
printf '%-28s %12s %10s %8s  %s\n' target execs "exec/s" corpus result
for target in "${targets[@]}"; do
  corpus=$build/corpus/$target
  mkdir -p "$corpus"
  log=$build/logs/$target.log
  # -timeout: one input taking 10 s is a hang; -rss_limit_mb: a runaway allocation is a finding too.
  nice "$build/fuzz/$target" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$build/artifacts/$target-" "$corpus" "$root/fuzz/corpus/$target" >"$log" 2>&1
  status=$?
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  size=$(find "$corpus" -type f | wc -l)
  if ((status == 0)); then
    result=ok
  else
    result="FAILED (exit $status): $(grep -m1 -E 'ERROR: |runtime error|Test unit written' "$log" || tail -1 "$log")"
    failed=1
  fi
  printf '%-28s %12s %10s %8s  %s\n' "$target" "${execs:-?}" "${rate:-?}" "$size" "$result"
  if ((status != 0)); then
    grep -E '^(==[0-9]+==ERROR|SUMMARY|.*runtime error|    #[0-9] )' "$log" | head -14 | cut -c1-220 | sed 's/^/    /'
    echo "    log: $log; reproduce with $build/fuzz/$target $(grep -o "$build/artifacts/[^ ]*" "$log" | tail -1)"
  fi
done
exit $failed
