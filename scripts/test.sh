#!/usr/bin/env bash
# The test command: installs what is missing, builds, runs every test (GoogleTest through ctest).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
cd build
ctest --output-on-failure -j "$(nproc)"
