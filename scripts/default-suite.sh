#!/usr/bin/env bash
# The default benchmark suite, run into one folder; scripts/benchmark.sh runs it on this machine and
# scripts/slurm/suite-array.sbatch one shard of it per Slurm array task.
#
#   scripts/default-suite.sh [--full] [--no-search] [--resume] [--shard K/N] [--jobs N] OUT
#
# Two parts, written to the same folder:
# 1. The published cases x three laws x every engine x its three contact paths x time steps 1e-4 and
#    5e-5 s, the reference on the beam and on each engine's chain. The forced cases run 50 s instead of
#    100 s (their transient is over within about 20 s and the scoring window stays the last 14 s);
#    --full runs them for their whole 100 s.
# 2. The stiff and extreme cases (scenarios/stiff, scenarios/extreme): for every engine's matched
#    contact path, the largest stable and accurate time steps, by bisection over 1e-5 to 1e-3 s
#    (--find-steps), each case cut to 5 s (the 1000 s energy-drift case too: its drift over 5 s).
#    --no-search skips this part.
# --resume continues a folder (part 2 always does: it adds to part 1's folder); --shard and --jobs are
# passed to both parts. The exit code is the suite's: 0, 1 some run unstable or failed (a finding), 2 bad
# input, 3 a write error, 130/143 interrupted (continue with the printed --resume command).
set -euo pipefail
cd "$(dirname "$0")/.."
impactbench=${IMPACTBENCH:-build/harness/cli/impactbench}
duration=(--duration 50)
search=1
resume=()
passed=()
while [[ ${1:-} == --* ]]; do
  case $1 in
    --full) duration=() ;;
    --no-search) search=0 ;;
    --resume) resume=(--resume) ;;
    --shard | --jobs)
      [[ $# -ge 2 ]] || { echo "default-suite.sh: $1 needs a value" >&2; exit 2; }
      passed+=("$1" "$2")
      shift
      ;;
    *) echo "default-suite.sh: unknown option $1; allowed: --full, --no-search, --resume, --shard K/N, --jobs N, then an output folder" >&2; exit 2 ;;
  esac
  shift
done
[[ $# -eq 1 ]] || { echo "default-suite.sh: expected one output folder after the options" >&2; exit 2; }
out=$1
status=0
"$impactbench" suite scenarios/paper --engines reference,mujoco,ode,bullet \
  --laws hertz,viscoelastic,newton --paths matched,injected,native --dt 1e-4,5e-5 "${duration[@]}" \
  "${passed[@]}" --out "$out" "${resume[@]}" || status=$?
if (( search )) && (( status != 2 && status < 3 )); then
  "$impactbench" suite scenarios/stiff scenarios/extreme --engines reference,mujoco,ode,bullet \
    --laws hertz,viscoelastic,newton --paths matched --find-steps --step-range 1e-5,1e-3 --duration 5 \
    "${passed[@]}" --out "$out" --resume || { search_status=$?; (( search_status > status )) && status=$search_status; }
fi
exit "$status"
