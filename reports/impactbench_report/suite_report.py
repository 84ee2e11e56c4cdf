"""A suite's or a study's report from its saved results: its answer (answer.py) and first screen, every case's
figures and tables, every law's stability map, a study's sweeps, the performance section; written as index.html and
summary.md (page_writer.py) beside summary.json. make_report.py is its entry point."""

import datetime
import html
import json
import math
import multiprocessing
import os
import shutil
import sys

from . import answer, data, figures, first_screen, machine, metric_catalog, report_views, tables
from . import budget_figures, front_figures, step_figures, zoom_figures
from . import dynamics, named_runs, spectral, sweep, sweep_starts, validation
from .page_writer import anchor, figure_html, html_head, markdown_figure, sections_html, sections_markdown

CAVEATS = [
    "The experiment's figures (rig.md section 7) are data shown beside the simulators, not targets: the "
    "model the reference solves is not expected to match them everywhere.",
    "For the Newton (instantaneous) law the true peak acceleration excludes the impulses and is not comparable "
    "with the compliant laws; its sensor peak is (an impulse is a velocity jump spread over one sensor window).",
    "The resonance case is chaotic in this model: impact times of any two simulators drift apart within seconds, "
    "so the time-domain displacement error is of order one there. The headline errors are statistics over the "
    "scoring window (peaks, contact durations, impacts per cycle).",
    "With the corrected mode shapes the post-resonance case produces no impacts (the forced amplitude, 0.46 mm, "
    "stays below the 1 mm gap); the experiment reported about "
    f"{sweep.POST_RESONANCE['impacts_per_beat']:g} impacts per beat.",  # experiment.toml's
    "A fixed-step engine resolves a contact's duration in whole steps; its errors at long steps include that.",
    "Costs are the simulators' own CPU time (stepping only) per simulated second, measured on the machine "
    "named above under the load average stated there; wall times are in runs.csv.",
]


STEPS_NOTE = ("Largest stable and accurate time steps (steps.csv), found by bisection: stable means the verdict "
              "ok or inaccurate; accuracy is judged against the reference on the engine's own chain. Each step is "
              "exact to one grid step (a ratio of 2^(1/4)); a probe that reached the time limit decides nothing.")


def read_commands(folder):
    """OUT/commands.jsonl: the suite commands that wrote the folder, with the verdict tolerances they
    used; [] for a folder that predates it."""
    path = os.path.join(folder, "commands.jsonl")
    commands = []
    if os.path.exists(path):
        with open(path) as f:
            for line in f:
                try:
                    commands.append(json.loads(line))
                except json.JSONDecodeError:
                    pass  # a line cut by an interruption: the others still name the commands
    return commands


def provenance(suite, commands, ran_on):
    """What ran, where (ran_on: machine.Machine) and under what load: the page's "What ran" list and summary.json's
    "suite"."""
    versions = sorted({f"{r['engine']}: {r['engine_version']}" for r in suite.runs if r["engine_version"]})
    scenarios = {}
    for r in suite.runs:
        if r["scenario"] and r["engine"] and r["scenario"] not in scenarios:
            scenarios[r["scenario"]] = (f"{r.number('duration_s'):g} s simulated, scored over "
                                        f"{r.number('window_start_s'):g}-{r.number('window_end_s'):g} s")
    loads = sorted(r.number("load_average") for r in suite.runs if not math.isnan(r.number("load_average")))
    steps = sorted({r.number("time_step_s") for r in suite.runs if r.number("time_step_s") > 0 and r["engine"] != "reference"})
    return {
        "made": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
        "commands": "; ".join(c.get("command", "?") + f" (started {c.get('started_utc', '?')})" for c in commands)
                    or "not recorded (a results folder older than commands.jsonl)",
        "cases": "; ".join(f"{name}: {text}" for name, text in scenarios.items()),
        "time steps [s]": ", ".join(f"{s:g}" for s in steps) or "adaptive only",
        "machine": ran_on.line,
        "load average during the runs (1 min)": (f"{loads[0]:.2f} to {loads[-1]:.2f}, median {loads[len(loads) // 2]:.2f}"
                                                 + (f" on {ran_on.cores} cores" if ran_on.cores else "")) if loads
                                                else "not recorded",
        "engines": "; ".join(versions),
        "suite folder": os.path.abspath(suite.folder),
    }


DYNAMICS = [dynamics.acceleration_histories, dynamics.phase_portraits, dynamics.poincare_sections, spectral.spectra,
            spectral.scalograms, dynamics.impact_distributions, dynamics.amplitude_decay]


def case_figures(suite, scenario, law, chosen, steps, tolerances, folder, stamp, summary_case):
    """A case's figures in reading order: error against cost, its error budget (budget_figures.py, from
    summary.json's case), the impact zoom, the researcher's views (dynamics.py, spectral.py), the step search's
    limits."""
    paths = [figures.error_against_cost(suite, scenario, law, folder, stamp, tolerances),
             budget_figures.case_figure(summary_case, tolerances, folder, budget_figures.figure_name(summary_case), stamp),
             zoom_figures.impact_zoom(suite, scenario, law, chosen, folder, stamp)]
    # The researcher's views compare series: only the runs that kept one (a step search's probes keep
    # none), and none at all when no engine run did (a panel per simulator saying "no series" is no view).
    with_series = {name: run for name, run in chosen.items() if suite.has_series(run)}
    if with_series:
        for view in DYNAMICS:
            paths.append(view(suite, scenario, law, with_series, folder, stamp))
    if data.steps_of(steps, scenario, law):
        paths.append(step_figures.step_limits(steps, scenario, law, folder, stamp))
    return [p for p in paths if p]


_CASES = {}  # what the worker processes draw from, set before they fork (nothing is pickled but the answer)


def _draw(task):
    """One task's figures: a case's (task ("case", index)), a law's stability map and comparison with
    the experiment (task ("law", law)), a frequency sweep's sections (task ("sweep", index)), figures and
    tables, or the fronts' two figures (task ("fronts", None))."""
    c = _CASES
    kind, key = task
    if kind == "fronts":
        return (front_figures.lead_figure(c["summary_cases"], c["folder"], c["stamp"]),
                front_figures.cases_figure(c["summary_cases"], c["folder"], c["stamp"]),
                budget_figures.lead_figure(c["summary_cases"], c["tolerances"], c["folder"], c["stamp"]))
    if kind == "case":
        scenario, law, chosen = c["cases"][key]
        return case_figures(c["suite"], scenario, law, chosen, c["steps"], c["tolerances"], c["folder"], c["stamp"],
                            c["summary_cases"][key])
    if kind == "sweep":
        name, data_of_sweep = c["sweeps"][key]
        return sweep.sections(data_of_sweep, c["folder"], c["stamp"], f"Frequency sweep ({name})")
    paths = [step_figures.stability_map(c["suite"], key, c["folder"], c["stamp"], c["steps"]),
             zoom_figures.against_experiment(c["suite"], key, c["chosen_by_law"][key], c["experiment"], c["folder"],
                                             c["stamp"])]
    return [p for p in paths if p]


def case_line(case):
    """What a case is: its law's stiffness, its duration and scoring window."""
    k = case["contact_stiffness"]
    parts = [f"contact law {case['law']}" + (f", k = {k['value']:.3g} {k['unit']}" if k else "")
             + (f", restitution e = {case['restitution']:g}" if case["restitution"] is not None else "")]
    if case["duration_s"] is not None:
        parts.append(f"{case['duration_s']:g} s simulated, scored over {case['window_start_s']:g} to "
                     f"{case['window_end_s']:g} s")
    if case["experiment_frame1_peak_acceleration_g"] is not None:
        parts.append(f"measured frame 1 peak {case['experiment_frame1_peak_acceleration_g']:g} g")
    return "; ".join(parts) + "."


def draw_figures(suite, cases, chosen_by_law, experiment, steps, tolerances, folder, stamp, sweeps, summary_cases):
    """The fronts' figures (from summary.json's cases), every case's figures, every law's and every sweep's
    sections, as (fronts' paths, paths per case, paths per law, sections per sweep), spread over the
    machine's cores (each figure is independent, and drawing them is most of the report's time); in one
    process where fork is not available. The costliest tasks go first
    (the cases with series: a dozen panels each), so that the two workers end together."""
    laws = sorted(chosen_by_law)
    _CASES.update(suite=suite, cases=cases, chosen_by_law=chosen_by_law, experiment=experiment, steps=steps,
                  tolerances=tolerances, folder=folder, stamp=stamp, sweeps=sweeps, summary_cases=summary_cases)
    with_series = [i for i, (_, _, chosen) in enumerate(cases) if any(suite.has_series(r) for r in chosen.values())]
    tasks = ([("case", i) for i in with_series] + [("fronts", None)] + [("law", law) for law in laws] +
             [("sweep", i) for i in range(len(sweeps))] +
             [("case", i) for i in range(len(cases)) if i not in with_series])
    workers = min(len(tasks), os.cpu_count() or 1)
    if workers < 2 or "fork" not in multiprocessing.get_all_start_methods():
        drawn = [_draw(task) for task in tasks]
    else:
        with multiprocessing.get_context("fork").Pool(workers) as pool:
            drawn = pool.map(_draw, tasks, chunksize=1)
    by_task = dict(zip(tasks, drawn))
    return (by_task[("fronts", None)], [by_task[("case", i)] for i in range(len(cases))],
            [by_task[("law", law)] for law in laws],
            [by_task[("sweep", i)] for i in range(len(sweeps))])


def add_validation(document, suite, experiment):
    """summary.json's `validation` (validation.py) where the study has OUT/validation/NAME/ folders; a study
    without one gets no key, and its page no section."""
    try:
        entries = validation.summarise(suite, experiment)
    except data.ResultsError as error:
        sys.exit(f"make_report: {error}")
    if entries:
        document["validation"] = entries


def make(suite_folder, out):
    """The report of a suite's or a study's folder into OUT."""
    if not os.path.exists(os.path.join(suite_folder, "runs.csv")):
        sys.exit(f"make_report: {suite_folder}/runs.csv: no such file (is this a suite's or a sweep's output folder?)")
    figures_folder = os.path.join(out, "figures")
    if os.path.isdir(figures_folder):
        shutil.rmtree(figures_folder)  # a figure a case no longer draws must not linger
    os.makedirs(figures_folder)

    try:
        suite = data.read_runs(suite_folder)
        steps = data.read_steps(suite_folder)  # None unless the suite searched steps (--find-steps)
    except data.ResultsError as error:
        sys.exit(f"make_report: {error}")
    experiment = data.read_experiment()
    commands = read_commands(suite_folder)
    tolerances = next((c["verdict_tolerances"] for c in reversed(commands) if "verdict_tolerances" in c),
                      metric_catalog.DEFAULT_TOLERANCES)
    ran_on = machine.of_results(suite_folder)
    facts = provenance(suite, commands, ran_on)
    document = answer.summarise(suite, steps, experiment, tolerances, facts)
    add_validation(document, suite, experiment)
    with open(os.path.join(out, "summary.json"), "w") as f:
        json.dump(document, f, indent=1, allow_nan=False)
    stamp = f"impactbench, {facts['made']}, {ran_on.stamp}"

    sections = []  # (title, markdown text, html text, [figure paths])
    chosen_by_law = {}
    cases = []
    for (scenario, law), case in zip(suite.cases(), document["cases"]):
        chosen = named_runs.drawn_runs(suite, case)  # the runs the answers name
        chosen_by_law.setdefault(law, {})[scenario] = chosen
        cases.append((scenario, law, chosen))
    # A study's frequency sweeps (a study file's [[sweep]] parts: SUITE/sweeps/NAME/), read here and drawn with the
    # cases, each with its answer first.
    sweeps = []
    sweeps_folder = os.path.join(suite_folder, "sweeps")
    for name in sorted(os.listdir(sweeps_folder)) if os.path.isdir(sweeps_folder) else []:
        folder = os.path.join(sweeps_folder, name)
        if not sweep.is_sweep(folder):
            continue
        try:
            sweeps.append((name, sweep.read(folder)))
        except data.ResultsError as error:
            sys.exit(f"make_report: {error}")
    sweep_starts.share_start_ensembles(sweeps)  # the engines' sweep judged at multistable ratios by the reference sweep's starts
    fronts_figures, paths_by_case, paths_by_law, sections_by_sweep = draw_figures(
        suite, cases, chosen_by_law, experiment, steps, tolerances, figures_folder, stamp, sweeps, document["cases"])
    for (scenario, law, chosen), paths, case in zip(cases, paths_by_case, document["cases"]):
        header, rows = tables.case_table(suite, scenario, law, experiment)
        line = case_line(case)
        if not any(suite.has_series(run) for run in chosen.values()):
            line += (" No engine run of this case kept its series (step-search probes keep none): the histories, "
                     "portraits, spectra and distributions are not drawn.")
        markdown_text = line + "\n\n" + tables.markdown(header, rows)
        html_text = f"<p class='case'>{line}</p>" + tables.html_table(header, rows)
        steps_header, steps_rows = tables.steps_table(steps, scenario, law)
        if steps_rows:
            markdown_text += "\n\n" + STEPS_NOTE + "\n\n" + tables.markdown(steps_header, steps_rows)
            html_text += f"<p>{STEPS_NOTE}</p>" + tables.html_table(steps_header, steps_rows)
        sections.append((f"{scenario}, {law}", markdown_text, html_text, paths))
    for law, paths in zip(sorted(chosen_by_law), paths_by_law):
        sections.append((f"{law}: stability and the experiment", "", "", paths))
    inputs = report_views.ViewInputs(suite_folder, document, out)
    try:
        sections = (report_views.sections(report_views.BEFORE_CASES, inputs) + sections
                    + report_views.sections(report_views.AFTER_CASES, inputs))
    except ValueError as error:  # a saved measurement that is not bench/'s JSON
        sys.exit(f"make_report: {error}")
    document["sweep_answers"] = []
    for (name, data_of_sweep), sweep_sections in zip(sweeps, sections_by_sweep):
        document["sweep_answers"].append(f"Frequency sweep ({name}): " + sweep.summary_sentence(data_of_sweep))
        if data_of_sweep.start_ensembles_from == "this sweep":  # the fractions where they were measured
            document.setdefault("sweep_start_ensembles", []).extend(
                dict(sweep=name, law=law, **t) for law in data_of_sweep.laws() for t in sweep_starts.start_ensemble_table(data_of_sweep, law))
        document["warnings"] += data_of_sweep.warning_entries()  # the page's one Warnings list
        sections += sweep_sections
    if document["sweep_answers"]:
        with open(os.path.join(out, "summary.json"), "w") as f:
            json.dump(document, f, indent=1, allow_nan=False)

    for name in ("runs.csv", "runs.jsonl", "steps.csv", "commands.jsonl"):
        source = os.path.join(suite_folder, name)
        if os.path.exists(source) and os.path.abspath(out) != os.path.abspath(suite_folder):
            shutil.copy(source, os.path.join(out, name))
    write_markdown(os.path.join(out, "summary.md"), document, facts, sections, out, fronts_figures)
    write_html(os.path.join(out, "index.html"), document, facts, sections, out, fronts_figures)
    print(f"report: {os.path.join(out, 'index.html')}, {os.path.join(out, 'summary.md')}, "
          f"{os.path.join(out, 'summary.json')}")


def write_markdown(path, document, facts, sections, out, fronts_figures=(None, None, None)):
    lead, by_case, budget = (markdown_figure(p, out) if p else "" for p in fronts_figures)
    lines = [first_screen.markdown(document, facts, lead, by_case, budget)] + [f"\n{a}" for a in document.get("sweep_answers", [])]
    lines += ["", "## Caveats", ""] + [f"- {c}" for c in CAVEATS]
    lines += sections_markdown(sections, out)
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def write_html(path, document, facts, sections, out, fronts_figures=(None, None, None)):
    parts = [html_head("impactbench report"),
             first_screen.html_page_top(document, facts, *(figure_html(p, out) if p else "" for p in fronts_figures)),
             "".join(f"<p class='lede'>{html.escape(a)}</p>" for a in document.get("sweep_answers", [])),
             "<nav><b>Cases:</b> " + " · ".join(f"<a href='#{anchor(t)}'>{html.escape(t)}</a>" for t, _, _, _ in sections)
             + " · <a href='#settings'>settings</a> · <a href='#provenance'>what ran</a> · <a href='#caveats'>caveats</a></nav>"]
    parts += sections_html(sections, out)
    parts.append(first_screen.html_settings_and_provenance(document, facts))
    parts += ["<h2 id='caveats'>Caveats</h2><ul class='caveats'>"] + [f"<li>{html.escape(c)}</li>" for c in CAVEATS] + ["</ul>"]
    parts.append("</body></html>")
    with open(path, "w") as f:
        f.write("\n".join(parts))
