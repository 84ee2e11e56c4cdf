#!/usr/bin/env bash
# Runs the Google Benchmarks of bench/ (built by scripts/build.sh --bench) and writes each one's JSON into the
# folder given (default results/performance): reference_benchmark.json (the reference per case and law,
# simulated seconds per wall second), engine_step_benchmark.json (each engine's cost per step) and
# harness_overhead_benchmark.json (the harness against a bare loop of the same engine model), each with
# the machine and versions (bench/machine.sh) in its context, and reference_siconos/ (the reference's Newton
# impacts against Siconos's event-driven scheme, bench/reference_siconos.py, at the settings its test uses).
# About three minutes.
# The report (impactbench report) shows them when the folder is RESULTS/performance.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-results/performance}
mkdir -p "$out"
context=()
while IFS= read -r line; do context+=("--benchmark_context=$line"); done < <(bench/machine.sh)
run() {
  local name=$1; shift
  echo "bench: $name -> $out/$name.json"
  "build/bench/$name" --benchmark_out="$out/$name.json" --benchmark_out_format=json "${context[@]}" "$@" >/dev/null
}
run reference_benchmark
run engine_step_benchmark --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
# interleaved harness and bare runs; a longer minimum time evens out the machine's drift
run harness_overhead_benchmark --benchmark_min_time=3
echo "bench: reference_siconos -> $out/reference_siconos"
/usr/bin/python3 bench/reference_siconos.py --impactbench build/cli/impactbench --siconos build/bench/siconos_reference \
  --out "$out/reference_siconos" --cases free_vibration,resonance --duration 5 --max-impacts 20 --rtol 1e-10 \
  --atol 1e-13 >/dev/null
