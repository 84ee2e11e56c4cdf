#!/usr/bin/env bash
# Does the cheap cost estimate hold? A run's cost is its logged run's own CPU time (the run whose series
# is recorded; no extra runs). This compares it, for each simulator, with separate timed runs of the same
# run in the same process (impactbench run --repeat N: the run again N times, nothing recorded to disk):
# ROUNDS invocations alternate on one case, each giving a logged time and N timed ones, so that the
# machine's drift reaches both alike. Writes OUT/timing_check.csv (every invocation) and
# OUT/timing_check.json (per simulator: the logged runs' median CPU time, the timed runs' median and
# spread, the difference, and whether it lies within the spread), with the machine (bench/machine.sh) and
# its load.
#   bench/timing_check.sh [--rounds R] [--repeat N] [--duration S] [--engines LIST] [OUT]
#     default: 3 rounds, 3 timed, 10 s, every simulator of the build (impactbench engines --names), OUT results/performance
set -euo pipefail
cd "$(dirname "$0")/.."
rounds=3 repeat=3 duration=10 engines=""
while [[ ${1:-} == --* ]]; do
  case $1 in
    --rounds) rounds=$2; shift ;;
    --repeat) repeat=$2; shift ;;
    --duration) duration=$2; shift ;;
    --engines) engines=$2; shift ;;
    *) echo "timing_check.sh: unknown option $1; allowed: --rounds R, --repeat N, --duration S, --engines LIST, then an output folder" >&2; exit 2 ;;
  esac
  shift
done
out=${1:-results/performance}
mkdir -p "$out"
impactbench=build/cli/impactbench
[[ -n $engines ]] || engines=$("$impactbench" engines --names)
work=$(mktemp -d "${TMPDIR:-/tmp}/impactbench-timing-XXXXXX")
trap 'rm -rf "$work"' EXIT
# The resonance case cut to the duration, scored over its second half (the window does not change the cost).
sed -e "s/^duration_s = .*/duration_s = $duration/" -e "s/^scoring_window_s = .*/scoring_window_s = $(awk "BEGIN {print $duration / 2}")/" \
  scenarios/paper/resonance.toml >"$work/resonance.toml"
csv="$out/timing_check.csv"
echo "round,engine,time_step_s,steps,logged_cpu_time_s,timed_runs,cpu_time_s,cpu_time_min_s,cpu_time_max_s,logged_wall_time_s,wall_time_s,load_average" >"$csv"
for round in $(seq 1 "$rounds"); do
  for engine in ${engines//,/ }; do
    echo "timing_check: round $round of $rounds, $engine"
    # The engine alone: no reference comparison is needed to time it (run compares, so keep the files small).
    "$impactbench" run "$work/resonance.toml" --engine "$engine" --law hertz --repeat "$repeat" --series none \
      --out "$work/$engine" >/dev/null
    /usr/bin/python3 - "$work/$engine/summary.json" "$round" >>"$csv" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
keys = ["engine", "time_step_s", "steps", "logged_cpu_time_s", "timed_runs", "cpu_time_s", "cpu_time_min_s",
        "cpu_time_max_s", "logged_wall_time_s", "wall_time_s", "load_average"]
print(",".join([sys.argv[2]] + [str(s[k]) for k in keys]))
PY
  done
done
/usr/bin/python3 - "$csv" "$out/timing_check.json" <<'PY'
import csv, json, statistics, subprocess, sys
rows = list(csv.DictReader(open(sys.argv[1])))
machine = dict(line.split("=", 1) for line in subprocess.run(["bench/machine.sh"], capture_output=True, text=True,
                                                              check=True).stdout.splitlines())
result = {"what": "logged run's CPU time (the cost runs.csv records) against timed runs of the same run "
                  "(bench/timing_check.sh)", "machine": machine, "simulators": []}
print(f"{'simulator':10} {'logged CPU [s]':>15} {'timed CPU median [s]':>21} {'timed spread [s]':>18} {'difference':>11}  within spread")
for engine in dict.fromkeys(r["engine"] for r in rows):
    mine = [r for r in rows if r["engine"] == engine]
    logged = statistics.median(float(r["logged_cpu_time_s"]) for r in mine)
    timed = statistics.median(float(r["cpu_time_s"]) for r in mine)
    low = min(float(r["cpu_time_min_s"]) for r in mine)
    high = max(float(r["cpu_time_max_s"]) for r in mine)
    within = low <= logged <= high
    entry = {"simulator": engine, "invocations": len(mine), "timed_runs_per_invocation": int(mine[0]["timed_runs"]),
             "steps": int(float(mine[0]["steps"])), "logged_cpu_time_median_s": logged, "timed_cpu_time_median_s": timed,
             "timed_cpu_time_min_s": low, "timed_cpu_time_max_s": high,
             "relative_difference": logged / timed - 1, "within_timed_spread": within,
             "load_average_median": statistics.median(float(r["load_average"]) for r in mine)}
    result["simulators"].append(entry)
    print(f"{engine:10} {logged:15.4f} {timed:21.4f} {low:8.4f} .. {high:.4f} {100 * (logged / timed - 1):+10.1f} %  {'yes' if within else 'no'}")
json.dump(result, open(sys.argv[2], "w"), indent=2)
PY
echo "timing_check: $csv, $out/timing_check.json"
