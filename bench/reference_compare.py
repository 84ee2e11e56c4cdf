#!/usr/bin/env python3
"""The reference's results from two impactbench binaries side by side, for a change that must alter nothing
but the cost (docs/performance.md, "The reference's cost (issue 30)").

    bench/reference_compare.py --before OLD/impactbench --after NEW/impactbench --out DIR [--option k=v]...

Runs `impactbench run FILE --engine reference --law LAW` for every scenario of scenarios/paper, stiff and
extreme and every law it defines, once with each binary (the same --option pairs for both, e.g. a
perturbation of the "before" side to show how far a chaotic case moves under a change of rounding alone:
--before-option slow_modes=0), then prints, for every metric of summary.json, the largest relative difference
|after - before| / max(|before|, |after|) and the case it occurs in. The CPU time of each side's runs, summed,
with the load average beside it. Writes DIR/differences.csv (one row per case and metric).
"""
import argparse
import csv
import json
import os
import subprocess
import sys
import time
from pathlib import Path

SOURCE = Path(__file__).resolve().parent.parent
LAWS = ("hertz", "viscoelastic", "newton")
# Not results: what a run cost, where it ran, and the solver's own work counters.
NOT_METRICS = {"wall_time_s", "cpu_time_s", "steps", "wall_time_per_simulated_s", "cpu_time_per_simulated_s",
               "load_average", "timed_runs", "wall_time_min_s", "wall_time_max_s", "cpu_time_min_s", "cpu_time_max_s",
               "logged_wall_time_s", "logged_cpu_time_s"}
WORK_COUNTERS = {"integrator_steps", "grid_intervals", "coarse_intervals", "grid_step_s"}


def scenario_files():
    for folder in ("paper", "stiff", "extreme"):
        yield from sorted((SOURCE / "scenarios" / folder).glob("*.toml"))


def laws_of(path):
    text = path.read_text()
    return [law for law in LAWS if f"[contact.{law}]" in text]


def run(binary, scenario, law, out, options):
    command = [binary, "run", str(scenario), "--engine", "reference", "--law", law, "--out", str(out)]
    for option in options:
        command += ["--option", option]
    start = os.times()
    done = subprocess.run(command, cwd=SOURCE, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    end = os.times()
    cpu = (end.children_user - start.children_user) + (end.children_system - start.children_system)
    if not (out / "summary.json").exists():
        sys.exit(f"{' '.join(command)} wrote no summary.json: {done.stderr}")
    return json.loads((out / "summary.json").read_text()), cpu


def numbers(summary):
    values = {k: v for k, v in summary.items() if isinstance(v, (int, float)) and not isinstance(v, bool)
              and k not in NOT_METRICS}
    for k, v in summary.get("diagnostics", {}).items():
        if isinstance(v, (int, float)) and k not in WORK_COUNTERS:
            values["diagnostics." + k] = v
    return values


def relative(a, b):
    if a == b:
        return 0.0
    scale = max(abs(a), abs(b))
    return abs(a - b) / scale if scale > 0 else 0.0


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--before", required=True)
    parser.add_argument("--after", required=True)
    parser.add_argument("--out", required=True, type=Path)
    parser.add_argument("--option", action="append", default=[], help="reference option for both sides")
    parser.add_argument("--before-option", action="append", default=[], help="reference option for the before side only")
    parser.add_argument("--only", default="", help="run only the scenario files whose path holds this text")
    args = parser.parse_args()
    rows, worst, cpu = [], {}, {"before": 0.0, "after": 0.0}
    loads = [os.getloadavg()[0]]
    for scenario in scenario_files():
        if args.only and args.only not in str(scenario):
            continue
        for law in laws_of(scenario):
            case = f"{scenario.parent.name}/{scenario.stem}/{law}"
            results = {}
            for side, binary, extra in (("before", args.before, args.before_option), ("after", args.after, [])):
                summary, seconds = run(binary, scenario, law, args.out / side / case, args.option + extra)
                results[side] = numbers(summary)
                cpu[side] += seconds
            for metric, a in results["before"].items():
                b = results["after"].get(metric)
                if a is None or b is None:
                    d = 0.0 if a is None and b is None else float("inf")
                else:
                    d = relative(a, b)
                rows.append((case, metric, a, b, d))
                if metric not in worst or d > worst[metric][0]:
                    worst[metric] = (d, case, a, b)
            print(f"{case}: done", file=sys.stderr)
    loads.append(os.getloadavg()[0])
    args.out.mkdir(parents=True, exist_ok=True)
    with open(args.out / "differences.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["case", "metric", "before", "after", "relative_difference"])
        w.writerows(rows)
    print(f"{'metric':55s} {'largest relative difference':>28s}  case")
    for metric, (d, case, a, b) in sorted(worst.items()):
        print(f"{metric:55s} {d:28.3g}  {case} ({a} / {b})")
    print(f"CPU of the runs: before {cpu['before']:.2f} s, after {cpu['after']:.2f} s "
          f"(load average {loads[0]:.2f} at the start, {loads[1]:.2f} at the end, {time.strftime('%Y-%m-%d %H:%M')})")


if __name__ == "__main__":
    main()
