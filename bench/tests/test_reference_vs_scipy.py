#!/usr/bin/python3
"""bench/reference_vs_scipy.py on a short case (ctest scipy_comparison, label bench): the published free
vibration cut to 0.4 s (two impacts) with every law. SciPy's run, scored by `impactbench score` like any
simulator's, must agree with the reference's:
- impacts and raw onsets: equal;
- every other metric within 1e-6 relative, and the tip displacements within 1e-6 relative RMS: both
  solvers run at rtol 1e-9 (measured differences: up to about 1e-7, in the RMS acceleration with Hertz), so
  1e-6 leaves margin, while a modelling or recording mismatch (a lever, a law, a peak missed between
  samples, an interval off by one sample) shows at 1e-5 to 1e-1;
- each one's error against the tight reference (rtol 1e-12) within 1e-6, for the same reason.
Speed is never asserted. Run: /usr/bin/python3 bench/tests/test_reference_vs_scipy.py IMPACTBENCH
"""
import csv
import gzip
import json
import os
import subprocess
import sys
import tempfile
import unittest

BENCH = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
COMPARISON = os.path.join(BENCH, "reference_vs_scipy.py")
TOLERANCE = 1e-6
IMPACTBENCH = None  # from the command line


class ShortComparison(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.folder = tempfile.TemporaryDirectory()
        cls.out = os.path.join(cls.folder.name, "comparison")
        done = subprocess.run([sys.executable, COMPARISON, "--impactbench", IMPACTBENCH, "--out", cls.out,
                               "--cases", "free_vibration", "--duration", "0.4", "--repeat", "1"],
                              capture_output=True, text=True)
        if done.returncode != 0:
            raise AssertionError(f"the comparison failed:\n{done.stdout}\n{done.stderr}")
        with open(os.path.join(cls.out, "comparison.json"), encoding="utf-8") as f:
            cls.record = json.load(f)

    @classmethod
    def tearDownClass(cls):
        cls.folder.cleanup()

    def test_every_law_compared_on_the_cut_case(self):
        self.assertEqual([c["law"] for c in self.record["cases"]], ["hertz", "viscoelastic", "newton"])
        for c in self.record["cases"]:
            self.assertEqual((c["duration_s"], c["scoring_window_s"], c["cut"]), (0.4, 0.4, True))
            self.assertEqual(c["summary"]["impacts_reference"], 2, "the short case must have impacts to compare")

    def test_scipy_agrees_with_the_reference(self):
        for c in self.record["cases"]:
            for row in c["metrics"]:
                where = f"{c['law']} {row['metric']}"
                if row["kind"] == "difference":
                    self.assertEqual(row["scipy"], row["reference"], where)
                    continue
                if row["kind"] == "relative":  # a value the reference has, SciPy must have too
                    self.assertEqual(row["scipy"] is None, row["reference"] is None, where)
                if row["scipy_vs_reference"] is not None:
                    self.assertLessEqual(abs(row["scipy_vs_reference"]), TOLERANCE, where)

    def test_both_close_to_the_tight_reference(self):
        for c in self.record["cases"]:
            for row in c["metrics"]:
                for field in ("reference_error", "scipy_error"):
                    if row[field] is not None:
                        self.assertLessEqual(abs(row[field]), TOLERANCE, f"{c['law']} {row['metric']} {field}")

    def test_tables_and_provenance_written(self):
        for name in ("timings.csv", "metrics.csv", "comparison.md"):
            self.assertTrue(os.path.getsize(os.path.join(self.out, name)) > 0, name)
        for key in ("scipy", "numpy", "python", "impactbench_commit"):
            self.assertTrue(self.record["versions"][key], key)
        self.assertTrue(self.record["machine"]["cpu_model"])
        with open(os.path.join(self.out, "comparison.md"), encoding="utf-8") as f:
            self.assertIn("free_vibration to 0.4 s", f.read())

    def test_series_equal_the_references_sample_by_sample(self):
        """Every column of series.csv, the peak_* columns (the exact maximum over each output interval)
        included, within TOLERANCE of the column's largest magnitude: the metrics alone take one maximum
        over the whole window, which would not see peaks put in the wrong interval."""
        for c in self.record["cases"]:
            reference, scipy = (read_series(os.path.join(c["folder"], run)) for run in ("reference", "scipy"))
            self.assertEqual(list(reference), list(scipy), "the same columns in the same order")
            for name, values in reference.items():
                scale = max(abs(v) for v in values) or 1.0
                worst = max(abs(a - b) for a, b in zip(values, scipy[name], strict=True)) / scale
                self.assertLessEqual(worst, TOLERANCE, f"{c['law']} {name}")


def read_series(folder):
    """A run folder's series: impactbench writes series.csv.gz, bench/scipy_reference.py series.csv."""
    path = os.path.join(folder, "series.csv")
    opener, path = (gzip.open, path + ".gz") if os.path.exists(path + ".gz") else (open, path)
    with opener(path, "rt", encoding="utf-8") as f:
        rows = list(csv.reader(f))
    return {name: [float(row[i]) for row in rows[1:]] for i, name in enumerate(rows[0])}


class Failure(unittest.TestCase):
    def test_a_failing_step_is_named(self):
        with tempfile.TemporaryDirectory() as folder:
            done = subprocess.run([sys.executable, COMPARISON, "--impactbench", IMPACTBENCH, "--out", folder,
                                   "--cases", os.path.join(folder, "missing.toml"), "--laws", "hertz"],
                                  capture_output=True, text=True)
        self.assertEqual(done.returncode, 1)
        self.assertIn("missing.toml", done.stderr)


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit("usage: test_reference_vs_scipy.py IMPACTBENCH")
    IMPACTBENCH = sys.argv.pop(1)
    unittest.main()
