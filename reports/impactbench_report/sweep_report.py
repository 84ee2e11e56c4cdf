"""The report of a sweep's folder alone (impactbench sweep --out FOLDER): its answer, its figures and the engines'
agreement with the reference, per law; a study's sweeps are drawn in the suite's report (suite_report.py)."""

import datetime
import html
import json
import math
import os
import shutil
import sys

from . import data, first_screen, machine, sweep
from .page_writer import html_head, sections_html, sections_markdown, write_pages


def make(folder, out):
    """The sweep report of FOLDER into OUT."""
    figures_folder = os.path.join(out, "figures")
    if os.path.isdir(figures_folder):
        shutil.rmtree(figures_folder)
    os.makedirs(figures_folder)
    try:
        data_of_sweep = sweep.read(folder)
    except data.ResultsError as error:
        sys.exit(f"make_report: {error}")
    if not data_of_sweep.rows:
        sys.exit(f"make_report: {folder}/sweep.csv holds no rows yet (no ratio has ended)")
    made = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    ran_on = machine.of_results(folder)
    stamp = f"impactbench, {made}, {ran_on.stamp}"
    sections = sweep.sections(data_of_sweep, figures_folder, stamp, "Frequency sweep")
    settings = json.dumps(data_of_sweep.settings, indent=1)
    loads = sorted(r["load_average"] for r in data_of_sweep.rows if not math.isnan(r["load_average"]))
    machine_line = f"{ran_on.line}; load average {loads[0]:.2f} to {loads[-1]:.2f}" if loads else ran_on.line
    warnings = data_of_sweep.warning_entries()
    answer = sweep.summary_sentence(data_of_sweep)
    lines = ["# impactbench: frequency sweep", "", answer] + first_screen.warnings_markdown(warnings, unit="rows")
    lines += sections_markdown(sections, out)
    lines += ["", "## What ran", "", f"Made {made}. Machine: {machine_line}.", "", "```json", settings, "```"]
    parts = [html_head("impactbench sweep report", viewport=False), "<h1>impactbench: frequency sweep</h1>",
             f"<p class='lede'>{html.escape(answer)}</p>", first_screen.warnings_html(warnings, unit="rows")]
    parts += sections_html(sections, out)
    parts += ["<h2 id='provenance'>What ran</h2>", f"<p>Made {made}. Machine: {html.escape(machine_line)}.</p>",
              f"<pre>{html.escape(settings)}</pre></body></html>"]
    write_pages(out, lines, parts)
    print(f"report: {os.path.join(out, 'index.html')}, {os.path.join(out, 'summary.md')}")
