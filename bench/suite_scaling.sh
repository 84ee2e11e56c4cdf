#!/usr/bin/env bash
# Suite scaling: the full study's forced cases with impacts (the first [[suite]] of studies/full.toml; every engine,
# law, contact path and step) run whole on 1, 2, ... worker processes, each into its own fresh folder. Parallel
# efficiency E(n) = T(1) / (n T(n)). Writes OUT/scaling.csv and OUT/scaling.json (with the machine and
# versions, bench/machine.sh); the report shows them when OUT is RESULTS/performance.
#   bench/suite_scaling.sh [--workers 1,2] [--duration S] [OUT]     (default OUT: results/performance)
# --duration S cuts every run to S seconds (default: the full study's 20 s): the same jobs, shorter;
# the per-job costs that do not scale with the duration (process start, reading the references, writing
# files) then weigh more, so a cut run understates the efficiency of the full one.
set -euo pipefail
cd "$(dirname "$0")/.."
workers=1,2
duration=""
while [[ ${1:-} == --* ]]; do
  case $1 in
    --workers) workers=$2; shift ;;
    --duration) duration=$2; shift ;;
    *) echo "suite_scaling.sh: unknown option $1; allowed: --workers N,M,..., --duration S, then an output folder" >&2; exit 2 ;;
  esac
  shift
done
out=${1:-results/performance}
mkdir -p "$out"
impactbench=build/cli/impactbench
csv="$out/scaling.csv"
# that one part as a study of its own, its duration replaced when --duration is given
part=$(mktemp "${TMPDIR:-/tmp}/impactbench-scaling-XXXXXX.toml")
/usr/bin/python3 - studies/full.toml "$duration" >"$part" <<'PY'
import json, sys, tomllib
suite = tomllib.load(open(sys.argv[1], "rb"))["suite"][0]
if sys.argv[2]:
    suite["duration_s"] = float(sys.argv[2])
print("[[suite]]")
for key, value in suite.items():
    print(f"{key} = {json.dumps(value)}")
PY
echo "workers,wall_time_s,jobs,sum_of_run_wall_times_s" >"$csv"
IFS=, read -r -a counts <<<"$workers"
for n in "${counts[@]}"; do
  folder=$(mktemp -d "${TMPDIR:-/tmp}/impactbench-scaling-$n-XXXXXX")
  echo "suite_scaling: $n worker(s) -> $folder"
  start=$(date +%s.%N)
  status=0
  $impactbench study "$part" --jobs "$n" --out "$folder" --no-report 2>/dev/null || status=$?
  end=$(date +%s.%N)
  if (( status == 2 || status >= 3 )); then echo "suite_scaling: the suite on $n workers ended with $status" >&2; exit "$status"; fi
  /usr/bin/python3 - "$folder/runs.csv" "$n" "$start" "$end" >>"$csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
total = sum(float(r["wall_time_s"]) for r in rows if r["wall_time_s"] not in ("", "nan"))
print(f"{sys.argv[2]},{float(sys.argv[4]) - float(sys.argv[3]):.3f},{len(rows)},{total:.3f}")
PY
  rm -rf "$folder"
done
rm -f "$part"
/usr/bin/python3 - "$csv" "$out/scaling.json" "${duration:-the study's}" <<'PY'
import csv, json, subprocess, sys
rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(open(sys.argv[1]))]
one = next((r for r in rows if r["workers"] == 1), None)
for r in rows:
    r["parallel_efficiency"] = one["wall_time_s"] / (r["workers"] * r["wall_time_s"]) if one else None
machine = dict(line.split("=", 1) for line in subprocess.run(["bench/machine.sh"], capture_output=True, text=True,
                                                              check=True).stdout.splitlines())
json.dump({"suite": "the full study's published cases (studies/full.toml, its first [[suite]])",
           "duration_option": sys.argv[3], "rows": rows, "machine": machine}, open(sys.argv[2], "w"), indent=2)
for r in rows:
    eff = f'{100 * r["parallel_efficiency"]:.1f} %' if r["parallel_efficiency"] is not None else "n/a"
    print(f'{int(r["workers"])} worker(s): {r["wall_time_s"]:.1f} s wall for {int(r["jobs"])} jobs, efficiency {eff}')
PY
