#!/usr/bin/env bash
# Submits a frequency sweep to Slurm as SHARDS array tasks (scripts/slurm/sweep-array.sbatch) and its merge
# after them (scripts/slurm/merge.sbatch, --dependency=afterany): results in results/NAME/shard-K, joined in
# results/NAME/merged with its report.
#
#   scripts/slurm/submit-sweep.sh NAME SHARDS SCENARIO [SWEEP_OPTIONS...] [-- SBATCH_OPTIONS...]
#
# e.g. scripts/slurm/submit-sweep.sh fine 12 scenarios/paper/resonance.toml --ratios 0.85:1.20:0.005
#      --start both --engines "$(build/cli/impactbench engines --names)" --laws hertz,viscoelastic
# (every simulator of the build; with the reference and five engines: 2 starts x 6 x 2 laws = 24 chains
# over 12 tasks). Options after -- go to both sbatch calls.
set -euo pipefail
cd "$(dirname "$0")/../.."
usage="usage: scripts/slurm/submit-sweep.sh NAME SHARDS SCENARIO [SWEEP_OPTIONS...] [-- SBATCH_OPTIONS...]"
name=${1:?$usage}
shards=${2:?$usage}
scenario=${3:?$usage}
shift 3
sweep_options=()
while [[ $# -gt 0 && $1 != -- ]]; do sweep_options+=("$1"); shift; done
[[ ${1:-} == -- ]] && shift
[[ $shards =~ ^[1-9][0-9]*$ ]] || { echo "submit-sweep.sh: SHARDS $shards: allowed: a whole number >= 1" >&2; exit 2; }
[[ -f $scenario ]] || { echo "submit-sweep.sh: SCENARIO $scenario: no such file" >&2; exit 2; }
[[ -x build/cli/impactbench ]] || { echo "submit-sweep.sh: build/cli/impactbench missing: run scripts/build.sh first" >&2; exit 2; }
array=$(sbatch --parsable "$@" --array="1-$shards" scripts/slurm/sweep-array.sbatch "$name" "$shards" "$scenario" "${sweep_options[@]}")
array=${array%%;*}
merge=$(sbatch --parsable "$@" --dependency="afterany:$array" scripts/slurm/merge.sbatch "$name")
echo "array job $array: $shards shards into results/$name/shard-1 .. shard-$shards"
echo "merge job ${merge%%;*} after it: results/$name/merged (sweep.csv, poincare.csv; report: results/$name/merged/report/index.html)"
