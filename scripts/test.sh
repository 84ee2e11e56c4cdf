#!/usr/bin/env bash
# The test command (what CI's .ci/run calls): installs what is missing, builds impactbench in build/ and runs
# the tests that need the optimized build (the engines against the reference, the adapters, the report, the
# cluster, the timings; GoogleTest through ctest), then builds the code we own again with AddressSanitizer
# and UndefinedBehaviorSanitizer (build-sanitize/) and runs the tests of our own code there. Any sanitizer
# report fails its test (-fno-sanitize-recover; ASan aborts). Each phase's time and the ten slowest tests are
# printed, so that a regression shows in the log (docs/budgets.md: CI at most 30 minutes).
# IMPACTBENCH_SKIP_SANITIZE=1 skips the sanitizer phase and runs every test in build/ (for a quick local run;
# CI never sets it).
set -euo pipefail
cd "$(dirname "$0")/.."
started=$SECONDS
phase_started=$SECONDS
phases=()
end_phase() {
  local took=$((SECONDS - phase_started))
  phases+=("$(printf '%-42s %3d:%02d' "$1" $((took / 60)) $((took % 60)))")
  phase_started=$SECONDS
}
summary() {
  local status=$1 took=$((SECONDS - started))
  echo
  ((status == 0)) || echo "test: FAILED (exit code $status) in the phase after those listed below"
  echo "test: phases (load average $(cut -d' ' -f1-3 /proc/loadavg), $(nproc) cores)"
  printf '  %s\n' "${phases[@]}"
  printf '  %-42s %3d:%02d\n' "in all" $((took / 60)) $((took % 60))
}
trap 'summary $?' EXIT

# ctest starts the longest tests first when it knows their cost: a fresh build/ starts from the costs
# kept in tests/ctest-cost-data.txt, build-sanitize/ from tests/ctest-cost-data-sanitize.txt (the
# sanitizers slow some tests far more than others; refresh both with scripts/update-test-costs.sh), then
# from its own.
seed_costs() {
  local kept=tests/ctest-cost-data.txt
  [[ $1 == build-sanitize ]] && kept=tests/ctest-cost-data-sanitize.txt
  mkdir -p "$1/Testing/Temporary"
  [[ -f $1/Testing/Temporary/CTestCostData.txt ]] || cp "$kept" "$1/Testing/Temporary/CTestCostData.txt"
}
# ctest with its output kept in DIR/ctest.log, then the ten slowest tests of that run.
run_ctest() {
  local dir=$1; shift
  seed_costs "$dir"
  local status=0
  (cd "$dir" && ctest --output-on-failure -j "$(nproc)" "$@") 2>&1 | tee "$dir/ctest.log" || status=$?
  echo "test: the ten slowest tests in $dir:"
  # awk reads all of sort's output (head would close the pipe early: SIGPIPE, and pipefail would stop the script)
  sed -n 's/^ *[0-9]*\/[0-9]* Test *#[0-9]*: \([^ ]*\) \.*[^0-9]*\([0-9.]*\) sec$/\2 \1/p' "$dir/ctest.log" |
    sort -rn | awk 'NR <= 10 { printf "  %8.1f s  %s\n", $1, $2 }'
  return $status
}

# The tests of our own code run once, under the sanitizers (build-sanitize/, below); build/ builds and runs
# the tests that need the optimized build. Skipping the sanitizers runs them all here.
if [[ "${IMPACTBENCH_SKIP_SANITIZE:-0}" == 1 ]]; then
  scripts/build.sh --tests
else
  scripts/build.sh --release-tests
fi
end_phase "install, configure and build"
run_ctest build
end_phase "tests ($(grep -c ' Test *#' build/ctest.log) in build/)"

# The layers are checked in the tests above: scripts/check_layers.py (ctest "layering", every include), the
# harness's unit tests linking the model, the physics and the harness alone (tests/CMakeLists.txt,
# harness_unit_tests, in build-sanitize/ below), and a copy of the tree built with a toy engine as its only engine, no real engine's
# headers, paths or definitions anywhere (ctest new_engine_is_its_folder_and_one_line, tests/new_engine/).

if [[ "${IMPACTBENCH_SKIP_SANITIZE:-0}" == 1 ]]; then
  echo "test: sanitizer build skipped (IMPACTBENCH_SKIP_SANITIZE=1)"
  exit 0
fi
# -O1 keeps the instrumented physics fast enough for CI; -g1 (line tables) is all a sanitizer's report
# needs to name the file and line.
cmake -S . -B build-sanitize -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" \
      -DIMPACTBENCH_SANITIZE=ON -DIMPACTBENCH_BENCH=OFF -DIMPACTBENCH_TESTS=ON -DIMPACTBENCH_OWN_CODE_TESTS=ON >/dev/null
cmake --build build-sanitize -j "$(nproc)"
end_phase "sanitizer build"
# The engines' Debian libraries are not instrumented; ASan still checks every access our code makes, and
# the tests built here are those of our code (tests/CMakeLists.txt says which). Leak checking stays on.
# allocator_may_return_null=1: an allocation too large to satisfy returns null, as with libc, instead of
# aborting (MuJoCo's "could not allocate" error relies on it); it hides no memory error.
export ASAN_OPTIONS="abort_on_error=1:allocator_may_return_null=1${ASAN_OPTIONS:+:$ASAN_OPTIONS}"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}"
# leaks that are a library's own, each with why: scripts/lsan-suppressions.txt (Siconos's shared-pointer cycles)
export LSAN_OPTIONS="suppressions=$PWD/scripts/lsan-suppressions.txt${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
run_ctest build-sanitize
end_phase "sanitizer tests ($(grep -c ' Test *#' build-sanitize/ctest.log) in build-sanitize/)"
