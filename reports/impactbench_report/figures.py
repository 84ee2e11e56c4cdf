"""The report's figures, drawn with matplotlib and saved as SVG."""

import math
import os
import textwrap

import matplotlib

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt  # noqa: E402

from . import analysis, data  # noqa: E402

VERDICT_COLOURS = {"ok": "#2ca02c", "inaccurate": "#ff7f0e", "unstable": "#d62728", "failed": "#7f7f7f"}
FLOOR = 1e-7  # errors of exactly zero are drawn here on the logarithmic axes


def colour_of(config, configs):
    palette = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    return palette[configs.index(config) % len(palette)] if config in configs else "black"


def save(figure, folder, name, caption):
    """Saves a figure as SVG with its caption (what it shows and what produced it) on top, and as the
    SVG's title; returns the path."""
    figure.suptitle(textwrap.fill(caption, 170), fontsize=7)
    path = os.path.join(folder, name + ".svg")
    figure.savefig(path, format="svg", metadata={"Title": caption})
    plt.close(figure)
    return path


def error_against_cost(suite, scenario, law, folder, provenance):
    """One panel per headline metric: |error| against wall time, log-log, one curve per engine and
    configuration (one point per time step; filled: against the beam reference, hollow: against the
    reference on the engine's own chain), the reference's own cost as a vertical line."""
    runs = suite.runs_of(scenario, law)
    configs = analysis.configurations(runs)
    reference = suite.beam_reference(scenario, law)
    figure, axes = plt.subplots(1, len(analysis.HEADLINE), figsize=(12, 3.8), constrained_layout=True)
    for ax, (title, column, kind) in zip(axes, analysis.HEADLINE):
        for config in configs:
            steps = [r for r in analysis.runs_of_config(runs, config) if r.stable]
            if not steps:
                continue
            cost = [r.number("wall_time_s") for r in steps]
            for against, filled in (("vs_reference_", True), ("vs_chain_reference_", False)):
                errors = [analysis.error(r, column, against) for r in steps]
                points = [(c, max(e, FLOOR)) for c, e in zip(cost, errors) if not math.isnan(e)]
                if not points:
                    continue
                xs, ys = zip(*points)
                colour = colour_of(config, configs)
                ax.plot(xs, ys, "-o" if filled else "--o", color=colour, markerfacecolor=colour if filled else "none",
                        label=config if filled else None, linewidth=1, markersize=4)
        if reference and not math.isnan(reference.number("wall_time_s")):
            ax.axvline(reference.number("wall_time_s"), color="black", linestyle=":", linewidth=1)
            ax.annotate("reference", (reference.number("wall_time_s"), 1), xycoords=("data", "axes fraction"),
                        rotation=90, va="top", ha="right", fontsize=7)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("run time [s]")
        ax.set_ylabel("|" + ("relative error" if kind == "relative" else "difference") + "|")
        ax.set_title(title, fontsize=9)
        ax.grid(True, which="both", linewidth=0.3)
    # one legend for all panels, from whichever panels drew the configurations: a panel can be empty (no
    # stable run, or a metric undefined in the case), and a legend without lines makes matplotlib warn
    legend = {}
    for ax in axes:
        for handle, label in zip(*ax.get_legend_handles_labels()):
            legend.setdefault(label, handle)
    if legend:
        axes[0].legend(legend.values(), legend.keys(), fontsize=7, loc="best")
    return save(figure, folder, f"error_vs_cost_{scenario}_{law}",
                f"{scenario}, {law}: error against run time (filled: vs beam reference, hollow: vs the engine's own "
                f"chain; zero errors drawn at {FLOOR:g}); {provenance}")


def sensor_time_history(suite, scenario, law, chosen, folder, provenance, seconds=2.0):
    """Frame 1's sensor acceleration over the last `seconds` of the window: the reference and each
    configuration at its best time step, as the paper shows the measured signals."""
    reference = suite.beam_reference(scenario, law)
    if reference is None:
        return None
    series = suite.series(reference)
    if series is None or not series["time_s"]:
        return None
    end = series["time_s"][-1]
    configs = [c for c in chosen]
    figure, ax = plt.subplots(figsize=(12, 3.6), constrained_layout=True)
    for label, run, colour, width in [("reference", reference, "black", 1.4)] + [
            (config, run, colour_of(config, configs), 0.9) for config, run in chosen.items() if run is not None]:
        s = series if run is reference else suite.series(run)
        if s is None:
            continue
        t, a = data.sensor_acceleration(s, 1)
        keep = [(x, y) for x, y in zip(t, a) if x >= end - seconds]
        if keep:
            xs, ys = zip(*keep)
            dt = run.number("time_step_s")
            ax.plot(xs, ys, color=colour, linewidth=width,
                    label=label if run is reference else f"{label}, dt = {dt:g} s")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("frame 1 sensor acceleration [g]")
    ax.grid(True, linewidth=0.3)
    ax.legend(fontsize=7, loc="upper right")
    return save(figure, folder, f"sensor_{scenario}_{law}",
                f"{scenario}, {law}: frame 1 acceleration as the 2048 Hz sensor reads it, last {seconds:g} s; {provenance}")


def impact_zoom(suite, scenario, law, chosen, folder, provenance):
    """Each simulator's strongest impact in the window (impact.csv.gz: the reference at 1 MHz, an engine at
    every step), aligned on its onset: frame 1's acceleration and the contact force. The impacts fall at
    different times in different simulators (the motion is chaotic), so each shows its own."""
    reference = suite.beam_reference(scenario, law)
    if reference is None:
        return None
    configs = list(chosen)
    figure, (top, bottom) = plt.subplots(2, 1, figsize=(12, 5), sharex=True, constrained_layout=True)
    drawn = 0
    for label, run, colour, width in [("reference", reference, "black", 1.4)] + [
            (config, run, colour_of(config, configs), 0.9) for config, run in chosen.items() if run is not None]:
        s = suite.series(run, "impact.csv")
        if s is None or not s["time_s"]:
            continue
        onset = next((t for t, f in zip(s["time_s"], s["contact_force_n"]) if f != 0), None)
        if onset is None:
            continue
        t = [(x - onset) * 1e3 for x in s["time_s"]]
        step = "" if run is reference else f", dt = {run.number('time_step_s'):g} s"
        top.plot(t, [a / data.G for a in s["frame1_acceleration_m_s2"]], ".-" if step else "-", color=colour,
                 linewidth=width, markersize=2, label=label + step)
        bottom.plot(t, s["contact_force_n"], ".-" if step else "-", color=colour, linewidth=width, markersize=2)
        drawn += 1
    if drawn == 0:
        plt.close(figure)
        return None
    top.set_ylabel("frame 1 acceleration [g]")
    bottom.set_ylabel("contact force [N]")
    bottom.set_xlabel("time from the impact's onset [ms]")
    for ax in (top, bottom):
        ax.set_xlim(-0.3, 1.0)
        ax.grid(True, linewidth=0.3)
    top.legend(fontsize=7)
    return save(figure, folder, f"impact_{scenario}_{law}",
                f"{scenario}, {law}: each simulator's strongest impact in the window, aligned on its onset "
                f"(reference: 1 MHz samples; engines: every step); {provenance}")


def stability_map(suite, law, folder, provenance, steps=None):
    """Engine configuration x time step x contact stiffness, each run a point coloured by its verdict;
    with steps.csv, each searched case's largest stable step (black bar, joined across stiffnesses) and
    largest step within tolerance per metric (markers) over it."""
    # Engine runs with a step: not the references, nor a law a scenario has no parameters for (recorded
    # as failed with no engine and no step, which a log axis cannot place).
    runs = [r for r in suite.runs if r["law"] == law and r["engine"] not in ("reference", "")
            and r.number("time_step_s") > 0]
    configs = analysis.configurations(runs)
    if not configs:
        return None
    figure, axes = plt.subplots(1, len(configs), figsize=(max(4, 3.2 * len(configs)), 3.6), sharey=True,
                                squeeze=False, constrained_layout=True)
    stiffness_of = {}
    for ax, config in zip(axes[0], configs):
        for r in analysis.runs_of_config(runs, config):
            file = r["scenario_file"]
            if file not in stiffness_of:
                stiffness_of[file] = data.contact_stiffness(data.read_scenario(file), law)
            k = stiffness_of[file]
            x = k if not math.isnan(k) else 1.0
            ax.scatter([x], [r.number("time_step_s")], color=VERDICT_COLOURS.get(r["verdict"], "black"), s=18)
        searched = []
        for row in (s for s in (steps or []) if s["law"] == law and s.config == config):
            file = next((r["scenario_file"] for r in suite.runs if r["scenario"] == row["scenario"]), "")
            if file not in stiffness_of:
                stiffness_of[file] = data.contact_stiffness(data.read_scenario(file), law)
            k = stiffness_of[file]
            searched.append((k if not math.isnan(k) else 1.0, row))
        searched.sort(key=lambda pair: pair[0])
        stable = [(x, row.number("largest_stable_step_s")) for x, row in searched
                  if not math.isnan(row.number("largest_stable_step_s"))]
        if stable:
            ax.plot(*zip(*stable), "_-", color="black", markersize=14, markeredgewidth=2, linewidth=0.8, zorder=3)
        palette = plt.rcParams["axes.prop_cycle"].by_key()["color"]
        for i, (prefix, _, _) in enumerate(data.STEP_METRICS):
            points = [(x, row.number(f"{prefix}_largest_step_within_tolerance_s")) for x, row in searched
                      if not math.isnan(row.number(f"{prefix}_largest_step_within_tolerance_s"))]
            if points:
                ax.scatter(*zip(*points), marker=STEP_MARKERS[prefix], facecolors="none", edgecolors=palette[i], s=40,
                           zorder=4)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(config, fontsize=8)
        ax.set_xlabel("contact stiffness" + (" [N/m]" if law == "viscoelastic" else " [N/m^n]" if law == "hertz" else " (n/a)"))
        ax.grid(True, which="both", linewidth=0.3)
    axes[0][0].set_ylabel("time step [s]")
    for verdict, colour in VERDICT_COLOURS.items():
        axes[0][-1].scatter([], [], color=colour, label=verdict, s=18)
    searched = any(s["law"] == law for s in (steps or []))
    if searched:
        palette = plt.rcParams["axes.prop_cycle"].by_key()["color"]
        axes[0][-1].plot([], [], "_-", color="black", markersize=14, markeredgewidth=2, linewidth=0.8,
                         label="largest stable step")
        for i, (prefix, label, _) in enumerate(data.STEP_METRICS):
            axes[0][-1].scatter([], [], marker=STEP_MARKERS[prefix], facecolors="none", edgecolors=palette[i], s=40,
                                label=f"{label} within tolerance up to")
    axes[0][-1].legend(fontsize=7, loc="best")
    return save(figure, folder, f"stability_{law}", f"{law}: verdict of every engine run by time step and contact stiffness"
                + ("; the largest stable and accurate steps found by the step search (steps.csv)" if searched else "")
                + f"; {provenance}")


def against_experiment(suite, law, chosen_by_case, experiment, folder, provenance):
    """Frame 1's sensor peak and impacts per cycle per published case: the experiment beside the
    reference and each configuration at its best step."""
    cases = [s for s, l in suite.cases() if l == law]
    if not cases:
        return None
    labels = ["experiment", "reference"]
    for chosen in chosen_by_case.values():
        labels += [c for c in chosen if c not in labels]
    figure, (left, right) = plt.subplots(1, 2, figsize=(12, 4), constrained_layout=True)
    width = 0.8 / len(labels)
    for i, label in enumerate(labels):
        peaks, rates = [], []
        for case in cases:
            if label == "experiment":
                peaks.append(experiment.get(case, {}).get("frame1_peak_acceleration_g", math.nan))
                rates.append(math.nan)
                continue
            run = suite.beam_reference(case, law) if label == "reference" else chosen_by_case.get(case, {}).get(label)
            peaks.append(run.number("frame1_sensor_peak_acceleration_g") if run else math.nan)
            rates.append(run.number("impacts_per_cycle") if run else math.nan)
        colour = "#444444" if label == "experiment" else "black" if label == "reference" else colour_of(label, labels[2:])
        positions = [c + (i - (len(labels) - 1) / 2) * width for c in range(len(cases))]
        left.bar(positions, [0 if math.isnan(p) else p for p in peaks], width, color=colour, label=label,
                 hatch="//" if label == "experiment" else None, alpha=0.9)
        right.bar(positions, [0 if math.isnan(r) else r for r in rates], width, color=colour, alpha=0.9)
    for ax, ylabel in ((left, "frame 1 peak acceleration [g]"), (right, "impacts per excitation cycle")):
        ax.set_xticks(range(len(cases)))
        ax.set_xticklabels(cases, fontsize=8)
        ax.set_ylabel(ylabel)
        ax.grid(True, axis="y", linewidth=0.3)
    left.legend(fontsize=7)
    return save(figure, folder, f"experiment_{law}",
                f"{law}: simulated sensor peaks and impacts per cycle beside the experiment's (rig.md section 7; the "
                f"experiment gives no impacts per cycle); {provenance}")


STEP_MARKERS = {"frame1_sensor_peak": "o", "contact_duration": "^", "impacts_per_cycle": "D"}


def step_limits(steps, scenario, law, folder, provenance):
    """From steps.csv: per engine configuration, the largest stable step (black bar from the smallest
    step searched, the smallest unstable step as a red x) and the largest step at which each headline
    metric is within its tolerance of the reference (one marker each), on a log axis."""
    rows = data.steps_of(steps, scenario, law)
    if not rows:
        return None
    figure, ax = plt.subplots(figsize=(9, 0.5 * len(rows) + 1.6), constrained_layout=True)
    metric_colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for y, row in enumerate(rows):
        low, stable = row.number("step_range_min_s"), row.number("largest_stable_step_s")
        if not math.isnan(stable):
            ax.plot([low, stable], [y, y], color="black", linewidth=3, solid_capstyle="butt")
        unstable = row.number("smallest_unstable_step_s")
        if not math.isnan(unstable):
            ax.scatter([unstable], [y], marker="x", color=VERDICT_COLOURS["unstable"], s=40, zorder=3)
        for i, (prefix, label, _) in enumerate(data.STEP_METRICS):
            step = row.number(f"{prefix}_largest_step_within_tolerance_s")
            if not math.isnan(step):
                ax.scatter([step], [y + 0.12 * (i - 1)], marker=STEP_MARKERS[prefix], color=metric_colours[i], s=30,
                           zorder=4)
        # what the markers cannot show: a metric within tolerance at no step of the range, or not decided
        missing = [f"{label}: {row[prefix + '_status']}" for prefix, label, _ in data.STEP_METRICS
                   if math.isnan(row.number(f"{prefix}_largest_step_within_tolerance_s"))
                   and not row[f"{prefix}_status"].startswith("not applicable")]
        if missing:
            ax.annotate("; ".join(missing), (low, y + 0.32), fontsize=6, color="#555555", va="center")
    ax.set_yticks(range(len(rows)))
    ax.set_yticklabels([r.config for r in rows], fontsize=7)
    ax.set_ylim(-0.6, len(rows) - 0.4)
    ax.invert_yaxis()
    ax.set_xscale("log")
    ax.set_xlabel("time step [s]")
    ax.grid(True, which="both", axis="x", linewidth=0.3)
    # the legend from empty proxies, so that it is complete whichever rows have which markers
    ax.plot([], [], color="black", linewidth=3, label="stable (from the smallest step searched)")
    ax.scatter([], [], marker="x", color=VERDICT_COLOURS["unstable"], s=40, label="smallest unstable step found")
    for i, (prefix, label, _) in enumerate(data.STEP_METRICS):
        ax.scatter([], [], marker=STEP_MARKERS[prefix], color=metric_colours[i], s=30, label=f"{label}: largest step within tolerance")
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1))
    tolerances = ", ".join(f"{label} {rows[0].number(data.STEP_TOLERANCE_COLUMNS[prefix]):g}"
                           + (" relative" if kind == "relative" else "")
                           for prefix, label, kind in data.STEP_METRICS)
    return save(figure, folder, f"steps_{scenario}_{law}",
                f"{scenario}, {law}: largest stable step and largest step within tolerance of the reference on the "
                f"engine's own chain ({tolerances}), found by bisection on a grid of "
                f"{rows[0].number('grid_points_per_octave'):g} steps per octave; {provenance}")
