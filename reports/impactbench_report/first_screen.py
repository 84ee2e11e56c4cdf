"""The report's first screen, rendered from the summary document (answer.py) in HTML and Markdown: the
fronts, what to use (id "answer"), the best configuration per case (id "cases"), one line per engine, then the settings behind every configuration and what
ran where. Every number printed here is in summary.json, which names the runs.csv row it came from."""

import html

from . import analysis, engines, front_order, fronts, operating_points
from .answer import error_cell, warning_lines
from .tables import step_text

ANSWER_HEADER = ["case, law", "best contact handling out of the box: engine, step [s] (largest stable)",
                 "largest error vs own chain", "vs beam (the chain's share)", "CPU [s/s]",
                 "best contact handling tuned: engine, contact, step [s] (largest stable)",
                 "largest error vs own chain", "vs beam (the chain's share)", "CPU [s/s]"]


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
            own = run.get("largest_error_vs_own_chain")
            measured = intervals_measured(case, run)
            own_cell = (error_cell(own, measured) + verdict_mark(run, "own_chain")) if own else "no chain"
            cell = error_cell(run["largest_error_vs_beam"], measured) + verdict_mark(run)
            cell += chain_share_text(case, run)
            row += [f"{name}, {step_text(run['runs_csv']['time_step_s'])} ({limit_text(entry['step_limit'])})"
                    + tie_text(case["best_" + kind], name), own_cell, cell, "–" if cost is None else f"{cost:.3g}"]
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


def intervals_measured(case, run):
    """Whether intervals exist in the case (its reference ran from several starts, or the run did)."""
    return bool((case.get("ensemble_need") or {}).get("needed") is not None or run.get("ensemble"))


def chain_share_text(case, run):
    """' (chain +24 %)': the chain's share of the run's largest error vs beam, from its point's budget (fronts)."""
    point = next((p for e in case["fronts"]["engines"].values() for p in e["points"] if p["job_id"] == run["job_id"]), None)
    return "" if point is None else operating_points.chain_share(point)


def verdict_mark(run, against="beam"):
    """✗ beyond the tolerances; with intervals, ? where one straddles its tolerance (undecided)."""
    largest = run["largest_error_vs_" + against]
    if not largest:
        return ""
    decided = largest.get("verdict")
    if decided is not None:
        return {"beyond": " ✗", "undecided": " ?"}.get(decided, "")
    return "" if largest["tolerance_multiple"] <= 1 else " ✗"


def lead_sentence(document):
    """The lead case's answer sentence (answer_sentence.py), '' without a case."""
    case = fronts.lead_case(document["cases"])
    return (case.get("answer") or {}).get("sentence", "") if case else ""


def other_sentences(document):
    """Every other case's answer sentence, in the cases' order."""
    lead = fronts.lead_case(document["cases"])
    return [c["answer"]["sentence"] for c in document["cases"] if c is not lead and c.get("answer")]


def html_page_top(document, facts, lead_front_html="", cases_fronts_html="", budget_html=""):
    """The page's first screen: the lead case's answer sentence (id "answer-sentence"), its front
    (front_figures.py) and its error budget (budget_figures.py), what to use (operating_points.py, the element
    with id "answer"), every other case's sentence (id "answers") and front, the observed orders of the fronts'
    lines (front_order.py, id "front-orders"), then the table of the best contact
    handling per case (id "cases"), the engines' lines, the warnings and the error convention."""
    sentence = lead_sentence(document)
    parts = ["<h1>impactbench: which engine, which setting, what error, at what cost</h1>",
             f"<p class='answer-sentence' id='answer-sentence'><b>{html.escape(sentence)}</b></p>" if sentence else "",
             lead_front_html, budget_html, operating_points.html_section(document),
             "<ul id='answers' class='answers'>" + "".join(f"<li>{html.escape(s)}</li>" for s in other_sentences(document))
             + "</ul>", cases_fronts_html, front_order.html_section(document),
             "<p class='lede'>For each case and contact law: the configuration whose contact handling comes closest to "
             "the reference on its own chain out of the box (the engine's own contact and defaults) and once tuned "
             "(the law matched in or injected into the engine), a run that passes its verdict first: its largest "
             "error against its own chain (what the engine controls), its largest error against the beam (what a "
             "user sees at that chain) with the chain's own share of it, (✗: beyond the verdict's tolerance; ?: an "
             "interval straddles it), its largest stable time step and its CPU cost per simulated second (CPU [s/s]). "
             "≥: the largest step tried was stable. The configurations' settings and every run are below; "
             "report/summary.json holds the same, each number with the runs.csv row it came from.</p>",
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
                 "An engine's contact handling is ranked by its largest error vs its own chain, in multiples of "
                 "these tolerances (a run that passes its verdict before one that fails it), then the cheaper; the "
                 "error vs beam is the total a user sees, of which the chain's share is the same for every engine "
                 "on that chain. References carry no accuracy verdict."
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


def markdown(document, facts, lead_front="", cases_fronts="", budget=""):
    from .tables import markdown as markdown_table
    lines = ["# impactbench: which engine, which setting, what error, at what cost", ""]
    lines += [f"**{lead_sentence(document)}**", ""] if lead_sentence(document) else []
    lines += [lead_front, ""] if lead_front else []
    lines += [budget, ""] if budget else []
    lines += operating_points.markdown(document)
    lines += [f"- {s}" for s in other_sentences(document)] + [""]
    lines += [cases_fronts, ""] if cases_fronts else []
    orders = front_order.markdown(document)
    lines += [orders, ""] if orders else []
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
