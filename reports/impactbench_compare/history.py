"""Several result folders in order (one per engine version, say): each configuration's headline errors against
the beam and its CPU cost along them, and what moved between each folder and the next (changes.py).
Written as DIR/history.html with a figure per configuration that moved somewhere along the line, and
DIR/history.md."""

import html
import math
import os

from impactbench_report import analysis, metric_catalog

from . import changes, page, writers
from .page import plt


def series(folders, job_id):
    """{label: [value per folder]} for a configuration: each headline error against the beam (NaN where the
    folder lacks the configuration or the error) and the CPU time per simulated second. A sweep's row (its id
    under its prefix) gives its measured values instead, which have no error of their own."""
    runs = [folder.configurations.get(job_id) for folder in folders]
    out = {}
    if any(isinstance(r, dict) for r in runs):  # a sweep's row
        for m in metric_catalog.SWEEP:
            out[m.label] = [r.get(m.column, math.nan) if r is not None else math.nan for r in runs]
        out["CPU s per simulated s"] = [changes.sweep_cost(r)[0] if r is not None else math.nan for r in runs]
        return out
    for m in metric_catalog.SCORED:
        values = [analysis.signed_error(r, m.error_column, "beam") if r is not None else math.nan for r in runs]
        if any(not math.isnan(v) for v in values):
            out[m.label + (" error [%]" if m.kind == "relative" else " error")] = [
                100 * v if m.kind == "relative" else v for v in values]
    out["CPU s per simulated s"] = [r.number("cpu_time_per_simulated_s") if r is not None else math.nan for r in runs]
    return out


def figure_svg(folders, job_id):
    lines = series(folders, job_id)
    figure, axes = plt.subplots(len(lines), 1, figsize=(6.4, 1.2 + 1.3 * len(lines)), sharex=True, squeeze=False)
    x = range(len(folders))
    for ax, (label, values) in zip(axes[:, 0], lines.items()):
        ax.plot(x, values, "o-", color="C0")
        ax.set_ylabel(label, fontsize=8)
        ax.axhline(0, color="0.7", linewidth=0.6)
    axes[-1, 0].set_xticks(list(x), [os.path.basename(os.path.normpath(f.path)) for f in folders], rotation=20, fontsize=8)
    axes[0, 0].set_title(job_id, fontsize=9)
    return page.svg_text(figure)


def summary_lines(folders, steps):
    """steps: [(base, new, differences, found)] for each folder and the next (found: changes.compare's)."""
    lines = [f"compare: {len(folders)} folders in order: " + " -> ".join(f.path for f in folders)]
    for base, new, differences, found in steps:
        moved = [c for c in found if c.moved]
        lines.append(f"{base.path} -> {new.path}: " + (f"{len(moved)} configurations moved beyond the noise" if moved
                                                       else "nothing moved beyond the noise"))
        lines += [f"  differs: {what}: {a} -> {b}" for what, a, b in differences]
        lines += ["  " + writers.what_moved(c) for c in moved[:writers.SUMMARY_LINES]]
        if len(moved) > writers.SUMMARY_LINES:
            lines.append(f"  and {len(moved) - writers.SUMMARY_LINES} more (in the files)")
    return lines


def write_page(folder, folders, steps):
    os.makedirs(folder, exist_ok=True)
    moved_ids = sorted({c.job_id for _, _, _, found in steps for c in found if c.moved})
    e = html.escape
    parts = ["<!DOCTYPE html><html><head><meta charset='utf-8'><title>impactbench history</title>",
             "<style>body{font-family:sans-serif;max-width:70em;margin:1em auto}</style></head><body>",
             "<h1>History</h1>", "<pre>" + e("\n".join(summary_lines(folders, steps))) + "</pre>",
             f"<h2>Configurations that moved along the folders ({len(moved_ids)})</h2>"]
    parts += [figure_svg(folders, job_id) for job_id in moved_ids]
    parts.append("</body></html>\n")
    with open(os.path.join(folder, "history.html"), "w") as f:
        f.write("\n".join(parts))
    with open(os.path.join(folder, "history.md"), "w") as f:
        f.write("# History\n\n" + "\n".join(f"    {line}" for line in summary_lines(folders, steps)) + "\n")
