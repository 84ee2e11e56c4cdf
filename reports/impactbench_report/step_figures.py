"""The stability map (every engine run by case, time step and contact stiffness) and the step search's
limits (steps.csv). Shared styling: figures.py."""

import math
import os
import textwrap

from matplotlib import ticker, transforms

from . import analysis, data, metric_catalog
from .figures import (METRIC_COLOURS, REPOSITORY, STEP_MARKERS, VERDICT_COLOURS, VERDICT_MARKERS, legend_axis,
                      log_axis, padded, plt, proxy, save)
from .tables import step_text

# ---- stability map ---------------------------------------------------------------------------------------

def scenario_file(path):
    """A scenario file named in runs.csv (relative to the repository when not found as given)."""
    return data.read_scenario(path if os.path.exists(path) else os.path.join(REPOSITORY, path))


def contact_text(scenario, law):
    contact = scenario.get("contact", {}).get(law, {})
    stiffness = f"{data.contact_stiffness(scenario, law):.3g}".replace("e+0", "e").replace("e+", "e")
    if law == "hertz":
        return f"k = {stiffness} N/m^{contact.get('exponent', 1.5):g}"
    if law == "viscoelastic":
        return f"k = {stiffness} N/m"
    return f"e = {contact['restitution']:g}" if "restitution" in contact else ""


def stability_map(suite, law, folder, provenance, steps=None):
    """One panel per engine configuration, one column per case (its contact stiffness under its name), each
    run a point at its time step coloured and shaped by its verdict, so that no case hides another's points;
    with steps.csv, the searched cases' largest stable step and largest step within tolerance per metric
    beside the runs."""
    runs = [r for r in suite.runs if r["law"] == law and r["engine"] not in ("reference", "")
            and r.number("time_step_s") > 0]
    configs = analysis.configurations(runs)
    if not configs:
        return None
    cases = [s for s, l in suite.cases() if l == law and any(r["scenario"] == s for r in runs)]
    files = {r["scenario"]: r["scenario_file"] for r in runs}
    ticks = [textwrap.fill(case.replace("_", " "), 14) + "\n" + contact_text(scenario_file(files[case]), law)
             for case in cases]
    searched = [s for s in (steps or []) if s["law"] == law]
    columns = min(3, len(configs))
    rows = math.ceil(len(configs) / columns)
    figure = plt.figure(figsize=(4.2 * columns + 2.8, 3.4 * rows + 0.6), constrained_layout=True)
    grid = figure.add_gridspec(rows, columns + 1, width_ratios=[1] * columns + [0.7])
    all_steps = [r.number("time_step_s") for r in runs] + [
        s.number(c) for s in searched for c in ["largest_stable_step_s"] +
        [f"{m.step_prefix}_largest_step_within_tolerance_s" for m in metric_catalog.STEP_SEARCHED] if s.number(c) > 0]
    palette = METRIC_COLOURS
    for index, config in enumerate(configs):
        ax = figure.add_subplot(grid[index // columns, index % columns])
        for column, case in enumerate(cases):
            if not any(r["scenario"] == case for r in runs if r.config == config):
                ax.text(column, 0.5, "not run", ha="center",
                        transform=transforms.blended_transform_factory(ax.transData, ax.transAxes), va="center",
                        fontsize=7, color="#777777", rotation=90)
        for r in analysis.runs_of_config(runs, config):
            verdict = r["verdict"]
            ax.scatter([cases.index(r["scenario"]) - 0.12], [r.number("time_step_s")], s=30, zorder=3,
                       marker=VERDICT_MARKERS.get(verdict, "o"), color=VERDICT_COLOURS.get(verdict, "black"))
        for row in (s for s in searched if s.config == config and s["scenario"] in cases):
            x = cases.index(row["scenario"]) + 0.18
            if row.number("largest_stable_step_s") > 0:
                ax.plot([x], [row.number("largest_stable_step_s")], "_", color="black", markersize=16,
                        markeredgewidth=2, zorder=4)
            for i, prefix in enumerate(m.step_prefix for m in metric_catalog.STEP_SEARCHED):
                value = row.number(f"{prefix}_largest_step_within_tolerance_s")
                if value > 0:
                    ax.scatter([x + 0.1 * (i - 1)], [value], marker=STEP_MARKERS[prefix], facecolors="none",
                               edgecolors=palette[i], s=36, zorder=5)
        ax.set_yscale("log")
        ax.set_ylim(*padded(all_steps, 1.4))
        # every step tried is a tick (the points sit on them), labelled where the label below leaves room
        ax.yaxis.set_major_locator(ticker.FixedLocator(sorted(set(all_steps))))
        labelled = spaced_steps(all_steps)
        ax.yaxis.set_major_formatter(ticker.FuncFormatter(lambda v, _: step_text(v) if v in labelled else ""))
        ax.yaxis.set_minor_locator(ticker.NullLocator())
        ax.set_xticks(range(len(cases)))
        ax.set_xticklabels(ticks, fontsize=6, rotation=35, ha="right", rotation_mode="anchor")
        ax.set_xlim(-0.6, len(cases) - 0.4)
        ax.set_title(config, fontsize=8)
        ax.set_ylabel("time step [s]")
        ax.grid(True, axis="y", which="major", linewidth=0.4)
        for boundary in range(1, len(cases)):
            ax.axvline(boundary - 0.5, color="#cccccc", linewidth=0.6)
    handles = [proxy(f"run: {verdict}", marker=VERDICT_MARKERS[verdict], color=colour)
               for verdict, colour in VERDICT_COLOURS.items()]
    if searched:
        handles.append(proxy("step search: largest stable step", marker="_", color="black", markersize=16,
                             markeredgewidth=2))
        handles += [proxy(f"step search: largest step with\n{label} within tolerance", marker=STEP_MARKERS[prefix],
                          color=palette[i], markerfacecolor="none")
                    for i, (prefix, label) in enumerate((m.step_prefix, m.label) for m in metric_catalog.STEP_SEARCHED)]
    legend_axis(figure.add_subplot(grid[:, columns]), handles)
    return save(figure, folder, f"stability_{law}",
                f"{law}: the verdict of every engine run, by case (its contact parameter under its name) and time "
                f"step, one panel per configuration" + ("; right of the runs, the step search's results "
                                                        "(steps.csv)" if searched else "") + f"; {provenance}")


# Two step labels on a log axis closer than this (decades) would overlap at the figure's size: 6.25e-5 and 7e-5
# are 0.05 apart, 5e-5 and 6.25e-5 0.1.
LABEL_SPACING_DECADES = 0.15


def spaced_steps(steps):
    """The steps whose tick is labelled: from the smallest up, each at least LABEL_SPACING_DECADES above the last
    labelled one."""
    labelled = []
    for step in sorted(set(steps)):
        if not labelled or math.log10(step / labelled[-1]) >= LABEL_SPACING_DECADES:
            labelled.append(step)
    return set(labelled)


# ---- step limits -----------------------------------------------------------------------------------------

def probed_steps(row):
    """{step: verdict} of the runs a search made (steps.csv probe_outcomes: "step:verdict;...")."""
    probes = {}
    for outcome in row["probe_outcomes"].split(";"):
        step, _, verdict = outcome.partition(":")
        try:
            probes[float(step)] = verdict
        except ValueError:
            continue
    return probes


def step_limits(steps, scenario, law, folder, provenance):
    """From steps.csv: per engine configuration, the largest stable step (black bar from the smallest
    step searched, the smallest unstable step as a red x) and the largest step at which each headline
    metric is within its tolerance of the reference (one marker each), on a log axis."""
    rows = data.steps_of(steps, scenario, law)
    if not rows:
        return None
    figure, ax = plt.subplots(figsize=(10, 0.55 * len(rows) + 1.8), constrained_layout=True)
    metric_colours = METRIC_COLOURS
    values = []
    for y, row in enumerate(rows):
        probes = probed_steps(row)
        low, stable = min(probes or [row.number("step_range_min_s")]), row.number("largest_stable_step_s")
        values += [v for v in [low, stable, row.number("step_range_max_s")] + list(probes) if v > 0]
        for step, verdict in probes.items():
            ax.scatter([step], [y], marker="|", color=VERDICT_COLOURS.get(verdict, "black"), s=160,
                       linewidths=1.5, zorder=3.5)
        if not math.isnan(stable):
            ax.plot([low, stable], [y, y], color="black", linewidth=3, solid_capstyle="butt")
        unstable = row.number("smallest_unstable_step_s")
        if not math.isnan(unstable):  # a failed run counts as not stable: grey, not red
            failed = min(probes.items(), key=lambda p: abs(p[0] / unstable - 1), default=(0, ""))[1] == "failed"
            ax.scatter([unstable], [y], marker="x", color=VERDICT_COLOURS["failed" if failed else "unstable"], s=40,
                       zorder=3)
        for i, prefix in enumerate(m.step_prefix for m in metric_catalog.STEP_SEARCHED):
            step = row.number(f"{prefix}_largest_step_within_tolerance_s")
            if not math.isnan(step):
                ax.scatter([step], [y + 0.12 * (i - 1)], marker=STEP_MARKERS[prefix], color=metric_colours[i], s=30,
                           zorder=4)
        # what the markers cannot show: a metric within tolerance at no step of the range, or not decided
        missing = [f"{m.label}: {row[m.step_prefix + '_status']}" for m in metric_catalog.STEP_SEARCHED
                   if math.isnan(row.number(f"{m.step_prefix}_largest_step_within_tolerance_s"))
                   and not row[f"{m.step_prefix}_status"].startswith("not applicable")]
        if missing:
            ax.annotate(textwrap.fill("; ".join(missing), 120), (low, y + 0.34), fontsize=6, color="#555555",
                        va="center")
    ax.set_yticks(range(len(rows)))
    ax.set_yticklabels([r.config for r in rows], fontsize=7)
    ax.set_ylim(-0.6, len(rows) - 0.4)
    ax.invert_yaxis()
    log_axis(ax, "x", *padded(values, 1.3))
    ax.set_xlabel("time step [s]")
    ax.grid(True, which="major", axis="x", linewidth=0.4)
    # the legend from empty proxies, so that it is complete whichever rows have which markers
    handles = [proxy("stable (from the smallest step probed)", color="black", linewidth=3, linestyle="-"),
               proxy("smallest unstable step found", marker="x", color=VERDICT_COLOURS["unstable"]),
               proxy("smallest step found failing (counted as not stable)", marker="x",
                     color=VERDICT_COLOURS["failed"])]
    handles += [proxy(f"a step probed by the search: {verdict}", marker="|", color=colour, markersize=10)
                for verdict, colour in VERDICT_COLOURS.items()]
    handles += [proxy(f"{label}: largest step within tolerance", marker=STEP_MARKERS[prefix], color=metric_colours[i])
                for i, (prefix, label) in enumerate((m.step_prefix, m.label) for m in metric_catalog.STEP_SEARCHED)]
    ax.legend(handles=handles, fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1))
    tolerances = ", ".join(f"{m.label} {rows[0].number(m.step_tolerance_column):g}"
                           + (" relative" if m.kind == "relative" else "")
                           for m in metric_catalog.STEP_SEARCHED)
    return save(figure, folder, f"steps_{scenario}_{law}",
                f"{scenario}, {law}: largest stable step and largest step within tolerance of the reference on the "
                f"engine's own chain ({tolerances}), found by bisection on a grid of "
                f"{rows[0].number('grid_points_per_octave'):g} steps per octave; {provenance}")
