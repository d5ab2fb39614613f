#!/usr/bin/env bash
# Builds the libFuzzer targets (clang-14, ASan + UBSan, -DASGARD_FUZZ=ON)
# into build-fuzz/ (or the build tree named by ASGARD_FUZZ_BUILD, which
# scripts/sanitize.sh sets to its own) and runs each for the given time on
# its seed corpus (tests/fuzz/corpus/<target>/; new inputs go to
# <build>/corpus/).  Prints executions per target; a crash leaves its input
# in the build tree and makes the script exit 1.
#
# Usage: scripts/fuzz.sh [SECONDS per target, default 10] [target...]
#   targets: sgml xml scene expr protocol (default: all)
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-10}
shift || true
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then targets=(sgml xml scene expr protocol); fi
build=${ASGARD_FUZZ_BUILD:-build-fuzz}
if [ ! -f "$build/build.ninja" ]; then
  cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 -DASGARD_FUZZ=ON \
    -DASGARD_BUILD_TESTS=OFF -DASGARD_BUILD_BENCH=OFF \
    ${CMAKE_CXX_COMPILER_LAUNCHER:+-DCMAKE_CXX_COMPILER_LAUNCHER=$CMAKE_CXX_COMPILER_LAUNCHER} \
    ${CMAKE_C_COMPILER_LAUNCHER:+-DCMAKE_C_COMPILER_LAUNCHER=$CMAKE_C_COMPILER_LAUNCHER} >/dev/null
fi
cmake --build "$build" -j "$(nproc 2>/dev/null || echo 2)" \
  --target "${targets[@]/#/fuzz_}"
status=0
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=0}
for t in "${targets[@]}"; do
  mkdir -p "$build/corpus/$t"
  log=$build/fuzz_$t.log
  if ! (cd "$build" && "tests/fuzz/fuzz_$t" -max_total_time="$seconds" -timeout=10 \
        -rss_limit_mb=2048 -max_len=65536 -print_final_stats=1 \
        "corpus/$t" "$OLDPWD/tests/fuzz/corpus/$t") >"$log" 2>&1; then
    echo "fuzz_$t: FAILED (see $log)"
    grep -E "ERROR|SUMMARY|Test unit written" "$log" | head -5 || true
    status=1
  fi
  runs=$(grep -oE "stat::number_of_executed_units: *[0-9]+" "$log" | grep -oE "[0-9]+$" || echo 0)
  echo "fuzz_$t: $runs executions in ${seconds} s"
done
exit $status
