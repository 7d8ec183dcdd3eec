#!/usr/bin/env bash
# Sets up a fresh Debian 12 machine (packages), builds the krug app optimised and runs the default
# scenario (or the one given as the first argument). Results go to out/<scenario name>/.
set -euo pipefail
cd "$(dirname "$0")/.."
scenario="${1:-examples/verification/sedov_spherical.json}"

./scripts/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)" --target krug_app

name=$(basename "$scenario" .json)
./build/apps/krug/krug run "$scenario" --out "out/$name"
echo "Open out/$name/run.pvd in ParaView; figures and ledgers: out/$name/summary.json, out/$name/history.csv"
