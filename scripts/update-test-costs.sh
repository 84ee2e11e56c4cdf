#!/usr/bin/env bash
# Keeps ctest's measured cost of every test (build/Testing/Temporary/CTestCostData.txt, written by each ctest
# run) as tests/ctest-cost-data.txt, from which scripts/test.sh seeds a fresh build folder, so that ctest
# starts the longest tests first also in a fresh clone (CI). Run it after a full scripts/test.sh when tests
# were added or their lengths changed; a test missing from the file only starts later, nothing fails.
set -euo pipefail
cd "$(dirname "$0")/.."
costs=build/Testing/Temporary/CTestCostData.txt
[[ -f $costs ]] || { echo "update-test-costs.sh: $costs missing: run scripts/test.sh first" >&2; exit 2; }
# the measured costs, without the list of last failures that follows the '---' line
sed '/^---$/,$d' "$costs" | sort > tests/ctest-cost-data.txt
echo "---" >> tests/ctest-cost-data.txt
echo "update-test-costs.sh: $(($(wc -l < tests/ctest-cost-data.txt) - 1)) tests' costs in tests/ctest-cost-data.txt"
