#!/usr/bin/env bash
# The main job: install dependencies, build, simulate the seed's two-part
# pendulum (samples/pendulum.al) and write its trajectories and a summary.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
mkdir -p out
build/core/app/asgard simulate samples/pendulum.al --out out/pendulum.csv --stats \
  | tee out/pendulum-summary.txt
build/core/app/asgard simulate samples/pendulum.al --out out/pendulum.json --quiet
mkdir -p out/documents
for d in memo two-animations; do
  build/host-shim/dochost convert samples/$d.ens -o out/documents/$d.html
  build/host-shim/dochost convert samples/$d.ens -o out/documents/$d.pdf
done
echo
echo "Trajectories: out/pendulum.csv and out/pendulum.json; summary: out/pendulum-summary.txt"
echo "Documents: out/documents/memo.{html,pdf} and out/documents/two-animations.{html,pdf}"
