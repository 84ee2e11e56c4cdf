#!/usr/bin/python3
"""Makes a suite's report from its saved results, without rerunning anything:

    reports/make_report.py SUITE_FOLDER [--out REPORT_FOLDER]

writes REPORT_FOLDER (default SUITE_FOLDER/report): index.html (self-contained: the SVG figures are
inside it), summary.md, figures/*.svg, and the runs.csv and runs.jsonl it was made from; with a
performance section when SUITE_FOLDER/performance/ holds bench/ measurements (impactbench_report/performance.py). Needs
Debian's python3-matplotlib (run with /usr/bin/python3)."""

import argparse
import datetime
import os
import platform
import shutil
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from impactbench_report import analysis, data, figures, performance, tables  # noqa: E402

CAVEATS = [
    "The experiment's figures (rig.md section 7) are data shown beside the simulators, not targets: the "
    "model the reference solves is not expected to match them everywhere.",
    "For the Newton (instantaneous) law the true peak acceleration excludes the impulses and is not comparable "
    "with the compliant laws; its sensor peak is (an impulse is a velocity jump spread over one sensor window).",
    "The resonance case is chaotic in this model: impact times of any two simulators drift apart within seconds, "
    "so the time-domain displacement error is of order one there. The headline errors are statistics over the "
    "scoring window (peaks, contact durations, impacts per cycle).",
    "With the corrected mode shapes the post-resonance case produces no impacts (the forced amplitude, 0.46 mm, "
    "stays below the 1 mm gap); the experiment reported about 8 impacts per beat.",
    "A fixed-step engine resolves a contact's duration in whole steps; its errors at long steps include that.",
    "Run times are the simulators' own (stepping only), measured on the machine named below.",
]


STEPS_NOTE = ("Largest stable and accurate time steps (steps.csv), found by bisection: stable means the verdict "
              "ok or inaccurate; accuracy is judged against the reference on the engine's own chain. Each step is "
              "exact to one grid step (a ratio of 2^(1/4)); a probe that reached the time limit decides nothing.")


def machine():
    model = ""
    try:
        with open("/proc/cpuinfo") as f:
            model = next((line.split(":", 1)[1].strip() for line in f if line.startswith("model name")), "")
    except OSError:
        pass
    return f"{model or platform.processor()} x {os.cpu_count()} cores, {platform.system()} {platform.release()}"


def provenance(suite):
    versions = sorted({f"{r['engine']}: {r['engine_version']}" for r in suite.runs if r["engine_version"]})
    steps = sorted({r.number("time_step_s") for r in suite.runs if r.number("time_step_s") > 0})
    rates = sorted({r.number("output_rate_hz") for r in suite.runs if r.number("output_rate_hz") > 0})
    return {
        "date": datetime.datetime.now().strftime("%Y-%m-%d %H:%M"),
        "machine": machine(),
        "engines": "; ".join(versions),
        "time steps [s]": ", ".join(f"{s:g}" for s in steps) or "adaptive only",
        "output rate [Hz]": ", ".join(f"{r:g}" for r in rates),
        "suite": os.path.abspath(suite.folder),
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("suite", help="a suite's output folder (holds runs.csv)")
    parser.add_argument("--out", help="report folder (default: SUITE/report)")
    args = parser.parse_args()
    if not os.path.exists(os.path.join(args.suite, "runs.csv")):
        sys.exit(f"make_report: {args.suite}/runs.csv: no such file (is this a suite's output folder?)")
    out = args.out or os.path.join(args.suite, "report")
    figures_folder = os.path.join(out, "figures")
    os.makedirs(figures_folder, exist_ok=True)

    try:
        suite = data.read_runs(args.suite)
        steps = data.read_steps(args.suite)  # None unless the suite searched steps (--find-steps)
    except data.ResultsError as error:
        sys.exit(f"make_report: {error}")
    experiment = data.read_experiment(os.path.join(os.path.dirname(os.path.abspath(__file__)), "experiment.toml"))
    facts = provenance(suite)
    versions = ", ".join(sorted({r["engine_version"] for r in suite.runs if r["engine_version"] and r["engine"] != "reference"}))
    stamp = f"impactbench, {facts['date']}, {facts['machine']}" + (f"; {versions}" if versions else "")

    sections = []  # (title, markdown text, html text, [figure paths])
    chosen_by_law = {}
    for scenario, law in suite.cases():
        runs = suite.runs_of(scenario, law)
        chosen = {config: analysis.best_step(runs, config) for config in analysis.configurations(runs)}
        chosen_by_law.setdefault(law, {})[scenario] = chosen
        header, rows = tables.case_table(suite, scenario, law, experiment)
        winner = tables.winner_line(suite, scenario, law)
        paths = [figures.error_against_cost(suite, scenario, law, figures_folder, stamp),
                 figures.sensor_time_history(suite, scenario, law, chosen, figures_folder, stamp),
                 figures.impact_zoom(suite, scenario, law, chosen, figures_folder, stamp)]
        markdown_text = tables.markdown(header, rows) + "\n\n" + winner
        html_text = tables.html_table(header, rows) + f"<p>{winner}</p>"
        steps_header, steps_rows = tables.steps_table(steps, scenario, law)
        if steps_rows:
            markdown_text += "\n\n" + STEPS_NOTE + "\n\n" + tables.markdown(steps_header, steps_rows)
            html_text += f"<p>{STEPS_NOTE}</p>" + tables.html_table(steps_header, steps_rows)
            paths.append(figures.step_limits(steps, scenario, law, figures_folder, stamp))
        sections.append((f"{scenario}, {law}", markdown_text, html_text, [p for p in paths if p]))
    for law in sorted(chosen_by_law):
        paths = [figures.stability_map(suite, law, figures_folder, stamp, steps),
                 figures.against_experiment(suite, law, chosen_by_law[law], experiment, figures_folder, stamp)]
        sections.append((f"{law}: stability and the experiment", "", "", [p for p in paths if p]))

    try:
        measured = performance.section(args.suite)  # SUITE/performance/: bench/ timings, if any were saved
    except ValueError as error:
        sys.exit(f"make_report: {error}")
    if measured:
        sections.append(("Performance", measured[0], measured[1], []))

    for name in ("runs.csv", "runs.jsonl"):
        source = os.path.join(args.suite, name)
        if os.path.exists(source) and os.path.abspath(out) != os.path.abspath(args.suite):
            shutil.copy(source, os.path.join(out, name))
    write_markdown(os.path.join(out, "summary.md"), facts, sections, out)
    write_html(os.path.join(out, "index.html"), facts, sections)
    print(f"report: {os.path.join(out, 'index.html')}, {os.path.join(out, 'summary.md')}")


def write_markdown(path, facts, sections, out):
    lines = ["# impactbench report", ""]
    lines += [f"- {name}: {value}" for name, value in facts.items()]
    lines += ["", "## Caveats", ""] + [f"- {c}" for c in CAVEATS]
    for title, text, _, paths in sections:
        lines += ["", f"## {title}", ""]
        if text:
            lines += [text, ""]
        lines += [f"![{os.path.basename(p)}]({os.path.relpath(p, out)})" for p in paths]
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


STYLE = """
body { font-family: sans-serif; margin: 1.5em auto; max-width: 1250px; padding: 0 1em; color: #222; }
h1 { font-size: 1.5em; } h2 { font-size: 1.2em; border-bottom: 1px solid #ccc; margin-top: 2em; }
table { border-collapse: collapse; font-size: 0.85em; margin: 0.8em 0; }
th, td { border: 1px solid #ccc; padding: 0.25em 0.5em; text-align: right; }
th { background: #f2f2f2; } td:first-child, th:first-child { text-align: left; }
figure { margin: 1em 0; } figure svg { width: 100%; height: auto; }
dl { display: grid; grid-template-columns: max-content auto; gap: 0.2em 1em; font-size: 0.9em; }
dt { font-weight: bold; } .caveats li { margin: 0.3em 0; }
"""


def inline_svg(path):
    with open(path) as f:
        text = f.read()
    return text[text.find("<svg"):]  # drop the XML prolog and doctype: the SVG sits inside the page


def write_html(path, facts, sections):
    import html
    parts = ["<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'>",
             "<meta name='viewport' content='width=device-width, initial-scale=1'>",
             f"<title>impactbench report</title><style>{STYLE}</style></head><body>",
             "<h1>impactbench report</h1><dl>"]
    parts += [f"<dt>{html.escape(k)}</dt><dd>{html.escape(v)}</dd>" for k, v in facts.items()]
    parts += ["</dl><h2>Caveats</h2><ul class='caveats'>"] + [f"<li>{html.escape(c)}</li>" for c in CAVEATS] + ["</ul>"]
    for title, _, table_html, paths in sections:
        parts.append(f"<h2>{html.escape(title)}</h2>{table_html}")
        parts += [f"<figure>{inline_svg(p)}</figure>" for p in paths]
    parts.append("</body></html>")
    with open(path, "w") as f:
        f.write("\n".join(parts))


if __name__ == "__main__":
    main()
