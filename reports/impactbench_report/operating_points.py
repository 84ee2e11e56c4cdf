"""What to use: each engine's two operating points and its authors' recommended configuration in the lead case
(fronts.py), the beam reference's own cost and distance to the experiment beside them, and every recommended
setting with its source; rendered for the first screen in HTML and Markdown from summary.json's cases."""

import html

from . import engines, fronts
from .answer import error_cell
from .tables import html_table, signed_text, step_text
from .tables import markdown as markdown_table


HEADER = ["engine", "which run", "settings, step [s]", "largest error vs own chain",
          "largest error vs beam (the chain's share)", "CPU [s/s]"]

# The three runs of each engine the table names, each answering its own question.
QUESTIONS = [("most_accurate", "most accurate contact handling (vs own chain)"),
             ("cheapest_within_tolerance_vs_beam", "cheapest within every tolerance of the beam"),
             ("recommended", "its authors' recommended configuration")]


def point_setting(point):
    """'matched, 5e-5' or 'matched; length_unit=cm, 5e-5': the options a user sets, then the step."""
    return f"{fronts.settings_text(point)}, {step_text(point['time_step_s'])}"


def operating_rows(case):
    """Each engine's two operating points and its recommended configuration in a case (fronts.py), then the
    beam reference's own cost and its distance to the experiment; and the notes the rows point to."""
    rows, notes = [], []
    for engine, entry in case["fronts"]["engines"].items():
        by_id = {p["job_id"]: p for p in entry["points"]}
        for key, question in QUESTIONS:
            point = entry[key]
            row = [engines.display_name(engine), question]
            if point is None:
                rows.append(row + [entry[key + "_why_none"], "–", "–", "–"])
                continue
            tied = [by_id[j] for j in point.get("tied_with_job_ids") or [] if j in by_id]
            ties = ("; tied within the noise with " + ", ".join(point_setting(p) for p in tied)) if tied else ""
            verdict = "" if point.get("passes_its_verdict", True) else " (fails its verdict: no run passes)"
            measured = (case.get("ensemble_need") or {}).get("needed") is not None
            own = point.get("largest_error_vs_own_chain")
            rows.append(row + [point_setting(point) + ties + verdict, error_cell(own, measured) if own else "no chain",
                               error_cell(point["largest_error_vs_beam"], measured) + chain_share(point),
                               "–" if point["cpu_time_per_simulated_s"] is None else f"{point['cpu_time_per_simulated_s']:.3g}"])
    reference = case.get("reference")
    if reference:
        cost = reference["runs_csv"].get("cpu_time_per_simulated_s")
        against = reference.get("vs_experiment_frame1_peak_relative_error")
        measured = case.get("experiment_frame1_peak_acceleration_g")
        peak = reference["runs_csv"].get("frame1_sensor_peak_acceleration_g")
        distance = ("–" if against is None else
                    f"vs experiment: frame 1 sensor peak {peak:.3g} g against the measured {measured:.4g} g "
                    f"({100 * against:+.1f} %)")
        rows.append(["beam reference (modal solver)", "its own model", "", "", distance,
                     "–" if cost is None else f"{cost:.2g}"])
        engine_costs = [e["most_accurate"]["cpu_time_per_simulated_s"] for e in case["fronts"]["engines"].values()
                        if e["most_accurate"] and e["most_accurate"]["cpu_time_per_simulated_s"]]
        if cost and engine_costs:
            notes.append(f"The beam reference costs {cost:.2g} s of CPU per simulated second, "
                         f"{min(engine_costs) / cost:.0f} times less than the cheapest engine's most accurate point.")
    return rows, notes


def chain_share(point):
    """' (chain -3.7 %)': the chain's share of the point's largest error vs beam, from its budget."""
    largest = point.get("largest_error_vs_beam")
    entry = ((point.get("budget") or {}).get("metrics") or {}).get(largest["metric"]) if largest else None
    if not entry or entry.get("chain") is None:
        return ""
    return f" (chain {signed_text(entry['chain'], entry['kind'])})"


def intro(case):
    return (f"What to use, {case['scenario']}, {case['law']}: three runs of each engine, each answering its own "
            "question. The most accurate contact handling is ranked by the error against the engine's own chain (what "
            "the engine controls; a run that passes its verdict first), with the runs the noise cannot tell from it; "
            "the cheapest within every tolerance of the beam is what a user gets at that chain (a run that passes "
            "its verdict first); the authors' recommended configuration, each setting with its source below. The "
            "error against the beam is the total, the chain's share of it in brackets (the budget figure above); "
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
