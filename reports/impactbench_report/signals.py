"""The signal processing behind the researcher's views (dynamics.py), as pure functions the tests check
against closed forms: one peak per cycle and the logarithmic decrement, Poincare sampling, Welch amplitude
spectra and the Morlet wavelet transform's amplitude."""

import math

import numpy as np
from scipy import signal, stats

MORLET_W = 6.0  # cycles of the Morlet wavelet: the usual balance of time and frequency resolution


def cycle_peaks(times, displacements):
    """One peak per whole cycle: the largest displacement between two upward zero crossings, so that higher
    modes riding on the first do not count (the same cycles as harness/scoring/amplitude_decay.cpp). Returns
    (peak times, peaks) as arrays."""
    t, u = np.asarray(times, float), np.asarray(displacements, float)
    up = np.flatnonzero((u[:-1] <= 0) & (u[1:] > 0)) + 1
    peak_index = [a + int(np.argmax(u[a:b])) for a, b in zip(up[:-1], up[1:])]
    return t[peak_index], u[peak_index]


def log_decrement(times, displacements):
    """(logarithmic decrement per cycle [-], decay rate [1/s]) of a free vibration: the least-squares slope of
    ln(peak) against the cycle's index over its cycle peaks, and that slope over the mean cycle period (the
    slope of the peaks' times against their index). For u = A exp(-zeta w t) sin(w_d t) they are
    2 pi zeta / sqrt(1 - zeta^2) and zeta w. NaN, NaN with fewer than three cycles or a non-positive peak."""
    peak_times, peaks = cycle_peaks(times, displacements)
    if len(peaks) < 3 or np.any(peaks <= 0):
        return math.nan, math.nan
    index = np.arange(len(peaks))
    decrement = -stats.linregress(index, np.log(peaks)).slope
    period = stats.linregress(index, peak_times).slope
    return decrement, decrement / period


def poincare_points(times, displacements, velocities, frequency_hz, start_s, end_s):
    """The states (u, v) once per excitation period, at the motor's phase zero (t = k / f) inside
    [start_s, end_s] and inside the series (np.interp would hold the last value beyond it), interpolated
    linearly between samples."""
    start_s, end_s = max(start_s, times[0]), min(end_s, times[-1])
    k = np.arange(math.ceil(start_s * frequency_hz - 1e-9), math.floor(end_s * frequency_hz + 1e-9) + 1)
    instants = k / frequency_hz
    return (np.interp(instants, times, displacements), np.interp(instants, times, velocities))


def amplitude_spectrum(values, rate_hz, segment_s=2.0):
    """(frequencies [Hz], amplitude of a sine component [unit of values]) by Welch's method: Hann-windowed
    segments of segment_s with half overlap, power per bin averaged, sqrt(2 P) so a sine of amplitude A on
    a bin reads A."""
    values = np.asarray(values, float)
    segment = min(len(values), int(round(segment_s * rate_hz)))
    frequencies, power = signal.welch(values, fs=rate_hz, window="hann", nperseg=segment, scaling="spectrum")
    return frequencies, np.sqrt(2 * power)


def wavelet_amplitude(values, rate_hz, frequencies_hz, w=MORLET_W):
    """Continuous wavelet transform (Morlet wavelet scipy.signal.morlet2 with w cycles) as an amplitude: each
    scale's |coefficient| divided by the response to a unit cosine at its centre frequency, so a sine of
    amplitude A at f reads A at (t, f). Rows follow frequencies_hz."""
    frequencies_hz = np.asarray(frequencies_hz, float)
    values = np.asarray(values, float)
    widths = w * rate_hz / (2 * np.pi * frequencies_hz)  # scale in samples whose centre frequency is f
    # scipy.signal.cwt's transform (wavelets of up to 10 widths, 'same' convolution), but by FFT: cwt's direct
    # convolution costs the length of the signal times the wavelet's, and the low frequencies' wavelets are
    # as long as the signal
    coefficients = np.empty((len(widths), len(values)), complex)
    for row, width in enumerate(widths):
        wavelet = signal.morlet2(np.min([10 * width, len(values)]), width, w=w)
        coefficients[row] = signal.fftconvolve(values, np.conj(wavelet[::-1]), mode="same")
    # sum_m cos(2 pi f m) psi*(m) = (1/2) pi^(-1/4) sqrt(2 pi s) for morlet2's unit-energy normalisation
    unit_response = 0.5 * np.pi ** -0.25 * np.sqrt(2 * np.pi * widths)
    return np.abs(coefficients) / unit_response[:, None]
