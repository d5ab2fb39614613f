#!/usr/bin/env bash
# Installs every system package Asgard needs to build and test, from Debian's
# repositories. Idempotent: packages already present are left alone, and the
# package index is refreshed only when something is missing.
#
# Usage: scripts/install-deps.sh [--check]
#   --check   only report missing packages (exit 1 if any), install nothing
set -euo pipefail

packages=(
  # toolchain
  g++ cmake ninja-build pkg-config clang-format
  # libFuzzer and the sanitizers (scripts/fuzz.sh, scripts/sanitize.sh)
  clang-14 libclang-rt-14-dev
  # core
  tcl8.6-dev libeigen3-dev libsuitesparse-dev libqhull-dev libccd-dev
  nlohmann-json3-dev
  # the editor server (web/server/): Boost.Beast and Asio, header-only; see docs/editor-server.md
  libboost-dev
  # rendering and exports
  libcairo2-dev libpango1.0-dev libosmesa6-dev libpng-dev libxml2-dev ffmpeg
  # tests and benchmarks
  libgtest-dev libgmock-dev libbenchmark-dev
  ghostscript poppler-utils povray chromium nodejs
)

source "$(dirname "$0")/lib/apt-install.sh"
apt_install install-deps "${1:-}" "${packages[@]}"
# npm ships inside some nodejs packages; install Debian's only when absent.
if [ "${1:-}" != "--check" ] && ! command -v npm >/dev/null 2>&1; then
  sudo_cmd=()
  if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
  "${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends npm
fi
