#!/usr/bin/env bash
# The project's Slurm scripts run for real on a private one-node cluster (scripts/slurm/cluster.sh): a small
# suite and a small sweep, each submitted as a two-task job array with the merge job after it
# (--dependency=afterany), and the merged results compared with a local run of the same jobs
# (bench/compare_runs.py: every value but the machine's measurements the same). Then a sweep task is
# cancelled while it runs (scancel: SIGTERM to every process of the task, in no order) and submitted
# again: its resumed results equal the uninterrupted ones; and a suite task the same way (no worker stopped by
# the signal recorded as failed). The cluster is stopped on every exit.
#
#   tests/slurm/test_slurm_cluster.sh BUILD_DIR      (as root: ctest slurm_cluster runs it)
set -euo pipefail
project=$(cd "$(dirname "$0")/../.." && pwd)
build=$(cd "${1:?usage: tests/slurm/test_slurm_cluster.sh BUILD_DIR}" && pwd)
export IMPACTBENCH=$build/cli/impactbench
[[ -x $IMPACTBENCH ]] || { echo "test_slurm_cluster: $IMPACTBENCH missing: build first" >&2; exit 2; }
# The build's first two engines (engines --names, the reference first; the second when the build has one): the
# scripts are tested, not an engine.
IFS=, read -r -a simulators <<<"$("$IMPACTBENCH" engines --names)"
((${#simulators[@]} >= 2)) || { echo "test_slurm_cluster: needs a build with an engine: ${simulators[*]}" >&2; exit 2; }
engine_1=${simulators[1]} engine_2=${simulators[2]:-}
work=$(mktemp -d /tmp/impactbench-slurm.XXXXXX)
cleanup() {
  local status=$?
  "$project/scripts/slurm/cluster.sh" stop "$work/cluster" || true
  if ((status == 0)); then rm -rf "$work"; else echo "test_slurm_cluster: FAILED; its files are in $work" >&2; fi
}
trap cleanup EXIT
started_ms=$(( $(date +%s%N) / 1000000 ))
seconds_since_start() { local ms=$(( $(date +%s%N) / 1000000 - started_ms )); printf "%d.%d" $((ms / 1000)) $((ms % 1000 / 100)); }
eval "$("$project/scripts/slurm/cluster.sh" start "$work/cluster")"
echo "cluster up in $(seconds_since_start) s ($SLURM_CONF)"
# The sbatch scripts run in the folder they were submitted from and write results/NAME there: a folder of
# the test's own with the project's scripts in it.
mkdir -p "$work/submit"
ln -s "$project/scripts" "$work/submit/scripts"
cd "$work/submit"

# Submits ARRAY_SCRIPT as 2 tasks with the merge after them, waits for the merge and returns its exit code.
run_array() {
  local name=$1 script=$2
  shift 2
  local array
  array=$(sbatch --parsable --array=1-2 --cpus-per-task=1 -o "$work/$name-%a.log" "scripts/slurm/$script" "$name" 2 "$@")
  array=${array%%;*}
  sbatch --wait --dependency="afterany:$array" -o "$work/$name-merge.log" scripts/slurm/merge.sbatch "$name" >/dev/null
}

local_run() {  # impactbench ARGUMENTS: 1 (a run unstable: a finding) is a result too
  "$IMPACTBENCH" "$@" >/dev/null 2>&1 || (($? == 1)) || { echo "test_slurm_cluster: impactbench $* failed" >&2; exit 1; }
}

same_results() {  # LOCAL MERGED
  "$project/bench/compare_runs.py" "$1" "$2" || { echo "test_slurm_cluster: $2 differs from $1 (above)" >&2; exit 1; }
}

# a. A suite: the free vibration with the reference and an engine, two laws, 1 s.
suite=("$project/scenarios/paper/free_vibration.toml" --engines "reference,$engine_1" --laws hertz,newton --duration 1 --dt 1e-4)
run_array suite suite-array.sbatch -- "${suite[@]}" || { echo "test_slurm_cluster: the suite's merge failed: $work/suite-merge.log" >&2; exit 1; }
local_run suite "${suite[@]}" --out "$work/local-suite"
same_results "$work/local-suite" results/suite/merged

# b. A sweep: the reference and an engine continued up and down over three ratios (4 chains, 2 a task).
sweep=("$project/scenarios/paper/resonance.toml" --ratios 0.98:1.0:0.01 --start both --engines "reference,$engine_1"
       --laws hertz --duration 3 --rest-duration 3 --window 2)
run_array sweep sweep-array.sbatch "${sweep[@]}" || { echo "test_slurm_cluster: the sweep's merge failed: $work/sweep-merge.log" >&2; exit 1; }
local_run sweep "${sweep[@]}" --out "$work/local-sweep"
same_results "$work/local-sweep" results/sweep/merged

# c. Cancelled while it runs, then submitted again (as a requeue would): the same results. One task runs the
# whole sweep (a longer one: 5 ratios, 6 s each); scancel sends SIGTERM to every process of the task.
long=("$project/scenarios/paper/resonance.toml" --ratios 0.96:1.0:0.01 --start both --engines "reference,$engine_1"
      --laws hertz --duration 6 --rest-duration 6 --window 2)
job=$(sbatch --parsable --array=1 --cpus-per-task=1 -o "$work/cancelled-%a.log" scripts/slurm/sweep-array.sbatch cancelled 1 "${long[@]}")
job=${job%%;*}
for _ in $(seq 300); do  # until the task has recorded a ratio or two
  [[ -s results/cancelled/shard-1/sweep.csv ]] && (( $(wc -l < results/cancelled/shard-1/sweep.csv) >= 3 )) && break
  sleep 0.1
done
scancel "${job}_1"
while squeue -h -j "$job" 2>/dev/null | grep -q .; do sleep 0.2; done
recorded=$(( $(wc -l < results/cancelled/shard-1/sweep.csv) - 1 ))
sbatch --wait --array=1 --cpus-per-task=1 -o "$work/resumed-%a.log" scripts/slurm/sweep-array.sbatch cancelled 1 "${long[@]}" >/dev/null
local_run sweep "${long[@]}" --out "$work/local-long"
same_results "$work/local-long" results/cancelled/shard-1
echo "cancelled after $recorded of 10 ratios, resubmitted: the same results as an uninterrupted run"

# d. The same for a suite task: scancel's SIGTERM reaches the workers and the suite in no order; a worker
# stopped that way is not a finding (no run recorded as failed), and the resubmitted task finishes the suite.
cut=("$project/scenarios/paper/free_vibration.toml" --engines "reference,$engine_1${engine_2:+,$engine_2}" --laws hertz,viscoelastic
     --duration 2 --dt 1e-4,5e-5)
job=$(sbatch --parsable --array=1 --cpus-per-task=2 -o "$work/cut-%a.log" scripts/slurm/suite-array.sbatch cut 1 -- "${cut[@]}")
job=${job%%;*}
for _ in $(seq 600); do  # until the task has recorded a few runs
  [[ -s results/cut/shard-1/runs.jsonl ]] && (( $(wc -l < results/cut/shard-1/runs.jsonl) >= 4 )) && break
  sleep 0.1
done
scancel "${job}_1"
while squeue -h -j "$job" 2>/dev/null | grep -q .; do sleep 0.2; done
recorded=$(wc -l < results/cut/shard-1/runs.jsonl)
if grep -q "died of signal" results/cut/shard-1/runs.jsonl; then
  echo "test_slurm_cluster: a run stopped by scancel was recorded as failed:" >&2
  grep "died of signal" results/cut/shard-1/runs.jsonl >&2
  exit 1
fi
sbatch --wait --array=1 --cpus-per-task=2 -o "$work/cut-resumed-%a.log" scripts/slurm/suite-array.sbatch cut 1 -- "${cut[@]}" >/dev/null
local_run suite "${cut[@]}" --out "$work/local-cut"
same_results "$work/local-cut" results/cut/shard-1
echo "suite cancelled after $recorded runs, resubmitted: the same results as an uninterrupted run"
echo "test_slurm_cluster: passed in $(seconds_since_start) s"
