#!/usr/bin/env bash
# Submits the default benchmark suite to Slurm as SHARDS array tasks (scripts/slurm/suite-array.sbatch)
# and its merge after them (scripts/slurm/merge.sbatch, --dependency=afterany): results in
# results/NAME/shard-K, joined in results/NAME/merged with its report.
#
#   scripts/slurm/submit.sh NAME SHARDS [--full | --study FILE] [--no-search] [-- SBATCH_OPTIONS...]
#
# Options after -- go to both sbatch calls (e.g. -- --partition=short --account=me). Run it from
# anywhere on a login node; impactbench must be built (scripts/build.sh) on a file system the nodes see.
set -euo pipefail
cd "$(dirname "$0")/../.."
name=${1:?usage: scripts/slurm/submit.sh NAME SHARDS [--full | --study FILE] [--no-search] [-- SBATCH_OPTIONS...]}
shards=${2:?usage: scripts/slurm/submit.sh NAME SHARDS [--full | --study FILE] [--no-search] [-- SBATCH_OPTIONS...]}
shift 2
suite_options=()
while [[ $# -gt 0 && $1 != -- ]]; do suite_options+=("$1"); shift; done
[[ ${1:-} == -- ]] && shift
[[ $shards =~ ^[1-9][0-9]*$ ]] || { echo "submit.sh: SHARDS $shards: allowed: a whole number >= 1" >&2; exit 2; }
[[ -x build/cli/impactbench ]] || { echo "submit.sh: build/cli/impactbench missing: run scripts/build.sh first" >&2; exit 2; }
array=$(sbatch --parsable "$@" --array="1-$shards" scripts/slurm/suite-array.sbatch "$name" "$shards" "${suite_options[@]}")
array=${array%%;*}  # --parsable prints "id" or "id;cluster"
merge=$(sbatch --parsable "$@" --dependency="afterany:$array" scripts/slurm/merge.sbatch "$name")
echo "array job $array: $shards shards into results/$name/shard-1 .. shard-$shards"
echo "merge job ${merge%%;*} after it: results/$name/merged (report: results/$name/merged/report/index.html)"
