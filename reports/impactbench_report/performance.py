"""The report's performance section, from the measurements saved in SUITE/performance/ (each optional):

- reference_benchmark.json, engine_step_benchmark.json, harness_overhead_benchmark.json: Google
  Benchmark's JSON (bench/run-benchmarks.sh), machine and versions in its context;
- scaling.json: the suite on 1, 2, ... workers (bench/suite_scaling.sh);
- reference_vs_scipy/comparison.json: the reference against SciPy's solve_ivp
  (bench/reference_vs_scipy.py --out SUITE/performance/reference_vs_scipy);
- reference_cvode_scipy/comparison.json: the reference, SUNDIALS CVODE and SciPy side by side, CPU time per
  simulated second at equal accuracy (bench/reference_cvode_scipy.py --out SUITE/performance/reference_cvode_scipy);
- reference_siconos/comparison.json: the reference's Newton impacts against a second Newton reference written in
  another library (bench/reference_siconos.py --out SUITE/performance/reference_siconos).

Every table says what machine and software it was measured with. Nothing here is computed from the
suite's runs: these are separate, repeated timings."""

import html
import json
import math
import os

from . import engines, tables

# bench/machine.sh's keys: the machine, then the package versions (the engines' from their descriptors).
MACHINE_KEYS = ["cpu_model", "cpu_cores", "memory_gib", "os", "compiler", *engines.repository_packages(),
                "libbenchmark-dev", "python3-scipy", "libsundials-dev", "impactbench_commit"]


def read_json(folder, name):
    path = os.path.join(folder, name)
    if not os.path.exists(path):
        return None
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError) as error:
        raise ValueError(f"{path}: not readable JSON ({error})")


def machine_line(machine):
    """'measured on: AMD EPYC x 2 cores, 23.5 GiB, ...' from bench/machine.sh's keys."""
    if not machine:
        return "measured on: (no machine record)"
    parts = [f"{machine.get('cpu_model', '?')} x {machine.get('cpu_cores', '?')} cores",
             f"{machine.get('memory_gib', '?')} GiB", machine.get("os", ""), machine.get("compiler", "")]
    versions = [f"{k} {machine[k]}" for k in MACHINE_KEYS[5:] if k in machine]
    return "measured on: " + ", ".join(p for p in parts if p) + ("; " + ", ".join(versions) if versions else "")


def benchmark_rows(document):
    """Google Benchmark's records by name, preferring the median aggregate when repetitions ran."""
    rows = {}
    for b in document.get("benchmarks", []):
        name = b.get("run_name", b["name"]).removesuffix("/real_time")
        if b.get("run_type") == "aggregate" and b.get("aggregate_name") != "median":
            continue
        if b.get("run_type") == "aggregate" or name not in rows:
            rows[name] = b
    return rows


def number(record, key):
    value = record.get(key)
    return float(value) if isinstance(value, (int, float)) else math.nan


def reference_table(document):
    header = ["case / law", "simulated s per wall s", "impacts", "time per run [ms]"]
    rows = [[name, tables.fmt(number(b, "sim_s_per_wall_s")), tables.fmt(number(b, "impacts")),
             tables.fmt(number(b, "real_time"))] for name, b in benchmark_rows(document).items()]
    return "The reference: each published case and law over its whole duration (rtol 1e-9, 10 modes per frame)", header, rows


def engine_step_table(document):
    header = ["engine / law", "us per step", "steps per run"]
    rows = [[name, tables.fmt(number(b, "us_per_step"), 3), tables.fmt(number(b, "steps"))]
            for name, b in benchmark_rows(document).items()]
    return "Each engine's cost per step on the rig (resonance, 2 s, matched path, default step)", header, rows


def overhead_table(document):
    header = ["engine / law", "through the harness [ms]", "bare loop [ms]", "harness overhead"]
    rows = [[name, tables.fmt(number(b, "harness_ms"), 3), tables.fmt(number(b, "bare_ms"), 3),
             f"{number(b, 'overhead_percent'):+.1f} %"] for name, b in benchmark_rows(document).items()]
    return ("The harness against a bare loop stepping the same engine model (resonance, 2 s, model building "
            "included; target under 5 %)", header, rows)


def scaling_table(document):
    header = ["workers", "suite wall time [s]", "jobs", "parallel efficiency"]
    rows = []
    for r in document.get("rows", []):
        efficiency = r.get("parallel_efficiency")
        rows.append([tables.fmt(r["workers"]), tables.fmt(r["wall_time_s"]), tables.fmt(r["jobs"]),
                     "–" if efficiency is None else f"{100 * efficiency:.1f} %"])
    duration = document.get("duration_option") or "the default"
    return (f"Suite scaling: {document.get('suite', 'the default suite')}, run duration {duration} "
            "(target: efficiency above 90 %)", header, rows)


def scipy_table(document):
    header = ["case / law", "simulated [s]", "reference [s]", "SciPy solve_ivp [s]", "speed ratio (wall)",
              "speed ratio (CPU)", "largest difference", "error: reference", "error: SciPy"]
    rows = []
    for c in document.get("cases", []):
        r = c.get("summary", {})
        rows.append([f"{r.get('case', '?')} / {r.get('law', '?')}", tables.fmt(r.get("duration_s")),
                     tables.fmt(r.get("reference_wall_time_s"), 3), tables.fmt(r.get("scipy_integration_time_s"), 3),
                     tables.fmt(r.get("speed_ratio"), 3), tables.fmt(r.get("speed_ratio_cpu"), 3),
                     tables.fmt(r.get("largest_relative_difference"), 2), tables.fmt(r.get("largest_reference_error"), 2),
                     tables.fmt(r.get("largest_scipy_error"), 2)])
    settings = document.get("settings", {})
    title = (f"The reference against SciPy's solve_ivp ({settings.get('method', '?')}) on the same modal equations at "
             f"the same tolerance (rtol {settings.get('rtol', '?')}); errors against the reference at rtol "
             f"{settings.get('tight_rtol', '?')}")
    return title, header, rows


def three_way_cost(summary, key):
    """'0.0021 (rtol 1e-07)': a solver's CPU time per simulated second at equal accuracy and its tolerance there;
    ' *' where it met the criterion at no tolerance tried (the cost shown is then at the tightest)."""
    value = summary.get(f"{key}_cpu_time_per_simulated_s")
    if value is None:
        return "–"
    mark = "" if summary.get(f"{key}_met_criterion") else " *"
    return f"{tables.fmt(value, 3)} (rtol {tables.fmt(summary.get(f'{key}_rtol'), 2)}){mark}"


def three_way_table(document):
    header = ["case / law", "simulated [s]", "events", "reference: CPU s per simulated s", "CVODE", "SciPy solve_ivp",
              "CVODE / reference", "SciPy / reference"]
    rows = []
    for c in document.get("cases", []):
        r = c.get("summary", {})
        rows.append([f"{r.get('case', '?')} / {r.get('law', '?')}", tables.fmt(r.get("duration_s")),
                     tables.fmt(r.get("truth_events")), three_way_cost(r, "reference"), three_way_cost(r, "cvode"),
                     three_way_cost(r, "scipy"), tables.fmt(r.get("cvode_over_reference_cpu"), 3),
                     tables.fmt(r.get("scipy_over_reference_cpu"), 3)])
    s, m = document.get("settings", {}), document.get("machine", {})
    load = [m.get("proc_loadavg_at_start"), m.get("proc_loadavg_at_end")]
    load_text = " and ".join(f"{x[0]:.2f}" for x in load if x) or "?"
    title = (f"The reference, SUNDIALS CVODE ({s.get('cvode_method', '?')}) and SciPy's solve_ivp "
             f"({s.get('scipy_method', '?')}) at equal accuracy: CPU time per simulated second, each at the loosest "
             f"tolerance whose events match the reference's at rtol {s.get('truth_rtol', '?')} (same count, onsets and "
             f"ends within {s.get('time_tolerance_s', '?')} s, velocities within {s.get('velocity_tolerance', '?')}); "
             f"a * marks a solver that met it at no tolerance tried (its cost then at the tightest, a lower bound); "
             f"load average {load_text} at the start and at the end")
    return title, header, rows


def second_newton_table(document):
    """The reference's first Newton impacts against the second Newton reference's (issue 49); the comparator is
    named by the file (its library and version), so that no engine name is written here."""
    header = ["case", "simulated [s]", "impacts compared", "largest impact time difference [s]",
              "largest approach velocity difference [-]", "largest restitution difference [-]", "reference CPU [s]",
              "comparator CPU [s]"]
    rows = []
    for c in document.get("cases", []):
        rows.append([c.get("case", "?"), tables.fmt(c.get("duration_s")), tables.fmt(c.get("impacts_compared")),
                     tables.fmt(c.get("max_impact_time_difference_s"), 2),
                     tables.fmt(c.get("max_approach_velocity_relative_difference"), 2),
                     tables.fmt(c.get("max_restitution_difference"), 2), tables.fmt(c.get("reference_cpu_time_s"), 3),
                     tables.fmt(c.get("siconos_cpu_time_s"), 3)])
    m = document.get("machine", {})
    load = [m.get("proc_loadavg_at_start"), m.get("proc_loadavg_at_end")]
    load_text = " and ".join(f"{x[0]:.2f}" for x in load if x) or "?"
    title = (f"The reference's Newton impacts against a second Newton reference, {document.get('comparator', '?')}: "
             f"the first impacts of each matched in order (the approach velocity relative to the reference's); "
             f"the reference's CPU time is its whole run, the comparator's its integration up to its last impact "
             f"compared or the end; load average {load_text} at the start and at the end")
    return title, header, rows


READERS = [("reference_benchmark.json", reference_table, lambda d: d.get("context")),
           ("engine_step_benchmark.json", engine_step_table, lambda d: d.get("context")),
           ("harness_overhead_benchmark.json", overhead_table, lambda d: d.get("context")),
           ("scaling.json", scaling_table, lambda d: d.get("machine")),
           ("reference_vs_scipy/comparison.json", scipy_table, lambda d: d.get("machine")),
           ("reference_cvode_scipy/comparison.json", three_way_table, lambda d: d.get("machine")),
           ("reference_siconos/comparison.json", second_newton_table, lambda d: d.get("machine"))]


def section(suite_folder):
    """(markdown, html) of the performance section, or None when the suite folder has no measurements."""
    folder = os.path.join(suite_folder, "performance")
    if not os.path.isdir(folder):
        return None
    markdown_parts, html_parts = [], []
    for name, reader, machine in READERS:
        document = read_json(folder, name)
        if document is None:
            continue
        title, header, rows = reader(document)
        line = machine_line(machine(document)) + f" (performance/{name})"
        markdown_parts.append(f"**{title}**\n\n{tables.markdown(header, rows)}\n\n{line}")
        html_parts.append(f"<h3>{html.escape(title)}</h3>{tables.html_table(header, rows)}"
                          f"<p><small>{html.escape(line)}</small></p>")
    if not markdown_parts:
        return None
    return "\n\n".join(markdown_parts), "".join(html_parts)
