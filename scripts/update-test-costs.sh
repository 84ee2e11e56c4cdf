#!/usr/bin/env bash
# Keeps ctest's measured cost of every test (DIR/Testing/Temporary/CTestCostData.txt, written by each ctest
# run) as tests/ctest-cost-data.txt (build/) and tests/ctest-cost-data-sanitize.txt (build-sanitize/: under
# the sanitizers the tests' costs are in another order), from which scripts/test.sh seeds a fresh build
# folder, so that ctest starts the longest tests first also in a fresh clone (CI). Run it after a full
# scripts/test.sh when tests were added or their lengths changed; a test missing from the file only starts
# later, nothing fails.
set -euo pipefail
cd "$(dirname "$0")/.."
keep() {
  local costs=$1/Testing/Temporary/CTestCostData.txt kept=$2
  [[ -f $costs ]] || { echo "update-test-costs.sh: $costs missing: run scripts/test.sh first" >&2; exit 2; }
  # the measured costs, without the list of last failures that follows the '---' line
  sed '/^---$/,$d' "$costs" | sort > "$kept"
  echo "---" >> "$kept"
  echo "update-test-costs.sh: $(($(wc -l < "$kept") - 1)) tests' costs in $kept"
}
keep build tests/ctest-cost-data.txt
keep build-sanitize tests/ctest-cost-data-sanitize.txt
