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

from . import analysis, data  # noqa: E402

VERDICT_COLOURS = {"ok": "#2ca02c", "inaccurate": "#ff7f0e", "unstable": "#d62728", "failed": "#7f7f7f"}
VERDICT_MARKERS = {"ok": "o", "inaccurate": "s", "unstable": "X", "failed": "P"}
STEP_MARKERS = {"frame1_sensor_peak": "o", "contact_duration": "^", "impacts_per_cycle": "D"}
METRIC_COLOURS = ["#1f77b4", "#9467bd", "#000000"]  # the step search's metrics: no verdict's colour
REPOSITORY = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


# A configuration's colour from its engine and contact path, the same in every figure whichever configurations
# a figure holds; none is a verdict's colour (green, orange, red, grey).
ENGINE_COLOURS = {("bullet", "matched"): "#1f77b4", ("bullet", "native"): "#17becf", ("bullet", "injected"): "#0b3d91",
                  ("mujoco", "matched"): "#9467bd", ("mujoco", "native"): "#e377c2", ("mujoco", "injected"): "#5b2a86",
                  ("ode", "matched"): "#8c564b", ("ode", "native"): "#bcbd22", ("ode", "injected"): "#4e2a1e"}
SPARE_COLOURS = ["#393b79", "#637939", "#8c6d31", "#843c39", "#7b4173", "#3182bd", "#31a354", "#756bb1"]


def colour_key(config):
    engine, _, options = config.partition(" [")
    contact = next((o.split("=", 1)[1] for o in options.rstrip("]").split(";") if o.startswith("contact=")), "matched")
    return engine, contact


def colour_of(config, configs):
    """The engine and contact path's own colour; a second configuration of the same engine and contact path
    (other options) in `configs` takes a spare colour by its place in the list."""
    key = colour_key(config)
    earlier = [c for c in configs[:configs.index(config)]] if config in configs else []
    if key in ENGINE_COLOURS and not any(colour_key(c) == key for c in earlier):
        return ENGINE_COLOURS[key]
    return SPARE_COLOURS[configs.index(config) % len(SPARE_COLOURS)] if config in configs else "black"


def save(figure, folder, name, caption):
    """Saves a figure as SVG with its caption (what it shows and what produced it) on top, and as the
    SVG's title; returns the path."""
    figure.suptitle(textwrap.fill(caption, max(60, int(17 * figure.get_figwidth()))), fontsize=7)
    path = os.path.join(folder, name + ".svg")
    figure.savefig(path, format="svg", metadata={"Title": caption})
    plt.close(figure)
    return path


# ---- shared pieces ---------------------------------------------------------------------------------------

def step_text(step):
    """A time step as short text: 1e-4, 6.25e-5."""
    mantissa, exponent = f"{step:.2e}".split("e")
    return f"{float(mantissa):g}e{int(exponent)}"


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
    """CPU time per simulated second [s/s] over the part of the run that was simulated: a run stopped as
    unstable at t = 0.02 s of 20 s would otherwise look a thousand times cheaper than it is. NaN when the
    run never stepped."""
    steps, step = run.number("steps"), run.number("time_step_s")
    if steps > 0 and step > 0 and steps * step < 0.999 * run.number("duration_s"):
        return run.number("cpu_time_s") / (steps * step)
    cost = run.number("cpu_time_per_simulated_s")
    return cost if cost > 0 else math.nan


def tolerance_of(column, tolerances):
    key = next(key for _, _, error_column, _, key in analysis.SCORED if error_column == column)
    return tolerances.get(key, analysis.DEFAULT_TOLERANCES[key])


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
    tolerances = tolerances or analysis.DEFAULT_TOLERANCES
    runs = suite.runs_of(scenario, law)
    engine_runs = [r for r in runs if r["engine"] not in ("reference", "")]
    configs = analysis.configurations(runs)
    beam = suite.beam_reference(scenario, law)
    chains = [r for r in runs if r["engine"] == "reference" and not r.is_beam_reference]
    defined = lambda column: any(not math.isnan(analysis.signed_error(r, column, prefix))  # noqa: E731
                                 for r in engine_runs + chains for prefix in analysis.AGAINST.values())
    metrics = [m for m in analysis.HEADLINE if defined(m[1])]
    dropped = [why_undefined(column, scenario, law, suite) for _, column, _ in analysis.HEADLINE if not defined(column)]
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
                proxy("5e-5 beside a point: its time step [s]", color="none"),
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
        strip.annotate(f"{run['verdict']} {step_text(run.number('time_step_s'))}", (cost, row), xytext=(5, 0),
                       textcoords="offset points", fontsize=6, va="center", color=colour_of(run.config, configs))
    for (row, verdict), steps in never.items():
        strip.text(0.01, row, f"{verdict} before any step (no cost): {', '.join(steps)} s",
                   transform=transforms.blended_transform_factory(strip.transAxes, strip.transData), fontsize=6,
                   va="center", color=colour_of(stopped_configs[row], configs))
    strip.set_ylim(len(stopped_configs) - 0.5, -0.5)
    strip.set_yticks([])
    strip.tick_params(labelbottom=False)
    strip.grid(True, axis="x", which="major", linewidth=0.4)


CHAIN = "8-link chain reference"


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
            strip.annotate(text, (cost, row), xytext=(5, 0), textcoords="offset points", fontsize=6, va="center",
                           color=colour)
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
                ax.annotate(step_text(p[2].number("time_step_s")), (p[3], p[4]), xytext=(4, 2 if filled else -7),
                            textcoords="offset points", fontsize=6, color=colour)
    for p in points:
        if p[0] == CHAIN and p[4] > 0:
            ax.plot([p[3]], [p[4]], "*", color="black", markersize=9, zorder=5)
    ax.axhline(tolerance * scale, color="#555555", linestyle="-.", linewidth=1)
    ax.annotate(f"tolerance {tolerance * scale:g}{' %' if scale == 100 else ''}", (0.01, tolerance * scale),
                xycoords=transforms.blended_transform_factory(ax.transAxes, ax.transData), xytext=(0, 2),
                textcoords="offset points", fontsize=6, color="#555555")
    if beam is not None and run_cost(beam) > 0:
        ax.axvline(run_cost(beam), color="black", linestyle=":", linewidth=1)
        ax.annotate(f"beam reference {run_cost(beam):.2g} s/s", (run_cost(beam), 0.5), xycoords=edge, rotation=90,
                    xytext=(-2, 0), textcoords="offset points", va="center", ha="right", fontsize=6)
    ax.set_xlabel("CPU time per simulated second [s/s]")
    ax.set_ylabel("|relative error| [%]" if scale == 100 else "|difference| [impacts per cycle]")
    ax.grid(True, which="major", linewidth=0.4)
    ax.grid(True, which="minor", linewidth=0.15, color="#dddddd")


# ---- acceleration history (kept until dynamics.py replaces it) ---------------------------------------------

def sensor_time_history(suite, scenario, law, chosen, folder, provenance, seconds=2.0):
    """Frame 1's sensor acceleration over the last `seconds` of the window: the reference and each
    configuration at its best time step, as the paper shows the measured signals."""
    reference = suite.beam_reference(scenario, law)
    series = suite.series(reference) if reference else None
    if series is None or not series["time_s"]:
        return None
    end = series["time_s"][-1]
    configs = list(chosen)
    figure, ax = plt.subplots(figsize=(12, 3.6), constrained_layout=True)
    for label, run, colour, width in [("beam reference", reference, "black", 1.4)] + [
            (config, run, colour_of(config, configs), 0.9) for config, run in chosen.items() if run is not None]:
        s = series if run is reference else suite.series(run)
        if s is None:
            continue
        t, a = data.sensor_acceleration(s, 1)
        keep = [(x, y) for x, y in zip(t, a) if x >= end - seconds]
        if keep:
            xs, ys = zip(*keep)
            step = "" if run is reference else f", dt = {run.number('time_step_s'):g} s"
            ax.plot(xs, ys, color=colour, linewidth=width, label=label + step, rasterized=True)
    ax.set_xlabel("time [s]")
    ax.set_ylabel("frame 1 sensor acceleration [g]")
    ax.grid(True, linewidth=0.3)
    ax.legend(fontsize=7, loc="upper right")
    return save(figure, folder, f"sensor_{scenario}_{law}",
                f"{scenario}, {law}: frame 1 acceleration as the 2048 Hz sensor reads it, last {seconds:g} s; "
                f"{provenance}")


# ---- impact zoom -----------------------------------------------------------------------------------------

def impact_of(suite, run):
    """(impact series, onset time [s], the events.csv episode of that impact or None), or a text saying
    why there is none. A fixed-step engine's episode starts at the state before its first step with a force
    (that step's force acts over the interval ending at its sample); the reference's at its first sample
    with a force; a Newton reference has no force, its episode is the event inside the file's span."""
    s = suite.series(run, "impact.csv")
    if s is None or not s["time_s"]:
        return "no impact file (impact.csv.gz)"
    times, forces = s["time_s"], s["contact_force_n"]
    first = next((i for i, f in enumerate(forces) if f != 0 and not math.isnan(f)), None)
    step = run.number("time_step_s")
    events = suite.events(run) or {"onset_time_s": []}
    if first is not None:
        onset = times[max(first - 1, 0)] if step > 0 else times[first]
    else:
        onset = next((t for t in events["onset_time_s"] if times[0] <= t <= times[-1]), None)
        if onset is None:
            return "no contact in its impact file"
    slack = 0.5 * step if step > 0 else 1e-6
    matched = [i for i, t in enumerate(events["onset_time_s"]) if abs(t - onset) <= slack]
    episode = {name: values[matched[0]] for name, values in events.items()} if matched else None
    return s, onset, episode


def first_episode(suite, run):
    """The first contact episode whose onset lies in the scoring window (events.csv), or None."""
    events = suite.events(run) or {"onset_time_s": []}
    start = run.number("window_start_s")
    first = next((i for i, t in enumerate(events["onset_time_s"]) if not t < start), None)
    return {name: values[first] for name, values in events.items()} if first is not None else None


def impact_zoom(suite, scenario, law, chosen, folder, provenance):
    """The first impact of the scoring window in every simulator (impact.csv.gz: the reference at 1 MHz, an
    engine at every step), aligned on its onset: frame 1's acceleration and velocity, and the contact force
    (Newton law: the impulse, as impacts are instantaneous). Engine samples are drawn as steps."""
    reference = suite.beam_reference(scenario, law)
    configs = analysis.configurations(suite.runs_of(scenario, law))
    newton = law == "newton"
    figure = plt.figure(figsize=(12, 7.2), constrained_layout=True)
    grid = figure.add_gridspec(3, 2, width_ratios=[4, 1.1])
    top = figure.add_subplot(grid[0, 0])
    middle = figure.add_subplot(grid[1, 0], sharex=top)
    bottom = figure.add_subplot(grid[2, 0], sharex=None if newton else top)
    simulators = [("beam reference", reference, "black")] + [(c, r, colour_of(c, configs)) for c, r in chosen.items()
                                                             if r is not None]
    handles, notes, impulses, durations, last = [], [], [], {}, 0.0
    for label, run, colour in simulators:
        if run is None:
            notes.append("beam reference: no run in this case")
            continue
        found = impact_of(suite, run)
        if isinstance(found, str):
            episode = first_episode(suite, run) if newton else None
            impulses.append((label, colour, episode["impulse_n_s"] if episode else found))
            notes.append(f"{label}: {found}" + (" (its impulse: the first episode of the window in events.csv)"
                                                if episode else ""))
            continue
        s, onset, episode = found
        engine = run.number("time_step_s") > 0
        t = [(x - onset) * 1e3 for x in s["time_s"]]
        style = dict(color=colour, linewidth=0.9 if engine else 1.4, drawstyle="steps-pre" if engine else "default",
                     rasterized=len(t) > 1000)
        last = max(last, t[-1])
        top.plot(t, [a / data.G for a in s["frame1_acceleration_m_s2"]], **style)
        middle.plot(t, s["frame1_velocity_m_s"], **style)
        if not newton:
            bottom.plot(t, s["contact_force_n"], **style)
        at = f"onset {onset:.5f} s" + (f", dt = {step_text(run.number('time_step_s'))} s" if engine else ", 1 MHz")
        handles.append(proxy(f"{label} ({at})", color=colour, linestyle="-"))
        impulses.append((label, colour, episode["impulse_n_s"] if episode else math.nan))
        durations[len(handles) - 1] = episode["duration_s"] * 1e3 if episode else math.nan
    if len(notes) == len(simulators):
        plt.close(figure)
        return None
    notes += [f"{config}: no stable run" for config in analysis.configurations(suite.runs_of(scenario, law))
              if chosen.get(config) is None]
    # the frame fits the reference's contact; an engine's much longer contact (a soft native contact) is
    # cut, and its legend entry says how long it lasts
    reference_duration = durations.get(0, math.nan) if reference is not None and handles and \
        handles[0].get_label().startswith("beam reference") else math.nan
    end = max(1.0, 3.0 * reference_duration) if not math.isnan(reference_duration) else 1.0
    for i, duration in durations.items():
        if duration > end:
            handles[i].set_label(handles[i].get_label() + f"\n  contact lasts {duration:.3g} ms, beyond the frame")
    top.set_xlim(-0.3, min(end, last) if last > 0.5 else end)
    for ax, label in ((top, "frame 1 acceleration [g]"), (middle, "frame 1 velocity [m/s]")):
        ax.set_ylabel(label)
        ax.grid(True, linewidth=0.3)
        ax.axvline(0, color="#888888", linewidth=0.6, linestyle=":")
    top.tick_params(labelbottom=False)
    if newton:
        middle.set_xlabel("time from the impact's onset [ms]")
        draw_impulses(bottom, impulses)
    else:
        middle.tick_params(labelbottom=False)
        bottom.set_ylabel("contact force [N]")
        bottom.set_xlabel("time from the impact's onset [ms]")
        bottom.grid(True, linewidth=0.3)
        bottom.axvline(0, color="#888888", linewidth=0.6, linestyle=":")
    handles += [proxy("engine: held over each step (a sample's value\nbelongs to the step ending at it)",
                      color="#555555", linestyle="-", drawstyle="steps-pre"),
                proxy("reference: continuous, 1 MHz samples", color="#555555", linestyle="-"),
                proxy("onset (t = 0)", color="#888888", linestyle=":")]
    handles += [proxy("not drawn: " + textwrap.fill(note, 50), color="none") for note in notes]
    legend = figure.add_subplot(grid[:, 1])
    legend_axis(legend, handles)
    free = math.isnan(suite.motor_frequency_hz(scenario))
    caption = (f"{scenario}, {law}: the first impact whose onset lies in the scoring window, in every simulator ("
               + ("without a motor, the same physical impact in all" if free else
                  "in a forced case whose motion may be chaotic, each simulator's own first impact of the window, "
                  "k = 1, not necessarily the same physical event") +
               "), aligned on its onset (an engine's: the state before its first step with a force)")
    if newton:
        caption += ("; Newton law: the impact is instantaneous, its impulse (events.csv) is drawn instead of a "
                    "force; an engine spreads it over one or more steps, so its acceleration shows spikes where the "
                    "reference's velocity jumps")
    return save(figure, folder, f"impact_{scenario}_{law}", caption + f"; {provenance}")


def draw_impulses(ax, impulses):
    for x, (label, colour, impulse) in enumerate(impulses):
        if isinstance(impulse, str) or math.isnan(impulse):
            ax.text(x, 0, textwrap.fill(impulse if isinstance(impulse, str) else "no events.csv episode at the "
                                        "onset", 16), ha="center", va="bottom", fontsize=7, color="#aa0000")
            continue
        ax.vlines(x, 0, impulse, color=colour, linewidth=2)
        ax.plot([x], [impulse], "o", color=colour)
        ax.annotate(f"{impulse * 1e3:.2f} mN s", (x, impulse), xytext=(6, 0), textcoords="offset points",
                    fontsize=7, va="center")
    ax.set_xticks(range(len(impulses)))
    ax.set_xticklabels([textwrap.fill(label, 18) for label, _, _ in impulses], fontsize=7)
    ax.set_xlim(-0.6, len(impulses) - 0.4)
    top = max([i for _, _, i in impulses if not isinstance(i, str) and i > 0] or [1.0])
    ax.set_ylim(0, 1.25 * top)
    ax.set_ylabel("impulse of the impact [N s]")
    ax.grid(True, axis="y", linewidth=0.3)


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
        [f"{p}_largest_step_within_tolerance_s" for p, _, _ in data.STEP_METRICS] if s.number(c) > 0]
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
            for i, (prefix, _, _) in enumerate(data.STEP_METRICS):
                value = row.number(f"{prefix}_largest_step_within_tolerance_s")
                if value > 0:
                    ax.scatter([x + 0.1 * (i - 1)], [value], marker=STEP_MARKERS[prefix], facecolors="none",
                               edgecolors=palette[i], s=36, zorder=5)
        ax.set_yscale("log")
        ax.set_ylim(*padded(all_steps, 1.4))
        # every step tried is a labelled tick: the points sit on them
        ax.yaxis.set_major_locator(ticker.FixedLocator(sorted(set(all_steps))))
        ax.yaxis.set_major_formatter(ticker.FuncFormatter(lambda v, _: step_text(v)))
        ax.yaxis.set_minor_locator(ticker.NullLocator())
        ax.set_xticks(range(len(cases)))
        ax.set_xticklabels(ticks, fontsize=6.5)
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
                    for i, (prefix, label, _) in enumerate(data.STEP_METRICS)]
    legend_axis(figure.add_subplot(grid[:, columns]), handles)
    return save(figure, folder, f"stability_{law}",
                f"{law}: the verdict of every engine run, by case (its contact parameter under its name) and time "
                f"step, one panel per configuration" + ("; right of the runs, the step search's results "
                                                        "(steps.csv)" if searched else "") + f"; {provenance}")


# ---- the experiment --------------------------------------------------------------------------------------

def against_experiment(suite, law, chosen_by_case, experiment, folder, provenance):
    """Each simulator's signed error against the measured frame 1 peak acceleration, per published case:
    the beam reference and each configuration at its best step. The experiment is data, not a target."""
    cases = [s for s, l in suite.cases() if l == law and s in experiment]
    if not cases:
        return None
    labels = ["beam reference"]
    for case in cases:
        labels += [c for c in chosen_by_case.get(case, {}) if c not in labels]
    configs = labels[1:]
    figure, (ax, legend) = plt.subplots(1, 2, figsize=(max(7.0, 2.6 * len(cases) + 3.2), 4.4),
                                        constrained_layout=True, gridspec_kw={"width_ratios": [2.6 * len(cases), 3]})
    width = 0.8 / len(labels)
    for c, case in enumerate(cases):
        measured = experiment[case].get("frame1_peak_acceleration_g")
        if measured is None:
            ax.text(c, 0.5, "no measurement\nof the frame 1 peak", ha="center", va="center", fontsize=8,
                    color="#555555", transform=transforms.blended_transform_factory(ax.transData, ax.transAxes))
            continue
        for i, label in enumerate(labels):
            run = suite.beam_reference(case, law) if i == 0 else chosen_by_case.get(case, {}).get(label)
            x = c + (i - (len(labels) - 1) / 2) * width
            simulated = run.number("frame1_sensor_peak_acceleration_g") if run else math.nan
            if math.isnan(simulated):
                ax.text(x, 0, "no stable run" if i else "no reference run", rotation=90, ha="center", va="bottom",
                        fontsize=6, color="#555555")
                continue
            error = 100 * (simulated - measured) / measured
            ax.bar([x], [error], width, color="black" if i == 0 else colour_of(label, configs))
            ax.annotate(f"{error:+.0f} %\n{simulated:.3g} g", (x, error), xytext=(0, 3 if error >= 0 else -3),
                        textcoords="offset points", ha="center", va="bottom" if error >= 0 else "top", fontsize=6)
    ax.axhline(0, color="black", linewidth=0.8)
    ax.use_sticky_edges = False  # room above and below the bars for their labels
    ax.margins(y=0.2)
    ax.set_xlim(-0.6, len(cases) - 0.4)
    ax.set_xticks(range(len(cases)))
    ax.set_xticklabels([case + (f"\nmeasured {experiment[case]['frame1_peak_acceleration_g']:g} g"
                                if "frame1_peak_acceleration_g" in experiment[case] else "") for case in cases],
                       fontsize=8)
    ax.set_ylabel("simulated - measured frame 1 peak [% of measured]")
    ax.grid(True, axis="y", linewidth=0.3)
    handles = [proxy("beam reference", marker="s", color="black", markersize=8)]
    handles += [proxy(f"{config}\n(at its best step)", marker="s", color=colour_of(config, configs), markersize=8)
                for config in configs]
    legend_axis(legend, handles)
    missing = [case for case in experiment if not any(s == case for s, l in suite.cases() if l == law)]
    return save(figure, folder, f"experiment_{law}",
                f"{law}: each simulator's frame 1 sensor peak against the measured one (rig.md section 7), signed, "
                f"in percent of the measurement; the experiment is data beside the simulators, not a target" +
                (f"; published cases not in this suite: {', '.join(missing)}" if missing else "") + f"; {provenance}")


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
                for i, (prefix, label, _) in enumerate(data.STEP_METRICS)]
    ax.legend(handles=handles, fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1))
    tolerances = ", ".join(f"{label} {rows[0].number(data.STEP_TOLERANCE_COLUMNS[prefix]):g}"
                           + (" relative" if kind == "relative" else "")
                           for prefix, label, kind in data.STEP_METRICS)
    return save(figure, folder, f"steps_{scenario}_{law}",
                f"{scenario}, {law}: largest stable step and largest step within tolerance of the reference on the "
                f"engine's own chain ({tolerances}), found by bisection on a grid of "
                f"{rows[0].number('grid_points_per_octave'):g} steps per octave; {provenance}")
