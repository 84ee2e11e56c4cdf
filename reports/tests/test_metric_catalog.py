"""The scored metrics' one list (reports/impactbench_report/metric_catalog.py) names what the harness writes: each
metric's column and error columns are runs.csv's, its tolerance key and default are the suite's
(commands.jsonl's verdict_tolerances, harness/scoring/verdict.h), a sweep's metrics are sweep.csv's and the step
search's are steps.csv's (the C++ sources' quoted names, read as text).

    /usr/bin/python3 reports/tests/test_metric_catalog.py
"""

import csv
import os
import re
import sys
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..", "..")
sys.path.insert(0, os.path.join(HERE, ".."))
from impactbench_report import metric_catalog  # noqa: E402
from impactbench_report.metric_catalog import DEFAULT_TOLERANCES, HEADLINE, SCORED, STEP_SEARCHED, SWEEP  # noqa: E402


def source(path):
    with open(os.path.join(ROOT, path)) as f:
        return f.read()


class MetricCatalog(unittest.TestCase):
    def test_columns_are_runs_csv_columns(self):
        with open(os.path.join(HERE, "data", "ensemble_rows.csv"), newline="") as f:
            header = next(csv.reader(f))
        for m in SCORED:
            for column in (m.column, "vs_reference_" + m.error_column, "vs_chain_reference_" + m.error_column):
                self.assertIn(column, header, m.label)

    def test_tolerances_are_the_suites(self):
        """Each key is a key of commands.jsonl's verdict_tolerances, and its default is verdict.h's."""
        command = source("cli/command_suite.cpp")
        verdict = source("harness/scoring/verdict.h")
        for key, value in DEFAULT_TOLERANCES.items():
            written = re.search(r'"' + key + r'"\s*,\s*v\.accuracy\.(\w+)', command)
            self.assertIsNotNone(written, key)
            default = re.search(r"double\s+" + written.group(1) + r"\s*=\s*([0-9.eE+-]+)\s*;", verdict)
            self.assertIsNotNone(default, written.group(1))
            self.assertEqual(float(default.group(1)), value, key)
        self.assertEqual({m.tolerance_key for m in SCORED}, set(DEFAULT_TOLERANCES))

    def test_sweep_and_step_search_names(self):
        sweep_row, steps_file = source("harness/sweep/sweep_row.cpp"), source("harness/suite/steps_file.cpp")
        for m in SWEEP:
            self.assertIn(f'"{m.column}"', sweep_row, m.label)
        for m in STEP_SEARCHED:
            self.assertIn(f'"{m.error_column}"', steps_file, m.label)
            self.assertTrue(m.error_column.startswith(m.step_prefix), m.label)

    def test_the_views_are_scored_metrics_and_lookups_find_them(self):
        for view in (HEADLINE, STEP_SEARCHED, SWEEP):
            self.assertLessEqual(set(view), set(SCORED))
        self.assertEqual(len({m.label for m in SCORED}), len(SCORED))
        for m in SCORED:
            self.assertIn(m.kind, ("relative", "difference"))
            self.assertEqual(m.better, metric_catalog.SMALLER_ERROR)
            self.assertIs(metric_catalog.by_label(m.label), m)
            self.assertIs(metric_catalog.by_error_column("vs_chain_reference_" + m.error_column), m)
        self.assertIsNone(metric_catalog.by_error_column("impacts"))
        with self.assertRaises(KeyError):
            metric_catalog.by_label("frame 3 sensor peak")


if __name__ == "__main__":
    unittest.main()
