"""The report's tables as plain rows, rendered to Markdown and HTML. Numbers are formatted from the
values in runs.csv and nothing else, so that a table can be checked against the CSV."""

import html
import math

from . import analysis, metric_catalog

EXPERIMENT_NOTE = "experiment (rig.md section 7)"


def fmt(value, digits=4):
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "–"
    if isinstance(value, str):
        return value
    return f"{value:.{digits}g}"


def step_text(step):
    """A time step as short text: 1e-4, 6.25e-5."""
    mantissa, exponent = f"{step:.2e}".split("e")
    return f"{float(mantissa):g}e{int(exponent)}"


def signed_text(value, kind):
    """'+2.5 %' for a relative error (a fraction), '+0.14' for a difference; 'n/a' where not defined; an exact
    zero without a sign ('0', not '+0': no error has a direction)."""
    if value is None or math.isnan(value):
        return "n/a"
    if value == 0:
        return "0 %" if kind == "relative" else "0"
    return f"{100 * value:+.2g} %" if kind == "relative" else f"{value:+.2g}"


def percent(value):
    if math.isnan(value):
        return "–"
    return f"{100 * value:+.0f} %" if abs(value) >= 10 else f"{100 * value:+.3g} %"


def case_metrics():
    """The case table's metrics, the folder's scored ones: (label with unit, runs.csv column, error column without
    prefix, kind)."""
    return [(f"{m.label} [{m.unit}]", m.column, m.error_column, m.kind) for m in metric_catalog.SCORED]


def error_cell(run, column, kind, against):
    """A signed error: the row's, or with an ensemble the difference of the means ± its 95 % half-width."""
    value = analysis.signed_error(run, column, against)
    if math.isnan(value):
        return "–"
    text = percent(value) if kind == "relative" else f"{value:+.3g}"
    interval = analysis.error_interval(run, column, against)
    if interval is not None and interval.half_width is not None:
        text += f" ± {100 * interval.half_width:.2g} %" if kind == "relative" else f" ± {interval.half_width:.2g}"
    return text


def metric_cell(run, column):
    """A metric: the row's, or with an ensemble its mean ± its 95 % half-width (Student t)."""
    ensemble = run.ensemble
    interval = ensemble.metrics.get(column) if ensemble is not None else None
    if interval is None or interval.n <= 1:
        return fmt(run.number(column))
    return f"{fmt(interval.mean)} ± {interval.half_width:.2g}"


def starts(run):
    """How many starts a configuration ran from (1 for a single run)."""
    return 1 if run.ensemble is None else run.ensemble.n


def verdict_cell(run):
    if run["engine"] == "reference":
        return "reference (beam)" if run.is_beam_reference else "reference (chain: no verdict)"
    judged = "own chain" if not math.isnan(run.number("vs_chain_reference_frame1_sensor_peak_relative_error")) else "beam"
    text = run["verdict"] + (f" (vs {judged})" if run.stable else "")
    ensemble = run.ensemble
    if ensemble is not None and ensemble.n > 1:  # member 0's verdict; the others' where they differ
        unstable = ensemble.n - len(ensemble.stable_members)
        if unstable:
            text += f"; {unstable} of {ensemble.n} starts unstable"
    return text


def case_table(suite, scenario, law, experiment):
    """Every run of a case: each headline metric with its signed error vs beam and vs own chain (the
    reference a verdict judges against, named in the verdict cell), the CPU cost per simulated second,
    the verdict and its reason. Columns no run of the case defines are left out (impacts per cycle
    without a motor, the log decrement with one)."""
    runs = suite.runs_of(scenario, law)
    runs = sorted((r for r in runs if r["engine"]), key=lambda r: (r["engine"] != "reference", not r.is_beam_reference,
                                                                   r.config, r.number("time_step_s")))
    metrics = [m for m in case_metrics() if any(not math.isnan(r.number(m[1])) for r in runs)]
    header = ["configuration", "time step [s]"]
    with_starts = any(starts(r) > 1 for r in runs)  # a column only where an ensemble ran
    if with_starts:
        header.append("starts")
    for label, _, _, _ in metrics:
        header += [label, "vs beam", "vs own chain"]
    header += ["CPU [s per simulated s]", "verdict", "reason"]
    rows = []
    measured = experiment.get(scenario, {}).get("frame1_peak_acceleration_g")
    if measured is not None:
        cells = sum(([fmt(measured), "", ""] if m[1] == "frame1_sensor_peak_acceleration_g" else ["", "", ""]
                     for m in metrics), [])
        rows.append([EXPERIMENT_NOTE, ""] + ([""] if with_starts else []) + cells + ["", "data, not a target", ""])
    for run in runs:
        step = "adaptive" if run["engine"] == "reference" else fmt(run.number("time_step_s"))
        row = [run.config, step] + ([str(starts(run))] if with_starts else [])
        for _, column, error_column, kind in metrics:
            row += [metric_cell(run, column), error_cell(run, error_column, kind, "beam"),
                    error_cell(run, error_column, kind, "own chain")]
        row += [fmt(run.number("cpu_time_per_simulated_s"), 3), verdict_cell(run), run["reason"]]
        rows.append(row)
    return header, rows


def markdown(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(cell.replace("|", "\\|") for cell in row) + " |" for row in rows]
    return "\n".join(lines)


# From this many columns a table is "dense" (page_style.py): set smaller, so that it fits the page's width
# without breaking its numbers (a case table has three columns per metric).
DENSE_COLUMNS = 9


def html_table(header, rows):
    head = "".join(f"<th>{html.escape(h)}</th>" for h in header)
    body = "".join("<tr>" + "".join(f"<td>{html.escape(c)}</td>" for c in row) + "</tr>" for row in rows)
    dense = " class='dense'" if len(header) >= DENSE_COLUMNS else ""
    return f"<table{dense}><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>"


def step_cell(row, prefix):
    """A largest-step cell: the step, or why there is none (the search's status)."""
    value = row.number(f"{prefix}_largest_step_within_tolerance_s" if prefix != "stability" else "largest_stable_step_s")
    if not math.isnan(value):
        return fmt(value)
    status = row[f"{prefix}_status"]
    return status.replace("not applicable: ", "n/a: ") if status else "–"


def steps_table(steps, scenario, law):
    """From steps.csv: per engine configuration, the largest stable step, the smallest unstable step
    found, the largest step within tolerance per headline metric, and the search's cost and notes."""
    from .data import steps_of
    rows = steps_of(steps, scenario, law)
    if not rows:
        return None, None
    header = ["configuration", "largest stable step [s]", "smallest unstable step [s]"]
    for m in metric_catalog.STEP_SEARCHED:
        tolerance = rows[0].number(m.step_tolerance_column)
        header.append(f"{m.label} within {100 * tolerance:g} % up to [s]" if m.kind == "relative"
                      else f"{m.label} within {tolerance:g} up to [s]")
    header += ["probes", "probe run time [s]", "notes"]
    table = []
    for row in rows:
        table.append([row.config, step_cell(row, "stability"), fmt(row.number("smallest_unstable_step_s"))]
                     + [step_cell(row, m.step_prefix) for m in metric_catalog.STEP_SEARCHED]
                     + [fmt(row.number("probes")), fmt(row.number("probes_wall_time_s"), 3), row["notes"] or ""])
    return header, table
