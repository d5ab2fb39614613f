#!/usr/bin/env bash
# Installs the bench-only peer libraries (Debian 12 packages): SUNDIALS
# (CVODE, ARKODE, KLU linear solver), Boost (odeint), MuJoCo, Bullet, ODE,
# and gnuplot for PNG plots.  The main build and tests never need them.
# Idempotent: does nothing when every package is present.
#
# Usage: scripts/bench-setup.sh [--check]
set -euo pipefail

packages=(
  libsundials-dev libboost-dev libmujoco-dev libbullet-dev libode-dev gnuplot-nox
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed'; then
    missing+=("$p")
  fi
done

if [ "${1:-}" = "--check" ]; then
  if [ ${#missing[@]} -eq 0 ]; then echo "bench-setup: all peers present"; exit 0; fi
  echo "bench-setup: missing: ${missing[*]}"; exit 1
fi

if [ ${#missing[@]} -eq 0 ]; then
  echo "bench-setup: all ${#packages[@]} packages already installed"
  exit 0
fi

echo "bench-setup: installing ${missing[*]}"
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -q
"${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
