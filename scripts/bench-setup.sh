#!/usr/bin/env bash
# Installs the bench-only peer libraries (Debian 12 packages): SUNDIALS
# (CVODE, ARKODE, KLU linear solver), Boost (odeint), MuJoCo, Bullet, ODE.
# The plots are SVG written by bench/report.py.  The main build and tests
# never need them.
# Idempotent: does nothing when every package is present.
#
# Usage: scripts/bench-setup.sh [--check]
set -euo pipefail

packages=(
  libsundials-dev libboost-dev libmujoco-dev libbullet-dev libode-dev
)

source "$(dirname "$0")/lib/apt-install.sh"
apt_install bench-setup "${1:-}" "${packages[@]}"
