"""A comparison as an HTML page: what differs between the folders, then a figure per moved configuration
(each moved metric's change with its noise band, and the cost's), then the table of every configuration.
Written with the Markdown beside it (writers.py) into one folder."""

import html
import io
import math
import os

import matplotlib

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt  # noqa: E402

from . import writers  # noqa: E402


def moved_figure(change):
    """An SVG: each moved metric's change (a dot) against its noise band (grey, around no change), in % for a
    relative metric; the cost's ratio the same way."""
    rows = []
    for m in change.moved_metrics:
        if math.isnan(m.change):
            continue
        scale = 100 if m.kind == "relative" else 1
        rows.append((m.label + (" [%]" if m.kind == "relative" else ""), scale * m.change, scale * m.noise))
    if change.cost is not None and change.cost.moved:
        rows.append(("CPU cost [%]", 100 * (change.cost.ratio - 1), 100 * change.cost.noise))
    for i in change.moved_impacts:  # the medians' change; the test's noise is no band
        if i.base_median:
            rows.append((f"per-impact {i.label}, median [%]", 100 * (i.new_median / i.base_median - 1), 0.0))
    moved_instability = change.instability is not None and change.instability.moved
    if moved_instability and not math.isnan(change.instability.new_time_s - change.instability.base_time_s):
        rows.append(("unstable at t, change [s]", change.instability.new_time_s - change.instability.base_time_s,
                     change.instability.slack_s))
    if not rows:
        return ""
    figure, axes = plt.subplots(figsize=(6.4, 1.1 + 0.45 * len(rows)))
    for i, (_, value, noise) in enumerate(rows):
        axes.barh(i, 2 * noise, left=-noise, height=0.5, color="0.8")
        axes.plot([value], [i], "o", color="C3")
    axes.axvline(0, color="0.3", linewidth=0.8)
    axes.set_yticks(range(len(rows)), [label for label, _, _ in rows])
    axes.set_ylim(-0.7, len(rows) - 0.3)
    axes.set_xlabel("change from base to new (red); grey: the noise it is judged against (95 %)", fontsize=8)
    return svg_text(figure)


def svg_text(figure):
    """The figure as an <svg> element to put inside a page (closed after)."""
    figure.tight_layout()
    out = io.StringIO()
    figure.savefig(out, format="svg")
    plt.close(figure)
    text = out.getvalue()
    return text[text.find("<svg"):]


def write_page(folder, base, new, differences, changes):
    """FOLDER/compare.html (self-contained) and FOLDER/compare.md."""
    os.makedirs(folder, exist_ok=True)
    markdown = writers.markdown(base, new, differences, changes)
    with open(os.path.join(folder, "compare.md"), "w") as f:
        f.write(markdown)
    e = html.escape
    parts = ["<!DOCTYPE html><html><head><meta charset='utf-8'><title>impactbench compare</title>",
             "<style>body{font-family:sans-serif;max-width:70em;margin:1em auto}table{border-collapse:collapse}"
             "td,th{border:1px solid #ccc;padding:2px 6px;font-size:90%}.moved{color:#b00}</style></head><body>",
             f"<h1>Comparison</h1><p>Base <code>{e(base.path)}</code>, new <code>{e(new.path)}</code>.</p>",
             "<pre>" + e("\n".join(writers.summary_lines(base, new, differences, changes))) + "</pre>",
             "<h2>What differs between the folders</h2>"]
    if differences:
        parts.append("<table><tr><th>what</th><th>base</th><th>new</th></tr>" +
                     "".join(f"<tr><td>{e(w)}</td><td>{e(str(a))}</td><td>{e(str(b))}</td></tr>" for w, a, b in differences) +
                     "</table>")
    else:
        parts.append("<p>Nothing, as far as the folders say.</p>")
    moved = [c for c in changes if c.moved]
    parts.append(f"<h2>What moved beyond the noise ({len(moved)})</h2>")
    for c in moved:
        parts.append(f"<h3 class='moved'>{e(writers.what_moved(c))}</h3>")
        parts.append(moved_figure(c))
    others = writers.listed("Not comparable (run otherwise):", [writers.what_moved(c) for c in changes if c.not_comparable])
    others += writers.listed("Not judged (a noise wider than the metric):", writers.not_judged_lines(changes))
    if others:
        parts.append("<h2>Not compared</h2><pre>" + e("\n".join(others)) + "</pre>")
    parts.append("<h2>Every configuration</h2><table><tr><th>job</th><th>judgement</th><th>presence</th><th>verdicts</th>"
                 "<th>metrics (noise)</th><th>cost</th></tr>")
    for c in changes:
        metrics = "<br>".join(("<b class='moved'>" if m.moved else "") + e(writers.change_text(m)) + ("</b>" if m.moved else "")
                              for m in c.metrics)
        cost = e(f"{writers.number(c.cost.base_s_per_s)} -> {writers.number(c.cost.new_s_per_s)} s/s: {c.cost.judgement}") if c.cost else ""
        parts.append(f"<tr><td>{e(c.job_id)}</td><td>{e(c.judgement)}</td><td>{c.presence}</td><td>{e(writers.verdicts_text(c.base_verdicts))} -> "
                     f"{e(writers.verdicts_text(c.new_verdicts))}</td><td>{metrics}</td><td>{cost}</td></tr>")
    parts.append("</table></body></html>\n")
    with open(os.path.join(folder, "compare.html"), "w") as f:
        f.write("\n".join(parts))
