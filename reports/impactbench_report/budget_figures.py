"""The error budget as a figure, next to the fronts: for the runs a case's answer names (each engine's most
accurate run, its cheapest within every tolerance of the beam, and the answer's own run), every scored metric's
error against the beam as its parts (budget.py): the chain's share (grey, from zero), then the engine's (its
colour, from the chain's end), the total as a black diamond with the noise's 95 % bar, the tolerance as dashed
lines. A metric the case does not rank on (chain_convergence.py) is drawn faint, its title says why."""

import math

import matplotlib.pyplot as plt
from matplotlib import ticker

from . import analysis, engines, fronts, metric_catalog
from .figures import save
from .tables import step_text

CHAIN_COLOUR = "#9a9a9a"
# The axis reaches this many tolerances at most: a native run 50 times off would leave the parts of the runs
# within their tolerances a pixel wide. Beyond it, the total is written at the edge.
AXIS_TOLERANCES = 4.0


def named_points(case):
    """The points the case's answers name, each once, in the order: the answer's run, then per engine its most
    accurate and its cheapest within the beam's tolerances; [(point, why named)]."""
    by_id = {p["job_id"]: p for e in case["fronts"]["engines"].values() for p in e["points"]}
    chosen = []
    answer = (case.get("answer") or {}).get("job_id")
    if answer in by_id:
        chosen.append((by_id[answer], "the answer"))
    for entry in case["fronts"]["engines"].values():
        for key, why in (("most_accurate", "most accurate vs own chain"),
                         ("cheapest_within_tolerance_vs_beam", "cheapest within the beam's tolerances")):
            point = entry.get(key)
            if point and point["job_id"] in by_id and all(point["job_id"] != p["job_id"] for p, _ in chosen):
                chosen.append((by_id[point["job_id"]], why))
    return [(p, why) for p, why in chosen if p.get("budget")]


def row_label(point):
    links = f", K={point['chain_links']}" if point.get("chain_links") else ""
    step = f" {step_text(point['time_step_s'])} s" if point.get("time_step_s") else ""
    return f"{engines.display_name(point['engine'])} {analysis.contact_path(point)}{step}{links}"


def scale(kind):
    return 100.0 if kind == "relative" else 1.0


def draw_metric(ax, label, rows, tolerance, kind, flagged):
    """One metric's panel: a row per named point, its parts as bars."""
    factor = scale(kind)
    alpha = 0.35 if flagged else 1.0
    extent = tolerance * factor
    limit = AXIS_TOLERANCES * tolerance * factor
    beyond = []
    for y, (point, _) in enumerate(rows):
        entry = point["budget"]["metrics"].get(label)
        if not entry:
            continue
        total = entry["total"] * factor
        chain = (entry["chain"] or 0.0) * factor
        engine = (entry["engine"] or 0.0) * factor
        ax.barh(y, chain, left=0, height=0.6, color=CHAIN_COLOUR, alpha=alpha)
        ax.barh(y, engine, left=chain, height=0.35, color=engines.colour(point["engine"], analysis.contact_path(point))
                or "black", alpha=alpha)
        noise = entry.get("noise_half_width")
        ax.errorbar([total], [y], xerr=[[noise * factor]] * 2 if noise else None, fmt="D", color="black",
                    markersize=3.5, linewidth=0.8, capsize=2, alpha=alpha)
        extent = max(extent, abs(total) + (noise or 0) * factor, abs(chain), abs(chain + engine))
        if abs(total) > limit:
            beyond.append((y, total))
    for sign in (-1, 1):
        ax.axvline(sign * tolerance * factor, color="#555555", linestyle="--", linewidth=0.8)
    ax.axvline(0, color="black", linewidth=0.6)
    extent = min(1.1 * extent, limit)
    ax.set_xlim(-extent, extent)
    for y, total in beyond:  # the total past the axis, written inside its edge
        ax.text(math.copysign(0.97 * extent, total), y - 0.3, f"{total:+.3g}" + (" %" if kind == "relative" else ""),
                ha="right" if total > 0 else "left", va="center", fontsize=5.5)
    ax.set_ylim(-0.6, len(rows) - 0.4)
    ax.xaxis.set_major_locator(ticker.MaxNLocator(nbins=4))  # few enough labels to stand apart in a narrow panel
    ax.set_title(label + (" (not ranked)" if flagged else ""), fontsize=7)
    ax.set_xlabel("error vs beam [%]" if kind == "relative" else "difference vs beam", fontsize=6)
    ax.tick_params(labelsize=6)


def case_figure(case, tolerances, folder, name, stamp):
    """A case's budget figure; None where no named point has a budget."""
    rows = named_points(case)
    metrics = [(m.label, m.kind, m.tolerance_key) for m in metric_catalog.SCORED
               if any(m.label in p["budget"]["metrics"] for p, _ in rows)]
    if not rows or not metrics:
        return None
    flagged = {f["metric"] for f in case.get("metrics_not_ranked") or []}
    figure, axes = plt.subplots(1, len(metrics), figsize=(11, 0.9 + 0.32 * len(rows)), sharey=True,
                                constrained_layout=True, squeeze=False)
    for ax, (label, kind, key) in zip(axes[0], metrics):
        draw_metric(ax, label, rows, tolerances[key], kind, label in flagged)
    axes[0][0].set_yticks(range(len(rows)))
    axes[0][0].set_yticklabels([row_label(p) for p, _ in rows], fontsize=6)
    axes[0][0].invert_yaxis()
    caption = (f"Error budget, {case['scenario']}, {case['law']}: each named run's error against the beam as the "
               "chain's share (grey: the reference on the run's own chain against the beam) plus the engine's "
               "(colour: the run against its own chain), the total as a diamond with its 95 % noise bar, the "
               f"verdict tolerance dashed; {stamp}")
    return save(figure, folder, name, caption)


def lead_figure(cases, tolerances, folder, stamp):
    """The lead case's budget (fronts.lead_case), for the first screen; None without one."""
    case = fronts.lead_case(cases)
    return None if case is None else case_figure(case, tolerances, folder, "budget", stamp)


def figure_name(case):
    return "budget_" + "".join(c if c.isalnum() else "_" for c in f"{case['scenario']}_{case['law']}")
