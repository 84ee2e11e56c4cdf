"""The tables of bench/reference_cvode_scipy.py: per case and law, each solver's CPU time per simulated second
at equal accuracy (the loosest tolerance tried at which its events meet the criterion against the truth)
and the ratios; per solver, the tolerances tried and the errors of its events. Files: comparison.json,
timings.csv, comparison.md."""
import os

from comparison_tables import write_record

SOLVERS = (("reference", "reference"), ("cvode", "CVODE"), ("scipy", "SciPy"))


def ratio(a, b):
    return a / b if a is not None and b else None


def summary_row(result):
    """One row per case and law: each solver's tolerance and CPU time per simulated second at equal accuracy,
    whether it met the criterion at all, and the ratios to the reference's."""
    s = result["solvers"]
    row = {"case": result["case"], "law": result["law"], "duration_s": result["duration_s"],
           "truth_events": result["truth_events"]}
    for key, _ in SOLVERS:
        row[f"{key}_rtol"] = s[key]["rtol"]
        row[f"{key}_met_criterion"] = s[key]["met"]
        row[f"{key}_cpu_time_s"] = s[key]["cpu_time_s"]
        row[f"{key}_cpu_time_per_simulated_s"] = s[key]["cpu_time_per_simulated_s"]
    reference = s["reference"]["cpu_time_per_simulated_s"]
    row["cvode_over_reference_cpu"] = ratio(s["cvode"]["cpu_time_per_simulated_s"], reference)
    row["scipy_over_reference_cpu"] = ratio(s["scipy"]["cpu_time_per_simulated_s"], reference)
    row["scipy_over_cvode_cpu"] = ratio(s["scipy"]["cpu_time_per_simulated_s"], s["cvode"]["cpu_time_per_simulated_s"])
    return row


def text(value, digits=3):
    if value is None:
        return "-"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, int):
        return str(value)
    return f"{value:.{digits}g}"


def cost(row, key):
    """'2.1e-3 s (rtol 1e-7)', a '*' where the criterion was met at no tolerance tried."""
    mark = "" if row[f"{key}_met_criterion"] else " *"
    return f"{text(row[f'{key}_cpu_time_per_simulated_s'])} ({text(row[f'{key}_rtol'], 2)}){mark}"


def markdown(record):
    m, v, s = record["machine"], record["versions"], record["settings"]
    start, end = m["proc_loadavg_at_start"], m["proc_loadavg_at_end"]
    lines = [
        "# The reference, CVODE and SciPy at equal accuracy",
        "",
        f"Machine: {m['cpu_model']}, {m['cpu_cores']} cores; load average (/proc/loadavg, 1 / 5 / 15 min) "
        f"{start[0]:.2f} / {start[1]:.2f} / {start[2]:.2f} at the start, {end[0]:.2f} / {end[1]:.2f} / {end[2]:.2f} at "
        f"the end. SUNDIALS {v.get('sundials', '?')} (CVODE, {s['cvode_method']}), Python {v['python']}, NumPy "
        f"{v['numpy']}, SciPy {v['scipy']} (solve_ivp, {s['scipy_method']}), impactbench {v['impactbench_commit']}. "
        f"Started {record['started']}, {record['elapsed_s']:.0f} s in all.",
        "",
        f"Equal accuracy: the same impact events as the reference at rtol {s['truth_rtol']:g}: the same number, "
        f"every onset and end within {s['time_tolerance_s']:g} s, every approach and rebound velocity within "
        f"{s['velocity_tolerance']:g} of the largest approach velocity. Each solver runs at rtol "
        f"{', '.join(f'{r:g}' for r in s['rtols'])} (atol = rtol x {s['atol_per_rtol_m_sqrt_kg']:g} m sqrt(kg)), "
        f"loosest first, until it meets that; its CPU time there (median of {s['repeat']} runs; SciPy's of fewer "
        "when long) over the simulated time is its cost. Cases cut to "
        f"{s['max_duration_s']:g} s, the output window to the last {s['window_s']:g} s. The reference's CPU time "
        "includes building its model and recording its output; CVODE's and SciPy's are their integrations'.",
        "",
        "| case | law | simulated [s] | events | reference: CPU s per simulated s (rtol) | CVODE | SciPy "
        "| CVODE / reference | SciPy / reference | SciPy / CVODE |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    for c in record["cases"]:
        r = c["summary"]
        lines.append(f"| {r['case']} | {r['law']} | {text(r['duration_s'])} | {r['truth_events']} | {cost(r, 'reference')} "
                     f"| {cost(r, 'cvode')} | {cost(r, 'scipy')} | {text(r['cvode_over_reference_cpu'])} "
                     f"| {text(r['scipy_over_reference_cpu'])} | {text(r['scipy_over_cvode_cpu'])} |")
    if any(not c["solvers"][k]["met"] for c in record["cases"] for k, _ in SOLVERS):
        lines += ["", "\\* met the criterion at no tolerance tried: the cost shown is at the tightest, a lower bound."]
    for c in record["cases"]:
        lines += ["", f"## {c['case']}, {c['law']} ({c['truth_events']} events in {c['duration_s']:g} s)", "",
                  "| solver | rtol | events | onset error [s] | end error [s] | velocity error | impulse error "
                  "| meets | CPU [s] |", "|---|---|---|---|---|---|---|---|---|"]
        for key, name in SOLVERS:
            for rung in c["solvers"][key]["ladder"]:
                lines.append(f"| {name} | {text(rung['rtol'], 2)} | {rung['events']} | {text(rung['onset_error_s'], 2)} "
                             f"| {text(rung['end_error_s'], 2)} | {text(rung['velocity_error'], 2)} "
                             f"| {text(rung['impulse_error'], 2)} | {text(rung['meets_criterion'])} "
                             f"| {text(rung['cpu_time_s'])} |")
    return "\n".join(lines) + "\n"


def write_outputs(record, out):
    write_record(record, out)
    with open(os.path.join(out, "comparison.md"), "w", encoding="utf-8") as f:
        f.write(markdown(record))
