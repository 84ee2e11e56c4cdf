"""The vibro-impact views (impactbench_report/dynamics.py, spectral.py): the signal processing behind them
against closed forms (the log decrement of a damped sine, a periodic signal's Poincare section, a sine's spectrum and
scalogram), and every figure built from a small synthetic suite written to a temporary folder: the views
that do not apply return None, a run that kept no series gets a panel that says so, the fitted decrement
written in the legend is the closed form's.

    /usr/bin/python3 reports/tests/test_dynamics_figures.py
"""

import csv
import gzip
import json
import math
import os
import shutil
import sys
import tempfile
import unittest

import numpy as np
from scipy import signal as scipy_signal

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import matplotlib  # noqa: E402
from impactbench_report import data, dynamics, signals, spectral  # noqa: E402

MOTOR_HZ = 7.0
SERIES_RATE_HZ = 4096.0
ZETA, FREE_HZ = 0.02, 7.0  # the synthetic free vibration: u1 = A exp(-zeta w t) sin(w_d t)
GAP = 1e-3


def damped_sine(times, amplitude=2e-3, zeta=ZETA, frequency=FREE_HZ):
    omega = 2 * np.pi * frequency
    omega_d = omega * np.sqrt(1 - zeta ** 2)
    envelope = amplitude * np.exp(-zeta * omega * times)
    displacement = envelope * np.sin(omega_d * times)
    velocity = envelope * (omega_d * np.cos(omega_d * times) - zeta * omega * np.sin(omega_d * times))
    return displacement, velocity


class SignalProcessing(unittest.TestCase):
    def test_log_decrement_of_a_damped_sine_is_the_closed_form(self):
        t = np.arange(0, 3, 1 / SERIES_RATE_HZ)
        u, _ = damped_sine(t)
        decrement, rate = signals.log_decrement(t, u)
        self.assertAlmostEqual(decrement, 2 * math.pi * ZETA / math.sqrt(1 - ZETA ** 2), delta=1e-3 * decrement)
        self.assertAlmostEqual(rate, ZETA * 2 * math.pi * FREE_HZ, delta=1e-3 * rate)
        # an undamped sine does not decay; too short a record has no decrement
        self.assertAlmostEqual(signals.log_decrement(t, np.sin(2 * np.pi * FREE_HZ * t))[0], 0, delta=1e-6)
        self.assertTrue(math.isnan(signals.log_decrement(t[:900], u[:900])[0]))

    def test_higher_modes_riding_on_the_first_do_not_count_as_cycles(self):
        t = np.arange(0, 2, 1 / SERIES_RATE_HZ)
        u, _ = damped_sine(t)
        ripple = 2e-5 * np.sin(2 * np.pi * 73 * t)
        peak_times, _ = signals.cycle_peaks(t, u + ripple)
        self.assertEqual(len(peak_times), len(signals.cycle_peaks(t, u)[0]))
        self.assertAlmostEqual(np.mean(np.diff(peak_times)), 1 / (FREE_HZ * math.sqrt(1 - ZETA ** 2)), delta=2e-3)

    def test_poincare_section_of_a_periodic_signal_collapses(self):
        t = np.arange(10, 20, 1 / SERIES_RATE_HZ)
        phase = 2 * np.pi * MOTOR_HZ * t
        u, v = 1e-3 * np.sin(phase + 0.4), 1e-3 * 2 * np.pi * MOTOR_HZ * np.cos(phase + 0.4)
        points_u, points_v = signals.poincare_points(t, u, v, MOTOR_HZ, 10, 20)
        self.assertEqual(len(points_u), 70)  # t = k / 7 Hz in [10, 20) s (the series ends before 20 s)
        self.assertLess(np.ptp(points_u), 1e-3 * 1e-3)  # one point, up to the linear interpolation
        self.assertLess(np.ptp(points_v), 1e-3 * np.ptp(v))
        self.assertAlmostEqual(points_u[0], 1e-3 * math.sin(0.4), delta=1e-8)
        # a period-2 response (a subharmonic at f/2) gives two points, a quasi-periodic one a cloud
        u2 = u + 5e-4 * np.sin(phase / 2)
        points_u2, _ = signals.poincare_points(t, u2, v, MOTOR_HZ, 10, 20)
        self.assertEqual(len(np.unique(np.round(points_u2, 8))), 2)
        u3 = u + 5e-4 * np.sin(phase / math.sqrt(5))
        self.assertGreater(len(np.unique(np.round(signals.poincare_points(t, u3, v, MOTOR_HZ, 10, 20)[0], 8))),
                           60)

    def test_spectrum_of_a_sine_peaks_at_its_frequency_with_its_amplitude(self):
        t = np.arange(0, 10, 1 / 2048.0)
        values = 0.3 * np.sin(2 * np.pi * 20.0 * t) + 0.01 * np.sin(2 * np.pi * 150.0 * t)
        frequencies, amplitude = signals.amplitude_spectrum(values, 2048.0)
        self.assertAlmostEqual(frequencies[np.argmax(amplitude)], 20.0)
        self.assertAlmostEqual(amplitude.max(), 0.3, delta=0.3 * 0.01)
        near_150 = np.abs(frequencies - 150.0) < 0.1
        self.assertAlmostEqual(amplitude[near_150].max(), 0.01, delta=0.01 * 0.02)

    def test_scalogram_of_a_sine_reads_its_amplitude_at_its_frequency(self):
        rate, frequencies = 512.0, np.geomspace(1, 200, 72)
        t = np.arange(0, 6, 1 / rate)
        for frequency, amplitude in ((30.0, 0.5), (7.0, 2.0)):
            values = amplitude * np.cos(2 * np.pi * frequency * t)
            scalogram = signals.wavelet_amplitude(values, rate, frequencies)
            middle = scalogram[:, len(t) // 2]
            nearest = np.argmin(np.abs(frequencies - frequency))
            self.assertLessEqual(abs(np.argmax(middle) - nearest), 1)
            self.assertAlmostEqual(middle.max(), amplitude, delta=0.03 * amplitude)

    @unittest.skipUnless(hasattr(scipy_signal, "cwt"), "scipy without signal.cwt (removed in 1.15)")
    def test_scalogram_is_scipys_continuous_wavelet_transform(self):
        rate, frequencies = 512.0, np.geomspace(1, 200, 72)
        t = np.arange(0, 5, 1 / rate)
        values = np.sin(2 * np.pi * 10 * t) + (np.arange(len(t)) % 97 == 0) * 5.0  # a sine and impulses
        widths = signals.MORLET_W * rate / (2 * np.pi * frequencies)
        expected = np.abs(scipy_signal.cwt(values, scipy_signal.morlet2, widths, w=signals.MORLET_W))
        expected /= (0.5 * np.pi ** -0.25 * np.sqrt(2 * np.pi * widths))[:, None]
        scalogram = signals.wavelet_amplitude(values, rate, frequencies)
        self.assertEqual(scalogram.shape, expected.shape)
        np.testing.assert_allclose(scalogram, expected, rtol=0, atol=1e-12 * expected.max())


def write_csv(path, columns):
    names = list(columns)
    opener = gzip.open if path.endswith(".gz") else open
    with opener(path, "wt", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(names)
        writer.writerows(zip(*(columns[name] for name in names)))


class Figures(unittest.TestCase):
    """A suite of two cases: "forced" (a motor at 7 Hz, scored over 10-20 s, a period-1 response with one
    impact per cycle) and "free" (no motor, 0-3 s, a damped sine); in each the beam reference, one engine
    run with series and one that kept none."""

    RUN_COLUMNS = ["job_id", "scenario", "law", "engine", "options", "time_step_s", "verdict", "reason",
                   "window_start_s", "window_end_s", "output_rate_hz", "scenario_file"]

    @classmethod
    def setUpClass(cls):
        cls.folder = tempfile.mkdtemp(prefix="impactbench_dynamics_test_")
        cls.out = os.path.join(cls.folder, "report")
        os.makedirs(cls.out)
        rows, records = [], []
        for scenario, start, end in (("forced", 10.0, 20.0), ("free", 0.0, 3.0)):
            for engine, options, step, kept in (("reference", "", 0.0, True), ("fake", "contact=matched", 1e-4, True),
                                                ("fake", "contact=native", 1e-4, False)):
                job = f"{scenario}/{engine}/hertz" + (f"/dt={step:g}/{options}" if step else "")
                rows.append({"job_id": job, "scenario": scenario, "law": "hertz", "engine": engine,
                             "options": options, "time_step_s": step, "verdict": "ok", "reason": "",
                             "window_start_s": start, "window_end_s": end, "output_rate_hz": SERIES_RATE_HZ,
                             "scenario_file": ""})
                diagnostics = {"frame1_first_frequency_hz": FREE_HZ, "frame2_first_frequency_hz": 8.25}
                if scenario == "forced" and engine == "reference":
                    diagnostics["motor_frequency_hz"] = MOTOR_HZ
                records.append({"job_id": job, "diagnostics": diagnostics if engine == "reference" else {}})
                if kept:
                    cls.write_run(job, scenario, start, end, 1.0 if engine == "reference" else 0.9)
        with open(os.path.join(cls.folder, "runs.csv"), "w", newline="") as f:
            writer = csv.DictWriter(f, fieldnames=cls.RUN_COLUMNS)
            writer.writeheader()
            writer.writerows(rows)
        with open(os.path.join(cls.folder, "runs.jsonl"), "w") as f:
            f.writelines(json.dumps(r) + "\n" for r in records)
        cls.suite = data.read_runs(cls.folder)

    @classmethod
    def write_run(cls, job, scenario, start, end, scale):
        folder = os.path.join(cls.folder, "runs", job)
        os.makedirs(folder)
        t = np.arange(start, end + 0.5 / SERIES_RATE_HZ, 1 / SERIES_RATE_HZ)
        if scenario == "forced":
            omega = 2 * np.pi * MOTOR_HZ
            u1, v1 = scale * 1.2e-3 * np.sin(omega * t), scale * 1.2e-3 * omega * np.cos(omega * t)
            onsets = (np.arange(math.ceil(start * MOTOR_HZ), math.floor(end * MOTOR_HZ)) + 0.25) / MOTOR_HZ
        else:
            u1, v1 = damped_sine(t)
            u1, v1 = scale * u1, scale * v1
            onsets = np.array([0.036, 0.179])
        u2, v2 = 0.3 * u1, 0.3 * v1
        a1, a2 = np.gradient(v1, t), np.gradient(v2, t)
        zero = np.zeros_like(t)
        write_csv(os.path.join(folder, "series.csv.gz"), {
            "time_s": t, "frame1_displacement_m": u1, "frame1_velocity_m_s": v1, "frame1_acceleration_m_s2": a1,
            "frame2_displacement_m": u2, "frame2_velocity_m_s": v2, "frame2_acceleration_m_s2": a2,
            "contact_force_n": zero})
        # the accelerometer's reading as the harness writes it (harness/scoring/metrics.h): the velocity change over
        # each 1/2048 s window divided by the window, at the window centres
        stride = round(SERIES_RATE_HZ / 2048)
        window = stride / SERIES_RATE_HZ
        write_csv(os.path.join(folder, "sensor.csv.gz"), {
            "time_s": t[:-stride:stride] + window / 2,
            "frame1_sensor_acceleration_m_s2": (v1[stride::stride] - v1[:-stride:stride]) / window,
            "frame2_sensor_acceleration_m_s2": (v2[stride::stride] - v2[:-stride:stride]) / window})
        count = len(onsets)
        write_csv(os.path.join(folder, "events.csv"), {
            "onset_time_s": onsets, "end_time_s": onsets + 2e-4, "duration_s": [2e-4] * count,
            "approach_velocity_m_s": np.linspace(0.04, 0.06, count) * scale, "rebound_velocity_m_s": [0.04] * count,
            "restitution": np.linspace(0.85, 0.9, count), "peak_force_n": [100.0] * count,
            "impulse_n_s": [0.02] * count, "max_indentation_m": [3e-6] * count})

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.folder)

    def chosen(self, scenario):
        runs = [r for r in self.suite.runs_of(scenario, "hertz") if r["engine"] == "fake"]
        return {r.config: r for r in runs}

    def build(self, function, scenario):
        # text as <text> elements, so that the test can read what a figure says
        with matplotlib.rc_context({"svg.fonttype": "none"}):
            view = getattr(spectral if function in ("spectra", "scalograms") else dynamics, function)
            path = view(self.suite, scenario, "hertz", self.chosen(scenario), self.out, "synthetic suite")
        if path is None:
            return None
        self.assertTrue(os.path.exists(path), path)
        self.assertLess(os.path.getsize(path), 400_000, f"{path}: keep an SVG small")
        with open(path) as f:
            return f.read()

    def test_every_view_of_the_forced_case(self):
        for function in ("acceleration_histories", "phase_portraits", "poincare_sections", "spectra", "scalograms",
                         "impact_distributions"):
            with self.subTest(function=function):
                svg = self.build(function, "forced")
                self.assertIsNotNone(svg)
                self.assertIn("beam reference", svg)
                self.assertIn("fake [contact=matched], dt = 1e-4 s", svg)
                self.assertIn("no series kept", svg)  # the native run kept none: said, not a blank panel
        self.assertIsNone(self.build("amplitude_decay", "forced"), "a forced vibration has no free decay")

    def test_poincare_legend_counts_the_motor_periods(self):
        svg = self.build("poincare_sections", "forced")
        self.assertIn("f_motor = 7 Hz (71 samples)", svg)  # t = k / 7 Hz in [10, 20] s: k = 70 .. 140

    def test_every_view_of_the_free_case(self):
        self.assertIsNone(self.build("poincare_sections", "free"), "no motor: no Poincare section")
        for function in ("acceleration_histories", "phase_portraits", "spectra", "scalograms", "impact_distributions",
                         "amplitude_decay"):
            with self.subTest(function=function):
                self.assertIn("no series kept", self.build(function, "free"))

    def test_decay_legend_holds_the_closed_form_decrement(self):
        svg = self.build("amplitude_decay", "free")
        closed_form = 2 * math.pi * ZETA / math.sqrt(1 - ZETA ** 2)
        self.assertIn(f"delta = {closed_form:.4f} per cycle", svg)

    def test_free_vibration_window_ends_after_the_last_impact(self):
        runs = dynamics.shown(self.suite, "free", "hertz", self.chosen("free"))
        self.assertEqual(dynamics.impact_window(self.suite, "free", runs), (0.0, 0.279))
        runs = dynamics.shown(self.suite, "forced", "hertz", self.chosen("forced"))
        self.assertEqual(dynamics.impact_window(self.suite, "forced", runs), (19.0, 20.0))


if __name__ == "__main__":
    unittest.main()
