"""The report's first screen, rendered from the summary document (answer.py) in HTML and Markdown: the
fronts, what to use (id "answer"), the best configuration per case (id "cases"), one line per engine, then the settings behind every configuration and what
ran where. Every number printed here is in summary.json, which names the runs.csv row it came from."""

import html

from . import analysis, engines, operating_points
from .answer import error_text, warning_lines
from .tables import step_text

ANSWER_HEADER = ["case, law", "best out of the box: engine, step [s]", "largest error vs beam",
                 "largest stable step [s]", "CPU [s/s]", "best tuned: engine, contact, step [s]",
                 "largest error vs beam", "largest stable step [s]", "CPU [s/s]"]


def limit_text(limit):
    """The largest stable step and what bounds it: '5e-5 (1e-4 unstable)', '6.25e-5 (searched)', or
    '≥ 1e-4' when the largest step tried was stable."""
    step = limit.get("largest_stable_step_s")
    if step is None:
        return "none stable"
    bound = limit["bounded_by"]
    if bound == "a larger step was unstable":
        return f"{step_text(step)} ({step_text(limit['smallest_unstable_step_s'])} unstable)"
    if bound == "step search":
        return f"{step_text(step)} (searched)"
    return f"≥ {step_text(step)}"


def pick(case, kind):
    """(configuration entry, best run entry) of the case's best out-of-box or tuned configuration."""
    name = case["best_" + kind]["configuration"]
    if name is None:
        return None, None
    entry = next(c for c in case["configurations"] if c["configuration"] == name)
    return entry, entry["best_run"]


def answer_rows(document):
    """The answer table's rows, and its notes: an engine error vs its own chain that the error vs beam
    does not show, marked [n] in its cell."""
    rows, notes = [], []
    for case in document["cases"]:
        row = [f"{case['scenario']}, {case['law']}"]
        for kind in ("out_of_box", "tuned"):
            entry, run = pick(case, kind)
            if entry is None:
                row += [case["best_" + kind]["why"], "–", "–", "–"]
                continue
            cost = run["runs_csv"].get("cpu_time_per_simulated_s")
            name = engines.display_name(run["engine"])
            if kind == "tuned":
                name += " " + run["contact_path"]
            cell = error_text(run["largest_error_vs_beam"]) + single_run_mark(case, run) + verdict_mark(run)
            note = own_chain_note(run)
            if note:
                notes.append(f"[{len(notes) + 1}] {case['scenario']}, {case['law']}, {name}: {note}")
                cell += f" [{len(notes)}]"
            row += [f"{name}, {step_text(run['runs_csv']['time_step_s'])}" + tie_text(case["best_" + kind], name),
                    cell, limit_text(entry["step_limit"]), "–" if cost is None else f"{cost:.3g}"]
        rows.append(row)
        line = ensemble_line(case)
        if line:
            notes.append(f"[{len(notes) + 1}] {case['scenario']}, {case['law']}: {line}")
            rows[-1][0] += f" [{len(notes)}]"
    return rows, notes


def configuration_name(configuration):
    """'<display name> matched' for '<engine> [contact=matched]' (the tuned column's words)."""
    engine, _, options = configuration.partition(" [")
    return f"{engines.display_name(engine)} {analysis.contact_path_of(options.rstrip(']'))}"


def tie_text(best, name):
    """' = <display name> matched (within intervals)' where the best is not distinguishable from others."""
    tied = best.get("tied_with") or []
    if not tied:
        return ""
    return " = " + " = ".join(configuration_name(c) for c in tied) + " (within intervals)"


def ensemble_line(case):
    """Whether the case needed an ensemble and why (its reference's scatter over its starts); '' when the
    reference ran once (nothing measured: the report of single runs as it always was)."""
    need = case.get("ensemble_need") or {}
    if need.get("needed") is None:
        return ""
    text = (f"needed an ensemble ({need['why']})" if need["needed"]
            else f"no ensemble needed over {need['reference_starts']} reference starts ({need['why']})")
    if need.get("note"):
        text += f"; the engines ran once: {need['note']}"
    return text


def own_chain_note(run):
    """The run's largest error vs its own chain where it is beyond tolerance and not the one vs beam
    already shown: an engine error that the chain's own discretisation error hides (an engine's excess
    damping in the free vibration, say, cancelling the chain's deficit against the beam)."""
    own = run.get("largest_error_vs_own_chain")
    beam = run["largest_error_vs_beam"]
    if not own or own["tolerance_multiple"] <= 1:
        return ""
    if beam and own["metric"] == beam["metric"] and abs(own["error"] - beam["error"]) <= 0.1 * abs(beam["error"]) + 0.02:
        return ""
    return f"vs its own chain {error_text(own)} ✗ (the engine's contact and stepping alone)"


def single_run_mark(case, run):
    """' (single run (1 vs 12 starts))' where the error has no interval in a case where intervals exist."""
    largest = run["largest_error_vs_beam"]
    measured = (case.get("ensemble_need") or {}).get("needed") is not None or run.get("ensemble")
    if not largest or largest.get("half_width") is not None or not measured:
        return ""
    return " (" + largest["interval_method"].split(";")[0] + ")"


def verdict_mark(run):
    """✗ beyond the tolerances; with intervals, ? where one straddles its tolerance (undecided)."""
    largest = run["largest_error_vs_beam"]
    if not largest:
        return ""
    decided = largest.get("verdict")
    if decided is not None:
        return {"beyond": " ✗", "undecided": " ?"}.get(decided, "")
    return "" if largest["tolerance_multiple"] <= 1 else " ✗"


def html_page_top(document, facts, lead_front_html="", cases_fronts_html=""):
    """The page's first screen: the lead case's front (front_figures.py), what to use (operating_points.py,
    the element with id "answer"), every other case's front, then the table of the best configuration per case
    (id "cases"), the engines' lines, the warnings and the error convention."""
    parts = ["<h1>impactbench: which engine, which setting, what error, at what cost</h1>", lead_front_html,
             operating_points.html_section(document), cases_fronts_html,
             "<p class='lede'>For each case and contact law: the configuration that comes closest to the "
             "continuous-beam reference out of the box (the engine's own contact and defaults) and once tuned "
             "(the law matched in or injected into the engine), its largest headline error against the beam "
             "(✗: beyond the verdict's tolerance; ?: an interval straddles it), its largest stable time step and its CPU cost per simulated "
             "second (CPU [s/s]). ≥: the largest step tried was stable. The configurations' settings and every run are below; report/summary.json holds the "
             "same, each number with the runs.csv row it came from.</p>",
             table(ANSWER_HEADER, answer_rows(document)[0], "cases"),
             "<p class='notes'>" + "<br>".join(html.escape(n) for n in answer_rows(document)[1]) + "</p>",
             "<ul class='engines'>"]
    parts += [f"<li>{html.escape(s['line'])}</li>" for s in document["engines"]]
    parts.append("</ul>")
    parts.append(warnings_html(document.get("warnings", [])))
    tolerances = document["verdict_tolerances"]
    parts.append("<p class='convention'>Errors are signed and named by what they are measured against: "
                 "<b>vs beam</b>, the continuous-beam reference (the physical question), or <b>vs own chain</b>, "
                 "the reference solved on the engine's own K-link chain (the engine's contact handling and time "
                 "stepping alone). Verdicts judge the error vs own chain: inaccurate beyond "
                 f"{100 * tolerances['sensor_peak_relative_error']:g} % in either sensor peak, "
                 f"{100 * tolerances['contact_duration_relative_error']:g} % in the contact duration, "
                 f"{tolerances['impacts_per_cycle_difference']:g} in impacts per cycle or "
                 f"{100 * tolerances['log_decrement_relative_error']:g} % in the free decay's log decrement. "
                 "The best configuration is the one with the smallest largest error vs beam, measured in "
                 "multiples of these tolerances, then the cheaper. References carry no accuracy verdict."
                 + (ENSEMBLES_NOTE if has_ensembles(document) else "") + "</p>")

    return "\n".join(parts)


ENSEMBLES_NOTE = (" Where a configuration ran from several starts (an ensemble), an error is the difference of the "
                  "engine's and the reference's means ± its 95 % half-width (Welch-Satterthwaite; a metric's: Student "
                  "t), and a configuration is best only where Welch's interval of the difference of its score and "
                  "another's excludes 0; otherwise the row names the ties.")


def has_ensembles(document):
    """Whether any case's reference or best run ran from more than one start."""
    return any((c.get("ensemble_need") or {}).get("needed") is not None or
               any(e["best_run"] and e["best_run"].get("ensemble") for e in c["configurations"])
               for c in document["cases"])


def warnings_html(entries, unit="runs"):
    """The "Warnings" list (id "warnings"): what the results recorded as doubtful, on the first screen,
    where a reader of the answer sees it; "" when there is none."""
    if not entries:
        return ""
    return ("<h2 id='warnings'>Warnings</h2><ul class='warnings'>"
            + "".join(f"<li>{html.escape(line)}</li>" for line in warning_lines(entries, unit=unit)) + "</ul>")


def warnings_markdown(entries, unit="runs"):
    """The same list in Markdown: its lines, [] when there is none."""
    if not entries:
        return []
    return ["", "## Warnings", ""] + [f"- {line}" for line in warning_lines(entries, unit=unit)]


def html_settings_and_provenance(document, facts):
    rows = []
    for name, config in document["configurations"].items():
        text = "; ".join(f"{k}: {v}" for k, v in config["settings"].items())
        rows.append([name, text])
    parts = ["<h2 id='settings'>Settings behind every configuration</h2>",
             table(["configuration", "settings (from the run's own diagnostics, runs.jsonl)"], rows, "settings-table"),
             "<h2 id='provenance'>What ran</h2><dl>"]
    parts += [f"<dt>{html.escape(k)}</dt><dd>{html.escape(str(v))}</dd>" for k, v in facts.items()]
    parts.append("</dl>")
    return "\n".join(parts)


def table(header, rows, element_id=None):
    head = "".join(f"<th>{html.escape(h)}</th>" for h in header)
    body = "".join("<tr>" + "".join(f"<td>{html.escape(str(c))}</td>" for c in row) + "</tr>" for row in rows)
    attribute = f" id='{element_id}'" if element_id else ""
    return f"<table{attribute}><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>"


def markdown(document, facts, lead_front="", cases_fronts=""):
    from .tables import markdown as markdown_table
    lines = ["# impactbench: which engine, which setting, what error, at what cost", ""]
    lines += [lead_front, ""] if lead_front else []
    lines += operating_points.markdown(document)
    lines += [cases_fronts, ""] if cases_fronts else []
    lines += [markdown_table(ANSWER_HEADER, answer_rows(document)[0]), ""]
    lines += answer_rows(document)[1] + [""]
    lines += [f"- {s['line']}" for s in document["engines"]]
    lines += warnings_markdown(document.get("warnings", []))
    lines += ["", "## Settings behind every configuration", ""]
    lines += [f"- **{name}**: " + "; ".join(f"{k}: {v}" for k, v in c["settings"].items())
              for name, c in document["configurations"].items()]
    lines += ["", "## What ran", ""] + [f"- {k}: {v}" for k, v in facts.items()]
    return "\n".join(lines)


__all__ = ["html_page_top", "html_settings_and_provenance", "markdown", "warnings_html", "warnings_markdown"]
