#!/usr/bin/env bash
# Builds Asgard with AddressSanitizer + UndefinedBehaviorSanitizer
# (-DASGARD_SANITIZE=ON) into build-asan/ and runs the whole test suite
# there.  Any sanitizer report ends the process that made it, so the test
# that ran it fails.
#
# Usage: scripts/sanitize.sh [ctest arguments...]    e.g. -R Lang
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
