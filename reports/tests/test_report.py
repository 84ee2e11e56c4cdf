"""The report as a reader meets it: built from a small suite's saved results (without rerunning), every
figure a parseable SVG, the page self-contained, and every number in its tables equal to runs.csv's.

    /usr/bin/python3 reports/tests/test_report.py IMPACTBENCH_EXECUTABLE SCENARIO_FOLDER
"""

import csv
import json
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
from impactbench_report import metric_catalog, tables  # noqa: E402

EXECUTABLE = SCENARIOS = None


def build_engines(count):
    """The first `count` engines of the build under test, in its catalog's order (`impactbench engines --names`,
    the reference first): the report is tested on whatever engines the build has, named nowhere here."""
    names = subprocess.run([EXECUTABLE, "engines", "--names"], capture_output=True, text=True, check=True).stdout
    return [n for n in names.strip().split(",") if n and n != "reference"][:count]


def path_of(row):
    options = dict(o.split("=", 1) for o in row["options"].split(";") if "=" in o)
    return options.get("contact", "matched")


def independent_score(row, tolerances, prefix="vs_reference_"):
    """The largest |error vs beam| / tolerance of a runs.csv row (prefix vs_chain_reference_: vs its own chain),
    written here from the columns alone."""
    pairs = [("frame1_sensor_peak_relative_error", "sensor_peak_relative_error"),
             ("frame2_sensor_peak_relative_error", "sensor_peak_relative_error"),
             ("contact_duration_relative_error", "contact_duration_relative_error"),
             ("impacts_per_cycle_difference", "impacts_per_cycle_difference"),
             ("frame1_log_decrement_relative_error", "log_decrement_relative_error")]
    multiples = [abs(float(row[prefix + c])) / tolerances[t] for c, t in pairs if row.get(prefix + c)]
    return max(multiples) if multiples else math.inf


class Report(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.folder = tempfile.mkdtemp(prefix="impactbench_report_test_")
        cls.suite = os.path.join(cls.folder, "suite")
        cls.engines = build_engines(3)
        # --window 2: the scenarios' own windows (the free vibration's 0.3 s run is scored whole either way),
        # named on the command line so that the suite warns about short_resonance's, inside its start-up
        # transient; no --paths: the engines' default (matched) alone, no native run
        run = subprocess.run([EXECUTABLE, "suite", SCENARIOS, "--engines", ",".join(["reference"] + cls.engines),
                              "--laws", "viscoelastic,newton", "--dt", "1e-4,5e-5", "--window", "2", "--jobs", "2",
                              "--out", cls.suite], capture_output=True, text=True)
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

    def test_the_folder_names_the_engines_that_made_it(self):
        """engines.json (harness/records/engines_file.h): every simulator of the build with its version, the
        reference first, each engine of runs.csv among them."""
        with open(os.path.join(self.suite, "engines.json")) as f:
            simulators = json.load(f)["simulators"]
        names = [d["name"] for d in simulators]
        self.assertEqual(names[0], "reference")
        self.assertLessEqual({row["engine"] for row in self.rows}, set(names))
        self.assertTrue(all(d["version"] for d in simulators))

    def test_every_figure_is_an_svg(self):
        figures = os.listdir(os.path.join(self.report, "figures"))
        kinds = {name.split("_")[0] for name in figures}
        # the short cases have no measured peak: no experiment figure
        self.assertTrue({"error", "impact", "stability", "acceleration", "phase", "poincare", "spectrum", "scalogram",
                         "impacts", "decay"} <= kinds, kinds)
        for name in figures:
            root = ElementTree.parse(os.path.join(self.report, "figures", name)).getroot()
            self.assertTrue(root.tag.endswith("svg"), name)

    def test_the_page_names_every_figure_and_fetches_nothing_from_elsewhere(self):
        with open(os.path.join(self.report, "index.html")) as f:
            page = f.read()
        figures = sorted(os.listdir(os.path.join(self.report, "figures")))
        self.assertEqual(sorted(re.findall(r"<img src='figures/([^']+)'", page)), figures)
        self.assertNotRegex(page, r"(src|href)=['\"](https?:)?//")  # nothing fetched from elsewhere
        self.assertLess(len(page), 400_000)  # opens at once: the figures are separate files
        with open(os.path.join(self.suite, "engines.json")) as f:  # each engine under its name for people
            display = {d["name"]: d["display_name"] for d in json.load(f)["simulators"]}
        self.assertTrue(self.engines)
        for fact in ["machine", "engines", "load average", "commands", "Caveats", "id='answer'"] + \
                [display[e] for e in self.engines]:
            self.assertIn(fact, page)
        for name in ("runs.csv", "runs.jsonl", "summary.md", "summary.json"):
            self.assertTrue(os.path.exists(os.path.join(self.report, name)), name)

    def test_case_tables_equal_the_csv(self):
        """Every run row of every case table: the metric, its signed errors vs beam and vs own chain, the
        CPU cost and the verdict are runs.csv's, formatted."""
        with open(os.path.join(self.report, "summary.md")) as f:
            text = f.read()
        checked = 0
        for section in re.split(r"\n## ", text)[1:]:
            match = re.match(r"(\w+), (\w+)$", section.splitlines()[0])
            if not match:
                continue
            scenario, law = match.groups()
            lines = [line for line in section.splitlines() if line.startswith("| ")]
            header = [c.strip() for c in lines[0].strip().strip("|").split("|")]
            for line in lines[1:]:
                cells = dict(zip(header, (c.strip() for c in line.strip().strip("|").split("|"))))
                config = cells["configuration"]
                if config.startswith("experiment") or cells["time step [s]"] == "adaptive":
                    continue
                engine, _, options = config.partition(" [")
                row = next(r for r in self.rows if r["scenario"] == scenario and r["law"] == law and
                           r["engine"] == engine and r["options"] == options.rstrip("]") and
                           tables.fmt(float(r["time_step_s"])) == cells["time step [s]"])
                number = lambda name: float(row[name]) if row[name] else math.nan  # noqa: E731
                position = header.index("frame 1 sensor peak [g]")
                values = line.strip().strip("|").split("|")
                self.assertEqual(values[position].strip(), tables.fmt(number("frame1_sensor_peak_acceleration_g")))
                self.assertEqual(values[position + 1].strip(),
                                 tables.percent(number("vs_reference_frame1_sensor_peak_relative_error")))
                self.assertEqual(values[position + 2].strip(),
                                 tables.percent(number("vs_chain_reference_frame1_sensor_peak_relative_error")))
                self.assertEqual(cells["CPU [s per simulated s]"], tables.fmt(number("cpu_time_per_simulated_s"), 3))
                self.assertTrue(cells["verdict"].startswith(row["verdict"]), (cells["verdict"], row["verdict"]))
                if row["verdict"] in ("ok", "inaccurate"):
                    self.assertIn("(vs own chain)", cells["verdict"])  # the verdict names its reference
                checked += 1
        self.assertGreater(checked, 10)

    def summary_and_rows(self):
        """summary.json, runs.csv's rows by job id, and the verdict tolerances the summary names."""
        with open(os.path.join(self.report, "summary.json")) as f:
            summary = json.load(f)
        return summary, {r["job_id"]: r for r in self.rows}, summary["verdict_tolerances"]

    def test_the_summary_traces_to_runs_csv(self):
        """summary.json: every run it names is a row of runs.csv with the same values; each case's best
        configuration is stable and no other stable configuration of its kind scores better."""
        summary, by_id, tolerances = self.summary_and_rows()
        traced = 0
        for case in summary["cases"]:
            for config in case["configurations"]:
                run = config["best_run"]
                if run is None:
                    continue
                row = by_id[run["job_id"]]
                for column, value in list(run["runs_csv"].items()) + list(run["errors_vs_beam"].items()) \
                        + list(run["errors_vs_own_chain"].items()):
                    if isinstance(value, str):
                        self.assertEqual(value, row[column], column)
                    elif value is None:
                        self.assertEqual(row[column], "", column)
                    else:
                        self.assertEqual(value, float(row[column]), column)
                    traced += 1
                self.assertIn(row["verdict"], ("ok", "inaccurate"))
            for kind, paths in (("tuned", ("matched", "injected")), ("out_of_box", ("native",))):
                best = case["best_" + kind]
                if best["configuration"] is None:
                    continue
                best_score = independent_score(by_id[best["job_id"]], tolerances)
                for r in self.rows:
                    if (r["scenario"], r["law"]) == (case["scenario"], case["law"]) and r["engine"] != "reference" \
                            and r["verdict"] in ("ok", "inaccurate") and path_of(r) in paths:
                        self.assertLessEqual(best_score, independent_score(r, tolerances) + 1e-12, r["job_id"])
        self.assertGreater(traced, 100)
        self.assertEqual({e["engine"] for e in summary["engines"]}, set(self.engines))

    def test_every_point_of_a_front_traces_to_runs_csv(self):
        """summary.json's fronts: each point is its runs.csv row (step, cost, verdict) with its score
        computed from that row; each engine's most accurate point scores no worse against its own chain than its
        other stable points that pass their verdict as it does (this suite's runs are single, without a measured
        noise), and passes its verdict where one of them does."""
        summary, by_id, tolerances = self.summary_and_rows()
        checked = 0
        for case in summary["cases"]:
            if case["metrics_not_ranked"]:
                continue  # scored over fewer metrics than independent_score reads
            for engine, entry in case["fronts"]["engines"].items():
                stable_scores, own_scores = [], {True: [], False: []}
                for point in entry["points"]:
                    row = by_id[point["job_id"]]
                    self.assertEqual((row["engine"], row["verdict"]), (engine, point["verdict"]))
                    self.assertEqual(point["time_step_s"], float(row["time_step_s"]))
                    self.assertEqual(point["cpu_time_per_simulated_s"], float(row["cpu_time_per_simulated_s"]))
                    score = independent_score(row, tolerances)
                    if point["score_vs_beam"] is not None:
                        self.assertAlmostEqual(point["score_vs_beam"], score, places=12)
                        if row["verdict"] in ("ok", "inaccurate"):
                            stable_scores.append(score)
                            own_scores[row["verdict"] == "ok"].append(independent_score(row, tolerances, "vs_chain_reference_"))
                    checked += 1
                accurate = entry["most_accurate"]
                if accurate is not None:
                    passes = accurate["verdict"] == "ok"
                    self.assertEqual(passes, bool(own_scores[True]), f"{engine}: a failing run named over a passing one")
                    self.assertAlmostEqual(accurate["score_vs_own_chain"], min(own_scores[passes]), places=12)
                self.assertTrue(set(entry["front_job_ids"]) <= {p["job_id"] for p in entry["points"]})
        self.assertGreater(checked, 20)

    def test_every_point_has_a_budget_whose_parts_add_up(self):
        """summary.json: each front point's budget, per scored metric: its total is the row's error vs the beam,
        its engine part the row's error vs its own chain in the beam's units, and chain + engine = total."""
        from impactbench_report import budget
        summary, by_id, _ = self.summary_and_rows()
        checked = 0
        for case in summary["cases"]:
            for entry in case["fronts"]["engines"].values():
                for point in entry["points"]:
                    row = by_id[point["job_id"]]
                    self.assertIsNotNone(point["budget"], point["job_id"])
                    for metric, part in point["budget"]["metrics"].items():
                        column = next(c for c in row if c.startswith("vs_reference_")  # the metric's, in runs.csv
                                      and getattr(metric_catalog.by_error_column(c), "label", None) == metric)
                        self.assertAlmostEqual(part["total"], float(row[column]), places=12)
                        if part["residual"] is None:
                            self.assertTrue(part["why_not_additive"], point["job_id"])
                            continue
                        # runs.csv's nine significant digits: the parts agree to budget.ADDITIVE_TOLERANCE
                        self.assertTrue(budget.adds_up(part["total"], part["chain"], part["engine"]), (point["job_id"], part))
                        self.assertNotIn("why_not_additive", part, point["job_id"])
                        own = float(row[column.replace("vs_reference_", "vs_chain_reference_")])
                        expected = own * (1 + part["chain"]) if part["kind"] == "relative" else own
                        self.assertAlmostEqual(part["engine"], expected, places=12)
                        checked += 1
        self.assertGreater(checked, 20)

    def test_the_sensor_files_hold_the_peaks_the_metrics_measured(self):
        """What the figures draw is what the metrics measured: each frame's largest reading inside the scoring
        window of a run's sensor.csv.gz (read as the figures read it) is that frame's sensor peak in the run's
        summary.json, within 1e-6 (the file's nine significant digits)."""
        from impactbench_report import data
        checked = 0
        for folder, _, files in os.walk(os.path.join(self.suite, "runs")):
            if "sensor.csv.gz" not in files:
                continue
            with open(os.path.join(folder, "summary.json")) as f:
                summary = json.load(f)
            sensor = data.read_series(os.path.join(folder, "sensor.csv.gz"))
            time = sensor["time_s"]
            inside = (time >= summary["window_start_s"] - 1e-12) & (time <= summary["window_end_s"] + 1e-12)
            for frame in (1, 2):
                reading_g = max(abs(sensor[f"frame{frame}_sensor_acceleration_m_s2"][inside])) / data.G
                peak_g = summary[f"frame{frame}_sensor_peak_acceleration_g"]
                self.assertLessEqual(abs(reading_g - peak_g), 1e-6 * max(peak_g, 1e-9), f"{folder}, frame {frame}")
                checked += 1
        self.assertGreater(checked, 10)

    def test_a_suite_without_native_runs_says_not_run_rather_than_no_stable_run(self):
        self.assertFalse(any(path_of(r) == "native" for r in self.rows if r["engine"] != "reference"))
        with open(os.path.join(self.report, "summary.json")) as f:
            summary = json.load(f)
        with open(os.path.join(self.report, "index.html")) as f:
            page = f.read()
        with open(os.path.join(self.report, "summary.md")) as f:
            markdown = f.read()
        for standing in summary["engines"]:
            self.assertEqual(standing["out_of_box"]["runs"], 0)
            self.assertGreater(standing["tuned"]["runs"], 0)
            self.assertIn("native contact: not run", standing["line"])
            self.assertIn(standing["line"], markdown)
        self.assertNotIn("native contact: no stable run", page + markdown)

    def test_the_contact_path_has_a_column_of_its_own(self):
        for r in self.rows:
            if r["engine"] in ("reference", ""):
                self.assertEqual((r["contact_path"], r["law_simulated"]), ("", "yes" if r["engine"] else ""), r["job_id"])
            else:
                self.assertEqual((r["contact_path"], r["law_simulated"]), (path_of(r), "yes"), r["job_id"])

    def test_a_warning_is_recorded_with_its_runs_and_listed_in_the_report(self):
        warned = {}
        with open(os.path.join(self.suite, "runs.jsonl")) as f:
            for line in f:
                record = json.loads(line)
                warned[record["job_id"]] = record["warnings"]
        self.assertEqual(set(warned), {r["job_id"] for r in self.rows})
        for job_id, warnings in warned.items():
            if job_id.startswith("short_resonance/"):
                self.assertEqual(len(warnings), 1, job_id)
                self.assertIn("short_resonance: the scoring window starts at 1 s, before the start-up transient's end",
                              warnings[0])
            else:
                self.assertEqual(warnings, [], job_id)  # no motor: no start-up transient
        with open(os.path.join(self.suite, "runs", next(iter(w for w in warned if w.startswith("short_resonance/"))),
                               "summary.json")) as f:
            self.assertEqual(json.load(f)["warnings"], warned[next(w for w in warned if w.startswith("short_resonance/"))])
        text = next(w[0] for w in warned.values() if w)
        count = sum(1 for w in warned.values() if w)
        with open(os.path.join(self.report, "index.html")) as f:
            page = f.read().replace("&#x27;", "'")
        with open(os.path.join(self.report, "summary.md")) as f:
            markdown = f.read()
        self.assertIn("<h2 id='warnings'>Warnings</h2>", page)
        self.assertIn(f"<li>{text} ({count} runs)</li>", page)
        self.assertIn(f"## Warnings\n\n- {text} ({count} runs)", markdown)

    def test_without_steps_csv_there_is_no_steps_view(self):
        self.assertFalse(os.path.exists(os.path.join(self.suite, "steps.csv")))
        self.assertFalse(any(n.startswith("steps_") for n in os.listdir(os.path.join(self.report, "figures"))))
        with open(os.path.join(self.report, "summary.md")) as f:
            self.assertNotIn("| configuration | largest stable step [s]", f.read())

    def test_a_report_is_made_again_from_the_saved_results_alone(self):
        again = os.path.join(self.folder, "again")
        report = subprocess.run([EXECUTABLE, "report", self.suite, "--out", again], capture_output=True, text=True)
        self.assertEqual(report.returncode, 0, report.stderr)
        strip = lambda path: [l for l in open(path) if not l.startswith("- made")]  # noqa: E731
        self.assertEqual(strip(os.path.join(self.report, "summary.md")), strip(os.path.join(again, "summary.md")))


class StepsReport(unittest.TestCase):
    """A suite that searched its largest stable and accurate steps (--find-steps): the report draws them
    per case and law and lists them in a table whose numbers equal steps.csv's."""

    @classmethod
    def setUpClass(cls):
        cls.folder = tempfile.mkdtemp(prefix="impactbench_steps_report_test_")
        cls.suite = os.path.join(cls.folder, "suite")
        run = subprocess.run([EXECUTABLE, "suite", SCENARIOS, "--engines", build_engines(1)[0], "--laws", "viscoelastic",
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
