#!/usr/bin/env bash
# The benchmark command: installs what is missing, builds, runs the default suite and writes the
# results under results/ (or the folder given as the first argument).
# At this stage the suite is the reference solver on the published scenarios, for each contact law.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
out=${1:-results}
mkdir -p "$out"
status=0
for scenario in scenarios/paper/*.toml; do
  name=$(basename "$scenario" .toml)
  for law in hertz viscoelastic newton; do
    build/harness/cli/impactbench run "$scenario" --engine reference --law "$law" --out "$out/$name/reference/$law" || status=1
  done
done
echo "results: $out/<scenario>/<engine>/<law>/{summary.json,series.csv,events.csv}"
exit $status
