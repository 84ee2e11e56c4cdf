"""What to use: each engine's two operating points and its authors' recommended configuration in the lead case
(fronts.py), the beam reference's own cost and distance to the experiment beside them, and every recommended
setting with its source; rendered for the first screen in HTML and Markdown from summary.json's cases."""

import html

from . import engines, fronts
from .answer import error_text
from .tables import html_table, step_text
from .tables import markdown as markdown_table


HEADER = ["engine", "most accurate: settings, step [s]", "largest error vs beam", "CPU [s/s]",
          "cheapest within every tolerance of the beam: settings, step [s]", "largest error vs beam", "CPU [s/s]",
          "the authors' recommended configuration: settings, step [s]", "largest error vs beam", "CPU [s/s]"]


def point_setting(point):
    """'matched, 5e-5' or 'matched; length_unit=cm, 5e-5': the options a user sets, then the step."""
    return f"{fronts.settings_text(point)}, {step_text(point['time_step_s'])}"


def operating_rows(case):
    """Each engine's two operating points and its recommended configuration in a case (fronts.py), then the
    beam reference's own cost and its distance to the experiment; and the notes the rows point to."""
    rows, notes = [], []
    for engine, entry in case["fronts"]["engines"].items():
        row = [engines.display_name(engine)]
        for key in ("most_accurate", "cheapest_within_tolerance_vs_beam", "recommended"):
            point = entry[key]
            if point is None:
                row += [entry[key + "_why_none"], "–", "–"]
                continue
            tied = point.get("tied_with_job_ids") or []
            row += [point_setting(point) + (f" (tied within the noise with {len(tied)} more)" if tied else ""),
                    error_text(point["largest_error_vs_beam"]),
                    "–" if point["cpu_time_per_simulated_s"] is None else f"{point['cpu_time_per_simulated_s']:.3g}"]
        rows.append(row)
    reference = case.get("reference")
    if reference:
        cost = reference["runs_csv"].get("cpu_time_per_simulated_s")
        against = reference.get("vs_experiment_frame1_peak_relative_error")
        measured = case.get("experiment_frame1_peak_acceleration_g")
        peak = reference["runs_csv"].get("frame1_sensor_peak_acceleration_g")
        distance = ("–" if against is None else
                    f"vs experiment: frame 1 sensor peak {peak:.3g} g against the measured {measured:.4g} g "
                    f"({100 * against:+.1f} %)")
        rows.append(["beam reference (modal solver)", "its own model", distance,
                     "–" if cost is None else f"{cost:.2g}"] + [""] * (len(HEADER) - 4))
        engine_costs = [e["most_accurate"]["cpu_time_per_simulated_s"] for e in case["fronts"]["engines"].values()
                        if e["most_accurate"] and e["most_accurate"]["cpu_time_per_simulated_s"]]
        if cost and engine_costs:
            notes.append(f"The beam reference costs {cost:.2g} s of CPU per simulated second, "
                         f"{min(engine_costs) / cost:.0f} times less than the cheapest engine's most accurate point.")
    return rows, notes


def intro(case):
    return (f"What to use, {case['scenario']}, {case['law']}: each engine's most accurate run (with how many others the "
            "noise cannot tell from it) and its cheapest run within every verdict tolerance of the beam, from the "
            "runs on the fronts above; and its authors' recommended configuration, each setting with its source below; "
            "every case's in summary.json (fronts).")


def html_section(document):
    """The lead case's table, its notes and the recommended settings' sources; "" without a case."""
    case = fronts.lead_case(document["cases"])
    if case is None:
        return ""
    rows, notes = operating_rows(case)
    return (f"<p class='lede'>{html.escape(intro(case))}</p><div id='answer'>{html_table(HEADER, rows)}</div>"
            + "".join(f"<p class='notes'>{html.escape(n)}</p>" for n in notes) + sources_html(case))


def markdown(document):
    """The same in Markdown: its lines, [] without a case."""
    case = fronts.lead_case(document["cases"])
    if case is None:
        return []
    rows, notes = operating_rows(case)
    return [intro(case), "", markdown_table(HEADER, rows), ""] + notes + [""] + sources_markdown(case)




def sources(case):
    """[(engine display name, [setting entries])] of the engines whose recommended configuration ran in the case."""
    found = []
    for engine, entry in case["fronts"]["engines"].items():
        point = entry.get("recommended")
        if point:
            found.append((engines.display_name(engine), point.get("settings", [])))
    return found


def source_text(setting):
    words = f" “{setting['words']}”" if setting.get("words") else ""
    return f"{setting['setting']} ({setting['value_is']}): {setting['why']}.{words}"


def sources_html(case):
    items = []
    for name, settings in sources(case):
        lines = "".join(f"<li>{html.escape(source_text(s))}" + (f" <a href='{html.escape(s['source'])}'>source</a>"
                                                                 if s.get("source", "").startswith("https://") else
                                                                 f" ({html.escape(s['source'])})" if s.get("source") else "")
                        + "</li>" for s in settings)
        items.append(f"<li><b>{html.escape(name)}</b><ul>{lines}</ul></li>")
    if not items:
        return ""
    return ("<details class='recommended'><summary>The authors' recommended configurations, each setting with its "
            "source (docs/engines.md)</summary><ul>" + "".join(items) + "</ul></details>")


def sources_markdown(case):
    lines = []
    for name, settings in sources(case):
        lines.append(f"- **{name}**: " + "; ".join(source_text(s) + (f" ({s['source']})" if s.get("source") else "")
                                                    for s in settings))
    return (["The authors' recommended configurations, each setting with its source:", ""] + lines + [""]) if lines else []
