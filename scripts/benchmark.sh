#!/usr/bin/env bash
# The benchmark command: installs what is missing, builds, runs a study and writes its report into
# results/<date-time>/ (or the folder given as the last argument): report/index.html there.
#
#   scripts/benchmark.sh [--full] [--no-search] [OUT]
#
# Default: studies/default.toml (its budget and last measured time: docs/budgets.md), with the impactbench
# executable alone built. --full: studies/full.toml (every published case, all three contact paths, the
# full step search), then the bench/ timings for the report's performance section. --no-search skips the
# step search. Every run's cost is its logged run's CPU and wall time (no timed repeats:
# bench/timing_check.sh shows the two agree). A study of your own: build/cli/impactbench study FILE --out DIR.
set -euo pipefail
cd "$(dirname "$0")/.."
study=default
skip=()
while [[ ${1:-} == --* ]]; do
  case $1 in
    --full) study=full ;;
    --no-search) skip=(--skip search) ;;
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
echo "benchmark: studies/$study.toml into $out"
status=0
# the report after the bench/ timings (--full), which it shows
"$impactbench" study "studies/$study.toml" --out "$out" --no-report "${skip[@]}" || status=$?
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
