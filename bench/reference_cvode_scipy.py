#!/usr/bin/python3
"""The reference, SUNDIALS CVODE and SciPy's solve_ivp side by side: CPU time per simulated second at equal
accuracy, equal accuracy meaning the same impact events to a stated tolerance.

    /usr/bin/python3 bench/reference_cvode_scipy.py [--out DIR] [--cases free_vibration,resonance,...]
        [--laws hertz,viscoelastic,newton] [--duration 5] [--window 0.01] [--rtols 1e-5,1e-6,...]
        [--time-tolerance 1e-6] [--velocity-tolerance 1e-5] [--repeat 3]

For each case and law: the truth is the reference at rtol 1e-12 (atol 1e-15 m sqrt(kg)). Each solver (the
reference, `impactbench run --engine reference`; CVODE, build/bench/cvode_reference; SciPy,
bench/scipy_reference.py, DOP853) runs at the tolerances of --rtols, loosest first, atol = rtol * 1e-3
m sqrt(kg) (the reference's own pairing, 1e-9 and 1e-12), until its events.csv meets the criterion against
the truth's (bench/event_agreement.py: the same number of events, every onset and end within
--time-tolerance, every approach and rebound velocity within --velocity-tolerance of the largest approach
velocity). Its CPU time there (the median of --repeat runs; SciPy's repeated only while short) over the
simulated time is its cost at equal accuracy. A solver that meets it at no tolerance of the list is shown
as such, with its errors at the tightest.

Cases are cut to --duration (the published ones run 14 to 100 s; SciPy needs seconds per simulated second)
and their scoring window to --window, so that recording the output series, which the reference does
exactly and CVODE not at all, costs next to nothing: what is timed is the integration and its events.
The reference's CPU time is summary.json's cpu_time_s: its model built, the run integrated and its window
recorded, an upper bound on its integration's (CVODE's and SciPy's are their integrations', reading the exported
model and writing files not timed). Beside it, comparison.json keeps the same case cut to its window alone
(setup_cpu_time_s) and the difference (integration_estimate_cpu_time_s), which the two runs' scatter of a few
ms swamps for the cheapest cases.

Writes DIR/comparison.json (everything, with bench/machine.sh's record, the load average from
/proc/loadavg at the start and the end, the versions), DIR/timings.csv (one row per case and law) and
DIR/comparison.md. Exits 1 with a message naming the step when anything fails. Speed is measured here,
never asserted.
"""
import argparse
import datetime
import math
import os
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from event_agreement import errors, meets, read_events  # noqa: E402
from reference_vs_scipy import ROOT, ComparisonError, machine, read_json, run, scenario_path, versions  # noqa: E402
from three_way_tables import summary_row, write_outputs  # noqa: E402

SCIPY_REFERENCE = os.path.join(ROOT, "bench", "scipy_reference.py")
SOLVERS = ("reference", "cvode", "scipy")


def load_average():
    """The 1, 5 and 15 minute load averages, as /proc/loadavg gives them."""
    with open("/proc/loadavg", encoding="utf-8") as f:
        return [float(x) for x in f.read().split()[:3]]


def cut_scenario(path, duration_s, window_s, folder):
    """A copy of the scenario with [scenario] duration_s = min(its own, duration_s) and scoring_window_s =
    min(that, window_s): returns (path, duration [s], window [s])."""
    import tomllib
    try:
        with open(path, "rb") as f:
            text = f.read().decode("utf-8")
        section = tomllib.loads(text).get("scenario", {})
    except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError) as error:
        raise ComparisonError(f"{path}: cannot read the scenario: {error}") from None
    if not isinstance(section.get("duration_s"), (int, float)):
        raise ComparisonError(f"{path}: [scenario] needs duration_s (a number, in s)")
    duration = min(float(section["duration_s"]), duration_s)
    window = min(duration, window_s)
    lines, in_scenario, done = text.splitlines(keepends=True), False, set()
    for i, line in enumerate(lines):
        stripped = line.strip()
        if stripped.startswith("["):
            in_scenario = stripped.split("]")[0] == "[scenario"
        key = stripped.split("=")[0].strip()
        if in_scenario and key in ("duration_s", "scoring_window_s") and key not in done:
            value = duration if key == "duration_s" else window
            lines[i] = f"{key} = {value!r}   # cut by bench/reference_cvode_scipy.py [s]\n"
            done.add(key)
    if done != {"duration_s", "scoring_window_s"}:
        raise ComparisonError(f"{path}: [scenario] needs duration_s and scoring_window_s")
    os.makedirs(folder, exist_ok=True)
    out = os.path.join(folder, os.path.basename(path).replace(".toml", f"_{duration:g}s_window_{window:g}s.toml"))
    with open(out, "w", encoding="utf-8") as f:
        f.write("".join(lines))
    return out, duration, window


class Case:
    """One case and law: the scenario cut, its exported model, the truth's events."""

    def __init__(self, args, case, law, out):
        self.args, self.law = args, law
        self.name = f"{os.path.basename(case).removesuffix('.toml')}_{law}"
        self.folder = os.path.join(out, "cases", self.name)
        os.makedirs(self.folder, exist_ok=True)
        self.scenario, self.duration, self.window = cut_scenario(scenario_path(case), args.duration, args.window,
                                                                 os.path.join(out, "scenarios"))
        # the same case cut to its window alone: what a run costs besides integrating the rest (the modal model built,
        # the window recorded), subtracted from the reference's time as CVODE and SciPy read the exported model
        self.setup_scenario = cut_scenario(scenario_path(case), self.window, self.window,
                                           os.path.join(out, "scenarios"))[0]
        self.model = os.path.join(self.folder, "model.json")
        run([args.impactbench, "export", self.scenario, "--engine", "reference", "--law", law, "--out", self.model],
            f"{self.name}: export")
        truth = os.path.join(self.folder, "truth")
        self.reference(truth, args.truth_rtol, args.truth_rtol * 1e-3, 0)
        self.truth = read_events(os.path.join(truth, "events.csv"))

    def reference(self, folder, rtol, atol, repeat):
        def cpu_of(scenario, out):
            command = [self.args.impactbench, "run", scenario, "--engine", "reference", "--law", self.law, "--out",
                       out, "--option", f"rtol={rtol!r}", "--option", f"atol={atol!r}"]
            run(command + (["--repeat", str(repeat)] if repeat else []), f"{self.name}: the reference at rtol {rtol:g}")
            return read_json(os.path.join(out, "summary.json"), f"{self.name}: the reference's summary")
        summary = cpu_of(self.scenario, folder)
        setup = cpu_of(self.setup_scenario, folder + "_window_only")
        # the whole run is the cost compared (an upper bound on the integration's); the difference is kept beside it,
        # since for the cheapest cases it lies within the two runs' own scatter (a few ms each)
        return {"cpu_time_s": summary["cpu_time_s"], "wall_time_s": summary["wall_time_s"],
                "setup_cpu_time_s": setup["cpu_time_s"],
                "integration_estimate_cpu_time_s": summary["cpu_time_s"] - setup["cpu_time_s"]}

    def cvode(self, folder, rtol, atol, repeat):
        run([self.args.cvode, self.model, "--out", folder, "--method", self.args.cvode_method, "--rtol", repr(rtol),
             "--atol", repr(atol), "--repeat", str(repeat)], f"{self.name}: CVODE at rtol {rtol:g}")
        summary = read_json(os.path.join(folder, "cvode_run.json"), f"{self.name}: CVODE's summary")
        return {"cpu_time_s": summary["integration_cpu_time_s"], "wall_time_s": summary["integration_wall_time_s"],
                "steps": summary["steps"], "rhs_evaluations": summary["rhs_evaluations"],
                "sundials": summary["versions"]["sundials"]}

    def scipy(self, folder, rtol, atol, repeat):
        runs = []
        while not runs or (len(runs) < repeat and sum(r["integration_cpu_time_s"] for r in runs) < self.args.short):
            run([sys.executable, SCIPY_REFERENCE, self.model, "--out", folder, "--method", self.args.scipy_method,
                 "--rtol", repr(rtol), "--atol", repr(atol)], f"{self.name}: SciPy at rtol {rtol:g}")
            runs.append(read_json(os.path.join(folder, "scipy_run.json"), f"{self.name}: SciPy's summary"))
        return {"cpu_time_s": statistics.median(r["integration_cpu_time_s"] for r in runs),
                "wall_time_s": statistics.median(r["integration_time_s"] for r in runs),
                "runs": len(runs), "rhs_evaluations": runs[-1]["rhs_evaluations"]}

    def equal_accuracy(self, solver):
        """The loosest tolerance of --rtols at which the solver's events meet the criterion, and its cost there."""
        ladder, chosen = [], None
        for rtol in self.args.rtols:
            folder = os.path.join(self.folder, solver, f"rtol_{rtol:g}")
            atol = float(f"{rtol * 1e-3:.12g}")  # 1e-9 -> 1e-12, not 1.0000000000000002e-12
            try:
                # one untimed run decides; only the run that meets the criterion is repeated for its time
                cost = getattr(self, solver)(folder, rtol, atol, 1 if solver != "reference" else 0)
            except ComparisonError as error:  # e.g. Newton sticking, which CVODE and SciPy do not implement
                ladder.append({"rtol": rtol, "atol_m_sqrt_kg": atol, "meets_criterion": False, "failed": str(error),
                               "cpu_time_s": None, "events": None, "events_truth": len(self.truth),
                               "event_count_difference": None, "onset_error_s": None, "end_error_s": None,
                               "velocity_error": None, "impulse_error": None})
                print(f"[{self.name}] {solver} failed at rtol {rtol:g}: {error}", flush=True)
                break
            error = errors(read_events(os.path.join(folder, "events.csv")), self.truth)
            passed = meets(error, self.args.time_tolerance, self.args.velocity_tolerance)
            ladder.append(dict(rtol=rtol, atol_m_sqrt_kg=atol, meets_criterion=passed, **error, **cost))
            if passed:
                # a SciPy run that took long already is its own time (its repeats would take minutes)
                if self.args.repeat > 1 and not (solver == "scipy" and cost["cpu_time_s"] >= self.args.short):
                    ladder[-1].update(getattr(self, solver)(folder, rtol, atol, self.args.repeat))
                chosen = ladder[-1]
                break
        row = chosen or ladder[-1]
        cpu = row["cpu_time_s"]
        per_second = None if cpu is None else cpu / self.duration
        print(f"[{self.name}] {solver}: " + (f"meets the criterion at rtol {row['rtol']:g}" if chosen else
              "meets the criterion at no tolerance tried") +
              ("" if cpu is None else f", CPU {cpu:.4g} s ({per_second:.3g} s per simulated s)"), flush=True)
        return {"ladder": ladder, "met": chosen is not None, "rtol": row["rtol"], "cpu_time_s": cpu,
                "cpu_time_per_simulated_s": per_second}


def parse_arguments():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    stamp = datetime.datetime.now().strftime("%Y-%m-%d_%H%M%S")
    parser.add_argument("--out", default=os.path.join(ROOT, "results", f"reference-cvode-scipy-{stamp}"))
    parser.add_argument("--impactbench", default=os.path.join(ROOT, "build", "cli", "impactbench"))
    parser.add_argument("--cvode", default=os.path.join(ROOT, "build", "bench", "cvode_reference"))
    parser.add_argument("--cases", default="free_vibration,resonance,pre_resonance,post_resonance",
                        help="names in scenarios/paper or scenario files, comma-separated")
    parser.add_argument("--laws", default="hertz,viscoelastic,newton")
    parser.add_argument("--duration", type=float, default=5.0, help="cut longer cases to this [s] (default 5)")
    parser.add_argument("--window", type=float, default=0.01, help="scoring window (output series) [s] (default 0.01)")
    parser.add_argument("--rtols", default="1e-5,1e-6,1e-7,1e-8,1e-9,1e-10,1e-11",
                        help="tolerances tried, loosest first (default 1e-5 to 1e-11)")
    parser.add_argument("--truth-rtol", type=float, default=1e-12, help="the truth's rtol (atol rtol * 1e-3)")
    parser.add_argument("--time-tolerance", type=float, default=1e-6,
                        help="every onset and end within this of the truth's [s] (default 1e-6)")
    parser.add_argument("--velocity-tolerance", type=float, default=1e-5,
                        help="approach and rebound velocities within this times the largest approach (default 1e-5)")
    parser.add_argument("--repeat", type=int, default=3, help="timed runs at the chosen tolerance, the median kept")
    parser.add_argument("--short", type=float, default=10.0, help="SciPy repeated while its runs took less than this [s]")
    parser.add_argument("--cvode-method", default="adams", choices=["adams", "adams-newton", "bdf"])
    parser.add_argument("--scipy-method", default="DOP853")
    args = parser.parse_args()
    try:
        args.rtols = sorted((float(x) for x in args.rtols.split(",")), reverse=True)
    except ValueError:
        parser.error(f"--rtols {args.rtols}: allowed: numbers > 0, comma-separated")
    for name in ("duration", "window", "truth_rtol", "time_tolerance", "velocity_tolerance", "short"):
        value = getattr(args, name)
        if not (math.isfinite(value) and value > 0):
            parser.error(f"--{name.replace('_', '-')} {value}: allowed: a number > 0")
    if not all(math.isfinite(r) and r > 0 for r in args.rtols):
        parser.error(f"--rtols: allowed: numbers > 0")
    if args.repeat < 1:
        parser.error(f"--repeat {args.repeat}: allowed: an integer >= 1")
    for option, path in (("--impactbench", args.impactbench), ("--cvode", args.cvode)):
        if not os.access(path, os.X_OK):
            parser.error(f"{option} {path}: not an executable; build first (cmake with -DIMPACTBENCH_BENCH=ON)")
    return args


def main():
    args = parse_arguments()
    os.makedirs(args.out, exist_ok=True)
    started = datetime.datetime.now()
    record = {"started": started.isoformat(timespec="seconds"), "machine": machine(), "versions": versions(args.impactbench),
              "settings": {"rtols": args.rtols, "atol_per_rtol_m_sqrt_kg": 1e-3, "truth_rtol": args.truth_rtol,
                           "time_tolerance_s": args.time_tolerance, "velocity_tolerance": args.velocity_tolerance,
                           "max_duration_s": args.duration, "window_s": args.window, "repeat": args.repeat,
                           "cvode_method": args.cvode_method, "scipy_method": args.scipy_method},
              "cases": []}
    record["machine"]["proc_loadavg_at_start"] = load_average()
    try:
        for case in args.cases.split(","):
            for law in args.laws.split(","):
                c = Case(args, case, law, args.out)
                result = {"case": c.name.removesuffix(f"_{law}"), "law": law, "scenario_file": c.scenario,
                          "duration_s": c.duration, "window_s": c.window, "truth_events": len(c.truth),
                          "folder": c.folder, "solvers": {s: c.equal_accuracy(s) for s in SOLVERS}}
                result["summary"] = summary_row(result)
                record["cases"].append(result)
                record["versions"]["sundials"] = result["solvers"]["cvode"]["ladder"][0].get("sundials", "?")
    except ComparisonError as error:
        sys.exit(f"reference_cvode_scipy: {error}")
    record["machine"]["proc_loadavg_at_end"] = load_average()
    record["elapsed_s"] = (datetime.datetime.now() - started).total_seconds()
    write_outputs(record, args.out)
    print(f"reference_cvode_scipy: {len(record['cases'])} comparisons in {record['elapsed_s']:.0f} s; "
          f"{os.path.join(args.out, 'comparison.md')}")


if __name__ == "__main__":
    main()
