#!/usr/bin/env bash
# Installs what is missing, then configures and builds impactbench (Release, Ninja) in build/.
#
#   scripts/build.sh           the impactbench executable alone (what scripts/benchmark.sh runs)
#   scripts/build.sh --bench   and the bench/ timings (benchmark.sh --full)
#   scripts/build.sh --tests   everything: the tests and the bench/ timings too
#   scripts/build.sh --release-tests   as --tests without the tests of our own code, which scripts/test.sh
#                              builds and runs under the sanitizers instead (IMPACTBENCH_OWN_CODE_TESTS)
#
# Each adds to build/ what the one before built: the libraries are compiled once whichever comes first.
set -euo pipefail
cd "$(dirname "$0")/.."
what=${1:-}
own=ON deps=$what
case $what in
  "") tests=OFF bench=OFF targets=(--target impactbench) ;;
  --bench) tests=OFF bench=ON targets=() ;;
  --tests) tests=ON bench=ON targets=() ;;
  --release-tests) tests=ON bench=ON targets=() own=OFF deps=--tests ;;
  *) echo "build.sh: unknown option '$what'; allowed: none, --bench, --tests, --release-tests" >&2; exit 2 ;;
esac
scripts/install-deps.sh $deps
# A build/ made by another generator (older checkouts used Make) cannot be reconfigured for Ninja.
if [[ -f build/CMakeCache.txt ]] && ! grep -q '^CMAKE_GENERATOR:INTERNAL=Ninja$' build/CMakeCache.txt; then
  echo "build.sh: build/ was configured with another generator; configuring it anew with Ninja"
  rm -rf build/CMakeCache.txt build/CMakeFiles
fi
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DIMPACTBENCH_TESTS=$tests -DIMPACTBENCH_BENCH=$bench \
      -DIMPACTBENCH_OWN_CODE_TESTS=$own >/dev/null
cmake --build build -j "$(nproc)" "${targets[@]}"
