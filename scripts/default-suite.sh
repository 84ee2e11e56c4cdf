# The benchmark's two studies as impactbench suite arguments, in one place: sourced by
# scripts/benchmark.sh (which runs them), scripts/slurm/suite-array.sbatch (one shard of them) and
# bench/suite_scaling.sh (which times the full study's published cases on 1, 2, ... workers).
#
# The default study answers in minutes (at most 5 on this 2-core machine after the build, report
# included, at most 150 MB): every engine, every law, the matched and native contact paths, at the two
# steps that separate the engines (1e-4 s, where Bullet's and Simbody's explicit hinge springs diverge and
# MuJoCo's and ODE's Hertz contacts gain energy in the free case, and 5e-5 s, where all are stable), on
# the published cases that have impacts:
#   - resonance and pre-resonance cut to 20 s and scored over the last 10 s: the impacts settle them
#     sooner than their structural damping alone would (the suite warns that the scoring window starts
#     before that 22.9 s transient), and the reference's metrics over 10-20 s are those of the published
#     100 s run's last 14 s within 0.004 impacts per cycle, 3 % in the sensor peak and 0.1 % in the
#     contact duration (docs/performance.md); post-resonance has no impacts (docs/published-cases.md),
#   - free vibration over its first 3 s, the whole run scored (every impact ends by 2.5 s: the reference's
#     metrics over 3 s equal those over the published 14 s).
# DART and Simbody run the resonance and the free vibration; the pre-resonance is theirs in the full study
# (their 20 s runs cost 0.4 and 0.65 s of CPU per simulated second at 5e-5 s, against MuJoCo's 0.1 and
# Bullet's 0.2: with them the default took 6:54). The runs at 1e-4 s keep no series (--series none: their
# summary, events and sensor reading only): the report's figures draw the 5e-5 s runs, and the series are
# nearly all of a study's size (2 MB per 10 s window).
# Each line is one suite's arguments, run in order into the same folder (those after the first with
# --resume); then the named configurations (an engine with options of its own, each a curve of its own
# in the report):
#  - DART in centimetres (length_unit=cm), Newton: DART makes impacts plastic below e v = 0.1 model units
#    per second, every impact of this rig in metres; in centimetres the same physics bounces
#    (adapters/dart/README.md). DART in metres stays in the study: both are reported.
#  - Simbody's error-controlled integration (Runge-Kutta-Merson, the step its own; --dt is then only the
#    recording interval), Hertz (Simbody's own Hunt-Crossley contact), accuracy 1e-3 and 1e-5 on the free
#    vibration. About 1.5 s of CPU per simulated second whatever the accuracy (its steps are bounded by the
#    chain's stiffness, not by the accuracy; adapters/simbody/README.md), so the resonance is the full
#    study's;
# then a coarse step search (a grid of one step per octave, 1e-3 down to 1.6e-5 s) on one stiff and one
# extreme case: the viscoelastic contact at k = 1e8 N/m and restitution 0 (sticking).
default_laws_paths="--laws hertz,viscoelastic,newton --paths matched,native"
default_forced="--duration 20 --window 10"
default_study_parts=(
  "scenarios/paper/resonance.toml $default_forced --engines reference,mujoco,ode,bullet,dart,simbody $default_laws_paths --dt 5e-5"
  "scenarios/paper/resonance.toml $default_forced --engines reference,mujoco,ode,bullet,dart,simbody $default_laws_paths --dt 1e-4 --series none"
  "scenarios/paper/pre_resonance.toml $default_forced --engines reference,mujoco,ode,bullet $default_laws_paths --dt 5e-5"
  "scenarios/paper/pre_resonance.toml $default_forced --engines reference,mujoco,ode,bullet $default_laws_paths --dt 1e-4 --series none"
  "scenarios/paper/free_vibration.toml --duration 3 --engines reference,mujoco,ode,bullet,dart,simbody $default_laws_paths --dt 5e-5"
  "scenarios/paper/free_vibration.toml --duration 3 --engines reference,mujoco,ode,bullet,dart,simbody $default_laws_paths --dt 1e-4 --series none"
  "scenarios/paper/resonance.toml $default_forced --engines reference,dart --laws newton --paths matched --dt 5e-5 --option dart.length_unit=cm"
  "scenarios/paper/free_vibration.toml --duration 3 --engines reference,dart --laws newton --paths matched --dt 5e-5 --option dart.length_unit=cm"
  "scenarios/paper/free_vibration.toml --duration 3 --engines reference,simbody --laws hertz --paths matched --dt 1e-4 --option simbody.accuracy=1e-3"
  "scenarios/paper/free_vibration.toml --duration 3 --engines reference,simbody --laws hertz --paths matched --dt 1e-4 --option simbody.accuracy=1e-5"
)
# Simbody's search is the full study's: its largest stable step is its hinge springs' explicit limit for
# every law (7.5e-5 s at K = 8, in each run's diagnostics; the default's 1e-4 s runs diverge), and its
# searches cost 40 s of CPU here.
default_search_args=(scenarios/stiff/spring_dashpot_k1e08.toml scenarios/extreme/restitution_0.toml
                     --engines reference,mujoco,ode,bullet,dart --laws hertz,viscoelastic,newton --paths matched
                     --find-steps --steps-per-octave 1 --step-range 1e-5,1e-3)

# The full study (benchmark.sh --full): every published case x the three laws x every engine x its three
# contact paths x steps 1e-4 and 5e-5 s, the forced cases cut to 50 s (their transient is over within
# about 20 s; the scoring window stays the last 14 s), then the full step search on every stiff and
# extreme case (each cut to 5 s) on the matched paths, 4 grid steps per octave over 1e-5 to 1e-3 s.
full_study_engines=(--engines reference,mujoco,ode,bullet,dart,simbody --laws hertz,viscoelastic,newton
                    --paths matched,injected,native --dt 1e-4,5e-5)
full_study_parts=("scenarios/paper --duration 50 ${full_study_engines[*]}")
# Then the full study's named configurations: DART in centimetres on every published case; Simbody's
# error-controlled integration with its own Hunt-Crossley contact (Hertz) on the resonance and the free
# vibration, Runge-Kutta-Merson at 1e-3, 1e-5 and 1e-7 and CPodes (BDF) at 1e-5: about 1.7 s of CPU per
# simulated second each, so three accuracies a decade apart and not more.
full_study_parts+=("scenarios/paper --duration 50 --engines reference,dart --laws newton --paths matched --dt 1e-4,5e-5 --option dart.length_unit=cm")
for accuracy in 1e-3 1e-5 1e-7; do
  full_study_parts+=("scenarios/paper/resonance.toml scenarios/paper/free_vibration.toml --duration 50 --engines reference,simbody --laws hertz --paths matched --dt 1e-4 --option simbody.accuracy=$accuracy")
done
full_study_parts+=("scenarios/paper/resonance.toml scenarios/paper/free_vibration.toml --duration 50 --engines reference,simbody --laws hertz --paths matched --dt 1e-4 --option simbody.accuracy=1e-5 --option simbody.integrator=cpodes")
full_search_args=(scenarios/stiff scenarios/extreme --engines reference,mujoco,ode,bullet,dart,simbody
                  --laws hertz,viscoelastic,newton --paths matched --find-steps --step-range 1e-5,1e-3 --duration 5)

# The frequency sweeps (docs/sweeps.md), each "NAME SWEEP_ARGUMENTS" into OUT/sweeps/NAME (a folder per sweep:
# its settings are one record). The default study's:
#  - reference: the reference alone on the fine grid, 0.85 to 1.20 f_1 in steps of 0.01, from rest (60 s:
#    the 22.9 s start-up transient is over by the window) and continued up and down (60 s a ratio), Hertz and
#    spring-dashpot: the bifurcation diagram every engine is read against (its regimes are stable under
#    refinement of the run length and of the tolerances: docs/sweeps.md). About 50 s of CPU.
#  - engines: every engine on its matched path at its default step with the reference beside it, Hertz,
#    swept up over 0.95 to 1.10 f_1 in steps of 0.05 (the first ratio from rest over 30 s, each next one
#    continued over 20 s): each engine's regime against the reference's at a glance, about 150 s of CPU,
#    Simbody's chain 80 s of it (listed first so that it starts first: the others share the second core).
default_sweep_parts=(
  "reference scenarios/paper/resonance.toml --ratios 0.85:1.20:0.01 --start rest,both --engines reference --laws hertz,viscoelastic --rest-duration 60"
  "engines scenarios/paper/resonance.toml --ratios 0.95:1.10:0.05 --start up --engines simbody,bullet,ode,dart,mujoco,reference --laws hertz --paths matched --rest-duration 30 --duration 20"
)
# The full study's: the reference as in the default study, and every engine on the fine grid, up and down,
# Hertz, on its matched path at its default step, 30 s a ratio (about 50 min of CPU, Simbody's 22 of them:
# the full study is a cluster's, scripts/slurm/submit.sh NAME N --full).
full_sweep_parts=(
  "${default_sweep_parts[0]}"
  "engines scenarios/paper/resonance.toml --ratios 0.85:1.20:0.01 --start both --engines simbody,bullet,ode,dart,mujoco,reference --laws hertz --paths matched --duration 30"
)

# Runs a study into OUT:
#   run_study OUT [SUITE_ARGUMENTS...]
# each part of ${study} (default or full) as a suite into the same folder (the parts after the first
# with --extend: their settings differ, DIR/suite.jsonl keeps each), then its step search unless search=0, then its sweeps (each into OUT/sweeps/NAME);
# SUITE_ARGUMENTS (e.g. --shard K/N, --jobs N, --resume) go to every part and sweep. Needs impactbench (the executable), study and search set. Returns the worst
# exit code: 0; 1 some run unstable or failed (a finding); 2 bad input; 3 a write error; 130/143
# interrupted.
run_study() {
  local out=$1 status=0 part_status part resume=() parts search_args sweep_parts
  shift
  if [[ $study == full ]]; then
    parts=("${full_study_parts[@]}"); search_args=("${full_search_args[@]}"); sweep_parts=("${full_sweep_parts[@]}")
  else
    parts=("${default_study_parts[@]}"); search_args=("${default_search_args[@]}"); sweep_parts=("${default_sweep_parts[@]}")
  fi
  for part in "${parts[@]}"; do
    read -r -a part_args <<<"$part"
    part_status=0
    "$impactbench" suite "${part_args[@]}" "$@" "${resume[@]}" --out "$out" || part_status=$?
    (( part_status > status )) && status=$part_status
    (( status == 2 || status >= 3 )) && return "$status"
    resume=(--extend)  # the next parts have other settings: each adds its suite to the folder (DIR/suite.jsonl)
  done
  if (( search )); then
    part_status=0
    "$impactbench" suite "${search_args[@]}" "$@" "${resume[@]}" --out "$out" || part_status=$?
    (( part_status > status )) && status=$part_status
    (( status == 2 || status >= 3 )) && return "$status"
  fi
  for part in "${sweep_parts[@]}"; do
    read -r -a part_args <<<"$part"
    part_status=0
    "$impactbench" sweep "${part_args[@]:1}" "$@" --out "$out/sweeps/${part_args[0]}" || part_status=$?
    (( part_status > status )) && status=$part_status
    (( status == 2 || status >= 3 )) && return "$status"
  done
  return "$status"
}
