#!/usr/bin/env bash
# Mutation check: the test suite must catch each of issue 20's six one-line physics mutations.
# Why: the engine and agreement tests compare an engine with a reference built from the same code (the
# contact laws, the rig, the metrics, the verdict), so a bug in that shared code moves both sides alike
# and they cannot see it. Each mutation below must instead fail a test of independent values (numbers
# written out, derived by hand or fitted from an engine's own forces; tests/*_test.cpp of commit 4c6a0b8).
# For each: apply it to the source, rebuild build/ (only what changed), run the ctest entries expected to
# catch it, then restore the file. "caught": they failed; "SURVIVED": they passed (the suite is blind to
# it); "build failed": not caught either. build/ is rebuilt unmutated at the end.
#   scripts/check-mutations.sh            needs build/ with the tests in it (scripts/build.sh --tests);
#                                         exit 0 when all six are caught, 1 otherwise, 2 when it cannot run
#   scripts/check-mutations.sh --dry-run  only checks that every original text occurs once; builds nothing
# Adding a mutation: append five fields to MUTATIONS: a name, the file, its exact original text (a literal
# occurring exactly once in that file), the mutated text, and a ctest regex (ctest -R) of the tests that
# must fail, kept narrow. gtest_discover_tests names are Suite.Test, or Prefix/Suite.Test/param followed by
# "  # GetParam() = ..." with CMake 3.25: do not anchor a parameterised name at its end.
set -euo pipefail
cd "$(dirname "$0")/.."

MUTATIONS=(
  # the energy-growth instability rule ten times looser (the bound is read here alone: model/simulator.h's
  # StabilityBounds value would rebuild the whole tree for the same verdicts)
  energy-bound-x10 harness/scoring/verdict.cpp
  'if (e > initial * (1 + settings.stability.energy_growth_tolerance) + 1e-12) {'
  'if (e > initial * (1 + 10 * settings.stability.energy_growth_tolerance) + 1e-12) {'
  '^VerdictThresholds\.EnergyGrowthWithoutInputIsOneThousandth$'
  # every engine's injected Newton impulse (adapters/common/fixed_step_loop.cpp applies it)
  newton-impulse-0.9e adapters/common/injected_contact.cpp
  'return (1 + newton->restitution) * effective_mass_kg_ * rate / h;'
  'return (1 + 0.9 * newton->restitution) * effective_mass_kg_ * rate / h;'
  'NewtonRestitution\..*/[a-z]+_injected'
  sensor-peak-tolerance-x2 harness/scoring/verdict.h
  'double sensor_peak_relative = 0.10;'
  'double sensor_peak_relative = 0.20;'
  '^VerdictThresholds\.AccuracyTolerancesAreTenPercentAndATenthOfAnImpactPerCycle$'
  # the two tips' combined effective mass, which the injected Newton impulse and MuJoCo's matched law use
  effective-mass+5% adapters/common/rig.cpp
  '1 / (1 / rig.frames[0].tip_effective_mass_kg + 1 / rig.frames[1].tip_effective_mass_kg);'
  '1.05 / (1 / rig.frames[0].tip_effective_mass_kg + 1 / rig.frames[1].tip_effective_mass_kg);'
  '^EffectiveMass\.'
  # ODE's spring-dashpot contact (ERP/CFM from k, c, h); the hinge stops keep their stiffness
  ode-contact-stiffness+5% adapters/ode/ode_contact.cpp
  'soft_constraint(spring->stiffness_n_per_m, spring->damping_n_s_per_m, time_step_s);'
  'soft_constraint(1.05 * spring->stiffness_n_per_m, spring->damping_n_s_per_m, time_step_s);'
  'ContactLawFit\..*/ode_matched_viscoelastic'
  # the reference's modal damping ratios, frame 2's half
  frame2-damping-x2 physics/modal_model.cpp
  'zeta << frames[0].zeta, frames[1].zeta;'
  'zeta << frames[0].zeta, 2 * frames[1].zeta;'
  '^Frame2FreeDecay\.'
)

dry_run=0
[[ $# == 0 || ( $# == 1 && $1 == --dry-run ) ]] || { echo "usage: $0 [--dry-run]" >&2; exit 2; }
[[ $# == 1 ]] && dry_run=1
die() { echo "check-mutations: $*" >&2; exit 2; }

# literal FILE ORIGINAL MUTATED count|apply: "count" prints "<occurrences> <line of the first>"; "apply"
# writes FILE with the one occurrence replaced (plain text, no regular expression).
literal() {
  python3 - "$@" <<'EOF'
import sys
path, old, new, mode = sys.argv[1:5]
text = open(path, encoding="utf-8").read()
if mode == "count":
    i = text.find(old)
    print(text.count(old), text.count("\n", 0, i) + 1 if i >= 0 else 0)
else:
    open(path, "w", encoding="utf-8").write(text.replace(old, new, 1))
EOF
}

(( ${#MUTATIONS[@]} % 5 == 0 )) || die "MUTATIONS must hold five fields per mutation"
count=$(( ${#MUTATIONS[@]} / 5 ))
all_regex=""
for ((i = 0; i < count; i++)); do
  name=${MUTATIONS[5*i]} file=${MUTATIONS[5*i+1]} before=${MUTATIONS[5*i+2]} after=${MUTATIONS[5*i+3]} regex=${MUTATIONS[5*i+4]}
  [[ -f $file ]] || die "$name: $file does not exist: update the table"
  read -r found line < <(literal "$file" "$before" "$after" count)
  [[ $found == 1 ]] || die "$name: the original text occurs $found times in $file, not once (the code moved: update the table): $before"
  if (( dry_run )); then
    printf '%-26s %s:%s\n    before: %s\n    after:  %s\n    ctest -R %s\n' "$name" "$file" "$line" "$before" "$after" "$regex"
  elif ! git diff --quiet HEAD -- "$file"; then
    die "$name: $file has uncommitted changes; commit or stash them first (this script restores files to their committed text)"
  fi
  all_regex+="${all_regex:+|}($regex)"
done
(( dry_run )) && { echo "dry run: all $count original texts found exactly once; nothing built or run"; exit 0; }

[[ -f build/build.ninja || -f build/Makefile ]] || die "no configured build/ (build/build.ninja or build/Makefile): run scripts/build.sh --tests first"
[[ -f build/tests/CTestTestfile.cmake ]] || die "build/ has no tests (configured with IMPACTBENCH_TESTS=OFF: run scripts/build.sh --tests)"
# scripts/test.sh leaves build/ without the tests of our own code (they run under the sanitizers there)
grep -q '^IMPACTBENCH_OWN_CODE_TESTS:BOOL=OFF$' build/CMakeCache.txt &&
  die "build/ has no tests of our own code (configured by scripts/test.sh with IMPACTBENCH_OWN_CODE_TESTS=OFF): run scripts/build.sh --tests"
logs=build/check-mutations && mkdir -p "$logs"
backup=$(mktemp)
current=""  # the file mutated right now, restored on any exit
restore() { if [[ -n $current ]]; then cp "$backup" "$current"; current=""; fi; }
trap '[[ -z $current ]] || echo "check-mutations: restoring $current" >&2; restore; rm -f "$backup"' EXIT
trap 'echo "check-mutations: interrupted; build/ may hold a mutated build: run cmake --build build" >&2; exit 130' INT TERM

echo "building build/ unmutated, then the selected tests must pass unmutated"
cmake --build build -j "$(nproc)" >"$logs/build.log" 2>&1 || die "build/ does not build unmutated (see $logs/build.log)"
for ((i = 0; i < count; i++)); do
  n=$(cd build && ctest -N -R "${MUTATIONS[5*i+4]}" | sed -n 's/^Total Tests: //p')
  [[ ${n:-0} -gt 0 ]] || die "${MUTATIONS[5*i]}: ctest -R '${MUTATIONS[5*i+4]}' selects no test in build/: update the table"
done
(cd build && ctest -R "$all_regex" -j2 --output-on-failure) >"$logs/baseline.log" 2>&1 ||
  die "the selected tests already fail unmutated (see $logs/baseline.log): a mutation's failure would prove nothing"

results=() times=() caught=0
for ((i = 0; i < count; i++)); do
  name=${MUTATIONS[5*i]} file=${MUTATIONS[5*i+1]} regex=${MUTATIONS[5*i+4]}
  start=$SECONDS
  cp "$file" "$backup"
  current=$file
  literal "$file" "${MUTATIONS[5*i+2]}" "${MUTATIONS[5*i+3]}" apply
  echo "$name: $file mutated; rebuilding and running ctest -R '$regex'"
  if ! cmake --build build -j "$(nproc)" >"$logs/$name.log" 2>&1; then
    result="build failed"
  elif (cd build && ctest -R "$regex" -j2 --output-on-failure) >>"$logs/$name.log" 2>&1; then
    result="SURVIVED"
  else
    result="caught"; caught=$((caught + 1))
  fi
  restore  # a copy, not cp -p: the new time stamp makes the next build recompile the restored file
  results+=("$result") times+=($((SECONDS - start)))
done
echo "rebuilding build/ unmutated"
cmake --build build -j "$(nproc)" >"$logs/build.log" 2>&1 || echo "check-mutations: the final rebuild failed (see $logs/build.log)" >&2

printf '\n%-26s %-13s %8s\n' mutation result seconds
for ((i = 0; i < count; i++)); do printf '%-26s %-13s %8s\n' "${MUTATIONS[5*i]}" "${results[i]}" "${times[i]}"; done
echo "$caught of $count caught (logs in $logs/)"
(( caught == count ))
