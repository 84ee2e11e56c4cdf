#!/usr/bin/env bash
# The benchmark command: installs what is missing, builds, runs the default suite (scripts/default-suite.sh:
# the published cases at two time steps, then the stiff and extreme cases' step search) and writes its
# report: results/<date-time>/ (or the folder given as the last argument), report/index.html there.
#   scripts/benchmark.sh [--full] [--no-search] [OUT]
# --full: the forced published cases for their whole 100 s (default 50 s); --no-search: part 1 alone.
# On 2 cores: about 15 minutes for part 1, 15 for part 2, 3 for the report.
set -euo pipefail
cd "$(dirname "$0")/.."
options=()
while [[ ${1:-} == --* ]]; do
  case $1 in
    --full | --no-search) options+=("$1") ;;
    *) echo "benchmark.sh: unknown option $1; allowed: --full, --no-search, then an output folder" >&2; exit 2 ;;
  esac
  shift
done
scripts/build.sh
out=${1:-results/$(date +%Y%m%d-%H%M%S)}
status=0
scripts/default-suite.sh "${options[@]}" "$out" || status=$?
(( status == 2 || status >= 3 )) || build/harness/cli/impactbench report "$out"
echo "results: $out/runs.csv, runs.jsonl and steps.csv; report: $out/report/index.html"
# 1: some runs were unstable or failed, a finding recorded in the report; 2 bad input, 3 a write error,
# 130/143 interrupted (continue with the printed --resume command)
exit $(( status == 1 ? 0 : status ))
