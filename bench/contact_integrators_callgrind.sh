#!/usr/bin/env bash
# Instructions per contact of bench/contact_integrators, counted by valgrind's callgrind: the same on every
# run, where CPU time on a shared machine moves by tens of percent. The program runs uninstrumented up to
# its measured blocks (the reference run that finds the onsets costs nothing here) and dumps one profile per
# (case, stepper, rtol) block, named case/stepper/rtol/contacts=N; this script divides each dump's total by N.
#   bench/contact_integrators_callgrind.sh [OUT.csv] [contact_integrators options...]
# e.g. bench/contact_integrators_callgrind.sh /tmp/ir.csv --case resonance_hertz --stepper dopri5
# Writes OUT.csv (default: results/performance/contact_integrators_instructions.csv): case, stepper, rtol,
# contacts, instructions per contact. The accuracy table the program prints goes to stdout as it runs.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-results/performance/contact_integrators_instructions.csv}
[[ $# -gt 0 ]] && shift
program=build/bench/contact_integrators
[[ -x $program ]] || { echo "contact_integrators_callgrind.sh: $program missing: ninja -C build contact_integrators" >&2; exit 2; }
command -v valgrind >/dev/null || { echo "contact_integrators_callgrind.sh: valgrind missing (apt-get install valgrind)" >&2; exit 2; }
mkdir -p "$(dirname "$out")"
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
valgrind --tool=callgrind --instr-atstart=no --collect-atstart=no \
  --callgrind-out-file="$scratch/callgrind.out" "$program" "$@" 2>"$scratch/valgrind.log" ||
  { tail -20 "$scratch/valgrind.log" >&2; exit 1; }
echo "case,stepper,rtol,contacts,instructions_per_contact" >"$out"
for dump in "$scratch"/callgrind.out.*; do
  # "desc: Trigger: Client Request: case/stepper/rtol/contacts=N" and "summary: <Ir>"
  awk '/^desc: Trigger: Client Request:/ { name = $NF }
       /^summary:/ { total = $2 }
       END { if (name == "") exit
             split(name, p, "/"); sub("contacts=", "", p[4])
             printf "%s,%s,%s,%s,%.0f\n", p[1], p[2], p[3], p[4], total / p[4] }' "$dump"
done | sort -t, -k1,1 -k2,2 -k3,3gr >>"$out"
column -s, -t "$out"
echo "contact_integrators_callgrind.sh: $out"
