#!/usr/bin/env bash
# Builds Asgard with AddressSanitizer + UndefinedBehaviorSanitizer
# (-DASGARD_SANITIZE=ON) into build-asan/ and runs the whole test suite
# there.  Any sanitizer report ends the process that made it, so the test
# that ran it fails.  Then, where clang-14 is installed (scripts/install-
# deps.sh installs it), each libFuzzer target of tests/fuzz runs for a short
# time on its seed corpus (scripts/fuzz.sh, build-fuzz/).
#
# Usage: scripts/sanitize.sh [ctest arguments...]    e.g. -R Lang
#   ASGARD_FUZZ_SECONDS: seconds per fuzz target (default 15; 0 leaves the
#   fuzz runs out, as do ctest arguments).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DASGARD_SANITIZE=ON \
  -DASGARD_BUILD_BENCH=OFF ${CMAKE_CXX_COMPILER_LAUNCHER:+-DCMAKE_CXX_COMPILER_LAUNCHER=$CMAKE_CXX_COMPILER_LAUNCHER} \
  ${CMAKE_C_COMPILER_LAUNCHER:+-DCMAKE_C_COMPILER_LAUNCHER=$CMAKE_C_COMPILER_LAUNCHER} >/dev/null
cmake --build build-asan -j "$(nproc 2>/dev/null || echo 2)"
# Leaks are reported too; Tcl's and fontconfig's process-lifetime caches are
# suppressed (scripts/lsan.supp).
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=0:detect_stack_use_after_return=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$PWD/scripts/lsan.supp}
ctest --test-dir build-asan --output-on-failure -j "$(nproc 2>/dev/null || echo 2)" --timeout 900 "$@"
seconds=${ASGARD_FUZZ_SECONDS:-15}
if [ "$seconds" != 0 ] && [ $# -eq 0 ] && command -v clang++-14 >/dev/null; then
  # Leak checks stay off here: a fuzz target keeps Tcl's and libxml2's
  # caches across inputs, which LeakSanitizer would report at exit.
  ASAN_OPTIONS=detect_leaks=0 scripts/fuzz.sh "$seconds"
fi
