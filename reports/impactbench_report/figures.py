"""The report's figures, drawn with matplotlib and saved as SVG. None hides or invents a point: unstable and
failed runs are drawn as such, exact zeros sit on the axis as labelled marks, a metric no run defines is
dropped with the reason in the caption, and every mark is in a legend."""

import math
import os
import textwrap

import matplotlib

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt  # noqa: E402

# text as SVG text, not as paths: files several times smaller and faster to write, and searchable
plt.rcParams["svg.fonttype"] = "none"
from matplotlib import ticker, transforms  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402

from . import analysis, engines, metric_catalog, svg_saving  # noqa: E402
from .label_placement import POSITIONS, label_point, place_labels  # noqa: E402
from .tables import step_text  # noqa: E402

svg_saving.install_text_metrics_cache()

VERDICT_COLOURS = {"ok": "#2ca02c", "inaccurate": "#ff7f0e", "unstable": "#d62728", "failed": "#7f7f7f"}
VERDICT_MARKERS = {"ok": "o", "inaccurate": "s", "unstable": "X", "failed": "P"}
STEP_MARKERS = {"frame1_sensor_peak": "o", "contact_duration": "^", "impacts_per_cycle": "D"}
METRIC_COLOURS = ["#1f77b4", "#9467bd", "#000000"]  # the step search's metrics: no verdict's colour
REPOSITORY = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


# A configuration's colour from its engine and contact path, the same in every figure whichever configurations
# a figure holds: the engine's descriptor (engines.json of the folder, adapters/<engine>/descriptor.json),
# whose colours are none of a verdict's (green, orange, red, grey); a spare one for an engine without.
SPARE_COLOURS = ["#637939", "#7b4173", "#3182bd", "#31a354", "#756bb1", "#b5cf6b", "#de9ed6", "#525252"]


def colour_key(config):
    engine, _, options = config.partition(" [")
    return engine, analysis.contact_path_of(options.rstrip("]"))


def colour_of(config, configs):
    """The engine and contact path's own colour; a second configuration of the same engine and contact path
    (other options) in `configs` takes a spare colour by its place in the list."""
    key = colour_key(config)
    earlier = [c for c in configs[:configs.index(config)]] if config in configs else []
    own = engines.colour(*key)
    if own and not any(colour_key(c) == key for c in earlier):
        return own
    return SPARE_COLOURS[configs.index(config) % len(SPARE_COLOURS)] if config in configs else "black"


def save(figure, folder, name, caption):
    """Saves a figure as SVG with its caption (what it shows and what produced it) on top, and as the
    SVG's title; returns the path."""
    figure.suptitle(textwrap.fill(caption, max(60, int(17 * figure.get_figwidth()))), fontsize=7)
    place_labels(figure)  # once the caption's room is known: the layout it makes moves the points
    path = os.path.join(folder, name + ".svg")
    svg_saving.save_svg(figure, path, {"Title": caption})
    plt.close(figure)
    return path


# ---- shared pieces ---------------------------------------------------------------------------------------



def log_axis(ax, which, low, high):
    """A logarithmic axis from low to high with several labelled ticks whatever the spread: 1-2-5 ticks
    over up to 2.5 decades, 1-3 up to 4.5, decades beyond; labels as plain numbers."""
    getattr(ax, f"set_{which}scale")("log")
    getattr(ax, f"set_{which}lim")(low, high)
    decades = math.log10(high / low)
    subs = (1.0, 2.0, 5.0) if decades <= 2.5 else (1.0, 3.0) if decades <= 4.5 else (1.0,) if decades <= 8 else None
    axis = ax.xaxis if which == "x" else ax.yaxis
    axis.set_major_locator(ticker.LogLocator(base=10, subs=subs, numticks=12) if subs
                           else ticker.LogLocator(numticks=8))
    axis.set_major_formatter(ticker.FuncFormatter(lambda v, _: f"{v:g}"))
    # unlabelled ticks at 2 and 5 where the labels are sparser (few: each tick is costly to lay out)
    axis.set_minor_locator(ticker.LogLocator(base=10, subs=(2.0, 5.0), numticks=12) if decades > 2.5
                           else ticker.NullLocator())
    axis.set_minor_formatter(ticker.NullFormatter())


def padded(values, factor):
    """(low, high) around positive values, `factor` to spare on each side on a log axis."""
    return min(values) / factor, max(values) * factor


def legend_axis(ax, handles, title=None):
    ax.axis("off")
    ax.legend(handles=handles, loc="upper left", fontsize=7, title=title, title_fontsize=7, frameon=False)


def proxy(label, **style):
    style.setdefault("linestyle", "none")
    return Line2D([], [], label=label, **style)


def run_cost(run):
    """CPU time per simulated second [s/s] (runs.csv divides by the time the run actually simulated, so a
    run stopped early is not drawn as cheap); NaN when the run never stepped."""
    cost = run.number("cpu_time_per_simulated_s")
    return cost if cost > 0 else math.nan


def tolerance_of(column, tolerances):
    key = next(m.tolerance_key for m in metric_catalog.SCORED if m.error_column == column)
    return tolerances.get(key, metric_catalog.DEFAULT_TOLERANCES[key])


def why_undefined(column, scenario, law, suite):
    if column.startswith("contact_duration") and law == "newton":
        return "contact duration is not defined under the Newton law (instantaneous impacts)"
    if column.startswith("impacts_per_cycle") and math.isnan(suite.motor_frequency_hz(scenario)):
        return "impacts per cycle is not defined without a motor"
    return f"no run defines {column.replace('_', ' ')}"


# ---- error against cost ----------------------------------------------------------------------------------

def error_against_cost(suite, scenario, law, folder, provenance, tolerances=None):
    """One panel per headline metric a run defines: |error| against CPU time per simulated second, log-log,
    one curve per engine configuration through its stable runs (filled and solid: vs beam; hollow and
    dashed: vs own chain), the time step at each point, the tolerance, exact zeros on the bottom axis,
    unstable and failed runs as crosses at the top, the references' costs."""
    tolerances = tolerances or metric_catalog.DEFAULT_TOLERANCES
    runs = suite.runs_of(scenario, law)
    engine_runs = [r for r in runs if r["engine"] not in ("reference", "")]
    configs = analysis.configurations(runs)
    beam = suite.beam_reference(scenario, law)
    chains = [r for r in runs if r["engine"] == "reference" and not r.is_beam_reference]
    defined = lambda column: any(not math.isnan(analysis.signed_error(r, column, prefix))  # noqa: E731
                                 for r in engine_runs + chains for prefix in analysis.AGAINST.values())
    headline = [(m.figure_label, m.error_column, m.kind) for m in metric_catalog.HEADLINE]
    metrics = [m for m in headline if defined(m[1])]
    dropped = [why_undefined(column, scenario, law, suite) for _, column, _ in headline if not defined(column)]
    panels = max(1, len(metrics))
    stopped = [r for r in engine_runs if not r.stable]
    stopped_configs = [c for c in configs if any(r.config == c for r in stopped)]
    points = {column: error_points(column, kind, engine_runs, configs, chains) for _, column, kind in metrics}
    zero_rows = {column: [c for c in configs + [CHAIN] if any(p[0] == c and p[4] == 0 for p in found)]
                 for column, found in points.items()}
    most_zeros = max([len(rows) for rows in zero_rows.values()] + [0])
    heights = ([0.1 + 0.09 * len(stopped_configs)] if stopped else []) + [1] + ([0.1 + 0.08 * most_zeros]
                                                                              if most_zeros else [])
    figure = plt.figure(figsize=(4.3 * panels + 3.6, 3.8 + 0.9 * (len(heights) - 1)
                                 + 0.16 * (len(stopped_configs) + most_zeros)), constrained_layout=True)
    grid = figure.add_gridspec(len(heights), panels + 1, width_ratios=[1] * panels + [0.85], height_ratios=heights)
    main = 1 if stopped else 0
    axes = [figure.add_subplot(grid[main, i]) for i in range(panels)]
    costs = [c for c in [run_cost(r) for r in engine_runs + chains] + [run_cost(beam) if beam else math.nan]
             if c > 0]
    xlim = (min(costs) / 1.8, max(costs) * 2.6) if costs else (1e-3, 1.0)
    for i, (ax, (title, column, kind)) in enumerate(zip(axes, metrics)):
        draw_error_panel(ax, column, kind, tolerance_of(column, tolerances), points[column], configs, beam, xlim)
        if not stopped:
            ax.set_title(title, fontsize=9)
        else:
            strip = figure.add_subplot(grid[0, i], sharex=ax)
            draw_stopped(strip, stopped, stopped_configs, configs)
            strip.set_title(title, fontsize=9)
        if zero_rows[column]:
            ax.tick_params(labelbottom=False)
            ax.set_xlabel("")
            draw_zeros(figure.add_subplot(grid[main + 1, i], sharex=ax), points[column], zero_rows[column], configs)
    if not metrics:
        axes[0].text(0.5, 0.5, "no data: " + "; ".join(dropped), ha="center", va="center", wrap=True, fontsize=8,
                     transform=axes[0].transAxes)
        axes[0].set_axis_off()
    handles = [proxy(config, color=colour_of(config, configs), marker="o", linestyle="-") for config in configs]
    handles += [proxy("filled, solid: |error| vs beam", color="black", marker="o", linestyle="-"),
                proxy("hollow, dashed: |error| vs own chain", color="black", marker="o", markerfacecolor="none",
                      linestyle="--"),
                proxy("5e-5 beside a point: its time step [s], where\nit fits (every run's in the case's table)", color="none"),
                proxy("tolerance of the verdict", color="#555555", linestyle="-.")]
    if most_zeros:
        handles.append(proxy("bottom strip: error exactly 0", marker="v", color="black"))
    handles += [proxy(f"top strip: {verdict} run (no meaningful\nerror), one row per configuration", marker="x",
                      color=VERDICT_COLOURS[verdict])
                for verdict in ("unstable", "failed") if any(r["verdict"] == verdict for r in stopped)]
    if chains:
        handles.append(proxy("8-link chain reference vs beam", marker="*", color="black", markersize=9))
    if beam is not None:
        handles.append(proxy("beam reference's cost", color="black", linestyle=":"))
    legend_axis(figure.add_subplot(grid[:, panels]), handles)
    caption = (f"{scenario}, {law}: |error| of each engine run against its CPU cost per simulated second "
               f"(filled: vs the beam reference; hollow: vs the reference on the engine's own chain, which the "
               f"verdict judges); unstable and failed runs in the strip on top, at their CPU cost per simulated "
               f"second up to where they stopped")
    if dropped:
        caption += "; not drawn: " + "; ".join(dropped)
    return save(figure, folder, f"error_vs_cost_{scenario}_{law}", caption + f"; {provenance}")


def draw_stopped(strip, stopped, stopped_configs, configs):
    """Unstable and failed runs, which have no meaningful error: a cross in the verdict's colour at the run's
    cost, one row per configuration, labelled with the verdict and the time step in the configuration's
    colour. A run that never stepped has no cost: its row lists it at the left."""
    never = {}
    for run in stopped:
        cost, row = run_cost(run), stopped_configs.index(run.config)
        if math.isnan(cost):
            never.setdefault((row, run["verdict"]), []).append(step_text(run.number("time_step_s")))
            continue
        strip.plot([cost], [row], "x", color=VERDICT_COLOURS.get(run["verdict"], "black"), markersize=7,
                   markeredgewidth=1.6)
        label_point(strip, f"{run['verdict']} {step_text(run.number('time_step_s'))}", (cost, row), ROW_POSITIONS,
                    fontsize=6, color=colour_of(run.config, configs))
    for (row, verdict), steps in never.items():
        strip.text(0.01, row, f"{verdict} before any step (no cost): {', '.join(steps)} s",
                   transform=transforms.blended_transform_factory(strip.transAxes, strip.transData), fontsize=6,
                   va="center", color=colour_of(stopped_configs[row], configs))
    strip.set_ylim(len(stopped_configs) - 0.5, -0.5)
    strip.set_yticks([])
    strip.tick_params(labelbottom=False)
    strip.grid(True, axis="x", which="major", linewidth=0.4)


CHAIN = "8-link chain reference"
# Where a point's label may go (label_placement.py): in a strip's row, beside the point only (above or below
# it would read as the next row's); in a panel, a filled point's label first above it, a hollow one's below.
ROW_POSITIONS = [(5, 0, "left", "center"), (-5, 0, "right", "center")]
ABOVE_FIRST = POSITIONS
BELOW_FIRST = [p for p in POSITIONS if p[1] < 0] + [p for p in POSITIONS if p[1] >= 0]
# A vertical line's label, turned along it: beside its middle, else further up or down the line.
ALONG_A_LINE = [(side, along, "right" if side < 0 else "left", "center") for along in (0, 40, -40, 80, -80)
                for side in (-2, 2)]


def error_points(column, kind, engine_runs, configs, chains):
    """(configuration or CHAIN, vs beam?, run, cost [s/s], |error| [% for a relative error]) of every stable
    engine run (vs beam and vs own chain) and of the chain reference (vs beam)."""
    scale = 100.0 if kind == "relative" else 1.0
    points = []
    for run in [r for r in engine_runs if r.stable and r.config in configs] + chains:
        for prefix, filled in ((analysis.AGAINST["beam"], True), (analysis.AGAINST["own chain"], False)):
            value = abs(analysis.signed_error(run, column, prefix)) * scale
            if not math.isnan(value) and run_cost(run) > 0 and (filled or run in engine_runs):
                points.append((run.config if run in engine_runs else CHAIN, filled, run, run_cost(run), value))
    return points


def draw_zeros(strip, points, rows, configs):
    """Errors of exactly 0, which a log axis cannot place: one row per configuration under the panel, a
    triangle at the run's cost (filled: vs beam, hollow: vs own chain), labelled with the time step."""
    for label, filled, run, cost, value in points:
        if value != 0:
            continue
        colour = "black" if label == CHAIN else colour_of(label, configs)
        row = rows.index(label)
        strip.plot([cost], [row], "*" if label == CHAIN else "v", color=colour, markersize=7 if filled else 6,
                   markerfacecolor=colour if filled else "none")
        if filled or not any(p[2] is run and p[1] and p[4] == 0 for p in points):  # one label per run
            text = "chain reference" if label == CHAIN else step_text(run.number("time_step_s"))
            label_point(strip, text, (cost, row), ROW_POSITIONS, fontsize=6, color=colour)
    strip.set_ylim(len(rows) - 0.5, -0.5)
    strip.set_yticks([])
    strip.set_ylabel("exactly 0", fontsize=7, rotation=0, ha="right", va="center")
    strip.set_xlabel("CPU time per simulated second [s/s]")
    strip.grid(True, axis="x", which="major", linewidth=0.4)


def draw_error_panel(ax, column, kind, tolerance, points, configs, beam, xlim):
    scale = 100.0 if kind == "relative" else 1.0  # relative errors in percent
    positive = [p[4] for p in points if p[4] > 0] + [tolerance * scale]
    log_axis(ax, "x", *xlim)
    log_axis(ax, "y", *padded(positive, 2.5))
    edge = transforms.blended_transform_factory(ax.transData, ax.transAxes)
    if beam is not None and run_cost(beam) > 0:  # first: its label goes before the points' labels
        ax.axvline(run_cost(beam), color="black", linestyle=":", linewidth=1)
        label_point(ax, f"beam reference {run_cost(beam):.2g} s/s", (run_cost(beam), 0.5), ALONG_A_LINE,
                    xycoords=edge, rotation=90, fontsize=6)
    for config in configs:
        colour = colour_of(config, configs)
        for filled in (True, False):
            mine = sorted((p for p in points if p[0] == config and p[1] == filled and p[4] > 0), key=lambda p: p[3])
            if mine:
                ax.plot([p[3] for p in mine], [p[4] for p in mine], "-o" if filled else "--o", color=colour,
                        markerfacecolor=colour if filled else "none", markersize=5, linewidth=1)
            for p in mine:
                if not filled and any(q[2] is p[2] and q[1] and 0 < q[4] and 0.6 < p[4] / q[4] < 1.6 for q in points):
                    continue  # the filled point of the same run is labelled, right beside it
                label_point(ax, step_text(p[2].number("time_step_s")), (p[3], p[4]),
                            ABOVE_FIRST if filled else BELOW_FIRST, fontsize=6, color=colour)
    for p in points:
        if p[0] == CHAIN and p[4] > 0:
            ax.plot([p[3]], [p[4]], "*", color="black", markersize=9, zorder=5)
    ax.axhline(tolerance * scale, color="#555555", linestyle="-.", linewidth=1)
    ax.annotate(f"tolerance {tolerance * scale:g}{' %' if scale == 100 else ''}", (0.01, tolerance * scale),
                xycoords=transforms.blended_transform_factory(ax.transAxes, ax.transData), xytext=(0, 2),
                textcoords="offset points", fontsize=6, color="#555555")
    ax.set_xlabel("CPU time per simulated second [s/s]")
    ax.set_ylabel("|relative error| [%]" if scale == 100 else "|difference| [impacts per cycle]")
    ax.grid(True, which="major", linewidth=0.4)
    ax.grid(True, which="minor", linewidth=0.15, color="#dddddd")
