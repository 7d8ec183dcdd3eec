#!/usr/bin/env bash
# Sets up a fresh Debian 12 machine (packages), builds the krug app optimised and runs the paper's
# case (a lead bullet through a 3 mm 6061-T6 plate, examples/paper/) or the scenario given as the
# first argument. Results go to out/<scenario name>/, pictures to out/<scenario name>/pictures/.
set -euo pipefail
cd "$(dirname "$0")/.."
scenario="${1:-examples/paper/monolithic_3mm_2.6g.json}"

./scripts/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)" --target krug_app

name=$(basename "$scenario" .json)
out="out/$name"
./build/apps/krug/krug run "$scenario" --out "$out"
mkdir -p "$out/pictures"
if /usr/bin/python3 -c "import matplotlib, meshio" 2>/dev/null; then
  if grep -q '"bullet"' "$scenario"; then
    /usr/bin/python3 scripts/paper_case.py figures "$out" "$out/pictures/meshes.png" --count 5 >/dev/null
    /usr/bin/python3 scripts/paper_case.py report "$out" --csv "$out/pictures/result.csv"
  fi
fi
echo "Results: $out/summary.json, $out/history.csv; ParaView: $out/run.pvd; pictures: $out/pictures/"
