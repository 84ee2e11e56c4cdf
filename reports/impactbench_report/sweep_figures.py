"""A sweep's figures (sweep.py reads the data): per law, the bifurcation diagram of every simulator (frame 1's
tip displacement once per motor period against the motor speed ratio, up and down in two colours, from rest
in grey) and the response (impacts per cycle, frame 1's sensor peak) against the ratio, with the experiment's
three operating points marked."""

import math

from . import analysis, engines, figures, sweep
from .figures import plt
from matplotlib.lines import Line2D

START_COLOURS = {"up": "#1f77b4", "down": "#ff7f0e", "rest": "#7f7f7f"}
START_STYLES = {"up": "-", "down": "--", "rest": ":"}


def engine_colour(config):
    engine, options = config[0], config[1]
    if engine == "reference":
        return "black"
    return engines.colour(engine, analysis.contact_path_of(options)) or figures.SPARE_COLOURS[hash(options) % len(figures.SPARE_COLOURS)]


def mark_experiment(ax, label=True):
    for x in sweep.EXPERIMENT_RATIOS:
        ax.axvline(x, color="#2ca02c", linestyle=":", linewidth=0.8)
        if label:  # above the panel, where no legend is
            ax.text(x, 1.01, f"exp. {x:g}", transform=ax.get_xaxis_transform(), fontsize=6, color="#2ca02c",
                    va="bottom", ha="center", clip_on=False)


def bifurcation(data, law, folder, stamp, name):
    """Small multiples, one per simulator, the same axes."""
    configs = [c for c in data.simulators() if any(data.rows_of(c, law, s) for s in sweep.STARTS)]
    if not configs:
        return None
    columns = min(3, len(configs))
    rows = math.ceil(len(configs) / columns)
    width = 9.0 if columns == 1 else 4.2 * columns
    figure, axes = plt.subplots(rows, columns, figsize=(width, (4.2 if columns == 1 else 3.0) * rows + 0.8), sharex=True,
                                sharey=True, squeeze=False)
    # up and down side by side at each ratio (a fifth of the spacing apart), so that neither hides the other
    ratios = data.all_ratios()
    spacing = min((b - a for a, b in zip(ratios, ratios[1:])), default=0.01)
    shift = {"up": -0.2 * spacing, "down": 0.2 * spacing, "rest": 0.0}
    drawn = set()
    for ax, config in zip(axes.flat, configs):
        for start in sweep.STARTS:
            xs, ys, unstable = [], [], []
            for r in data.rows_of(config, law, start, members=True):  # every start of an ensemble: its attractors
                if r["verdict"] != "ok":
                    unstable.append(r["ratio"])
                    continue
                values = data.samples.get(r["id"], [])
                xs += [r["ratio"] + shift[start]] * len(values)
                ys += [1e3 * v for v in values]
            if xs:
                # tens of thousands of points: drawn as an image inside the SVG (1.1 MB of vector marks otherwise)
                ax.plot(xs, ys, ".", markersize=1.5 if start != "rest" else 1.0, color=START_COLOURS[start], alpha=0.7,
                        rasterized=True)
                drawn.add(start)
            if unstable:
                ax.plot(unstable, [0] * len(unstable), "x", color=figures.VERDICT_COLOURS["unstable"], markersize=5)
                drawn.add("unstable")
        mark_experiment(ax, label=ax is axes.flat[0])
        ax.set_title(sweep.label(config), fontsize=8)
        ax.grid(alpha=0.3)
    for ax in axes.flat[len(configs):]:
        ax.set_visible(False)
    for ax in axes[-1]:
        ax.set_xlabel("motor speed / f_1 [-]")
    for ax in axes[:, 0]:
        ax.set_ylabel("frame 1 tip displacement\nonce per motor period [mm]")
    handles = [Line2D([], [], marker="o", linestyle="", color=START_COLOURS[s], label=f"swept {s}" if s != "rest" else "from rest")
               for s in sweep.STARTS if s in drawn]
    if "unstable" in drawn:
        handles.append(Line2D([], [], marker="x", linestyle="", color=figures.VERDICT_COLOURS["unstable"],
                              label="unstable or failed (no samples)"))
    axes.flat[0].legend(handles=handles, fontsize=6, loc="upper left")
    figure.tight_layout(rect=(0, 0, 1, 0.88 if rows == 1 else 0.93))
    return figures.save(figure, folder, name, f"Bifurcation diagram, {law}: frame 1's tip displacement sampled once per "
                        f"motor period in each ratio's scoring window, sweeping up and down (each ratio continued from the "
                        f"last; drawn just left and right of the ratio) and from rest; green dotted lines: the experiment's "
                        f"operating points. {stamp}")


def response(data, law, folder, stamp, name):
    """Impacts per cycle and frame 1's sensor peak against the ratio, every simulator, every start."""
    configs = [c for c in data.simulators() if any(data.rows_of(c, law, s) for s in sweep.STARTS)]
    if not configs:
        return None
    figure, (top, bottom) = plt.subplots(2, 1, figsize=(9, 6.2), sharex=True)
    handles = []
    for config in configs:
        colour = engine_colour(config)
        width = 2.0 if config[0] == "reference" else 1.0
        for start in sweep.STARTS:
            rows = [r for r in data.rows_of(config, law, start) if r["verdict"] == "ok"]
            if not rows:
                continue
            xs = [r["ratio"] for r in rows]
            top.plot(xs, [r["impacts_per_cycle"] for r in rows], START_STYLES[start], color=colour, linewidth=width,
                     marker="." if start == "rest" else None, markersize=3)
            bottom.plot(xs, [r["frame1_sensor_peak_acceleration_g"] for r in rows], START_STYLES[start], color=colour,
                        linewidth=width, marker="." if start == "rest" else None, markersize=3)
        handles.append(Line2D([], [], color=colour, linewidth=width, label=sweep.label(config)))
    handles += [Line2D([], [], color="grey", linestyle=START_STYLES[s], label=f"swept {s}" if s != "rest" else "from rest")
                for s in sweep.STARTS]
    for ax in (top, bottom):
        mark_experiment(ax, label=ax is top)
        ax.grid(alpha=0.3)
    top.set_ylabel("impacts per motor cycle [-]")
    bottom.set_ylabel("frame 1 sensor peak [g]")
    bottom.set_xlabel("motor speed / f_1 [-]")
    top.legend(handles=handles, fontsize=6, loc="upper right", ncol=2)
    figure.tight_layout(rect=(0, 0, 1, 0.93))
    return figures.save(figure, folder, name, f"Response against the motor speed, {law}: impacts per cycle and frame 1's "
                        f"sensor peak in each ratio's scoring window (runs not ok are left out; the table lists them). {stamp}")
