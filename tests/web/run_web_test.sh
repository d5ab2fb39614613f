#!/bin/sh
# ctest entry for the editor's tests.
# Usage: run_web_test.sh TEST ASGARD SOURCE_DIR WEB_ROOT OUT_DIR [SCENE]
# TEST is server, or a browser test (editor, handles, language, panel); SCENE
# (default samples/pendulum.al) is copied into OUT_DIR, which the test may save.
set -eu
WHICH=$1 ASGARD=$2 SOURCE=$3 WEB=$4 OUT=$5 SCENE=${6:-$3/samples/pendulum.al}
HERE=$(cd "$(dirname "$0")" && pwd)
if ! command -v node >/dev/null 2>&1; then
  echo "SKIP: node is not installed"; exit 77
fi
# server, docserve, restart and history need node alone (all but server its
# WebSocket: Node 20's --experimental-websocket).
FLAGS=
case $WHICH in docserve|restart|history) FLAGS=--experimental-websocket ;; esac
if [ "$WHICH" != server ] && [ -z "$FLAGS" ]; then
  if [ ! -x /usr/bin/chromium ]; then echo "SKIP: /usr/bin/chromium is not installed"; exit 77; fi
  if [ ! -f "$SOURCE/web/node_modules/playwright-core/package.json" ]; then
    echo "SKIP: playwright-core is not installed in web/node_modules (the build runs npm ci)"; exit 77
  fi
  if [ ! -f "$WEB/editor.js" ]; then echo "SKIP: the editor bundle was not built"; exit 77; fi
fi
rm -rf "$OUT"
mkdir -p "$OUT"
NAME=$(basename "$SCENE")
cp "$SCENE" "$OUT/$NAME"
export ASGARD_WEB_ROOT="$WEB"
export ASGARD_WEB_MODULES="$SOURCE/web/node_modules"
exec node $FLAGS "$HERE/${WHICH}_test.mjs" "$ASGARD" "$OUT/$NAME" "$OUT"
