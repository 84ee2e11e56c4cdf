"""Better or worse (reports/impactbench_compare/judgement.py, docs/compare.md): a small suite (the short free
vibration, the reference and the first engine of the build, an ensemble of 3) compared with copies in which
the engine's contact duration was moved in runs.csv, its errors with it: further from its own chain
(regressed, exit 4), onto it (improved, exit 1), across it (as large: moved, exit 1); its CPU cost raised
(regressed); the engine's runs removed (disappeared: regressed, with why). A suite of single runs whose
reference ran 3 starts, its reference's starts scattered, gives a "not judged" metric, not a move.

    /usr/bin/python3 reports/tests/test_compare_judgement.py IMPACTBENCH_EXECUTABLE SCENARIO_FOLDER
"""

import json
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import test_compare  # noqa: E402
from test_compare import compare, first_engine, rewrite_csv  # noqa: E402

EXECUTABLE = SCENARIOS = None
EXIT_NOTHING_MOVED, EXIT_MOVED, EXIT_REGRESSED = 0, 1, 4
DURATION, DURATION_ERROR = "contact_duration_mean_s", "contact_duration_relative_error"


def run_suite(out, engine, *ensemble):
    run = subprocess.run([EXECUTABLE, "suite", os.path.join(SCENARIOS, "short_free_vibration.toml"), "--engines",
                          f"reference,{engine}", "--laws", "hertz", "--dt", "1e-5", *ensemble, "--jobs", "2",
                          "--out", out], capture_output=True, text=True)
    assert run.returncode in (0, 1), run.stderr


def scale_duration(folder, engine, factor_of_row):
    """Each of the engine's rows' contact duration times factor_of_row(row), its errors against the beam and
    its own chain moved with it (error = value / reference - 1)."""
    def edit(rows):
        for row in rows:
            if row["engine"] != engine:
                continue
            factor = factor_of_row(row)
            row[DURATION] = repr(float(row[DURATION]) * factor)
            for prefix in ("vs_reference_", "vs_chain_reference_"):
                if row[prefix + DURATION_ERROR]:
                    row[prefix + DURATION_ERROR] = repr((1 + float(row[prefix + DURATION_ERROR])) * factor - 1)
    rewrite_csv(os.path.join(folder, "runs.csv"), edit)


def chain_error(row):
    return float(row["vs_chain_reference_" + DURATION_ERROR])


class Judgement(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.folder = tempfile.mkdtemp(prefix="impactbench_compare_judgement_")
        cls.engine = first_engine()
        cls.base = os.path.join(cls.folder, "base")
        run_suite(cls.base, cls.engine, "--ensemble", "3")

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.folder)

    def copy(self, name, factor_of_row=None):
        path = os.path.join(self.folder, name)
        shutil.copytree(self.base, path)
        if factor_of_row is not None:
            scale_duration(path, self.engine, factor_of_row)
        return path

    def engine_line(self, stdout):
        lines = [line for line in stdout.splitlines() if line.startswith(f"  {self.first_job()}")]
        self.assertEqual(len(lines), 1, stdout)
        return lines[0]

    def first_job(self):
        return f"short_free_vibration/{self.engine}/hertz/dt=1e-05"

    def test_a_folder_compared_with_itself_is_unchanged(self):
        result = compare(self.base, self.base)
        self.assertEqual(result.returncode, EXIT_NOTHING_MOVED, result.stdout + result.stderr)

    def test_further_from_its_own_chain_is_regressed_with_exit_4(self):
        # the error's size grows whatever its sign: away from zero by 10 % of the value
        worse = self.copy("worse", lambda row: 1.1 if chain_error(row) >= 0 else 0.9)
        out = os.path.join(self.folder, "worse.json")
        result = compare(self.base, worse, "--json", out)
        self.assertEqual(result.returncode, EXIT_REGRESSED, result.stdout + result.stderr)
        line = self.engine_line(result.stdout)
        self.assertIn(": regressed: contact duration", line)
        self.assertIn("error vs own chain", line)
        self.assertIn("(vs beam", line)
        with open(out) as f:
            comparison = json.load(f)
        self.assertTrue(comparison["regressed"])
        configuration = next(c for c in comparison["configurations"] if c["job_id"] == self.first_job())
        self.assertEqual(configuration["judgement"], "regressed")
        metric = next(m for m in configuration["metrics"] if m["column"] == DURATION)
        self.assertEqual((metric["judgement"], metric["judged_against"]), ("regressed", "own chain"))
        self.assertGreater(abs(metric["new_error_vs_own_chain"]), abs(metric["base_error_vs_own_chain"]))

    def test_onto_its_own_chain_is_improved_with_exit_1(self):
        better = self.copy("better", lambda row: 1 / (1 + chain_error(row)))  # the chain's own value
        result = compare(self.base, better)
        self.assertEqual(result.returncode, EXIT_MOVED, result.stdout + result.stderr)
        self.assertIn(": improved: contact duration", self.engine_line(result.stdout))

    def test_across_its_own_chain_is_a_move_with_the_error_as_large(self):
        across = self.copy("across", lambda row: (1 - chain_error(row)) / (1 + chain_error(row)))  # error -> -error
        result = compare(self.base, across)
        self.assertEqual(result.returncode, EXIT_MOVED, result.stdout + result.stderr)
        self.assertIn("moved, error as large", self.engine_line(result.stdout))

    def test_a_cost_that_rose_beyond_its_noise_is_regressed(self):
        timed, dearer = self.copy("timed"), self.copy("dearer")
        for folder, cpu_s in ((timed, 1.0), (dearer, 3.0)):  # long enough to time, 3 times the CPU

            def cost(rows, cpu_s=cpu_s):
                for row in rows:
                    if row["engine"] == self.engine:
                        row["cpu_time_s"] = repr(cpu_s)
                        row["cpu_time_per_simulated_s"] = repr(cpu_s / float(row["duration_s"]))
            rewrite_csv(os.path.join(folder, "runs.csv"), cost)
        result = compare(timed, dearer)
        self.assertEqual(result.returncode, EXIT_REGRESSED, result.stdout + result.stderr)
        self.assertIn("CPU cost x3 (noise ±30 %): regressed", self.engine_line(result.stdout))

    def test_a_configuration_that_disappeared_is_regressed_and_says_why(self):
        without = self.copy("without")
        rewrite_csv(os.path.join(without, "runs.csv"), lambda rows: rows.__setitem__(
            slice(None), [r for r in rows if r["engine"] != self.engine]))
        result = compare(self.base, without)
        self.assertEqual(result.returncode, EXIT_REGRESSED, result.stdout + result.stderr)
        self.assertIn(f"regressed: disappeared (was ok x3; its engine ({self.engine}) is not in NEW)",
                      self.engine_line(result.stdout))

    def test_single_runs_against_a_scattered_reference_are_not_judged(self):
        single = os.path.join(self.folder, "single")
        run_suite(single, self.engine, "--reference-ensemble", "3")
        scattered = os.path.join(self.folder, "scattered")
        shutil.copytree(single, scattered)
        column = "frame1_sensor_peak_acceleration_g"

        def scatter(rows):  # the beam reference's starts 20 % apart: a case that needs an ensemble
            for row in rows:
                if row["engine"] == "reference" and row["options"] == "" and "/start=" in row["job_id"]:
                    row[column] = repr(float(row[column]) * (1 + 0.2 * int(row["job_id"][-1])))
        rewrite_csv(os.path.join(scattered, "runs.csv"), scatter)
        moved = os.path.join(self.folder, "scattered_moved")
        shutil.copytree(scattered, moved)

        def nudge(rows):  # the engine's single run 5 % up: within the reference's scatter of one start
            for row in rows:
                if row["engine"] == self.engine:
                    row[column] = repr(float(row[column]) * 1.05)
        rewrite_csv(os.path.join(moved, "runs.csv"), nudge)
        result = compare(scattered, moved)
        self.assertEqual(result.returncode, EXIT_NOTHING_MOVED, result.stdout + result.stderr)
        self.assertIn("not judged (a noise wider than the metric: not counted as moved):", result.stdout)
        self.assertIn(f"  {self.first_job()}: frame 1 sensor peak: not judged: a single run of a case that needs "
                      "an ensemble (noise ±", result.stdout)


if __name__ == "__main__":
    EXECUTABLE, SCENARIOS = sys.argv[1], sys.argv[2]
    test_compare.EXECUTABLE, test_compare.SCENARIOS = EXECUTABLE, SCENARIOS  # its helpers run the same binary
    unittest.main(argv=sys.argv[:1], verbosity=2)
