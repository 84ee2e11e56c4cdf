"""The report as a reader meets it: built from a small suite's saved results (without rerunning), every
figure a parseable SVG, the page self-contained, and every number in its tables equal to runs.csv's.

    /usr/bin/python3 reports/tests/test_report.py IMPACTBENCH_EXECUTABLE SCENARIO_FOLDER
"""

import csv
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import unittest
import xml.etree.ElementTree as ElementTree

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from impactbench_report import tables  # noqa: E402

EXECUTABLE = SCENARIOS = None


class Report(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.folder = tempfile.mkdtemp(prefix="impactbench_report_test_")
        cls.suite = os.path.join(cls.folder, "suite")
        run = subprocess.run([EXECUTABLE, "suite", SCENARIOS, "--engines", "reference,mujoco,ode,bullet",
                              "--laws", "viscoelastic,newton", "--dt", "1e-4,5e-5", "--jobs", "2", "--out", cls.suite],
                             capture_output=True, text=True)
        # unstable runs (exit code 1) are findings the report must show, not failures of this test
        assert run.returncode in (0, 1), run.stderr
        report = subprocess.run([EXECUTABLE, "report", cls.suite], capture_output=True, text=True)
        assert report.returncode == 0, report.stderr
        cls.report = os.path.join(cls.suite, "report")
        with open(os.path.join(cls.suite, "runs.csv"), newline="") as f:
            cls.rows = list(csv.DictReader(f))

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.folder)

    def test_every_figure_is_an_svg(self):
        figures = os.listdir(os.path.join(self.report, "figures"))
        kinds = {name.split("_")[0] for name in figures}
        self.assertTrue({"error", "sensor", "impact", "stability", "experiment"} <= kinds, kinds)
        for name in figures:
            root = ElementTree.parse(os.path.join(self.report, "figures", name)).getroot()
            self.assertTrue(root.tag.endswith("svg"), name)

    def test_the_page_is_self_contained(self):
        with open(os.path.join(self.report, "index.html")) as f:
            page = f.read()
        figures = os.listdir(os.path.join(self.report, "figures"))
        self.assertEqual(page.count("<svg"), len(figures))
        self.assertNotRegex(page, r"<(img|script|link)\b[^>]*(src|href)=")  # nothing fetched from elsewhere
        for fact in ("machine", "engines", "time steps", "Caveats", "mujoco", "ode", "bullet"):
            self.assertIn(fact, page)
        for name in ("runs.csv", "runs.jsonl", "summary.md"):
            self.assertTrue(os.path.exists(os.path.join(self.report, name)), name)

    def test_table_numbers_equal_the_csv(self):
        with open(os.path.join(self.report, "summary.md")) as f:
            text = f.read()
        checked = 0
        for section in re.split(r"\n## ", text)[1:]:
            title = section.splitlines()[0]
            match = re.match(r"(\w+), (\w+)$", title)
            if not match:
                continue
            scenario, law = match.groups()
            for line in section.splitlines():
                cells = [c.strip() for c in line.strip().strip("|").split("|")]
                row = re.match(r"(.+) \((best step|largest stable step)\)$", cells[0]) if cells else None
                if not row or cells[1] in ("none stable", ""):
                    continue
                config = row.group(1)
                engine, _, options = config.partition(" [")
                options = options.rstrip("]")
                csv_row = next(r for r in self.rows if r["scenario"] == scenario and r["law"] == law and r["engine"] == engine
                               and r["options"] == options and tables.fmt(float(r["time_step_s"])) == cells[1])
                number = lambda name: float(csv_row[name]) if csv_row[name] else math.nan  # noqa: E731
                self.assertEqual(cells[2], tables.fmt(number("frame1_sensor_peak_acceleration_g")))
                self.assertEqual(cells[3], tables.percent(number("vs_reference_frame1_sensor_peak_relative_error")))
                self.assertEqual(cells[4], tables.fmt(number("contact_duration_mean_s")))
                self.assertEqual(cells[6], tables.fmt(number("impacts_per_cycle")))
                self.assertEqual(cells[8], tables.fmt(number("wall_time_s")))
                self.assertEqual(cells[9], csv_row["verdict"])
                checked += 1
        self.assertGreater(checked, 10)

    def test_without_steps_csv_there_is_no_steps_view(self):
        self.assertFalse(os.path.exists(os.path.join(self.suite, "steps.csv")))
        self.assertFalse(any(n.startswith("steps_") for n in os.listdir(os.path.join(self.report, "figures"))))
        with open(os.path.join(self.report, "summary.md")) as f:
            self.assertNotIn("largest stable step [s]", f.read())

    def test_a_report_is_made_again_from_the_saved_results_alone(self):
        again = os.path.join(self.folder, "again")
        report = subprocess.run([EXECUTABLE, "report", self.suite, "--out", again], capture_output=True, text=True)
        self.assertEqual(report.returncode, 0, report.stderr)
        strip = lambda path: [l for l in open(path) if not l.startswith("- date")]  # noqa: E731
        self.assertEqual(strip(os.path.join(self.report, "summary.md")), strip(os.path.join(again, "summary.md")))


class StepsReport(unittest.TestCase):
    """A suite that searched its largest stable and accurate steps (--find-steps): the report draws them
    per case and law and lists them in a table whose numbers equal steps.csv's."""

    @classmethod
    def setUpClass(cls):
        cls.folder = tempfile.mkdtemp(prefix="impactbench_steps_report_test_")
        cls.suite = os.path.join(cls.folder, "suite")
        run = subprocess.run([EXECUTABLE, "suite", SCENARIOS, "--engines", "mujoco", "--laws", "viscoelastic",
                              "--paths", "matched", "--find-steps", "--step-range", "5e-5,4e-4", "--jobs", "2",
                              "--out", cls.suite], capture_output=True, text=True)
        assert run.returncode in (0, 1), run.stderr
        report = subprocess.run([EXECUTABLE, "report", cls.suite], capture_output=True, text=True)
        assert report.returncode == 0, report.stderr
        cls.report = os.path.join(cls.suite, "report")
        with open(os.path.join(cls.suite, "steps.csv"), newline="") as f:
            cls.rows = list(csv.DictReader(f))

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.folder)

    def test_one_row_and_one_figure_per_case(self):
        cases = {(r["scenario"], r["law"]) for r in self.rows}
        self.assertEqual(len(self.rows), len(cases))
        self.assertGreaterEqual(len(cases), 2)
        figures = set(os.listdir(os.path.join(self.report, "figures")))
        for scenario, law in cases:
            name = f"steps_{scenario}_{law}.svg"
            self.assertIn(name, figures)
            root = ElementTree.parse(os.path.join(self.report, "figures", name)).getroot()
            self.assertTrue(root.tag.endswith("svg"), name)

    def test_table_numbers_equal_steps_csv(self):
        with open(os.path.join(self.report, "summary.md")) as f:
            text = f.read()
        checked = 0
        for section in re.split(r"\n## ", text)[1:]:
            match = re.match(r"(\w+), (\w+)$", section.splitlines()[0])
            if not match:
                continue
            scenario, law = match.groups()
            lines = section.splitlines()
            starts = [i for i, line in enumerate(lines) if line.startswith("| configuration | largest stable step [s]")]
            self.assertEqual(len(starts), 1, section[:200])
            for line in lines[starts[0] + 2:]:
                if not line.startswith("|"):
                    break
                cells = [c.strip() for c in line.strip().strip("|").split("|")]
                engine, _, options = cells[0].partition(" [")
                row = next(r for r in self.rows if r["scenario"] == scenario and r["law"] == law
                           and r["engine"] == engine and r["options"] == options.rstrip("]"))
                for cell, column, status in (
                        (cells[1], "largest_stable_step_s", "stability_status"),
                        (cells[3], "frame1_sensor_peak_largest_step_within_tolerance_s", "frame1_sensor_peak_status"),
                        (cells[4], "contact_duration_largest_step_within_tolerance_s", "contact_duration_status"),
                        (cells[5], "impacts_per_cycle_largest_step_within_tolerance_s", "impacts_per_cycle_status")):
                    if row[column]:
                        self.assertEqual(cell, tables.fmt(float(row[column])))
                    else:
                        self.assertEqual(cell, row[status].replace("not applicable: ", "n/a: "))
                self.assertEqual(cells[6], tables.fmt(float(row["probes"])))
                checked += 1
        self.assertEqual(checked, len(self.rows))


if __name__ == "__main__":
    EXECUTABLE, SCENARIOS = sys.argv[1], sys.argv[2]
    unittest.main(argv=sys.argv[:1], verbosity=2)
