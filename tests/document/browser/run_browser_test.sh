#!/bin/sh
# ctest entry for the browser test: installs playwright-core (npm ci, from the
# committed package-lock.json) when it is missing, converts the memo to HTML
# with dochost, and runs memo_test.mjs in headless Chromium.
# Usage: run_browser_test.sh DOCHOST SOURCE_DIR OUT_DIR
set -eu
DOCHOST=$1 SOURCE=$2 OUT=$3
HERE=$(cd "$(dirname "$0")" && pwd)
if [ ! -f "$HERE/node_modules/playwright-core/package.json" ]; then
  if ! (cd "$HERE" && npm ci --no-audit --no-fund --loglevel=error); then
    echo "FAIL: npm could not install playwright-core into $HERE/node_modules"
    echo "      (no network?  run 'npm ci' in tests/document/browser once online)"
    exit 1
  fi
fi
if [ ! -x /usr/bin/chromium ]; then
  echo "FAIL: /usr/bin/chromium is not installed (scripts/install-deps.sh installs it)"
  exit 1
fi
rm -rf "$OUT"
mkdir -p "$OUT"
"$DOCHOST" convert "$SOURCE/samples/memo.ens" -o "$OUT/memo.html" --quiet
exec node "$HERE/memo_test.mjs" "$OUT/memo.html" "$OUT"
