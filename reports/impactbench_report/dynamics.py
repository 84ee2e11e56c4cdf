"""The views a vibro-impact researcher expects, per case (scenario, law), the beam reference (black, first)
beside the runs the caller chose: acceleration histories as the sensor reads them, phase portraits, Poincare
sections, per-impact distributions and the free vibration's amplitude decay; the spectra and wavelet
scalograms are in spectral.py, which draws with the helpers here.

Every function takes (suite, scenario, law, chosen, folder, provenance), `chosen` an ordered dict
{configuration name: Run}, and returns the saved SVG's path, or None when it has nothing to draw. The pure
functions under "signal processing" are what the figures compute; the tests check them against closed forms."""

import math
import os
from dataclasses import dataclass

import matplotlib
import numpy as np

from . import data, figures
from .figures import REPOSITORY, proxy
from .tables import step_text
from .signals import cycle_peaks, log_decrement, poincare_points

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib import ticker, transforms  # noqa: E402


NO_SERIES = "no series kept (run with --series none or a step-search probe)"


# ---- what each figure draws --------------------------------------------------------------------------------

@dataclass
class Shown:
    """One simulator in a figure: its name, run, colour and its series (numpy arrays, None when not kept)."""
    name: str
    run: object
    colour: str
    series: dict

    @property
    def title(self):
        if self.run.is_beam_reference:
            return "beam reference (adaptive step)"
        step = self.run.number("time_step_s")
        title = f"{self.name}, dt = {step_text(step)} s" if step > 0 else self.name
        return title if self.run.stable else f"{title} ({self.run['verdict']}: {self.run['reason'] or 'stopped'})"

    def onsets(self, start, end):
        return self.events_in(start, end).get("onset_time_s", np.array([]))

    def events_in(self, start, end):
        """events.csv rows whose onset lies in [start, end], as a dict of arrays ({} when none kept)."""
        events = self.series.get("events") if self.series else None
        if not events:
            return {}
        onset = np.asarray(events["onset_time_s"], float)
        keep = (onset >= start) & (onset <= end)
        return {name: np.asarray(column, float)[keep] for name, column in events.items()}


_CACHE = {}  # (folder, job id) -> series: every figure of a case reads the same few runs


def series_of(suite, run):
    """A run's series.csv as numpy arrays plus its events under "events" and the accelerometer's reading the
    harness wrote (sensor.csv) under "sensor"; None when it kept no series."""
    key = (suite.folder, run["job_id"])
    if key not in _CACHE:
        if len(_CACHE) > 24:
            _CACHE.clear()
        raw = suite.series(run)
        sensor = None if raw is None else suite.series(run, "sensor.csv")
        _CACHE[key] = None if raw is None else {**{k: np.asarray(v, float) for k, v in raw.items()},
                                                "events": suite.events(run),
                                                "sensor": None if sensor is None else
                                                {k: np.asarray(v, float) for k, v in sensor.items()}}
    return _CACHE[key]


def shown(suite, scenario, law, chosen):
    """The beam reference first (black), then the chosen runs in their order and colours."""
    names = list(chosen)
    result = []
    reference = suite.beam_reference(scenario, law)
    if reference is not None:
        result.append(Shown("beam reference", reference, "black", series_of(suite, reference)))
    for name, run in chosen.items():
        if run is not None and not run.is_beam_reference:
            result.append(Shown(name, run, figures.colour_of(name, names), series_of(suite, run)))
    return result


def scoring_window(runs):
    run = runs[0].run
    return run.number("window_start_s"), run.number("window_end_s")


def impact_window(suite, scenario, runs):
    """A window that holds impacts: with a motor the last second of the scoring window; in free vibration
    its first second, or up to 0.1 s after the last impact when they end sooner."""
    start, end = scoring_window(runs)
    if not math.isnan(suite.motor_frequency_hz(scenario)):
        return max(start, end - 1.0), end
    last = max((o.max() for o in (s.onsets(start, end) for s in runs) if len(o)), default=math.nan)
    return start, min(start + 1.0, end, last + 0.1 if not math.isnan(last) else end)


def gap_of(run):
    """The gap between the tips [m] from the run's scenario file (1 mm, rig.md section 1, when unreadable)."""
    path = run["scenario_file"]
    if path and not os.path.isabs(path):
        path = os.path.join(REPOSITORY, path)
    return float(data.read_scenario(path).get("rig", {}).get("gap_m", 1e-3)) if path else 1e-3


def sensor(series, frame, start, end):
    """The accelerometer's reading [g] of a frame between two times, as the harness computed and wrote it
    (sensor.csv: the one computation of rig.md section 5's sensor); empty for results without that file."""
    reading = series.get("sensor")
    if reading is None:
        return np.array([]), np.array([])
    times, values = reading["time_s"], reading[f"frame{frame}_sensor_acceleration_m_s2"] / data.G
    keep = (times >= start) & (times <= end)
    return times[keep], values[keep]






def layout(count, columns, width, height, legend_height=0.5, **shared):
    """A figure of `count` panels in `columns` columns (shared axes as asked) and a row below them for the
    legend (matplotlib 3.6's constrained layout leaves no room for a figure legend). Returns the figure, the
    panels in reading order, and the legend's axes."""
    rows = math.ceil(count / columns)
    figure = plt.figure(figsize=(width * columns + 0.8, height * rows + legend_height + 0.6), constrained_layout=True)
    grid = figure.add_gridspec(rows + 1, columns, height_ratios=[height] * rows + [legend_height])
    axes = []
    for k in range(count):
        share = {key: axes[0] for key, wanted in (("sharex", shared.get("sharex")), ("sharey", shared.get("sharey")))
                 if wanted and axes}
        axes.append(figure.add_subplot(grid[k // columns, k % columns], **share))
    legend = figure.add_subplot(grid[rows, :])
    legend.axis("off")
    return figure, axes, legend


def bottom_legend(ax, handles, columns):
    ax.legend(handles=handles, loc="center", ncol=columns, fontsize=8, frameon=False)


def no_data(ax, text=NO_SERIES):
    """A panel that says why it is empty (axis off: clearing its ticks would clear those of shared axes)."""
    ax.text(0.5, 0.5, text, ha="center", va="center", fontsize=8, transform=ax.transAxes, wrap=True)
    ax.axis("off")


def mark_onsets(ax, onsets):
    """Impact onsets as small triangles along the top edge of a time axis."""
    top = transforms.blended_transform_factory(ax.transData, ax.transAxes)
    ax.plot(onsets, np.full(len(onsets), 0.97), "v", color="#d62728", markersize=4, transform=top, clip_on=False)


# ---- the figures -------------------------------------------------------------------------------------------

def acceleration_histories(suite, scenario, law, chosen, folder, provenance):
    """Both frames' acceleration as the 2048 Hz sensor reads it over a window that holds impacts, one row per
    simulator, frame 1 left and frame 2 right, one y scale for all, impact onsets marked."""
    runs = shown(suite, scenario, law, chosen)
    if not runs:
        return None
    start, end = impact_window(suite, scenario, runs)
    figure, panels, legend = layout(2 * len(runs), 2, 5.8, 1.35, sharex=True, sharey=True)
    axes = [panels[k:k + 2] for k in range(0, len(panels), 2)]
    for row, s in zip(axes, runs):
        for frame, ax in zip((1, 2), row):
            ax.set_title(f"{s.title}: frame {frame}", fontsize=8)
            if s.series is None:
                no_data(ax)
                continue
            t, a = sensor(s.series, frame, start, end)
            ax.plot(t, a, color=s.colour, linewidth=0.7, rasterized=True)
            mark_onsets(ax, s.onsets(start, end))
            ax.grid(alpha=0.3)
        row[0].set_ylabel("acceleration [g]", fontsize=8)
    for ax in axes[-1]:
        ax.set_xlabel("time [s]")
    axes[0][0].set_xlim(start, end)
    bottom_legend(legend, [proxy("sensor reading (2048 Hz), in the simulator's colour", color="black", linestyle="-"),
                           proxy("onset of a contact (events.csv)", marker="v", color="#d62728")], 2)
    what = "the last second of the scoring window" if start > scoring_window(runs)[0] else \
        f"the first {end - start:.2g} s of the free vibration"
    return figures.save(figure, folder, f"acceleration_{scenario}_{law}",
                        f"{scenario}, {law}: acceleration of both frames' tips as the accelerometer reads it "
                        f"(velocity change over each 1/2048 s), over {what}; {provenance}")


def state_panels(runs, has_data):
    """One panel per simulator on the same (u1, v1) axes, titled; a panel without data says so."""
    figure, axes, legend = layout(len(runs), min(4, len(runs)), 3.3, 2.9, sharex=True, sharey=True)
    for ax, s in zip(axes, runs):
        ax.set_title(s.title, fontsize=8)
        if not has_data(s):
            no_data(ax)
            continue
        ax.grid(alpha=0.3)
        ax.xaxis.set_major_locator(ticker.MaxNLocator(nbins=4))  # "-0.0010" labels need room in a 3.3 in panel
        ax.set_xlabel("frame 1 tip displacement u1 [m]", fontsize=8)
        ax.set_ylabel("velocity v1 [m/s]", fontsize=8)
    return figure, axes, legend


def phase_portraits(suite, scenario, law, chosen, folder, provenance):
    """Frame 1's tip displacement against its velocity over the scoring window, one panel per simulator on
    the same axes, the states at impact onsets marked, the gap (frame 2's tip at rest) as a line."""
    runs = shown(suite, scenario, law, chosen)
    if not runs:
        return None
    start, end = scoring_window(runs)
    gap = gap_of(runs[0].run)
    figure, axes, legend = state_panels(runs, lambda s: s.series is not None)
    for ax, s in zip(axes, runs):
        if s.series is not None:
            t, u, v = (s.series[k] for k in ("time_s", "frame1_displacement_m", "frame1_velocity_m_s"))
            ax.plot(u, v, color=s.colour, linewidth=0.4, rasterized=True)
            onsets = s.onsets(start, end)
            ax.plot(np.interp(onsets, t, u), np.interp(onsets, t, v), "o", markersize=3, markerfacecolor="none",
                    color="#d62728")
            ax.axvline(gap, color="#555555", linestyle=":", linewidth=1)
    bottom_legend(legend, [proxy("trajectory over the scoring window", color="black", linestyle="-"),
                           proxy("state at a contact onset (events.csv)", marker="o", markerfacecolor="none",
                                 color="#d62728"),
                           proxy(f"u1 = gap ({gap * 1e3:g} mm): contact if frame 2 is at rest", color="#555555",
                                 linestyle=":")], 3)
    return figures.save(figure, folder, f"phase_portrait_{scenario}_{law}",
                        f"{scenario}, {law}: phase portrait of frame 1's tip over the scoring window "
                        f"{start:g}-{end:g} s (contact when u1 - u2 reaches the gap); {provenance}")


def poincare_sections(suite, scenario, law, chosen, folder, provenance):
    """Frame 1's state once per motor period (at the motor force's phase zero), one panel per simulator,
    the reference's points in grey behind every engine's; None without a motor."""
    frequency = suite.motor_frequency_hz(scenario)
    runs = shown(suite, scenario, law, chosen)
    if math.isnan(frequency) or not runs:
        return None
    start, end = scoring_window(runs)
    points = {}
    for s in runs:
        if s.series is not None:
            points[s.name] = poincare_points(s.series["time_s"], s.series["frame1_displacement_m"],
                                             s.series["frame1_velocity_m_s"], frequency, start, end)
    reference = points.get(runs[0].name) if runs[0].run.is_beam_reference else None
    figure, axes, legend = state_panels(runs, lambda s: s.name in points)
    for ax, s in zip(axes, runs):
        if s.name in points:
            if reference is not None and s.name != runs[0].name:
                ax.plot(*reference, "o", color="#bbbbbb", markersize=5, rasterized=True)
            ax.plot(*points[s.name], ".", color=s.colour, markersize=5, rasterized=True)
    if points:  # frame the points, at least 5 % of the orbit wide: a collapsed section is then a dot, not noise
        for k, (column, limits) in enumerate((("frame1_displacement_m", axes[0].set_xlim),
                                              ("frame1_velocity_m_s", axes[0].set_ylim))):
            values = np.concatenate([p[k] for p in points.values()])
            orbit = max(np.ptp(s.series[column]) for s in runs if s.name in points)
            middle, half = (values.min() + values.max()) / 2, max(np.ptp(values), 0.05 * orbit) * 0.55
            limits(middle - half, middle + half)
    count = len(next(iter(points.values()))[0]) if points else 0
    bottom_legend(legend, [proxy(f"state at t = k / f_motor, f_motor = {frequency:.4g} Hz ({count} samples)",
                                 marker=".", color="black"),
                           proxy("beam reference's states, behind each engine's", marker="o", color="#bbbbbb")], 2)
    return figures.save(figure, folder, f"poincare_{scenario}_{law}",
                        f"{scenario}, {law}: Poincare section, frame 1's state sampled once per motor period "
                        f"over {start:g}-{end:g} s (a periodic response of period n collapses to n points); "
                        f"{provenance}")


def ecdf(ax, values, colour, label):
    values = np.sort(values[np.isfinite(values)])
    if len(values):
        ax.step(np.r_[values[0], values], np.r_[0, np.arange(1, len(values) + 1) / len(values)], where="post",
                color=colour, linewidth=1.6 if colour == "black" else 1.0, label=label)
    else:
        ax.plot([], [], color=colour, label=label)


def impact_distributions(suite, scenario, law, chosen, folder, provenance):
    """Empirical distributions (CDFs) of every contact's restitution and approach velocity over the scoring
    window, one curve per simulator."""
    runs = shown(suite, scenario, law, chosen)
    if not runs:
        return None
    start, end = scoring_window(runs)
    figure, axes, legend = layout(2, 2, 5.8, 3.8, legend_height=0.15 + 0.08 * len(runs))
    restitution = "restitution e [-]" + (" (the Newton law sets it: shown for the record)" if law == "newton" else "")
    for ax, column, label, title in zip(axes, ("restitution", "approach_velocity_m_s"),
                                        (restitution, "approach velocity [m/s]"),
                                        ("restitution of each contact", "approach velocity of each contact")):
        for s in runs:
            if s.series is None:
                ax.plot([], [], color=s.colour, label=f"{s.title}: {NO_SERIES}")
                continue
            values = s.events_in(start, end).get(column, np.array([]))
            ecdf(ax, values, s.colour, f"{s.title}: {len(values)} contacts")
        ax.set_xlabel(label)
        ax.set_ylabel("fraction of contacts at or below [-]")
        ax.set_title(title + " (events.csv)", fontsize=9)
        ax.grid(alpha=0.3)
    bottom_legend(legend, axes[1].get_legend_handles_labels()[0], 2)
    return figures.save(figure, folder, f"impacts_{scenario}_{law}",
                        f"{scenario}, {law}: empirical distribution of each contact's restitution (rebound over "
                        f"approach relative velocity) and approach velocity, contacts with onset in {start:g}-{end:g} "
                        f"s; {provenance}")


def amplitude_decay(suite, scenario, law, chosen, folder, provenance):
    """Free vibration only: frame 1's cycle peaks against time for every simulator on a log axis, in the legend
    the log decrement over the window (as runs.csv's frame1_log_decrement) and after the simulator's last
    contact (structural and numerical damping alone, no impact losses), its last contact marked; None with a
    motor."""
    runs = shown(suite, scenario, law, chosen)
    if not runs or not math.isnan(suite.motor_frequency_hz(scenario)):
        return None
    start, end = scoring_window(runs)
    figure, (ax,), legend = layout(1, 1, 10, 4.2, legend_height=0.3 + 0.09 * len(runs))
    handles = []
    for s in runs:
        if s.series is None:
            handles.append(proxy(f"{s.title}: {NO_SERIES}", color=s.colour))
            continue
        t, u = s.series["time_s"], s.series["frame1_displacement_m"]
        ax.plot(*cycle_peaks(t, u), "o-", color=s.colour, markersize=3, linewidth=1.6 if s.colour == "black" else 1)
        decrement, rate = log_decrement(t, u)
        ends = s.events_in(start, end).get("end_time_s", np.array([]))
        free = t > (ends.max() if len(ends) else start)
        after = log_decrement(t[free], u[free])[0]
        after = f"{after:.4f} after its last contact" if not math.isnan(after) else "< 3 cycles after its last contact"
        handles.append(proxy(f"{s.title}: delta = {decrement:.4f} per cycle ({rate:.3g} 1/s) over the window, "
                             f"{after}", color=s.colour, marker="o", linestyle="-"))
        if len(ends):
            ax.axvline(ends.max(), color=s.colour, linestyle=":", linewidth=1)
    ax.axhline(gap_of(runs[0].run), color="#555555", linestyle="--", linewidth=1)
    handles += [proxy("dotted: the end of the simulator's last contact", color="black", linestyle=":"),
                proxy("gap: a peak above it meets frame 2 at rest", color="#555555", linestyle="--")]
    ax.set_yscale("log")
    ax.yaxis.set_major_locator(ticker.LogLocator(subs=(1, 1.5, 2, 3, 4, 5, 6, 7, 8, 9), numticks=30))
    ax.yaxis.set_major_formatter(ticker.FuncFormatter(lambda v, _: f"{v:g}"))
    ax.yaxis.set_minor_formatter(ticker.NullFormatter())
    ax.set_xlabel("time [s]")
    ax.set_ylabel("frame 1 tip displacement, peak of each cycle [m]")
    ax.grid(alpha=0.3, which="both")
    bottom_legend(legend, handles, 1)
    return figures.save(figure, folder, f"decay_{scenario}_{law}",
                        f"{scenario}, {law}: amplitude decay of frame 1 (its largest displacement between upward zero "
                        f"crossings); logarithmic decrement delta = least-squares slope of -ln(peak) against the "
                        f"cycle, over {start:g}-{end:g} s (impacts included) and after each simulator's last contact; "
                        f"{provenance}")
