#!/usr/bin/python3
"""The reference's Newton impacts beside Siconos's (issue 49): the second, independent Newton reference.

    /usr/bin/python3 bench/reference_siconos.py [--out DIR] [--cases free_vibration,resonance]
        [--duration 5] [--max-impacts 20] [--rtol 1e-12] [--atol 1e-14]

For each case: the scenario cut to --duration (scoring window 0.5 s), the reference run with the Newton law
at its own settings (`impactbench run --engine reference --law newton`), and its modal model exported and
integrated by build/bench/siconos_reference (Siconos's event-driven scheme, Lsodar at --rtol and --atol) up
to --max-impacts impacts or 0.25 s past the reference's last impact compared. The first impacts of each are
compared in order: the largest difference of the impact times [s], of the approach velocities relative to
the reference's [-] and of the realised restitutions [-], with both CPU times (the reference's whole run,
summary.json's cpu_time_s, over the whole cut case; Siconos's integration up to where it stopped).

Writes DIR/comparison.json (the cases, the machine and its load average at the start and the end, the
versions) and DIR/comparison.md; reports/impactbench_report/performance.py tables comparison.json from
SUITE/performance/reference_siconos/. Exits 1 with a message naming the step when anything fails.
Agreement is asserted by bench/tests/test_siconos_reference.py, never speed.
"""
import argparse
import datetime
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from event_agreement import read_events  # noqa: E402
from reference_cvode_scipy import cut_scenario, load_average  # noqa: E402
from reference_vs_scipy import ROOT, ComparisonError, machine, read_json, run, scenario_path, versions  # noqa: E402

WINDOW_S = 0.5  # the cut cases' scoring window (at least one motor period, as the harness requires) [s]
# Siconos runs to the last impact compared plus this, not the whole case: its Lsodar at rtol 1e-12 costs
# about 10 s of CPU per simulated second, and an extra impact it found soon after would still show [s]
MARGIN_S = 0.25


def differences(siconos, reference, limit):
    """The first min(limit, both counts) impacts matched in order: their largest differences."""
    n = min(limit, len(siconos), len(reference))
    pairs = list(zip(siconos[:n], reference[:n]))
    return {
        "impacts_compared": n,
        "max_impact_time_difference_s": max((abs(a["onset_time_s"] - b["onset_time_s"]) for a, b in pairs),
                                            default=0.0),
        "max_approach_velocity_relative_difference": max(
            (abs(a["approach_velocity_m_s"] - b["approach_velocity_m_s"]) / abs(b["approach_velocity_m_s"])
             for a, b in pairs), default=0.0),
        "max_restitution_difference": max((abs(a["restitution"] - b["restitution"]) for a, b in pairs),
                                          default=0.0),
    }


def compare_case(args, case, out):
    name = os.path.basename(case).removesuffix(".toml")
    folder = os.path.join(out, "cases", name)
    os.makedirs(folder, exist_ok=True)
    scenario, duration, _ = cut_scenario(scenario_path(case), args.duration, WINDOW_S, os.path.join(out, "scenarios"))
    model = os.path.join(folder, "model.json")
    run([args.impactbench, "export", scenario, "--engine", "reference", "--law", "newton", "--out", model],
        f"{name}: export")
    reference_folder, siconos_folder = os.path.join(folder, "reference"), os.path.join(folder, "siconos")
    run([args.impactbench, "run", scenario, "--engine", "reference", "--law", "newton", "--out", reference_folder],
        f"{name}: the reference")
    reference = read_events(os.path.join(reference_folder, "events.csv"))
    compared = reference[:args.max_impacts]
    siconos_duration = min(duration, compared[-1]["onset_time_s"] + MARGIN_S) if compared else duration
    run([args.siconos, model, "--out", siconos_folder, "--max-impacts", str(args.max_impacts), "--duration",
         repr(siconos_duration), "--rtol", repr(args.rtol), "--atol", repr(args.atol)], f"{name}: Siconos")
    siconos = read_events(os.path.join(siconos_folder, "events.csv"))
    summary = read_json(os.path.join(reference_folder, "summary.json"), f"{name}: the reference's summary")
    sic = read_json(os.path.join(siconos_folder, "siconos_run.json"), f"{name}: Siconos's summary")
    with open(model, encoding="utf-8") as f:
        settings = json.load(f)["reference_settings"]
    result = {"case": name, "duration_s": duration, "folder": folder, "reference_impacts": len(reference),
              "siconos_impacts": len(siconos), "siconos_stopped_by": sic["stopped_by"],
              "siconos_duration_s": siconos_duration, "siconos_end_time_s": sic["end_time_s"],
              # Siconos stops after --max-impacts: up to there both must have found the same impacts
              "same_impact_count": len(siconos) == min(len(reference), args.max_impacts),
              **differences(siconos, reference, args.max_impacts),
              "reference_cpu_time_s": summary["cpu_time_s"], "siconos_cpu_time_s": sic["integration_cpu_time_s"],
              "reference_rtol": settings["rtol"], "reference_atol_m_sqrt_kg": settings["atol_m_sqrt_kg"],
              "siconos_rtol": sic["rtol"], "siconos_atol": sic["atol"], "siconos_version": sic["versions"]["siconos"]}
    print(f"[{name}] {result['impacts_compared']} impacts: times within {result['max_impact_time_difference_s']:.3g} s, "
          f"approach velocities {result['max_approach_velocity_relative_difference']:.3g}, restitution "
          f"{result['max_restitution_difference']:.3g}; CPU reference {result['reference_cpu_time_s']:.3g} s, "
          f"Siconos {result['siconos_cpu_time_s']:.3g} s", flush=True)
    return result


def write_markdown(record, path):
    lines = ["| case | impacts compared | max impact time difference [s] | max approach velocity difference [-] "
             "| max restitution difference [-] | reference CPU [s] | Siconos CPU [s] |",
             "|---|---|---|---|---|---|---|"]
    for c in record["cases"]:
        lines.append(f"| {c['case']} | {c['impacts_compared']} | {c['max_impact_time_difference_s']:.3g} | "
                     f"{c['max_approach_velocity_relative_difference']:.3g} | {c['max_restitution_difference']:.3g} | "
                     f"{c['reference_cpu_time_s']:.3g} | {c['siconos_cpu_time_s']:.3g} |")
    with open(path, "w", encoding="utf-8") as f:
        f.write("\n".join(lines) + "\n")


def parse_arguments():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    stamp = datetime.datetime.now().strftime("%Y-%m-%d_%H%M%S")
    parser.add_argument("--out", default=os.path.join(ROOT, "results", f"reference-siconos-{stamp}"))
    parser.add_argument("--impactbench", default=os.path.join(ROOT, "build", "cli", "impactbench"))
    parser.add_argument("--siconos", default=os.path.join(ROOT, "build", "bench", "siconos_reference"))
    parser.add_argument("--cases", default="free_vibration,resonance",
                        help="names in scenarios/paper or scenario files, comma-separated")
    parser.add_argument("--duration", type=float, default=5.0, help="cut longer cases to this [s] (default 5)")
    parser.add_argument("--max-impacts", type=int, default=20, help="impacts compared at most (default 20)")
    parser.add_argument("--rtol", type=float, default=1e-12, help="Lsodar's rtol (default 1e-12)")
    parser.add_argument("--atol", type=float, default=1e-14, help="Lsodar's atol (default 1e-14)")
    args = parser.parse_args()
    for name in ("duration", "rtol", "atol"):
        if not getattr(args, name) > 0:
            parser.error(f"--{name} {getattr(args, name)}: allowed: a number > 0")
    if args.max_impacts < 1:
        parser.error(f"--max-impacts {args.max_impacts}: allowed: an integer >= 1")
    for option, path in (("--impactbench", args.impactbench), ("--siconos", args.siconos)):
        if not os.access(path, os.X_OK):
            parser.error(f"{option} {path}: not an executable; build first (cmake with -DIMPACTBENCH_BENCH=ON)")
    return args


def main():
    args = parse_arguments()
    os.makedirs(args.out, exist_ok=True)
    started = datetime.datetime.now()
    record = {"started": started.isoformat(timespec="seconds"), "machine": machine(),
              "versions": versions(args.impactbench),
              "settings": {"max_duration_s": args.duration, "window_s": WINDOW_S, "max_impacts": args.max_impacts,
                           "siconos_rtol": args.rtol, "siconos_atol": args.atol},
              "cases": []}
    record["machine"]["proc_loadavg_at_start"] = load_average()
    try:
        for case in args.cases.split(","):
            record["cases"].append(compare_case(args, case, args.out))
    except ComparisonError as error:
        sys.exit(f"reference_siconos: {error}")
    if record["cases"]:
        record["versions"]["siconos"] = record["cases"][0]["siconos_version"]
        # the report's table names the comparator from here (reports/impactbench_report/performance.py)
        record["comparator"] = (f"Siconos {record['versions']['siconos']} (EventDriven, LsodarOSI at rtol "
                                f"{args.rtol:g}, atol {args.atol:g}; Newton impact LCPs)")
    record["machine"]["proc_loadavg_at_end"] = load_average()
    record["elapsed_s"] = (datetime.datetime.now() - started).total_seconds()
    with open(os.path.join(args.out, "comparison.json"), "w", encoding="utf-8") as f:
        json.dump(record, f, indent=2)
    write_markdown(record, os.path.join(args.out, "comparison.md"))
    print(f"reference_siconos: {len(record['cases'])} cases in {record['elapsed_s']:.0f} s; "
          f"{os.path.join(args.out, 'comparison.md')}")


if __name__ == "__main__":
    main()
