"""The report's tables as plain rows, rendered to Markdown and HTML. Numbers are formatted from the
values in runs.csv and nothing else, so that a table can be checked against the CSV."""

import html
import math

from . import analysis

EXPERIMENT_NOTE = "experiment (rig.md section 7)"


def fmt(value, digits=4):
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "–"
    if isinstance(value, str):
        return value
    return f"{value:.{digits}g}"


def percent(value):
    return "–" if math.isnan(value) else f"{100 * value:+.3g} %"


def case_table(suite, scenario, law, experiment):
    """Per engine configuration: errors against the beam reference and cost at its best time step and
    at its largest stable step; the reference's and the experiment's own figures first."""
    header = ["simulator", "time step [s]", "frame 1 sensor peak [g]", "vs reference", "contact duration [s]",
              "vs reference", "impacts per cycle", "vs reference", "run time [s]", "verdict"]
    rows = []
    measured = experiment.get(scenario, {})
    if measured.get("frame1_peak_acceleration_g") is not None:
        rows.append([EXPERIMENT_NOTE, "", fmt(measured["frame1_peak_acceleration_g"]), "", "", "", "", "", "", ""])
    runs = suite.runs_of(scenario, law)
    reference = suite.beam_reference(scenario, law)
    if reference:
        rows.append(["reference (beam)", "adaptive", fmt(reference.number("frame1_sensor_peak_acceleration_g")), "",
                     fmt(reference.number("contact_duration_mean_s")), "", fmt(reference.number("impacts_per_cycle")), "",
                     fmt(reference.number("wall_time_s")), reference["verdict"]])
    for config in analysis.configurations(runs):
        for label, run in (("best step", analysis.best_step(runs, config)),
                           ("largest stable step", analysis.largest_stable_step(runs, config))):
            if run is None:
                rows.append([f"{config} ({label})", "none stable", "", "", "", "", "", "", "", ""])
                continue
            rows.append([f"{config} ({label})", fmt(run.number("time_step_s")),
                         fmt(run.number("frame1_sensor_peak_acceleration_g")),
                         percent(run.number("vs_reference_frame1_sensor_peak_relative_error")),
                         fmt(run.number("contact_duration_mean_s")),
                         percent(run.number("vs_reference_contact_duration_relative_error")),
                         fmt(run.number("impacts_per_cycle")),
                         fmt(run.number("vs_reference_impacts_per_cycle_difference"), 3),
                         fmt(run.number("wall_time_s")), run["verdict"]])
    return header, rows


def winner_line(suite, scenario, law):
    result = analysis.winner_at_equal_cost(suite.runs_of(scenario, law))
    if result is None:
        return "Fewer than two engine configurations ran stably: no comparison at equal run time."
    budget, config, score = result
    return (f"At equal run time (at most {budget:.3g} s, the cost of the slowest configuration's cheapest stable "
            f"run), the smallest largest-headline-error is {config}'s: {100 * score:.3g} %.")


def markdown(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(cell.replace("|", "\\|") for cell in row) + " |" for row in rows]
    return "\n".join(lines)


def html_table(header, rows):
    head = "".join(f"<th>{html.escape(h)}</th>" for h in header)
    body = "".join("<tr>" + "".join(f"<td>{html.escape(c)}</td>" for c in row) + "</tr>" for row in rows)
    return f"<table><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>"


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
    from .data import STEP_METRICS, STEP_TOLERANCE_COLUMNS, steps_of
    rows = steps_of(steps, scenario, law)
    if not rows:
        return None, None
    header = ["configuration", "largest stable step [s]", "smallest unstable step [s]"]
    for prefix, label, kind in STEP_METRICS:
        tolerance = rows[0].number(STEP_TOLERANCE_COLUMNS[prefix])
        header.append(f"{label} within {100 * tolerance:g} % up to [s]" if kind == "relative"
                      else f"{label} within {tolerance:g} up to [s]")
    header += ["probes", "probe run time [s]", "notes"]
    table = []
    for row in rows:
        table.append([row.config, step_cell(row, "stability"), fmt(row.number("smallest_unstable_step_s"))]
                     + [step_cell(row, prefix) for prefix, _, _ in STEP_METRICS]
                     + [fmt(row.number("probes")), fmt(row.number("probes_wall_time_s"), 3), row["notes"] or ""])
    return header, table
