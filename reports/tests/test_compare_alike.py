"""Like with like (reports/impactbench_compare/alike.py, docs/compare.md): a suite of single runs whose
reference ran 3 starts (the short free vibration, 0.3 s) against the same suite cut to 0.2 s with a single
reference start is refused whole (exit 2), each configuration "not comparable" with the settings named, and
the folders do not read "made alike"; a copy in which one configuration's output rate differs splits it
out, the rest compared; a copy whose suite.jsonl names another sensor rate is run otherwise throughout.

    /usr/bin/python3 reports/tests/test_compare_alike.py IMPACTBENCH_EXECUTABLE SCENARIO_FOLDER
"""

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
EXIT_NOTHING_MOVED, EXIT_BAD_INPUT = 0, 2


def run_suite(out, engine, *settings):
    run = subprocess.run([EXECUTABLE, "suite", os.path.join(SCENARIOS, "short_free_vibration.toml"), "--engines",
                          f"reference,{engine}", "--laws", "hertz", "--dt", "1e-5", *settings, "--jobs", "2",
                          "--out", out], capture_output=True, text=True)
    assert run.returncode in (0, 1), run.stderr


class Alike(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.folder = tempfile.mkdtemp(prefix="impactbench_compare_alike_")
        cls.engine = first_engine()
        cls.base, cls.short = os.path.join(cls.folder, "base"), os.path.join(cls.folder, "short")
        run_suite(cls.base, cls.engine, "--reference-ensemble", "3")
        run_suite(cls.short, cls.engine, "--duration", "0.2")

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.folder)

    def test_a_folder_run_otherwise_throughout_is_refused_with_the_settings_named(self):
        result = compare(self.base, self.short)
        self.assertEqual(result.returncode, EXIT_BAD_INPUT, result.stdout + result.stderr)
        self.assertNotIn("made alike", result.stdout)
        self.assertNotIn("moved beyond the noise:", result.stdout)  # no metric or verdict read as a move
        self.assertIn("run differently: duration_s (every configuration): 0.3 -> 0.2", result.stdout)
        beam = "short_free_vibration/reference/hertz"
        self.assertIn(f"  {beam}: not comparable: duration_s 0.3 vs 0.2; window_s 0.3 vs 0.2; ensemble members 3 vs "
                      "1; reference ensemble 3 vs 1", result.stdout.splitlines())
        engine = f"short_free_vibration/{self.engine}/hertz/dt=1e-05"
        self.assertIn(f"  {engine}: not comparable: duration_s 0.3 vs 0.2; window_s 0.3 vs 0.2; reference ensemble "
                      "3 vs 1", result.stdout.splitlines())
        self.assertIn("no configuration of both was run alike", result.stderr)

    def test_one_configuration_run_otherwise_is_split_out_and_the_rest_compared(self):
        other_rate = os.path.join(self.folder, "other_rate")
        shutil.copytree(self.base, other_rate)

        def halve_rate(rows):
            for row in rows:
                if row["engine"] == self.engine:
                    row["output_rate_hz"] = repr(float(row["output_rate_hz"]) / 2)
        rewrite_csv(os.path.join(other_rate, "runs.csv"), halve_rate)
        result = compare(self.base, other_rate)
        self.assertEqual(result.returncode, EXIT_NOTHING_MOVED, result.stdout + result.stderr)
        self.assertIn(f"  short_free_vibration/{self.engine}/hertz/dt=1e-05: not comparable: output_rate_hz 4096 vs "
                      "2048", result.stdout.splitlines())
        self.assertIn("nothing moved beyond the noise (2 configurations compared alike", result.stdout)

    def test_another_sensor_rate_in_the_settings_record_is_run_otherwise(self):
        other_sensor = os.path.join(self.folder, "other_sensor")
        shutil.copytree(self.base, other_sensor)
        path = os.path.join(other_sensor, "suite.jsonl")
        with open(path) as f:
            text = f.read()
        self.assertIn('"sensor_rate_hz":2048', text)
        with open(path, "w") as f:
            f.write(text.replace('"sensor_rate_hz":2048', '"sensor_rate_hz":1024'))
        result = compare(self.base, other_sensor)
        self.assertEqual(result.returncode, EXIT_BAD_INPUT, result.stdout + result.stderr)
        self.assertIn("run differently: sensor_rate_hz (every configuration): 2048 -> 1024", result.stdout)


if __name__ == "__main__":
    EXECUTABLE, SCENARIOS = sys.argv[1], sys.argv[2]
    test_compare.EXECUTABLE, test_compare.SCENARIOS = EXECUTABLE, SCENARIOS  # its helpers run the same binary
    unittest.main(argv=sys.argv[:1], verbosity=2)
