#!/usr/bin/env bash
# The benchmark command: installs what is missing, builds, runs a study and writes its report into
# results/<date-time>/ (or the folder given as the last argument): report/index.html there.
#
#   scripts/benchmark.sh [--full] [--no-search] [OUT]
#
# Default: the quick study of scripts/default-suite.sh (its budget and last measured time: docs/budgets.md),
# with the impactbench executable alone built. --full: the whole study (every published case, all three
# contact paths, the full step search), then the bench/ timings for the report's performance section.
# --no-search skips the step search. Every run's cost is its logged run's CPU and wall time (no timed
# repeats: bench/timing_check.sh shows the two agree).
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/default-suite.sh
study=default
search=1
while [[ ${1:-} == --* ]]; do
  case $1 in
    --full) study=full ;;
    --no-search) search=0 ;;
    *) echo "benchmark.sh: unknown option $1; allowed: --full, --no-search, then an output folder" >&2; exit 2 ;;
  esac
  shift
done
# the impactbench executable alone; --full also runs the bench/ timings, built with Google Benchmark
build_started=$(date +%s)
if [[ $study == full ]]; then scripts/build.sh --bench; else scripts/build.sh; fi
build_took=$(( $(date +%s) - build_started ))
printf 'benchmark: installed and built in %d:%02d (docs/budgets.md: the build within 3 minutes)\n' \
  $((build_took / 60)) $((build_took % 60))
out=${1:-results/$(date +%Y%m%d-%H%M%S)}
impactbench=build/cli/impactbench
started=$(date +%s)
echo "benchmark: the $study study into $out (scripts/default-suite.sh says what it runs)"
status=0
run_study "$out" || status=$?
if [[ $study == full ]] && (( status != 2 && status < 3 )) && ! bench/run-benchmarks.sh "$out/performance"; then
  echo "benchmark: the bench/ timings failed (above); the report is made without them" >&2
fi
(( status == 2 || status >= 3 )) || $impactbench report "$out"
elapsed=$(( $(date +%s) - started ))
printf 'benchmark: %s study done in %d:%02d (build excluded), %s of results, load average %s\n' "$study" \
  $((elapsed / 60)) $((elapsed % 60)) "$(du -sh "$out" | cut -f1)" "$(cut -d' ' -f1-3 /proc/loadavg)"
echo "results: $out/runs.csv, runs.jsonl and steps.csv; report: $out/report/index.html"
# 1: some runs were unstable or failed, a finding recorded in the report; 2 bad input, 3 a write error,
# 130/143 interrupted (continue with the printed --resume command)
exit $(( status == 1 ? 0 : status ))
