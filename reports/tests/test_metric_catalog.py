"""The scored metrics' catalog (reports/impactbench_report/metric_catalog.py) is a folder's metrics.json, or the one
fallback for a folder without it; its columns and error columns are runs.csv's, a sweep's metrics are sweep.csv's and
the step search's are steps.csv's (the C++ sources' quoted names, read as text), and compare reads the metrics every
folder has. That the fallback is what the harness writes: test_metrics_file.py.

    /usr/bin/python3 reports/tests/test_metric_catalog.py
"""

import copy
import csv
import json
import os
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..", "..")
sys.path.insert(0, os.path.join(HERE, ".."))
from impactbench_report import metric_catalog  # noqa: E402


def source(path):
    with open(os.path.join(ROOT, path)) as f:
        return f.read()


class MetricCatalog(unittest.TestCase):
    def test_columns_are_runs_csv_columns(self):
        with open(os.path.join(HERE, "data", "ensemble_rows.csv"), newline="") as f:
            header = next(csv.reader(f))
        for m in metric_catalog.SCORED:
            for column in (m.column, "vs_reference_" + m.error_column, "vs_chain_reference_" + m.error_column):
                self.assertIn(column, header, m.label)

    def test_tolerance_keys_and_defaults(self):
        self.assertEqual(set(metric_catalog.DEFAULT_TOLERANCES), {m.tolerance_key for m in metric_catalog.SCORED})
        self.assertEqual(metric_catalog.DEFAULT_TOLERANCES["impacts_per_cycle_difference"], 0.10)

    def test_sweep_and_step_search_names(self):
        sweep_row, step_search = source("harness/sweep/sweep_row.cpp"), source("harness/suite/step_search.cpp")
        self.assertEqual([m.name for m in metric_catalog.SWEEP], list(metric_catalog.SWEEP_NAMES))
        for m in metric_catalog.SWEEP:
            self.assertIn(f'"{m.column}"', sweep_row, m.label)
        self.assertEqual(len(metric_catalog.STEP_SEARCHED), 3)
        for m in metric_catalog.STEP_SEARCHED:
            self.assertIn(f'"{m.step_prefix}"', step_search, m.label)  # HeadlineMetric's to_string
            self.assertTrue(m.error_column.startswith(m.step_prefix), m.label)

    def test_the_views_are_scored_metrics_and_lookups_find_them(self):
        for view in (metric_catalog.HEADLINE, metric_catalog.STEP_SEARCHED, metric_catalog.SWEEP):
            self.assertLessEqual(set(view), set(metric_catalog.SCORED))
        self.assertEqual(len({m.label for m in metric_catalog.SCORED}), len(metric_catalog.SCORED))
        for m in metric_catalog.SCORED:
            self.assertIn(m.kind, ("relative", "difference"))
            self.assertEqual(m.better, metric_catalog.SMALLER_ERROR)
            self.assertIs(metric_catalog.by_label(m.label), m)
            self.assertIs(metric_catalog.by_name(m.name), m)
            self.assertIs(metric_catalog.by_error_column("vs_chain_reference_" + m.error_column), m)
        self.assertIsNone(metric_catalog.by_error_column("impacts"))
        with self.assertRaises(KeyError):
            metric_catalog.by_label("frame 3 sensor peak")


def toy_catalog():
    """The fallback's catalog with a toy metric added and the contact duration's default tolerance changed."""
    document = copy.deepcopy(metric_catalog.CATALOG_OF_FOLDERS_WITHOUT_METRICS_JSON)
    document["metrics"][2]["default_tolerance"] = 0.25
    document["metrics"].append({"name": "toy_rebound", "label": "toy rebound", "column": "toy_rebound_m_s",
                                "unit": "m/s", "error_column": "toy_rebound_relative_error", "kind": "relative",
                                "tolerance_key": "toy_rebound_relative_error", "default_tolerance": 0.05,
                                "better": "smaller |error|", "scored_against": ["beam"], "step_searched": True})
    return document


class FromTheFolder(unittest.TestCase):
    def folder(self, document):
        folder = tempfile.mkdtemp(prefix="impactbench_metrics_test_")
        if document is not None:
            with open(os.path.join(folder, "metrics.json"), "w") as f:
                f.write(document if isinstance(document, str) else json.dumps(document))
        return folder

    def tearDown(self):
        metric_catalog.use(self.folder(None))  # the fallback again, for the other tests

    def test_the_folders_metrics_json_is_the_catalog(self):
        metric_catalog.use(self.folder(toy_catalog()))
        toy = metric_catalog.by_name("toy_rebound")
        self.assertEqual((toy.column, toy.unit, toy.kind, toy.scored_against), ("toy_rebound_m_s", "m/s", "relative",
                                                                                 ("beam",)))
        self.assertIn(toy, metric_catalog.STEP_SEARCHED)
        self.assertEqual(toy.step_prefix, "toy_rebound")
        self.assertEqual(metric_catalog.DEFAULT_TOLERANCES["contact_duration_relative_error"], 0.25)
        self.assertEqual(metric_catalog.DEFAULT_TOLERANCES["toy_rebound_relative_error"], 0.05)
        self.assertNotIn(toy, metric_catalog.HEADLINE)  # no figure label: a panel is the report's choice

    def test_a_folder_without_it_has_the_fallback_and_a_garbled_one_is_refused(self):
        metric_catalog.use(self.folder(toy_catalog()))
        metric_catalog.use(self.folder(None))
        self.assertEqual([m.name for m in metric_catalog.SCORED],
                         [m["name"] for m in metric_catalog.CATALOG_OF_FOLDERS_WITHOUT_METRICS_JSON["metrics"]])
        for garbled in ("{not json", {"metrics": "garbled"}, {"metrics": [{"name": "x"}]}):
            with self.assertRaises(metric_catalog.MetricsFileError):
                metric_catalog.load(self.folder(garbled))

    def test_compare_reads_the_metrics_every_folder_has(self):
        metric_catalog.use(self.folder(toy_catalog()), self.folder(None))
        self.assertEqual(len(metric_catalog.SCORED), 5)
        with self.assertRaises(KeyError):
            metric_catalog.by_name("toy_rebound")
        self.assertEqual(metric_catalog.DEFAULT_TOLERANCES["contact_duration_relative_error"], 0.25)  # the first's


if __name__ == "__main__":
    unittest.main()
