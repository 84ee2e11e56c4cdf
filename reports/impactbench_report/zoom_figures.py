"""The impact zoom (the window's first impact in every simulator, aligned on its onset) and each
simulator's error against the experiment's measured peaks. Shared styling: figures.py."""

import math
import textwrap

import numpy as np

from . import analysis, data
from .figures import colour_of, label_point, legend_axis, plt, proxy, save
from .tables import step_text
from matplotlib import transforms

# ---- impact zoom -----------------------------------------------------------------------------------------

def impact_of(suite, run):
    """(impact series, onset time [s], the events.csv episode of that impact or None), or a text saying
    why there is none. A fixed-step engine's episode starts at the state before its first step with a force
    (that step's force acts over the interval ending at its sample); the reference's at its first sample
    with a force; a Newton reference has no force, its episode is the event inside the file's span."""
    s = suite.series(run, "impact.csv")
    if s is None or len(s["time_s"]) == 0:
        return "no impact file (impact.csv.gz)"
    times, forces = s["time_s"], s["contact_force_n"]
    with_force = np.flatnonzero((forces != 0) & ~np.isnan(forces))
    first = int(with_force[0]) if len(with_force) else None
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
    # a Newton case's impulse panel holds a label per configuration, written along its tick: more height
    figure = plt.figure(figsize=(12, 8.4 if newton else 7.2), constrained_layout=True)
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
        t = (s["time_s"] - onset) * 1e3
        style = dict(color=colour, linewidth=0.9 if engine else 1.4, drawstyle="steps-pre" if engine else "default",
                     rasterized=len(t) > 1000)
        last = max(last, t[-1])
        top.plot(t, s["frame1_acceleration_m_s2"] / data.G, **style)
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


# Where a point's label may go (label_placement.py): an impulse's beside its stem, a bar's beyond its end.
BESIDE = [(6, 0, "left", "center"), (-6, 0, "right", "center")]
BAR_END_UP = [(0, 3, "center", "bottom")]
BAR_END_DOWN = [(0, -3, "center", "top")]


def draw_impulses(ax, impulses):
    for x, (label, colour, impulse) in enumerate(impulses):
        if isinstance(impulse, str) or math.isnan(impulse):
            ax.text(x, 0, textwrap.fill(impulse if isinstance(impulse, str) else "no events.csv episode at the "
                                        "onset", 16), ha="center", va="bottom", fontsize=7, color="#aa0000")
            continue
        ax.vlines(x, 0, impulse, color=colour, linewidth=2)
        ax.plot([x], [impulse], "o", color=colour)
        label_point(ax, f"{impulse * 1e3:.2f} mN s", (x, impulse), BESIDE, fontsize=7)
    ax.set_xticks(range(len(impulses)))
    # upright they overlap once a case has more than a few configurations: written along the ticks
    ax.set_xticklabels([label for label, _, _ in impulses], fontsize=6, rotation=90)
    ax.set_xlim(-0.6, len(impulses) - 0.4)
    top = max([i for _, _, i in impulses if not isinstance(i, str) and i > 0] or [1.0])
    ax.set_ylim(0, 1.25 * top)
    ax.set_ylabel("impulse [N s]")
    ax.grid(True, axis="y", linewidth=0.3)


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
            label_point(ax, f"{error:+.0f} %\n{simulated:.3g} g", (x, error), BAR_END_UP if error >= 0 else BAR_END_DOWN,
                        fontsize=6)
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
