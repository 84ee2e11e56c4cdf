#!/usr/bin/python3
"""build/bench/cvode_reference (the CVODE comparator, ctest cvode_reference_agreement, label bench) against
closed forms and against the reference's events. Agreement only; speed is never asserted.
- free decay of one damped mode per frame, no contact: both tips' displacement and velocity at every
  output sample within 1e-8 of the amplitude (rtol 1e-10);
- one impact of two free point masses (modes of vanishing frequency), where CVODE's root finding does all
  the work: spring-dashpot (duration, rebound, impulse, largest indentation) and undamped Hertz (the same
  and the largest force) within 1e-8 relative, the onset within 1e-12 s; Newton (restitution, impulse);
- the published free vibration cut to 0.4 s (two impacts) with every law, CVODE and the reference both at
  the reference's rtol 1e-9: the same events, onsets and ends within 1e-8 s (the contacts last about
  0.5 ms), approach and rebound velocities, impulse, largest force and indentation within 1e-6 relative
  (measured: see docs/performance.md, "CVODE beside SciPy (issue 30)");
- bench/reference_cvode_scipy.py on the free vibration cut to 0.4 s: each solver meets the event criterion;
- a malformed model file stops it with a message naming the file and the key.
Run: /usr/bin/python3 bench/tests/test_cvode_reference.py CVODE_REFERENCE IMPACTBENCH
"""
import json
import math
import os
import subprocess
import sys
import tempfile
import unittest

BENCH = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ROOT = os.path.dirname(BENCH)
sys.path.insert(0, BENCH)
sys.path.insert(0, os.path.join(BENCH, "tests"))
from event_agreement import errors, read_events  # noqa: E402
from test_scipy_reference import model_file, two_masses  # noqa: E402

CVODE = IMPACTBENCH = None  # from the command line
SHORT_CASE_TIME_S = 1e-8      # onsets and ends against the reference's [s]
SHORT_CASE_RELATIVE = 1e-6    # velocities, impulse, force, indentation against the reference's [-]


def cvode(model, folder, *options):
    done = subprocess.run([CVODE, model, "--out", folder, *options], capture_output=True, text=True)
    if done.returncode != 0:
        raise AssertionError(f"cvode_reference failed:\n{done.stdout}\n{done.stderr}")
    with open(os.path.join(folder, "cvode_run.json"), encoding="utf-8") as f:
        return json.load(f)


def read_csv_columns(path):
    with open(path, encoding="utf-8") as f:
        rows = [line.strip().split(",") for line in f]
    return {name: [float(r[i]) for r in rows[1:]] for i, name in enumerate(rows[0])}


class FreeDecay(unittest.TestCase):
    def test_samples_follow_the_closed_form(self):
        omega, zeta = [2 * math.pi * 7.5, 2 * math.pi * 9.0], [0.004, 0.02]
        tip1, tip2 = [1.2], [0.9]
        q0, v0 = [-2e-3, 0.0], [0.01, -0.05]
        with tempfile.TemporaryDirectory() as folder:
            model = model_file(folder, omega, zeta, tip1, tip2, 1.0, {"name": "newton", "restitution": 0.8}, q0, v0,
                               0.5, 2000)
            run = cvode(model, folder, "--samples")
            samples = read_csv_columns(os.path.join(folder, "samples.csv"))
            self.assertEqual(read_events(os.path.join(folder, "events.csv")), [])
        self.assertEqual(run["status"], "ok")
        self.assertEqual(len(samples["time_s"]), 1001)
        for frame, tip in ((1, tip1[0]), (2, tip2[0])):
            i = frame - 1
            w, z = omega[i], zeta[i]
            s, wd = z * w, w * math.sqrt(1 - z * z)
            a, b = q0[i], (v0[i] + s * q0[i]) / wd
            amplitude = tip * math.hypot(a, b)
            for t, x, v in zip(samples["time_s"], samples[f"frame{frame}_displacement_m"],
                               samples[f"frame{frame}_velocity_m_s"]):
                e, c, si = math.exp(-s * t), math.cos(wd * t), math.sin(wd * t)
                self.assertLess(abs(x - tip * e * (a * c + b * si)), 1e-8 * amplitude, f"frame {frame} t {t}")
                exact_v = tip * e * ((b * wd - a * s) * c - (a * wd + b * s) * si)
                self.assertLess(abs(v - exact_v), 1e-8 * amplitude * w, f"frame {frame} t {t}")


class OneImpact(unittest.TestCase):
    m1, m2, v0, gap = 0.6, 0.4, 0.1, 1e-4
    mu = m1 * m2 / (m1 + m2)  # reduced mass [kg]

    def one_event(self, law):
        with tempfile.TemporaryDirectory() as folder:
            cvode(two_masses(folder, law), folder)
            events = read_events(os.path.join(folder, "events.csv"))
        self.assertEqual(len(events), 1)
        e = events[0]
        self.assertAlmostEqual(e["onset_time_s"], self.gap / self.v0, delta=1e-12)
        self.assertAlmostEqual(e["approach_velocity_m_s"], self.v0, delta=1e-12)
        return e

    def test_spring_dashpot(self):
        k, c = 1e6, 20.0
        e = self.one_event({"name": "viscoelastic", "stiffness_n_per_m": k, "damping_n_s_per_m": c, "clip_tension": False})
        w0, z = math.sqrt(k / self.mu), c / (2 * math.sqrt(k * self.mu))
        wd = w0 * math.sqrt(1 - z * z)
        rebound = self.v0 * math.exp(-z * w0 * math.pi / wd)
        t_max = math.atan2(wd, z * w0) / wd  # delta' = 0: the largest indentation
        self.assertAlmostEqual(e["duration_s"] * wd / math.pi, 1, delta=1e-8)
        self.assertAlmostEqual(e["rebound_velocity_m_s"] / rebound, 1, delta=1e-8)
        self.assertAlmostEqual(e["impulse_n_s"] / (self.mu * (self.v0 + rebound)), 1, delta=1e-8)
        self.assertAlmostEqual(e["max_indentation_m"] / (self.v0 / wd * math.exp(-z * w0 * t_max) * math.sin(wd * t_max)),
                               1, delta=1e-8)

    def test_undamped_hertz(self):
        from scipy.special import beta
        k, n = 2e10, 1.5
        e = self.one_event({"name": "hertz", "stiffness_n_per_m_pow_n": k, "exponent": n,
                            "damping_n_s_per_m_pow_n_plus_1": 0.0})
        delta_max = ((n + 1) * self.mu * self.v0 ** 2 / (2 * k)) ** (1 / (n + 1))
        duration = 2 * delta_max / self.v0 * beta(1 / (n + 1), 0.5) / (n + 1)
        self.assertAlmostEqual(e["duration_s"] / duration, 1, delta=1e-8)
        self.assertAlmostEqual(e["rebound_velocity_m_s"] / self.v0, 1, delta=1e-8)
        self.assertAlmostEqual(e["max_indentation_m"] / delta_max, 1, delta=1e-8)
        self.assertAlmostEqual(e["peak_force_n"] / (k * delta_max ** n), 1, delta=1e-8)
        self.assertAlmostEqual(e["impulse_n_s"] / (2 * self.mu * self.v0), 1, delta=1e-8)

    def test_newton(self):
        e = self.one_event({"name": "newton", "restitution": 0.7})
        self.assertEqual(e["restitution"], 0.7)
        self.assertTrue(math.isnan(e["peak_force_n"]))
        self.assertAlmostEqual(e["impulse_n_s"] / (1.7 * self.mu * self.v0), 1, delta=1e-10)


class AgainstTheReference(unittest.TestCase):
    """The free vibration cut to 0.4 s: CVODE's events against the reference's, both at rtol 1e-9."""

    @classmethod
    def setUpClass(cls):
        cls.folder = tempfile.TemporaryDirectory()
        with open(os.path.join(ROOT, "scenarios", "paper", "free_vibration.toml"), encoding="utf-8") as f:
            text = f.read()
        text = text.replace("duration_s = 14.0", "duration_s = 0.4").replace("scoring_window_s = 14.0",
                                                                             "scoring_window_s = 0.4")
        cls.scenario = os.path.join(cls.folder.name, "free_vibration_0.4s.toml")
        with open(cls.scenario, "w", encoding="utf-8") as f:
            f.write(text)

    @classmethod
    def tearDownClass(cls):
        cls.folder.cleanup()

    def events(self, law):
        folder = os.path.join(self.folder.name, law)
        os.makedirs(folder)
        model = os.path.join(folder, "model.json")
        for command in (["export", self.scenario, "--engine", "reference", "--law", law, "--out", model],
                        ["run", self.scenario, "--engine", "reference", "--law", law, "--out",
                         os.path.join(folder, "reference")]):
            done = subprocess.run([IMPACTBENCH, *command], capture_output=True, text=True)
            self.assertEqual(done.returncode, 0, done.stderr)
        cvode(model, os.path.join(folder, "cvode"))
        return tuple(read_events(os.path.join(folder, run, "events.csv")) for run in ("cvode", "reference"))

    def test_the_same_events(self):
        for law in ("hertz", "viscoelastic", "newton"):
            with self.subTest(law=law):
                events, reference = self.events(law)
                self.assertEqual(len(reference), 2, "the short case must have impacts to compare")
                error = errors(events, reference)
                self.assertEqual(error["event_count_difference"], 0)
                self.assertLessEqual(error["onset_error_s"], SHORT_CASE_TIME_S)
                self.assertLessEqual(error["end_error_s"], SHORT_CASE_TIME_S)
                for a, b in zip(events, reference):
                    for key in ("approach_velocity_m_s", "rebound_velocity_m_s", "impulse_n_s", "peak_force_n",
                                "max_indentation_m"):
                        if law == "newton" and key == "peak_force_n":
                            self.assertTrue(math.isnan(a[key]) and math.isnan(b[key]))
                            continue
                        scale = abs(b[key]) or 1.0
                        self.assertLessEqual(abs(a[key] - b[key]) / scale, SHORT_CASE_RELATIVE, f"{law} {key}")


class ThreeWayComparison(unittest.TestCase):
    """bench/reference_cvode_scipy.py on the free vibration cut to 0.4 s (Hertz): the three solvers each meet
    the event criterion at some tolerance tried, and the tables are written. Agreement, not speed."""

    def test_each_solver_meets_the_criterion(self):
        with tempfile.TemporaryDirectory() as folder:
            done = subprocess.run([sys.executable, os.path.join(BENCH, "reference_cvode_scipy.py"), "--impactbench",
                                   IMPACTBENCH, "--cvode", CVODE, "--out", folder, "--cases", "free_vibration",
                                   "--laws", "hertz", "--duration", "0.4", "--rtols", "1e-8,1e-10", "--repeat", "1"],
                                  capture_output=True, text=True)
            self.assertEqual(done.returncode, 0, done.stdout + done.stderr)
            with open(os.path.join(folder, "comparison.json"), encoding="utf-8") as f:
                record = json.load(f)
            with open(os.path.join(folder, "comparison.md"), encoding="utf-8") as f:
                self.assertIn("| free_vibration | hertz | 0.4 |", f.read())
        (case,) = record["cases"]
        self.assertGreater(case["truth_events"], 0, "the short case must have impacts")
        for solver in ("reference", "cvode", "scipy"):
            self.assertTrue(case["solvers"][solver]["met"], solver)
            self.assertGreater(case["solvers"][solver]["cpu_time_s"], 0, solver)
        for key in ("proc_loadavg_at_start", "proc_loadavg_at_end"):
            self.assertEqual(len(record["machine"][key]), 3)
        self.assertTrue(record["versions"]["sundials"].startswith("6."))


class BadInput(unittest.TestCase):
    def test_missing_key_is_named(self):
        with tempfile.TemporaryDirectory() as folder:
            path = two_masses(folder, {"name": "newton", "restitution": 0.7})
            with open(path, encoding="utf-8") as f:
                data = json.load(f)
            del data["gap_m"]
            with open(path, "w", encoding="utf-8") as f:
                json.dump(data, f)
            done = subprocess.run([CVODE, path, "--out", folder], capture_output=True, text=True)
        self.assertEqual(done.returncode, 1)
        self.assertIn(path, done.stderr)
        self.assertIn("gap_m", done.stderr)


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit("usage: test_cvode_reference.py CVODE_REFERENCE IMPACTBENCH")
    CVODE, IMPACTBENCH = sys.argv.pop(1), sys.argv.pop(1)
    unittest.main()
