"""The report's first figures: error against run time as fronts (fronts.py). First the lead case's front
(the resonance, Hertz) with every engine; further down, one small panel per case and law. Each engine run is a point at its CPU time
per simulated second and its score (the largest headline error vs the beam in tolerance multiples) in its
engine's colour, the marker its contact path, with its score's 95 % interval as a bar where an ensemble gives one;
the points on the case's Pareto front are solid, the dominated
ones faint, each engine's own front joined by a line; unstable and failed runs are crosses along the top at
their cost; the beam reference's cost is a dotted line."""

import math

import matplotlib.pyplot as plt

from . import analysis, data, engines, fronts
from .figures import VERDICT_COLOURS, legend_axis, log_axis, proxy, save

PATH_MARKERS = {"matched": "o", "injected": "s", "native": "^"}
# A run on a chain coarser or finer than the case's usual one (its most common K) is a point of the chain's axis:
# its marker says which way, whatever its contact path.
COARSER_CHAIN_MARKER, FINER_CHAIN_MARKER = "d", "P"


def usual_links(case):
    """The K most of a case's points ran on (None without one)."""
    counts = {}
    for entry in case["fronts"]["engines"].values():
        for point in entry["points"]:
            if point.get("chain_links"):
                counts[point["chain_links"]] = counts.get(point["chain_links"], 0) + 1
    return max(counts, key=counts.get) if counts else None


def marker(point, usual):
    links = point.get("chain_links")
    if usual and links and links != usual:
        return COARSER_CHAIN_MARKER if links < usual else FINER_CHAIN_MARKER
    return PATH_MARKERS.get(analysis.contact_path(point), "o")
SMALL_COLUMNS = 3
SCORE_FLOOR = 1e-3  # a score of exactly 0 sits on the floor (no error in any metric, as to the printed digits)


def colour(point):
    return engines.colour(point["engine"], analysis.contact_path(point)) or "black"


def draw_case(ax, case, title, fontsize):
    """One case's points on a log-log panel; returns whether it drew any point."""
    fronts = case["fronts"]
    on_front = set(fronts["pareto_front_job_ids"])
    scored, stopped = [], []
    for engine, entry in fronts["engines"].items():
        for point in entry["points"]:
            cost, score = point["cpu_time_per_simulated_s"], point["score_vs_beam"]
            if cost is None or cost <= 0:
                continue
            if point["verdict"] in data.STABLE_VERDICTS and score is not None:
                scored.append((point, cost, max(score, SCORE_FLOOR)))
            elif point["verdict"] in ("unstable", "failed"):
                stopped.append((point, cost))
    reference = (case.get("reference") or {}).get("runs_csv", {}).get("cpu_time_per_simulated_s")
    usual = usual_links(case)
    costs = [c for _, c, _ in scored] + [c for _, c in stopped] + ([reference] if reference else [])
    if not costs:
        ax.text(0.5, 0.5, "no engine run with a cost", ha="center", va="center", fontsize=fontsize,
                transform=ax.transAxes)
        ax.set_title(title, fontsize=fontsize + 1)
        return False
    scores = [s for _, _, s in scored] or [1.0]
    low, high = min(scores + [0.5]) / 1.6, max(scores + [2.0]) * 2.5
    log_axis(ax, "x", min(costs) / 1.8, max(costs) * 1.8)
    log_axis(ax, "y", low, high)
    for engine, entry in fronts["engines"].items():
        own = {p["job_id"]: p for p in entry["points"]}
        line = [(own[j]["cpu_time_per_simulated_s"], max(own[j]["score_vs_beam"], SCORE_FLOOR))
                for j in entry["front_job_ids"]]
        if len(line) > 1:
            ax.plot(*zip(*line), color=colour(own[entry["front_job_ids"][0]]), linewidth=0.8, alpha=0.7, zorder=2)
    for point, cost, score in scored:
        half_width = point.get("score_half_width")
        if half_width:  # the score's 95 % interval, clipped at the floor (a log axis has no zero)
            ax.errorbar([cost], [score], yerr=[[score - max(score - half_width, SCORE_FLOOR)], [half_width]],
                        color=colour(point), alpha=0.8 if point["job_id"] in on_front else 0.25, linewidth=0.7,
                        capsize=1.5, zorder=3)
    for point, cost, score in scored:
        solid = point["job_id"] in on_front
        ax.scatter([cost], [score], color=colour(point), marker=marker(point, usual),
                   s=30 if solid else 14, alpha=1.0 if solid else 0.3, edgecolors="black" if solid else "none",
                   linewidths=0.6, zorder=4 if solid else 3)
    recommended = {e["recommended"]["job_id"] for e in fronts["engines"].values() if e.get("recommended")}
    for point, cost, score in scored:
        if point["job_id"] in recommended:  # the authors' recommended configuration: a ring around its point
            ax.scatter([cost], [score], facecolors="none", edgecolors=colour(point), marker="o", s=110, linewidths=1.2,
                       zorder=5)
    for point, cost in stopped:
        ax.scatter([cost], [high / 1.25], color=colour(point), marker="x", s=22, linewidths=1.2, zorder=3)
    if reference:
        ax.axvline(reference, color="black", linestyle=":", linewidth=0.9)
    ax.axhline(1.0, color="#555555", linestyle="-.", linewidth=0.8)
    ax.set_title(title, fontsize=fontsize + 1)
    ax.tick_params(labelsize=fontsize)
    ax.set_xlabel("CPU time per simulated second [s/s]", fontsize=fontsize)
    ax.set_ylabel("largest |error| vs beam / tolerance", fontsize=fontsize)
    return True


def legend_handles(cases):
    seen = {}
    for case in cases:
        for entry in case["fronts"]["engines"].values():
            for point in entry["points"]:
                seen.setdefault((point["engine"], analysis.contact_path(point)), colour(point))
    handles = [proxy(f"{engines.display_name(e)}, {p}", color=c, marker=PATH_MARKERS.get(p, "o"))
               for (e, p), c in seen.items()]
    for case in cases:
        usual = usual_links(case)
        links = {p.get("chain_links") for e in case["fronts"]["engines"].values() for p in e["points"]} - {None, usual}
        if any(k < usual for k in links):
            handles.append(proxy(f"diamond: a chain coarser than {usual} links", color="black", marker=COARSER_CHAIN_MARKER))
        if any(k > usual for k in links):
            handles.append(proxy(f"plus: a chain finer than {usual} links", color="black", marker=FINER_CHAIN_MARKER))
        break  # the usual K of the first case: the lead figure draws one case
    return handles + [
        proxy("solid, outlined: on the case's Pareto front", color="black", marker="o"),
        proxy("faint: dominated (another run is both cheaper and closer)", color="black", marker="o", alpha=0.3),
        proxy("line: an engine's own front", color="black", linestyle="-"),
        proxy("bar: the score's 95 % interval (ensembles)", color="black", marker="|", linestyle="none"),
        proxy("ring: the engine's recommended configuration", color="black", marker="o", markerfacecolor="none",
              markersize=10),
        proxy("cross along the top: unstable or failed, at its cost", color=VERDICT_COLOURS["unstable"], marker="x"),
        proxy("every error within its tolerance below this line", color="#555555", linestyle="-."),
        proxy("the beam reference's own cost", color="black", linestyle=":")]


CAPTION = ("every engine run at its CPU time per simulated second and its largest headline error against the beam "
           "in multiples of that metric's verdict tolerance (ensemble means where a run stands for one); the Pareto "
           "front solid, dominated runs faint, each engine's recommended configuration ringed")


def lead_figure(cases, folder, stamp):
    """The report's first figure: the lead case's front (fronts.lead_case), wide and short enough to leave
    the table of what to use on the first screen; None without an engine run."""
    case = fronts.lead_case(cases)
    if case is None:
        return None
    figure = plt.figure(figsize=(11, 3.6), constrained_layout=True)
    grid = figure.add_gridspec(1, 2, width_ratios=[2.6, 1])
    draw_case(figure.add_subplot(grid[0, 0]), case, f"{case['scenario']}, {case['law']}", 8)
    legend_axis(figure.add_subplot(grid[0, 1]), legend_handles([case]))
    caption = f"Error against run time, {case['scenario']}, {case['law']}: " + CAPTION
    return save(figure, folder, "fronts", caption + f"; {stamp}")


def cases_figure(cases, folder, stamp):
    """One small panel per case and law but the lead one, below the first; None when there is none."""
    lead = fronts.lead_case(cases)
    rest = [c for c in fronts.with_runs(cases) if c is not lead]
    if not rest:
        return None
    rows = math.ceil(len(rest) / SMALL_COLUMNS)
    figure = plt.figure(figsize=(11, 0.4 + 2.9 * rows), constrained_layout=True)
    grid = figure.add_gridspec(rows, SMALL_COLUMNS + 1, width_ratios=[1] * SMALL_COLUMNS + [0.8])
    for i, case in enumerate(rest):
        draw_case(figure.add_subplot(grid[i // SMALL_COLUMNS, i % SMALL_COLUMNS]), case,
                  f"{case['scenario']}, {case['law']}", 6)
    legend_axis(figure.add_subplot(grid[:, SMALL_COLUMNS]), legend_handles(rest))
    return save(figure, folder, "fronts_by_case", "Error against run time in every other case: " + CAPTION + f"; {stamp}")
