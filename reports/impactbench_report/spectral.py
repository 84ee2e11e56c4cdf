"""The frequency-domain views of a case (scenario, law), beside dynamics.py's time-domain ones and drawn with
its helpers: the amplitude spectrum and the wavelet scalogram of frame 1's sensor signal, the beam reference
(black) beside the runs the caller chose. Same signature and return value as dynamics.py's views."""

import math

import matplotlib
import numpy as np
from scipy import signal

from . import figures
from .dynamics import NO_SERIES, bottom_legend, impact_window, layout, no_data, scoring_window, sensor, shown
from .figures import proxy
from .signals import MORLET_W, amplitude_spectrum, wavelet_amplitude

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib import ticker  # noqa: E402

SENSOR_RATE_HZ = 2048.0  # the accelerometer's sampling rate (rig.md section 5)
SCALOGRAM_RATE_HZ = 512.0  # the sensor signal decimated to this before the wavelet transform (cheap, 0-256 Hz)
SCALOGRAM_BAND_HZ = (1.0, 200.0)
SCALOGRAM_SCALES = 72


def spectra(suite, scenario, law, chosen, folder, provenance):
    """Amplitude spectrum of frame 1's sensor signal over the scoring window, every simulator in one panel, the
    motor frequency and the frames' first natural frequencies marked."""
    runs = shown(suite, scenario, law, chosen)
    if not runs:
        return None
    start, end = scoring_window(runs)
    figure, (ax, side) = plt.subplots(1, 2, figsize=(13, 5), width_ratios=[3, 1], constrained_layout=True)
    missing = []
    for s in reversed(runs):  # the reference drawn last, on top
        if s.series is None:
            missing.append(s.title)
            continue
        frequencies, amplitude = amplitude_spectrum(sensor(s.series, 1, start, end)[1], SENSOR_RATE_HZ)
        ax.plot(frequencies[1:], amplitude[1:], color=s.colour, linewidth=1.2 if s.colour == "black" else 0.6,
                label=s.title, rasterized=True)
    handles = ax.get_legend_handles_labels()[0][::-1]
    diagnostics = suite.diagnostics(runs[0].run) if runs[0].run.is_beam_reference else {}
    marks = [("motor_frequency_hz", "motor frequency", "#d62728", "-"),
             ("frame1_first_frequency_hz", "frame 1's first natural frequency", "#555555", "--"),
             ("frame2_first_frequency_hz", "frame 2's first natural frequency", "#555555", ":")]
    for key, label, colour, style in marks:
        value = float(diagnostics.get(key) or math.nan)
        if value > 0:
            ax.axvline(value, color=colour, linestyle=style, linewidth=1, zorder=0)
            handles.append(proxy(f"{label}: {value:.4g} Hz", color=colour, linestyle=style))
    handles += [proxy(f"not drawn: {title}: {NO_SERIES}", color="none") for title in missing]
    ax.set_yscale("log")
    ax.set_xscale("log")
    ax.set_xlim(1.0, SENSOR_RATE_HZ / 2)
    ax.xaxis.set_major_formatter(ticker.FuncFormatter(lambda v, _: f"{v:g}"))
    ax.set_xlabel("frequency [Hz]")
    ax.set_ylabel("amplitude of a sine component [g]")
    ax.grid(alpha=0.3, which="both")
    side.axis("off")
    side.legend(handles=handles, fontsize=7, loc="upper left", frameon=False)
    return figures.save(figure, folder, f"spectrum_{scenario}_{law}",
                        f"{scenario}, {law}: amplitude spectrum of frame 1's sensor signal over {start:g}-{end:g} s "
                        f"(Welch, Hann windows of 2 s, half overlap; a sine of amplitude A reads A); {provenance}")


def scalograms(suite, scenario, law, chosen, folder, provenance):
    """Wavelet scalogram (Morlet CWT) of frame 1's sensor signal over the window of acceleration_histories,
    1-200 Hz on a log axis, one row per simulator, one colour scale in g; the transform runs on up to 2 s
    more on each side so that the window's edges are not the signal's, and the cone of influence is drawn."""
    runs = shown(suite, scenario, law, chosen)
    if not runs:
        return None
    start, end = impact_window(suite, scenario, runs)
    first, last = scoring_window(runs)
    frequencies = np.geomspace(*SCALOGRAM_BAND_HZ, SCALOGRAM_SCALES)
    maps = {}
    for s in runs:
        if s.series is None:
            continue
        t, a = sensor(s.series, 1, max(first, start - 2.0), min(last, end + 2.0))
        factor = int(round(SENSOR_RATE_HZ / SCALOGRAM_RATE_HZ))
        t, a = t[::factor], signal.decimate(a, factor, ftype="fir")  # output sample n is input sample n * factor
        amplitude = wavelet_amplitude(a, SENSOR_RATE_HZ / factor, frequencies)
        keep = (t >= start) & (t <= end)
        maps[s.name] = (t[keep], amplitude[:, keep], t[0], t[-1])
    top = max((m[1].max() for m in maps.values() if m[1].size), default=1.0)
    figure, axes, legend = layout(len(runs), 1, 10, 1.6, legend_height=0.3, sharex=True)
    image = None
    # e-folding time of a Morlet wavelet's edge effect at each frequency: sqrt(2) s, s = w / (2 pi f)
    reach = np.sqrt(2) * MORLET_W / (2 * np.pi * frequencies)
    for ax, s in zip(axes, runs):
        ax.set_title(s.title, fontsize=8)
        if s.name not in maps:
            no_data(ax)
            continue
        t, amplitude, t_first, t_last = maps[s.name]
        # an image on log10(f) (the scales are evenly spaced in it): three times cheaper to save than a mesh
        half_row = (np.log10(frequencies[1]) - np.log10(frequencies[0])) / 2
        image = ax.imshow(amplitude, origin="lower", aspect="auto", cmap="viridis", vmin=0, vmax=top,
                          interpolation="nearest", extent=(t[0], t[-1], np.log10(frequencies[0]) - half_row,
                                                           np.log10(frequencies[-1]) + half_row))
        for edge in (t_first + reach, t_last - reach):
            ax.plot(edge, np.log10(frequencies), color="white", linestyle="--", linewidth=0.8)
        ticks = [1, 2, 5, 10, 20, 50, 100, 200]
        ax.set_yticks(np.log10(ticks), [f"{f:g}" for f in ticks])
        ax.set_ylim(*np.log10(SCALOGRAM_BAND_HZ))
        ax.set_xlim(start, end)
        ax.set_ylabel("frequency [Hz]", fontsize=8)
    axes[-1].set_xlabel("time [s]")
    if image is not None:
        figure.colorbar(image, ax=list(axes), label="amplitude [g]", shrink=0.8)
    bottom_legend(legend, [proxy("white dashed line: cone of influence (the start or end of the series within "
                                 "about one wavelet width: edge effects there)", color="#555555", linestyle="--")], 1)
    return figures.save(figure, folder, f"scalogram_{scenario}_{law}",
                        f"{scenario}, {law}: continuous wavelet transform (Morlet, w = {MORLET_W:g}) of frame 1's "
                        f"sensor signal decimated to {SCALOGRAM_RATE_HZ:g} Hz, amplitude in g, over "
                        f"{start:g}-{end:g} s; {provenance}")
