#!/usr/bin/env bash
# Installs dependencies, builds everything and runs every test; then, as a
# second step, builds the whole tree again with AddressSanitizer +
# UndefinedBehaviorSanitizer (build-asan/) and runs every test there
# (scripts/sanitize.sh; on 2 cores it adds about 20 minutes, see
# docs/fuzzing.md).  ASGARD_SKIP_SANITIZE=1 leaves the second step out.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
jobs=$(nproc 2>/dev/null || echo 2)
ctest --test-dir build --output-on-failure -j "$jobs" --timeout 600
if [[ "${ASGARD_SKIP_SANITIZE:-}" != 1 ]]; then
  scripts/sanitize.sh
fi
