# The default suite's two parts as impactbench suite arguments, in one place: sourced by
# scripts/benchmark.sh (which runs them) and bench/suite_scaling.sh (which times part 1 on 1, 2, ... workers).
# duration: the forced cases' cut (benchmark.sh --full empties it).
paper_suite_args=(scenarios/paper --engines reference,mujoco,ode,bullet --laws hertz,viscoelastic,newton
                  --paths matched,injected,native --dt 1e-4,5e-5)
paper_suite_duration=(--duration 50)
search_suite_args=(scenarios/stiff scenarios/extreme --engines reference,mujoco,ode,bullet
                   --laws hertz,viscoelastic,newton --paths matched --find-steps --step-range 1e-5,1e-3 --duration 5
                   --repeat 0)

# Runs the two parts into OUT, as scripts/benchmark.sh and scripts/slurm/suite-array.sbatch do:
#   run_default_suite OUT [SUITE_ARGUMENTS...]
# part 1 with the forced cases cut by ${duration[@]} (empty: their whole 100 s), then part 2 (unless
# search=0) with --resume into the same folder; SUITE_ARGUMENTS (e.g. --shard K/N, --jobs N, --resume) go
# to both. Needs impactbench (the executable), duration and search set. Returns the suite's exit code:
# 0; 1 some run unstable or failed (a finding); 2 bad input; 3 a write error; 130/143 interrupted.
run_default_suite() {
  local out=$1 status=0 search_status
  shift
  "$impactbench" suite "${paper_suite_args[@]}" "${duration[@]}" "$@" --out "$out" || status=$?
  if (( search )) && (( status != 2 && status < 3 )); then
    "$impactbench" suite "${search_suite_args[@]}" "$@" --out "$out" --resume ||
      { search_status=$?; (( search_status > status )) && status=$search_status; }
  fi
  return "$status"
}
