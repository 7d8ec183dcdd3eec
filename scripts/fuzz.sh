#!/usr/bin/env bash
# Coverage-guided fuzzing of the scenario and checkpoint readers (libFuzzer, with AddressSanitizer and
# UndefinedBehaviorSanitizer), from a seed corpus: every example and test scenario, and a checkpoint
# of a small fracturing run.
#
#   scripts/fuzz.sh [SECONDS]     each target for SECONDS (default 60; scripts/test.sh runs 60)
#   scripts/fuzz.sh 3600          the longer run
#
# Needs clang and libFuzzer (Debian: clang, libclang-rt-14-dev; scripts/install-deps.sh installs them).
# Builds into build-fuzz/. The corpora grow in build-fuzz/corpus/<target>/ and are kept between runs;
# a finding (crash, sanitizer report, timeout of 10 s, more than 2 GB) stops the target, is saved as
# build-fuzz/findings/<target>/crash-*, timeout-* or oom-*, and makes this script exit non-zero.
# Reproduce one with: build-fuzz/tests/fuzz/<target> build-fuzz/findings/<target>/<file>
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
jobs=$(nproc)

mkdir -p build-fuzz
cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
  -DKRUG_FUZZ=ON -DKRUG_SANITIZE=address,undefined -DKRUG_WERROR=OFF \
  -DKRUG_BUILD_TESTS=OFF -DKRUG_BUILD_BENCHMARKS=OFF -DKRUG_BUILD_APP=OFF > build-fuzz/configure.log ||
  { tail -30 build-fuzz/configure.log; exit 1; }
cmake --build build-fuzz -j"$jobs" --target fuzz_scenario fuzz_checkpoint make_checkpoint_seed > build-fuzz/build.log ||
  { tail -30 build-fuzz/build.log; exit 1; }

mkdir -p build-fuzz/corpus/fuzz_scenario build-fuzz/corpus/fuzz_checkpoint
seeds=build-fuzz/seeds
rm -rf "$seeds"
mkdir -p "$seeds/fuzz_scenario" "$seeds/fuzz_checkpoint"
for file in examples/*/*.json examples/paper/coarse/*.json tests/app/data/*.json; do
  cp "$file" "$seeds/fuzz_scenario/$(echo "$file" | tr '/' '_')"
done
build-fuzz/tests/fuzz/make_checkpoint_seed "$seeds/fuzz_checkpoint/seed.bin"

export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
status=0
for target in fuzz_scenario fuzz_checkpoint; do
  findings=build-fuzz/findings/$target
  mkdir -p "$findings"
  echo "fuzz: $target for $seconds s"
  if ! build-fuzz/tests/fuzz/$target build-fuzz/corpus/$target "$seeds/$target" \
      -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=65536 \
      -artifact_prefix="$findings/" -print_final_stats=1 > "build-fuzz/$target.log" 2>&1; then
    echo "fuzz: $target FOUND A PROBLEM; see build-fuzz/$target.log and $findings/"
    tail -40 "build-fuzz/$target.log"
    status=1
  fi
  grep -E "stat::number_of_executed_units|stat::peak_rss_mb" "build-fuzz/$target.log" | sed "s/^/fuzz: $target /"
done
exit $status
