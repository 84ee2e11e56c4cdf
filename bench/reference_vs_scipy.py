#!/usr/bin/python3
"""The reference against SciPy's solve_ivp on the same modal equations, side by side in one run.

    /usr/bin/python3 bench/reference_vs_scipy.py [--out DIR] [--cases resonance,free_vibration]
        [--laws hertz,viscoelastic,newton] [--duration 20] [--repeat 3] [--method DOP853]

For each case and law: the reference (`impactbench run --engine reference`, its wall time from summary.json,
the median of --repeat runs), SciPy (bench/scipy_reference.py on the model `impactbench export --engine
reference` writes, at the same rtol and atol, its integration time the median of up to --repeat runs while
they are short) and a tight reference (rtol 1e-12, atol 1e-15) that both are measured against. All three
are scored by `impactbench score`, the harness's own metric code. Cases longer than --duration are cut to
it (the scoring window kept, but no longer than the run), so that SciPy finishes in minutes.

Writes DIR/comparison.json (everything, with the machine and the versions), DIR/timings.csv (one row
per case and law), DIR/metrics.csv (one row per case, law and metric) and DIR/comparison.md (the tables).
Exits 1 with a message naming the step when anything fails. Speed is measured here, never asserted.
"""
import argparse
import datetime
import json
import math
import os
import platform
import statistics
import subprocess
import sys
import tomllib

try:
    import numpy
    import scipy
except ImportError as missing:
    sys.exit(f"reference_vs_scipy: {missing}: needs NumPy and SciPy (Debian's python3-scipy); run with /usr/bin/python3")

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from comparison_tables import metric_rows, summary_row, write_outputs  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCIPY_REFERENCE = os.path.join(ROOT, "bench", "scipy_reference.py")


class ComparisonError(RuntimeError):
    pass


def run(command, what):
    """Runs a command; a failure stops the comparison with the command and the end of its output."""
    done = subprocess.run(command, capture_output=True, text=True)
    if done.returncode != 0:
        tail = (done.stdout + done.stderr).strip().splitlines()[-8:]
        raise ComparisonError(f"{what} failed (exit {done.returncode}): {' '.join(command)}\n  " + "\n  ".join(tail))
    return done.stdout


def read_json(path, what):
    try:
        with open(path, encoding="utf-8") as f:
            return json.load(f)
    except (OSError, json.JSONDecodeError) as error:
        raise ComparisonError(f"{what}: cannot read {path}: {error}") from None


def scenario_path(case):
    """A case name of scenarios/paper/ or a path to a scenario file."""
    if case.endswith(".toml"):
        return case
    return os.path.join(ROOT, "scenarios", "paper", case + ".toml")


def cut_scenario(path, max_duration_s, folder):
    """The scenario, or a copy cut to max_duration_s (its scoring window kept, no longer than the run) in
    folder: returns (path, duration [s], window [s], whether it was cut)."""
    try:
        with open(path, "rb") as f:
            text_bytes = f.read()
        data = tomllib.loads(text_bytes.decode("utf-8"))
    except (OSError, tomllib.TOMLDecodeError, UnicodeDecodeError) as error:
        raise ComparisonError(f"{path}: cannot read the scenario: {error}") from None
    section = data.get("scenario", {})
    duration, window = section.get("duration_s"), section.get("scoring_window_s")
    if not isinstance(duration, (int, float)) or not isinstance(window, (int, float)):
        raise ComparisonError(f"{path}: [scenario] needs duration_s and scoring_window_s (numbers, in s)")
    if duration <= max_duration_s:
        return path, float(duration), float(window), False
    lines, in_scenario, replaced = text_bytes.decode("utf-8").splitlines(keepends=True), False, set()
    new_window = min(window, max_duration_s)
    for i, line in enumerate(lines):
        stripped = line.strip()
        if stripped.startswith("["):
            in_scenario = stripped.split("]")[0] == "[scenario"
        key = stripped.split("=")[0].strip()
        if in_scenario and key in ("duration_s", "scoring_window_s") and key not in replaced:
            value = max_duration_s if key == "duration_s" else new_window
            lines[i] = f"{key} = {value!r}   # cut by bench/reference_vs_scipy.py --duration [s]\n"
            replaced.add(key)
    os.makedirs(folder, exist_ok=True)
    out = os.path.join(folder, os.path.basename(path).replace(".toml", f"_cut_{max_duration_s:g}s.toml"))
    with open(out, "w", encoding="utf-8") as f:
        f.write("".join(lines))
    check = tomllib.loads("".join(lines))["scenario"]
    if check["duration_s"] != max_duration_s or check["scoring_window_s"] != new_window:
        raise ComparisonError(f"{out}: the cut scenario does not read back as {max_duration_s} s")
    return out, float(max_duration_s), float(new_window), True


def score(impactbench, folder, scenario, against):
    """`impactbench score`: the run's metrics, and its errors against another run (vs_reference_*)."""
    text = run([impactbench, "score", folder, "--scenario", scenario, "--reference", against, "--json"],
               f"scoring {folder}")
    return json.loads(text)


def median_of_runs(once, repeat, keep_going):
    """Runs once() up to repeat times, at least once, while keep_going(times so far); the median time."""
    times = [once()]
    while len(times) < repeat and keep_going(times):
        times.append(once())
    return statistics.median(times), times


def compare_case(args, case, law, out):
    case_name = os.path.basename(case).removesuffix(".toml")
    name = f"{case_name}_{law}"
    folder = os.path.join(out, "cases", name)
    os.makedirs(folder, exist_ok=True)
    scenario, duration, window, cut = cut_scenario(scenario_path(case), args.duration, os.path.join(out, "scenarios"))
    ib = args.impactbench
    tolerances = ["--option", f"rtol={args.rtol!r}", "--option", f"atol={args.atol!r}"]
    model = os.path.join(folder, "model.json")
    run([ib, "export", scenario, "--engine", "reference", "--law", law, "--out", model] + tolerances, f"{name}: export")
    exported = read_json(model, f"{name}: the exported model")
    if exported["duration_s"] != duration:
        raise ComparisonError(f"{model}: duration_s {exported['duration_s']} s, expected {duration} s")
    print(f"[{name}] {duration:g} s{' (cut)' if cut else ''}, scored over the last {window:g} s", flush=True)

    reference = os.path.join(folder, "reference")

    reference_cpu_times = []

    def reference_once():
        run([ib, "run", scenario, "--engine", "reference", "--law", law, "--out", reference] + tolerances,
            f"{name}: the reference")
        summary = read_json(os.path.join(reference, "summary.json"), f"{name}: the reference's summary")
        reference_cpu_times.append(summary["cpu_time_s"])
        return summary["wall_time_s"]

    reference_time, reference_times = median_of_runs(reference_once, args.repeat, lambda t: True)
    tight = os.path.join(folder, "tight_reference")
    run([ib, "run", scenario, "--engine", "reference", "--law", law, "--out", tight, "--option",
         f"rtol={args.tight_rtol!r}", "--option", f"atol={args.tight_atol!r}"], f"{name}: the tight reference")

    scipy_folder = os.path.join(folder, "scipy")
    scipy_runs = []

    def scipy_once():
        run([sys.executable, SCIPY_REFERENCE, model, "--out", scipy_folder, "--method", args.method],
            f"{name}: SciPy ({args.method})")
        scipy_runs.append(read_json(os.path.join(scipy_folder, "scipy_run.json"), f"{name}: SciPy's summary"))
        return scipy_runs[-1]["integration_time_s"]

    scipy_time, scipy_times = median_of_runs(scipy_once, args.repeat, lambda t: sum(t) < args.short)
    print(f"[{name}] reference {reference_time:.4f} s, SciPy {scipy_time:.3f} s: {scipy_time / reference_time:.0f}x",
          flush=True)

    scores = {"reference": score(ib, reference, scenario, tight), "scipy": score(ib, scipy_folder, scenario, tight),
              "scipy_vs_reference": score(ib, scipy_folder, scenario, reference),
              "tight": score(ib, tight, scenario, tight)}
    last = scipy_runs[-1]
    reference_cpu = statistics.median(reference_cpu_times)
    scipy_cpu = statistics.median(r["integration_cpu_time_s"] for r in scipy_runs)
    timing = {"reference_wall_times_s": reference_times, "reference_wall_time_s": reference_time,
              "reference_cpu_time_s": reference_cpu, "scipy_integration_times_s": scipy_times,
              "scipy_integration_time_s": scipy_time, "scipy_integration_cpu_time_s": scipy_cpu,
              "speed_ratio_cpu": scipy_cpu / reference_cpu if reference_cpu > 0 else None,
              "scipy_output_time_s": last["output_time_s"], "scipy_rhs_evaluations": last["rhs_evaluations"],
              "scipy_solve_ivp_calls": last["solve_ivp_calls"], "speed_ratio": scipy_time / reference_time}
    return {"case": case_name, "law": law, "scenario_file": scenario, "duration_s": duration, "scoring_window_s": window, "cut": cut,
            "timing": timing, "scores": scores, "folder": folder}


def machine():
    """bench/machine.sh's record (CPU, cores, memory, OS, compiler, Debian versions, commit), as every
    bench/ measurement keeps it, and the load average at the start."""
    lines = run([os.path.join(ROOT, "bench", "machine.sh")], "bench/machine.sh").splitlines()
    record = dict(line.split("=", 1) for line in lines if "=" in line)
    record["load_average_1_5_15_min_at_start"] = list(os.getloadavg())
    return record


def versions(impactbench):
    commit = subprocess.run(["git", "-C", ROOT, "rev-parse", "HEAD"], capture_output=True, text=True).stdout.strip()
    dirty = subprocess.run(["git", "-C", ROOT, "status", "--porcelain", "--untracked-files=no"], capture_output=True,
                           text=True).stdout.strip()
    return {"python": platform.python_version(), "numpy": numpy.__version__, "scipy": scipy.__version__,
            "impactbench_commit": (commit or "unknown") + (" (with uncommitted changes)" if dirty else ""),
            "impactbench": impactbench}


def parse_arguments():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    stamp = datetime.datetime.now().strftime("%Y-%m-%d_%H%M%S")
    parser.add_argument("--out", default=os.path.join(ROOT, "results", f"reference-vs-scipy-{stamp}"))
    parser.add_argument("--impactbench", default=os.path.join(ROOT, "build", "cli", "impactbench"))
    parser.add_argument("--cases", default="resonance,free_vibration",
                        help="names in scenarios/paper or scenario files, comma-separated")
    parser.add_argument("--laws", default="hertz,viscoelastic,newton")
    parser.add_argument("--duration", type=float, default=20.0, help="cut longer cases to this [s] (default 20)")
    parser.add_argument("--repeat", type=int, default=3, help="runs per timing, the median taken (default 3)")
    parser.add_argument("--short", type=float, default=10.0,
                        help="SciPy is repeated while its runs so far took less than this in all [s] (default 10)")
    parser.add_argument("--method", default="DOP853", help="solve_ivp method (default DOP853)")
    parser.add_argument("--rtol", type=float, default=1e-9, help="both solvers' rtol (default: the reference's, 1e-9)")
    parser.add_argument("--atol", type=float, default=1e-12, help="both solvers' atol [m sqrt(kg)] (default 1e-12)")
    parser.add_argument("--tight-rtol", type=float, default=1e-12)
    parser.add_argument("--tight-atol", type=float, default=1e-15)
    args = parser.parse_args()
    for name in ("duration", "short", "rtol", "atol", "tight_rtol", "tight_atol"):
        value = getattr(args, name)
        if not (math.isfinite(value) and value > 0):
            parser.error(f"--{name.replace('_', '-')} {value}: allowed: a number > 0")
    if args.repeat < 1:
        parser.error(f"--repeat {args.repeat}: allowed: an integer >= 1")
    if not os.access(args.impactbench, os.X_OK):
        parser.error(f"--impactbench {args.impactbench}: not an executable; build first (scripts/build.sh)")
    return args


def main():
    args = parse_arguments()
    os.makedirs(args.out, exist_ok=True)
    started = datetime.datetime.now()
    record = {"started": started.isoformat(timespec="seconds"), "machine": machine(),
              "versions": versions(args.impactbench),
              "settings": {"rtol": args.rtol, "atol_m_sqrt_kg": args.atol, "tight_rtol": args.tight_rtol,
                           "tight_atol_m_sqrt_kg": args.tight_atol, "method": args.method,
                           "max_duration_s": args.duration, "repeat": args.repeat, "short_s": args.short},
              "cases": []}
    try:
        for case in args.cases.split(","):
            for law in args.laws.split(","):
                result = compare_case(args, case, law, args.out)
                result["summary"] = summary_row(result)
                result["metrics"] = metric_rows(result)
                record["cases"].append(result)
    except ComparisonError as error:
        sys.exit(f"reference_vs_scipy: {error}")
    record["machine"]["load_average_1_5_15_min_at_end"] = list(os.getloadavg())
    record["elapsed_s"] = (datetime.datetime.now() - started).total_seconds()
    write_outputs(record, args.out)
    print(f"reference_vs_scipy: {len(record['cases'])} comparisons in {record['elapsed_s']:.0f} s; "
          f"{os.path.join(args.out, 'comparison.md')}")


if __name__ == "__main__":
    main()
