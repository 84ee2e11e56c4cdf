"""The reference against the experiment from the C++ side's own folders (reports/impactbench_report/validation.py,
docs/validation.md): a validation folder's own nominal ensemble and tight rerun are the ones used, and a small real
study run by the executable has its folder's numbers in summary.json and on its pages.

    /usr/bin/python3 reports/tests/test_validation_study.py [IMPACTBENCH]

Without IMPACTBENCH the real study is skipped (ctest gives it: report_validation_study)."""
import csv
import json
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from impactbench_report import data, validation  # noqa: E402
from test_validation import COLUMNS, check_pages_print_the_json, response, row, write_csv, write_study  # noqa: E402

EXECUTABLE = None
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


class NominalEnsembleInTheFolder(unittest.TestCase):
    """A [[validation]] part runs each case's nominal reference from its starts and at tight tolerances in its own
    folder, cut and scored as its sample is: those are S, the chaos and u_solver, not the study's runs."""

    def test_the_folders_own_nominal_runs_are_used(self):
        folder = tempfile.mkdtemp(prefix="impactbench_validation_nominal_")
        try:
            study = os.path.join(folder, "study")
            write_study(study)
            rng = np.random.default_rng(7)
            own = []
            for start in range(3):  # the folder's ensemble: 3 starts, 2 g above the study's
                values = {k: v + 2 for k, v in response("resonance", None, rng).items()}
                job = "resonance/reference/hertz" + (f"/start={start}" if start else "")
                own.append(row(job, "resonance", values, start=start, starts=3))
            tight = dict(own[0], job_id="resonance/reference/hertz/atol=1e-15;rtol=1e-12",
                         options="atol=1e-15;rtol=1e-12", ensemble_starts="1",
                         frame1_sensor_peak_acceleration_g=repr(float(own[0]["frame1_sensor_peak_acceleration_g"]) +
                                                                0.5))
            runs_csv = os.path.join(study, "validation", "paper", "runs.csv")
            with open(runs_csv, newline="") as f:
                sample_rows = list(csv.DictReader(f))
            write_csv(runs_csv, sample_rows + own + [tight], COLUMNS)
            entry = validation.summarise(data.read_runs(study), data.read_experiment())[0]
            case = next(c for c in entry["cases"] if c["case"] == "resonance")
            self.assertEqual(case["nominal_job_ids"], [r["job_id"] for r in own])
            self.assertEqual(case["tight_job_id"], tight["job_id"])
            q = next(q for q in case["quantities"] if q["quantity"] == "frame1_sensor_peak_acceleration_g")
            peaks = [float(r["frame1_sensor_peak_acceleration_g"]) for r in own]
            self.assertAlmostEqual(q["vv20"]["s"], np.mean(peaks), places=12)
            self.assertAlmostEqual(q["vv20"]["u_solver"], 0.5, places=9)
            self.assertEqual(q["nominal"]["n"], 3)
        finally:
            shutil.rmtree(folder)


class FromARealStudy(unittest.TestCase):
    """The C++ side's own output: `impactbench study` with a small suite and a [[validation]] part (two cases at
    4 points, their nominal cases from 2 starts and at tight tolerances, 1 s each), then its report: summary.json's
    numbers are the validation folder's CSV files', and the pages print them. Runs only with the executable
    (ctest gives it: report_validation)."""

    @classmethod
    def setUpClass(cls):
        if EXECUTABLE is None:
            raise unittest.SkipTest("no impactbench executable given (test_validation.py IMPACTBENCH)")
        cls.folder = tempfile.mkdtemp(prefix="impactbench_validation_study_")
        study_file = os.path.join(cls.folder, "study.toml")
        with open(study_file, "w") as f:
            f.write(f"""[[suite]]
name = "nominal"
scenarios = ["{ROOT}/scenarios/paper/resonance.toml"]
laws = ["hertz"]
duration_s = 1
window_s = 0.5

[[validation]]
name = "tiny"
scenarios = ["{ROOT}/scenarios/paper/resonance.toml", "{ROOT}/scenarios/paper/pre_resonance.toml"]
inputs = "{ROOT}/scenarios/paper_inputs.toml"
points = 4
nominal_starts = 2
duration_s = 1
window_s = 0.5
""")
        cls.study = os.path.join(cls.folder, "study")
        run = subprocess.run([EXECUTABLE, "study", study_file, "--out", cls.study], capture_output=True, text=True)
        if run.returncode != 0:
            raise AssertionError(f"impactbench study failed ({run.returncode}): {run.stdout}{run.stderr}")
        report = os.path.join(cls.study, "report")
        with open(os.path.join(report, "summary.json")) as f:
            cls.summary = json.load(f)
        with open(os.path.join(report, "summary.md")) as f:
            cls.markdown = f.read()
        with open(os.path.join(report, "index.html")) as f:
            cls.html = f.read()

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.folder)

    def test_the_summary_holds_the_folders_numbers(self):
        entry = self.summary["validation"][0]
        self.assertEqual((entry["name"], entry["sample_size"]), ("tiny", 4))
        self.assertEqual(entry["input_names"][0], "frame1_column_thickness_m")
        folder = os.path.join(self.study, "validation", "tiny")
        with open(os.path.join(folder, "runs.csv")) as f:
            rows = list(csv.DictReader(f))
        with open(os.path.join(folder, "sample.csv")) as f:
            points = list(csv.DictReader(f))
        for case in entry["cases"]:
            variants = {p["scenario"] for p in points if p["case"] == case["case"]}
            y = [float(r["frame1_sensor_peak_acceleration_g"]) for r in rows if r["scenario"] in variants]
            nominal = [r for r in rows if r["scenario"] == case["case"] and r["options"] == ""]
            tight = [r for r in rows if r["scenario"] == case["case"] and "rtol" in r["options"]]
            q = next(q for q in case["quantities"] if q["quantity"] == "frame1_sensor_peak_acceleration_g")
            self.assertEqual(q["sample"]["n"], 4)
            self.assertAlmostEqual(q["sample"]["mean"], np.mean(y), places=9)
            self.assertEqual(case["nominal_job_ids"], [r["job_id"] for r in sorted(nominal, key=lambda r: int(r["ensemble_start"]))])
            self.assertEqual(case["tight_job_id"], tight[0]["job_id"])
            v = q["vv20"]
            self.assertAlmostEqual(v["s"], np.mean([float(r["frame1_sensor_peak_acceleration_g"]) for r in nominal]),
                                   places=9)
            self.assertAlmostEqual(v["u_solver"], abs(float(tight[0]["frame1_sensor_peak_acceleration_g"]) -
                                                      float(nominal[0]["frame1_sensor_peak_acceleration_g"])), places=9)

    def test_the_pages_print_the_jsons_numbers(self):
        check_pages_print_the_json(self, self.summary, self.markdown, self.html)


if __name__ == "__main__":
    if len(sys.argv) > 1 and not sys.argv[1].startswith("-"):
        EXECUTABLE = sys.argv.pop(1)
    unittest.main()
