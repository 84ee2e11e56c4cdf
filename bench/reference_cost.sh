#!/usr/bin/env bash
# The reference's cost targets (docs/performance.md, "The reference's cost"), two binaries side by side in one
# spell so that the machine's drift reaches both alike:
#   - the 100 s resonance run with Hertz and the default outputs, the whole process (parent and worker): CPU
#     time (user + system, /usr/bin/time) over ROUNDS alternating invocations, and callgrind's instruction
#     count of one invocation each (with --instructions), which the machine's load does not move;
#   - the default study's reference sweep (studies/default.toml, sweep "reference"), the whole command with its
#     workers: CPU time of one invocation each (with --sweep).
# The load average is written beside every figure. Writes OUT/reference_cost.csv.
#   bench/reference_cost.sh [--rounds R] [--instructions] [--sweep] BEFORE_BINARY AFTER_BINARY [OUT]
#     default: 5 rounds, OUT results/performance
set -euo pipefail
cd "$(dirname "$0")/.."
rounds=5 instructions=0 sweep=0
while [[ ${1:-} == --* ]]; do
  case $1 in
    --rounds) rounds=$2; shift ;;
    --instructions) instructions=1 ;;
    --sweep) sweep=1 ;;
    *) echo "reference_cost.sh: unknown option $1; allowed: --rounds R, --instructions, --sweep, then two binaries and an output folder" >&2; exit 2 ;;
  esac
  shift
done
if [[ $# -lt 2 ]]; then
  echo "reference_cost.sh: needs two impactbench binaries (before, after); got $#" >&2
  exit 2
fi
before=$1 after=$2 out=${3:-results/performance}
for binary in "$before" "$after"; do
  [[ -x $binary ]] || { echo "reference_cost.sh: $binary: not an executable impactbench binary" >&2; exit 2; }
done
mkdir -p "$out"
work=$(mktemp -d "${TMPDIR:-/tmp}/impactbench-reference-cost-XXXXXX")
trap 'rm -rf "$work"' EXIT
csv="$out/reference_cost.csv"
echo "what,binary,round,cpu_time_s,instructions,load_average_1min" >"$csv"
load() { cut -d' ' -f1 /proc/loadavg; }
cpu_of() {  # the command's user + system CPU time, its children included [s]
  /usr/bin/time -f "%U %S" -o "$work/time" "$@" >/dev/null 2>&1
  awk '{print $1 + $2}' "$work/time"
}
run_case=(run scenarios/paper/resonance.toml --engine reference --law hertz)
for round in $(seq 1 "$rounds"); do
  for side in before after; do
    binary=$before; [[ $side == after ]] && binary=$after
    rm -rf "$work/run"
    l=$(load)
    cpu=$(cpu_of "$binary" "${run_case[@]}" --out "$work/run")
    echo "resonance_100s_run,$side,$round,$cpu,,$l" | tee -a "$csv"
  done
done
if [[ $instructions == 1 ]]; then
  for side in before after; do
    binary=$before; [[ $side == after ]] && binary=$after
    rm -rf "$work/run" "$work"/callgrind.*
    l=$(load)
    valgrind --tool=callgrind --trace-children=yes --callgrind-out-file="$work/callgrind.%p" \
      "$binary" "${run_case[@]}" --out "$work/run" >/dev/null 2>"$work/valgrind.log"
    # the worker's count includes what its parent did before the fork; the parent's own is the smaller file's
    total=$(grep -h "^summary:" "$work"/callgrind.* | awk '{print $2}' | sort -n | tail -1)
    echo "resonance_100s_run_instructions,$side,1,,$total,$l" | tee -a "$csv"
  done
fi
if [[ $sweep == 1 ]]; then
  for side in before after; do
    binary=$before; [[ $side == after ]] && binary=$after
    rm -rf "$work/sweep"
    l=$(load)
    cpu=$(cpu_of "$binary" sweep scenarios/paper/resonance.toml --ratios 0.85:1.20:0.01 --start rest,both \
      --engines reference --laws hertz,viscoelastic --rest-duration 60 --jobs 2 --out "$work/sweep")
    echo "reference_sweep,$side,1,$cpu,,$l" | tee -a "$csv"
  done
fi
echo "reference_cost: $csv"
