#!/usr/bin/env bash
# The test command: installs what is missing, builds, runs every test (GoogleTest through ctest), then
# builds the tests again with AddressSanitizer and UndefinedBehaviorSanitizer in build-sanitize/ and
# runs them there. Any sanitizer report fails its test (-fno-sanitize-recover; ASan aborts).
# IMPACTBENCH_SKIP_SANITIZE=1 skips the second build (for a quick local run; CI never sets it).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
# The report's page is tested as a reader sees it, in headless Chromium (reports/tests/test_page_in_chromium.py):
# Debian's chromium, installed when missing (as root or with sudo, as the other packages).
command -v chromium >/dev/null || IMPACTBENCH_EXTRA_PACKAGES=chromium scripts/install-deps.sh --only-extra
(cd build && ctest --output-on-failure -j "$(nproc)")
# The layers (scripts/check_layers.py, ctest "layering" above): the model, the physics and the harness with
# their unit tests build and pass with no simulator at all, in build-harness-only/.
cmake -S . -B build-harness-only -DIMPACTBENCH_HARNESS_ONLY=ON >/dev/null
cmake --build build-harness-only -j "$(nproc)"
(cd build-harness-only && ctest --output-on-failure -j "$(nproc)")

if [[ "${IMPACTBENCH_SKIP_SANITIZE:-0}" == 1 ]]; then
  echo "test: sanitizer build skipped (IMPACTBENCH_SKIP_SANITIZE=1)"
  exit 0
fi
# -O1 keeps the instrumented physics fast enough for CI.
cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" \
      -DIMPACTBENCH_SANITIZE=ON >/dev/null
cmake --build build-sanitize -j "$(nproc)"
# The engines' Debian libraries are not instrumented; ASan still checks every access our code makes.
# Leak checking stays on. allocator_may_return_null=1: an allocation too large to satisfy returns null,
# as with libc, instead of aborting; tests/mujoco_error_handling_test.cpp asks MuJoCo for 2^62 bytes to
# check that MuJoCo's "could not allocate" error becomes an exception. It hides no memory error.
export ASAN_OPTIONS="abort_on_error=1:allocator_may_return_null=1${ASAN_OPTIONS:+:$ASAN_OPTIONS}"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}"
(cd build-sanitize && ctest --output-on-failure -j "$(nproc)" -LE "${IMPACTBENCH_SANITIZE_EXCLUDE:-agreement}")
