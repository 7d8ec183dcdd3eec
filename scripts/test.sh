#!/usr/bin/env bash
# Sets up a fresh Debian 12 machine (packages), builds Krug optimised and passes the test suite:
# unit, verification, app and package tests; the convergence studies at reduced size
# (KRUG_CONVERGENCE_SCALE, default 0.5 here; 1 is the full study); then a build of the unit tests
# and the app with AddressSanitizer and UndefinedBehaviorSanitizer (built without MPI, so that a
# build without it is compiled and its refusal of mpirun tested); then a bounded run (60 s each,
# KRUG_FUZZ_SECONDS) of the libFuzzer targets of the scenario and checkpoint readers
# (scripts/fuzz.sh; longer: scripts/fuzz.sh 3600).
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc)

./scripts/install-deps.sh

cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$jobs"
KRUG_CONVERGENCE_SCALE="${KRUG_CONVERGENCE_SCALE:-0.5}" \
  ctest --test-dir build --output-on-failure -j"$jobs" --timeout 1200

cmake -S . -B build-sanitize -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DKRUG_SANITIZE=address,undefined -DKRUG_BUILD_BENCHMARKS=OFF -DKRUG_MPI=OFF
cmake --build build-sanitize -j"$jobs" --target krug_unit_tests krug_app
UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
  ctest --test-dir build-sanitize -L unit --output-on-failure -j"$jobs" --timeout 1200

./scripts/fuzz.sh "${KRUG_FUZZ_SECONDS:-60}"
