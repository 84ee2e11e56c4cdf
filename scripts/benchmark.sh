#!/usr/bin/env bash
# The benchmark command: installs what is missing, builds, runs the default suite and writes the
# results to results/<date-time>/ (or the folder given as the first argument).
# At this stage the default suite is the reference solver on the published scenarios, every law.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
out=${1:-results/$(date +%Y%m%d-%H%M%S)}
status=0
build/harness/cli/impactbench suite scenarios/paper --engines reference --laws hertz,viscoelastic,newton --out "$out" || status=$?
echo "results: $out/runs.csv, $out/runs.jsonl and $out/runs/<scenario>/<engine>/<law>/"
exit $status
