"""The tables of bench/reference_vs_scipy.py: per case and law, the metrics of the reference, of SciPy and
of the tight reference (as `impactbench score --json` gives them, the names of runs.csv), their differences
and each one's error; and the files: comparison.json, timings.csv, metrics.csv, comparison.md."""
import csv
import json
import math
import os

# What score --json prints besides metrics, and metrics set by the scenario alone (equal by construction).
NOT_COMPARED = {"run_folder", "scenario_file", "reference_folder", "window_start_s", "window_end_s",
                "excitation_cycles", "beat_period_s"}
COUNTS = {"impacts", "raw_onsets"}  # compared as differences, not relative
DISPLACEMENT = ("frame1_displacement_relative_rms_error", "frame2_displacement_relative_rms_error")


def relative(value, against):
    if value is None or against is None:
        return None
    if against == 0:
        return 0.0 if value == 0 else None
    return (value - against) / abs(against)


def difference(value, against):
    return None if value is None or against is None else value - against


def metric_rows(result):
    """One row per metric: the three values, SciPy - reference (relative; counts: absolute), and the error of
    each against the tight reference; then the displacement RMS differences (RMS(u - u_other) / RMS(u_other))."""
    s = result["scores"]
    rows = []
    for name, tight in s["tight"].items():
        if name in NOT_COMPARED or name.startswith("vs_reference_"):
            continue
        ref, sci = s["reference"][name], s["scipy"][name]
        if ref is None and sci is None and tight is None:
            continue
        compare = difference if name in COUNTS else relative
        rows.append({"metric": name, "tight_reference": tight, "reference": ref, "scipy": sci,
                     "kind": "difference" if name in COUNTS else "relative",
                     "scipy_vs_reference": compare(sci, ref), "reference_error": compare(ref, tight),
                     "scipy_error": compare(sci, tight)})
    for name in DISPLACEMENT:
        key = "vs_reference_" + name
        rows.append({"metric": name, "tight_reference": 0.0, "reference": None, "scipy": None, "kind": "rms",
                     "scipy_vs_reference": s["scipy_vs_reference"][key], "reference_error": s["reference"][key],
                     "scipy_error": s["scipy"][key]})
    return rows


def largest(rows, field, kinds=("relative", "rms")):
    values = [abs(r[field]) for r in rows if r["kind"] in kinds and r[field] is not None]
    return max(values) if values else None


def summary_row(result):
    rows, t = metric_rows(result), result["timing"]
    counts = {r["metric"]: r for r in rows if r["kind"] == "difference"}
    reference_error, scipy_error = largest(rows, "reference_error"), largest(rows, "scipy_error")
    return {
        "case": result["case"], "law": result["law"], "duration_s": result["duration_s"],
        "scoring_window_s": result["scoring_window_s"], "cut": result["cut"],
        "reference_wall_time_s": t["reference_wall_time_s"], "scipy_integration_time_s": t["scipy_integration_time_s"],
        "reference_cpu_time_s": t["reference_cpu_time_s"], "scipy_integration_cpu_time_s": t["scipy_integration_cpu_time_s"],
        "scipy_output_time_s": t["scipy_output_time_s"], "scipy_rhs_evaluations": t["scipy_rhs_evaluations"],
        "speed_ratio": t["speed_ratio"], "speed_ratio_cpu": t["speed_ratio_cpu"],
        "speed_ratio_with_output": (t["scipy_integration_time_s"] + t["scipy_output_time_s"]) / t["reference_wall_time_s"],
        "impacts_reference": counts["impacts"]["reference"], "impacts_scipy": counts["impacts"]["scipy"],
        "raw_onsets_reference": counts["raw_onsets"]["reference"], "raw_onsets_scipy": counts["raw_onsets"]["scipy"],
        "largest_relative_difference": largest(rows, "scipy_vs_reference"),
        "largest_reference_error": reference_error, "largest_scipy_error": scipy_error,
        # at the same tolerance; when SciPy is the less accurate, equal accuracy would need it tighter, slower
        "reference_at_least_as_accurate": None if reference_error is None or scipy_error is None
        else reference_error <= scipy_error,
        "at_least_100x": t["speed_ratio"] >= 100,
    }


def text(value, digits=3):
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return "-"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, int) or (isinstance(value, float) and value.is_integer() and abs(value) < 1e6):
        return str(int(value))
    return f"{value:.{digits}g}"


def markdown(record):
    m, v, s = record["machine"], record["versions"], record["settings"]
    lines = [
        "# The reference against SciPy's solve_ivp",
        "",
        f"Machine: {m['cpu_model']}, {m['cpu_cores']} cores (load average {m['load_average_1_5_15_min_at_start'][0]:.2f} at "
        f"the start, {m['load_average_1_5_15_min_at_end'][0]:.2f} at the end: timings are approximate when the "
        "machine is shared). "
        f"Python {v['python']}, NumPy {v['numpy']}, SciPy {v['scipy']}, impactbench {v['impactbench_commit']}. "
        f"Started {record['started']}, {record['elapsed_s']:.0f} s in all.",
        "",
        f"Both solvers at rtol {s['rtol']:g}, atol {s['atol_m_sqrt_kg']:g} m sqrt(kg); SciPy with solve_ivp's "
        f"{s['method']}. Errors are against the reference at rtol {s['tight_rtol']:g}, atol "
        f"{s['tight_atol_m_sqrt_kg']:g}. Cases longer than {s['max_duration_s']:g} s are cut to it (the scoring "
        "window kept, no longer than the run): "
        + (", ".join(sorted({f"{c['case']} to {c['duration_s']:g} s (scored over the last {c['scoring_window_s']:g} s)"
                             for c in record["cases"] if c["cut"]})) or "none was") + ".",
        "",
        "Speed ratio: SciPy's integration time (solve_ivp calls with their event location and dense output, the "
        f"median of up to {s['repeat']} runs) over the reference's wall time (summary.json, median of "
        f"{s['repeat']}), which includes recording the series and its exact peaks; SciPy's recording is the "
        "output column, and the ratio with it follows. CPU time ratio: the same with both CPU times (less "
        "sensitive to other work on the machine). SciPy f evaluations: right-hand side evaluations, a cost that "
        "no load changes. Largest difference: the largest |SciPy - reference| / "
        "|reference| over the metrics (and RMS(u_SciPy - u_ref) / RMS(u_ref) of the tip displacements); errors: the "
        "same against the tight reference.",
        "",
        "| case | law | simulated [s] | reference [s] | SciPy [s] | SciPy output [s] | speed ratio | CPU time ratio "
        "| with output | SciPy f evaluations | impacts ref / SciPy | largest difference | error: reference "
        "| error: SciPy | reference as accurate | >= 100x |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for c in record["cases"]:
        r = c["summary"]
        lines.append(
            f"| {r['case']} | {r['law']} | {text(r['duration_s'])} | {r['reference_wall_time_s']:.4f} | "
            f"{r['scipy_integration_time_s']:.2f} | {r['scipy_output_time_s']:.2f} | {r['speed_ratio']:.0f} | "
            f"{text(r['speed_ratio_cpu'] and round(r['speed_ratio_cpu']))} | {r['speed_ratio_with_output']:.0f} | "
            f"{r['scipy_rhs_evaluations']:.3g} | {text(r['impacts_reference'])} / {text(r['impacts_scipy'])} | "
            f"{text(r['largest_relative_difference'], 2)} | {text(r['largest_reference_error'], 2)} | "
            f"{text(r['largest_scipy_error'], 2)} | {text(r['reference_at_least_as_accurate'])} | "
            f"{text(r['at_least_100x'])} |")
    if any(c["summary"]["largest_reference_error"] == 0 for c in record["cases"]):
        lines += ["", "An error of 0 for the reference means that its tight run gave the same numbers: its tolerances "
                  "act only inside compliant contacts, so with the Newton law (closed-form flight and the impulse map) "
                  "the tight run is the same run, and measures nothing but SciPy's error."]
    for c in record["cases"]:
        lines += ["", f"## {c['case']}, {c['law']}", "",
                  "| metric | tight reference | reference | SciPy | SciPy vs reference | reference error | SciPy error |",
                  "|---|---|---|---|---|---|---|"]
        for r in c["metrics"]:
            lines.append(f"| {r['metric']} | {text(r['tight_reference'], 10)} | {text(r['reference'], 10)} | "
                         f"{text(r['scipy'], 10)} | {text(r['scipy_vs_reference'], 2)} | "
                         f"{text(r['reference_error'], 2)} | {text(r['scipy_error'], 2)} |")
    lines += ["", "Counts (impacts, raw_onsets) are compared as differences, the displacement rows as relative RMS "
              "differences, every other metric relatively."]
    return "\n".join(lines) + "\n"


def write_record(record, out):
    """OUT/comparison.json (everything) and OUT/timings.csv (each case's summary row): what every comparator writes."""
    with open(os.path.join(out, "comparison.json"), "w", encoding="utf-8") as f:
        json.dump(record, f, indent=2)
        f.write("\n")
    summaries = [c["summary"] for c in record["cases"]]
    with open(os.path.join(out, "timings.csv"), "w", newline="", encoding="utf-8") as f:
        writer = csv.DictWriter(f, fieldnames=list(summaries[0]))
        writer.writeheader()
        writer.writerows(summaries)


def write_outputs(record, out):
    write_record(record, out)
    with open(os.path.join(out, "metrics.csv"), "w", newline="", encoding="utf-8") as f:
        fields = ["case", "law"] + list(record["cases"][0]["metrics"][0])
        writer = csv.DictWriter(f, fieldnames=fields)
        writer.writeheader()
        for c in record["cases"]:
            for r in c["metrics"]:
                writer.writerow({"case": c["case"], "law": c["law"], **r})
    with open(os.path.join(out, "comparison.md"), "w", encoding="utf-8") as f:
        f.write(markdown(record))
