#!/usr/bin/python3
"""bench/scipy_reference.py against closed forms (ctest scipy_reference_closed_form, label bench):
- free response of two damped modes per frame, no contact: the samples and the exact peak of |acceleration|
  between them (the peak search matters: the 300 Hz mode moves 0.46 rad between 4096 Hz samples);
- one impact of two free point masses (modes of vanishing frequency): spring-dashpot and undamped Hertz
  (duration, rebound, impulse, largest indentation and force) and Newton (restitution, impulse, velocities);
- the stacked dense-output evaluation equals SciPy's own OdeSolution;
- a malformed model file stops the script with a message naming the file and the key.
Run: /usr/bin/python3 bench/tests/test_scipy_reference.py
"""
import json
import math
import os
import subprocess
import sys
import tempfile
import unittest

import numpy as np
from scipy.integrate import solve_ivp
from scipy.special import beta

BENCH = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, BENCH)
from scipy_dense_record import DenseOutput  # noqa: E402
from scipy_modal_model import ModalModel  # noqa: E402
from scipy_reference import ScipySolver  # noqa: E402

SLOW = 1e-4  # rad/s: a "mode" that does nothing within milliseconds, so that a frame is a free point mass


def model_file(folder, omega, zeta, tip1, tip2, gap, law, q0, v0, duration, rate):
    """A model file in the format of `impactbench export --engine reference`; tip1, tip2: each frame's tip
    values (the stacked modes: frame 1's, then frame 2's)."""
    n1 = len(tip1)
    zero1, zero2 = [0.0] * n1, [0.0] * len(tip2)
    data = {"format": "impactbench modal model 1", "scenario": "closed form", "frame_mode_counts": [n1, len(tip2)],
            "omega_rad_s": omega, "zeta": zeta, "contact_lever_per_sqrt_kg": tip1 + [-x for x in tip2],
            "motor_lever_per_sqrt_kg": tip1 + zero2, "gap_m": gap, "contact_law": law,
            "initial": {"q_m_sqrt_kg": q0, "v_m_s_sqrt_kg": v0},
            "recorded": {"frame1_tip_lever_per_sqrt_kg": tip1 + zero2, "frame2_tip_lever_per_sqrt_kg": zero1 + tip2},
            "duration_s": duration, "series_start_s": 0.0, "output_rate_hz": rate, "scoring_window_start_s": 0.0,
            "scoring_window_end_s": duration,
            "reference_settings": {"rtol": 1e-10, "atol_m_sqrt_kg": 1e-14, "accumulation_time_s": 1e-6}}
    path = os.path.join(folder, "model.json")
    with open(path, "w", encoding="utf-8") as f:
        json.dump(data, f)
    return path


def solve(path):
    model = ModalModel(path)
    solver = ScipySolver(model, "DOP853", model.rtol, model.atol, chunk_s=0.25)
    solver.run()
    return model, solver


class FreeResponse(unittest.TestCase):
    def test_samples_and_peaks_between_them(self):
        omega = [2 * math.pi * 7, 2 * math.pi * 300, 2 * math.pi * 8, 2 * math.pi * 310]
        zeta = [0.003, 0.01, 0.003, 0.02]
        tip1, tip2 = [1.1, -0.4], [1.3, -0.5]
        q0, v0 = [-1.5e-3, 2e-5, 1e-4, -1e-5], [0.0, 0.03, 0.0, -0.02]
        with tempfile.TemporaryDirectory() as folder:
            model, solver = solve(model_file(folder, omega, zeta, tip1, tip2, 1.0,
                                             {"name": "newton", "restitution": 0.8}, q0, v0, 0.05, 4096))
        self.assertEqual(solver.events, [])
        w, z, q0, v0 = map(np.array, (omega, zeta, q0, v0))
        s, wd = z * w, w * np.sqrt(1 - z * z)

        def modal(t):  # q, q', q'' of each damped mode, released from (q0, v0)
            t = np.asarray(t)[None, :]
            a, b = q0[:, None], ((v0 + s * q0) / wd)[:, None]
            e, c, si = np.exp(-s[:, None] * t), np.cos(wd[:, None] * t), np.sin(wd[:, None] * t)
            q = e * (a * c + b * si)
            v = e * ((b * wd[:, None] - a * s[:, None]) * c - (a * wd[:, None] + b * s[:, None]) * si)
            return q, v, -2 * s[:, None] * v - (w ** 2)[:, None] * q

        rec = solver.recorder
        q, v, acc = modal(rec.time)
        for f in (0, 1):
            lever = model.tip[f]
            for column, exact in (("displacement", lever @ q), ("velocity", lever @ v), ("acceleration", lever @ acc)):
                got = rec.columns[f"{column}{f + 1}"]
                self.assertLess(np.max(np.abs(got - exact)) / np.max(np.abs(exact)), 1e-7, f"frame {f + 1} {column}")
        # the exact maximum of |a| over each interval (t_{k-1}, t_k], from 2000 closed-form points per interval
        fine = np.linspace(0, 1, 2001)
        peaks_between = 0
        for f in (0, 1):
            sample = np.abs(model.tip[f] @ acc)
            for k in range(1, len(rec.time)):
                t = rec.time[k - 1] + fine * (rec.time[k] - rec.time[k - 1])
                exact = np.max(np.abs(model.tip[f] @ modal(t)[2]))
                got = solver.recorder.peak_acc[f][k]
                got = max(got, sample[k - 1], sample[k])
                self.assertAlmostEqual(got / exact, 1, delta=1e-7, msg=f"frame {f + 1} interval {k}")
                peaks_between += exact > 1.001 * max(sample[k - 1], sample[k])
        self.assertGreater(peaks_between, 20, "the case must have peaks between samples, or it tests nothing")


def two_masses(folder, law, m1=0.6, m2=0.4, approach=0.1, gap=1e-4, duration=3e-3):
    """Frame 1 (mass m1) moving at `approach` toward frame 2 (m2) at rest, `gap` apart."""
    tip1, tip2 = [1 / math.sqrt(m1)], [1 / math.sqrt(m2)]
    return model_file(folder, [SLOW, SLOW], [0.0, 0.0], tip1, tip2, gap, law, [0.0, 0.0],
                      [approach * math.sqrt(m1), 0.0], duration, 1e5)


class OneImpact(unittest.TestCase):
    m1, m2, v0, gap = 0.6, 0.4, 0.1, 1e-4
    mu = m1 * m2 / (m1 + m2)  # reduced mass [kg]

    def one_event(self, law):
        with tempfile.TemporaryDirectory() as folder:
            model, solver = solve(two_masses(folder, law))
        self.assertEqual(len(solver.events), 1)
        event = solver.events[0]
        self.assertAlmostEqual(event["onset"], self.gap / self.v0, delta=1e-12)
        self.assertAlmostEqual(event["approach"], self.v0, delta=1e-12)
        return model, solver, event

    def test_spring_dashpot(self):
        k, c = 1e6, 20.0
        _, _, e = self.one_event({"name": "viscoelastic", "stiffness_n_per_m": k, "damping_n_s_per_m": c,
                                  "clip_tension": False})
        w0 = math.sqrt(k / self.mu)
        z = c / (2 * math.sqrt(k * self.mu))
        wd = w0 * math.sqrt(1 - z * z)
        rebound = self.v0 * math.exp(-z * w0 * math.pi / wd)
        t_max = math.atan2(wd, z * w0) / wd  # delta' = 0: largest indentation
        self.assertAlmostEqual((e["end"] - e["onset"]) * wd / math.pi, 1, delta=1e-9)
        self.assertAlmostEqual(e["rebound"] / rebound, 1, delta=1e-8)
        self.assertAlmostEqual(e["impulse"] / (self.mu * (self.v0 + rebound)), 1, delta=1e-8)
        self.assertAlmostEqual(e["max_indentation"] / (self.v0 / wd * math.exp(-z * w0 * t_max) * math.sin(wd * t_max)),
                               1, delta=1e-9)

    def test_undamped_hertz(self):
        k, n = 2e10, 1.5
        _, _, e = self.one_event({"name": "hertz", "stiffness_n_per_m_pow_n": k, "exponent": n,
                                  "damping_n_s_per_m_pow_n_plus_1": 0.0})
        # energy: mu v0^2 / 2 = k delta_max^(n+1) / (n+1); duration 2 delta_max / v0 * int_0^1 dx / sqrt(1 - x^(n+1))
        delta_max = ((n + 1) * self.mu * self.v0 ** 2 / (2 * k)) ** (1 / (n + 1))
        duration = 2 * delta_max / self.v0 * beta(1 / (n + 1), 0.5) / (n + 1)
        self.assertAlmostEqual((e["end"] - e["onset"]) / duration, 1, delta=1e-8)
        self.assertAlmostEqual(e["rebound"] / self.v0, 1, delta=1e-8)
        self.assertAlmostEqual(e["max_indentation"] / delta_max, 1, delta=1e-9)
        self.assertAlmostEqual(e["peak_force"] / (k * delta_max ** n), 1, delta=1e-8)
        self.assertAlmostEqual(e["impulse"] / (2 * self.mu * self.v0), 1, delta=1e-8)

    def test_newton(self):
        model, solver, e = self.one_event({"name": "newton", "restitution": 0.7})
        self.assertEqual(e["restitution"], 0.7)
        self.assertAlmostEqual(e["impulse"] / (1.7 * self.mu * self.v0), 1, delta=1e-10)
        # after the impact: momentum kept, relative velocity reversed with factor e
        rec, j = solver.recorder, 1.7 * self.mu * self.v0
        after = rec.time > e["onset"]
        np.testing.assert_allclose(rec.columns["velocity1"][after], self.v0 - j / self.m1, rtol=1e-9)
        np.testing.assert_allclose(rec.columns["velocity2"][after], j / self.m2, rtol=1e-9)


class DenseEvaluation(unittest.TestCase):
    def test_equals_scipys_ode_solution(self):
        rng = np.random.default_rng(1)
        a = rng.normal(size=(6, 6)) * 50
        for method in ("DOP853", "RK45", "RK23"):
            sol = solve_ivp(lambda t, y: a @ y + np.sin(30 * t), (0, 0.2), rng.normal(size=6), method=method,
                            rtol=1e-9, atol=1e-12, dense_output=True).sol
            t = np.sort(np.concatenate((rng.uniform(0, 0.2, 500), sol.ts)))
            np.testing.assert_allclose(DenseOutput(sol)(t), sol(t), rtol=1e-12, atol=1e-12 * np.abs(sol(t)).max(),
                                       err_msg=method)


class BadInput(unittest.TestCase):
    def test_missing_key_is_named(self):
        with tempfile.TemporaryDirectory() as folder:
            path = two_masses(folder, {"name": "newton", "restitution": 0.7})
            with open(path, encoding="utf-8") as f:
                data = json.load(f)
            del data["gap_m"]
            data["contact_law"]["restitution"] = 1.5
            with open(path, "w", encoding="utf-8") as f:
                json.dump(data, f)
            done = subprocess.run([sys.executable, os.path.join(BENCH, "scipy_reference.py"), path, "--out", folder],
                                  capture_output=True, text=True)
        self.assertNotEqual(done.returncode, 0)
        self.assertIn(path, done.stderr)
        self.assertIn("gap_m", done.stderr)


if __name__ == "__main__":
    unittest.main()
