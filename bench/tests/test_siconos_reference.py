#!/usr/bin/python3
"""build/bench/siconos_reference (the Siconos comparator, ctest siconos_reference, label bench) against the
reference's Newton impacts: the second, independent Newton reference of issue 49. Agreement only; speed is
never asserted.
- bench/reference_siconos.py on the free vibration and the resonance cut to 5 s, Newton law (e = 0.8): the
  reference at its own settings (rtol 1e-9, atol 1e-12 m sqrt(kg)), Siconos's Lsodar at rtol 1e-10 and atol
  1e-13 m sqrt(kg) (three quarters of the CPU of the script's defaults 1e-12 and 1e-14; measured, the impact
  times and approach velocities stay 9 times inside their tolerances; at atol 1e-12 the free vibration's
  approach velocities come within 1.2 times of theirs); the first 20 impacts of each (the free vibration has 8), matched in order: the same count, impact
  times within 1e-7 s, approach velocities within 1e-5 relative, the realised restitution within 1e-9 of
  the reference's (measured: see docs/performance.md, "Siconos beside the reference (issue 49)");
- the comparison itself fails on an impact moved by 2e-7 s or a restitution off by 2e-9;
- a malformed model file, and a law other than Newton, stop it with a message naming the file and the key.
Run: /usr/bin/python3 bench/tests/test_siconos_reference.py SICONOS_REFERENCE IMPACTBENCH
"""
import json
import os
import subprocess
import sys
import tempfile
import unittest

BENCH = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, BENCH)
sys.path.insert(0, os.path.join(BENCH, "tests"))
from event_agreement import read_events  # noqa: E402
from reference_siconos import differences  # noqa: E402
from test_scipy_reference import two_masses  # noqa: E402

SICONOS = IMPACTBENCH = None  # from the command line
IMPACTS = 20              # impacts compared at most
TIME_S = 1e-7             # impact times against the reference's [s]
APPROACH_RELATIVE = 1e-5  # approach velocities against the reference's [-]
RESTITUTION = 1e-9        # realised restitution against the reference's [-]


def agrees(case):
    """The criterion, as a list of what fails (empty when the case agrees)."""
    failures = []
    if not case["same_impact_count"]:
        failures.append(f"impact counts: Siconos {case['siconos_impacts']}, reference {case['reference_impacts']}")
    if case["max_impact_time_difference_s"] > TIME_S:
        failures.append(f"impact time differs by {case['max_impact_time_difference_s']:.3g} s")
    if case["max_approach_velocity_relative_difference"] > APPROACH_RELATIVE:
        failures.append(f"approach velocity differs by {case['max_approach_velocity_relative_difference']:.3g}")
    if case["max_restitution_difference"] > RESTITUTION:
        failures.append(f"restitution differs by {case['max_restitution_difference']:.3g}")
    return failures


class AgainstTheReference(unittest.TestCase):
    def test_the_same_impacts(self):
        with tempfile.TemporaryDirectory() as folder:
            done = subprocess.run([sys.executable, os.path.join(BENCH, "reference_siconos.py"), "--impactbench",
                                   IMPACTBENCH, "--siconos", SICONOS, "--out", folder, "--cases",
                                   "free_vibration,resonance", "--duration", "5", "--max-impacts", str(IMPACTS),
                                   "--rtol", "1e-10", "--atol", "1e-13"],
                                  capture_output=True, text=True)
            self.assertEqual(done.returncode, 0, done.stdout + done.stderr)
            print(done.stdout, end="", file=sys.stderr)
            with open(os.path.join(folder, "comparison.json"), encoding="utf-8") as f:
                record = json.load(f)
        cases = {c["case"]: c for c in record["cases"]}
        self.assertEqual(sorted(cases), ["free_vibration", "resonance"])
        self.assertEqual(cases["free_vibration"]["impacts_compared"], 8, "the free vibration's impacts all end by 2.5 s")
        self.assertEqual(cases["resonance"]["impacts_compared"], IMPACTS)
        for name, case in cases.items():
            with self.subTest(case=name):
                self.assertEqual(agrees(case), [])
                self.assertGreater(case["siconos_cpu_time_s"], 0)
        self.assertTrue(record["versions"]["siconos"].startswith("4."))


class TheCriterionCanFail(unittest.TestCase):
    """Cheap proof that the comparison sees a wrong answer: the reference's own impacts, perturbed."""

    def test_perturbed_events_fail(self):
        with tempfile.TemporaryDirectory() as folder:
            subprocess.run([SICONOS, two_masses(folder, {"name": "newton", "restitution": 0.7}), "--out", folder],
                           check=True, capture_output=True)
            events = read_events(os.path.join(folder, "events.csv"))
        self.assertEqual(len(events), 1)
        base = {"same_impact_count": True, **differences(events, events, IMPACTS)}
        self.assertEqual(agrees(base), [])
        for key, change in (("onset_time_s", 2e-7), ("restitution", 2e-9), ("approach_velocity_m_s", 2e-5 * 0.1)):
            moved = [dict(events[0], **{key: events[0][key] + change})]
            case = {"same_impact_count": True, **differences(moved, events, IMPACTS)}
            self.assertNotEqual(agrees(case), [], key)


class OneImpact(unittest.TestCase):
    """Two free point masses (modes of vanishing frequency) closing at 0.1 m/s over 1e-4 m."""

    def test_newton(self):
        with tempfile.TemporaryDirectory() as folder:
            subprocess.run([SICONOS, two_masses(folder, {"name": "newton", "restitution": 0.7}), "--out", folder],
                           check=True, capture_output=True)
            (e,) = read_events(os.path.join(folder, "events.csv"))
        mu = 0.6 * 0.4 / (0.6 + 0.4)  # reduced mass [kg]
        self.assertAlmostEqual(e["onset_time_s"], 1e-4 / 0.1, delta=1e-12)
        self.assertAlmostEqual(e["approach_velocity_m_s"], 0.1, delta=1e-12)
        self.assertAlmostEqual(e["restitution"], 0.7, delta=1e-12)
        self.assertAlmostEqual(e["impulse_n_s"] / (1.7 * mu * 0.1), 1, delta=1e-10)
        self.assertEqual(e["duration_s"], 0)


class BadInput(unittest.TestCase):
    def stops(self, path, *names):
        with tempfile.TemporaryDirectory() as out:
            done = subprocess.run([SICONOS, path, "--out", out], capture_output=True, text=True)
        self.assertEqual(done.returncode, 1)
        for name in (path, *names):
            self.assertIn(name, done.stderr)

    def test_missing_key_is_named(self):
        with tempfile.TemporaryDirectory() as folder:
            path = two_masses(folder, {"name": "newton", "restitution": 0.7})
            with open(path, encoding="utf-8") as f:
                data = json.load(f)
            del data["gap_m"]
            with open(path, "w", encoding="utf-8") as f:
                json.dump(data, f)
            self.stops(path, "gap_m")

    def test_only_newton(self):
        with tempfile.TemporaryDirectory() as folder:
            path = two_masses(folder, {"name": "viscoelastic", "stiffness_n_per_m": 1e6, "damping_n_s_per_m": 20.0,
                                       "clip_tension": False})
            self.stops(path, "viscoelastic", "allowed: newton")


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit("usage: test_siconos_reference.py SICONOS_REFERENCE IMPACTBENCH")
    SICONOS, IMPACTBENCH = sys.argv.pop(1), sys.argv.pop(1)
    unittest.main()
