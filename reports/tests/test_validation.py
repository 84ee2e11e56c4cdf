"""The reference against the experiment (reports/impactbench_report/validation.py, validation_page.py,
docs/validation.md): the first-order index, u_input and the verdict against closed forms on synthetic data; a
small synthetic study with a validation folder (written here, seeded), whose report's summary.json holds what its
summary.md and index.html print; a study without one gets no key and no section.

    /usr/bin/python3 reports/tests/test_validation.py
"""

import contextlib
import csv
import html
import io
import json
import math
import os
import re
import shutil
import sys
import tempfile
import unittest
import warnings
import xml.etree.ElementTree as ElementTree

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from impactbench_report import data, page_writer, report_views, suite_report, validation, validation_page  # noqa: E402

# ---- a synthetic study: the nominal reference from 8 starts in OUT/runs.csv, a validation folder OUT/validation/NAME/

# name (SI, as the C++ side names them), nominal, distribution, half-width or standard uncertainty
INPUTS = [("frame1_column_thickness_m", 1.75e-3, "uniform", 0.08e-3),
          ("youngs_modulus_pa", 200e9, "normal", 6e9),
          ("gap_m", 1.0e-3, "uniform", 0.1e-3),
          ("motor_speed_ratio_offset", 0.0, "uniform", 0.01),
          ("frame1_damping_ratio", 0.003, "normal", 0.0006)]
# per case: motor ratio, frame 1 peak at the nominal inputs [g], its chaotic scatter over starts [g]
CASES = {"resonance": (1.00, 8.7, 0.15), "post_resonance": (1.17, 4.0, 0.05), "pre_resonance": (0.95, 3.85, 0.0002)}
POINTS = 12
STARTS = 8
F1_HZ = 6.95
COLUMNS = ["job_id", "scenario", "law", "engine", "time_step_s", "options", "verdict", "reason", "duration_s",
           "window_start_s", "window_end_s", "frame1_sensor_peak_acceleration_g", "frame2_sensor_peak_acceleration_g",
           "impacts_per_cycle", "impacts_per_beat", "beat_period_s", "cpu_time_s", "scenario_file", "engine_version",
           "ensemble_start", "ensemble_starts", "initial_displacement_offset_m"]
FAILED = ("resonance", 3)        # a sample point whose run failed
NO_RUN = ("pre_resonance", 5)    # a sample point runs.csv has no run of


def draw_inputs(rng):
    values = {}
    for name, nominal, distribution, spread in INPUTS:
        values[name] = (nominal + rng.uniform(-spread, spread) if distribution == "uniform"
                        else nominal + rng.normal(0, spread))
    return values


def response(case, inputs, rng):
    """The quantities of one run: frame 1's peak moves with the gap and the motor speed (not with the others),
    plus one start's chaos; beats where the motor is off resonance."""
    ratio, peak, chaos = CASES[case]
    gap = (inputs["gap_m"] - 1.0e-3) / 0.1e-3 if inputs else 0.0
    speed = inputs["motor_speed_ratio_offset"] / 0.01 if inputs else 0.0
    frame1 = peak + 0.6 * gap + 0.2 * speed + rng.normal(0, chaos)
    detuning = abs(ratio + (inputs["motor_speed_ratio_offset"] if inputs else 0.0) - 1)
    beat = 1 / (detuning * F1_HZ) if detuning > 0.02 else math.nan  # two beats in the window, else none
    return {"frame1_sensor_peak_acceleration_g": frame1, "frame2_sensor_peak_acceleration_g": 1.5 * frame1,
            "impacts_per_cycle": 0.5 + 0.05 * gap, "beat_period_s": beat,
            "impacts_per_beat": 7.0 + 0.5 * speed if case == "post_resonance" else (6.3 if case == "pre_resonance"
                                                                                    else math.nan)}


def row(job_id, scenario, values, verdict="ok", reason="", options="", start=0, starts=1, scenario_file=""):
    out = {c: "" for c in COLUMNS}
    out.update(job_id=job_id, scenario=scenario, law="hertz", engine="reference", options=options, verdict=verdict,
               reason=reason, duration_s="30", window_start_s="20", window_end_s="30", cpu_time_s="0.1",
               scenario_file=scenario_file or f"scenarios/paper/{scenario}.toml", ensemble_start=str(start),
               ensemble_starts=str(starts), initial_displacement_offset_m=str(start * 1e-6))
    for name, value in values.items():
        out[name] = "" if value is None or math.isnan(value) else repr(float(value))
    return out


def write_csv(path, rows, columns):
    with open(path, "w", newline="") as f:
        writer = csv.DictWriter(f, columns)
        writer.writeheader()
        writer.writerows(rows)


def write_study(folder, with_validation=True, seed=50):
    """A study folder: OUT/runs.csv with each case's nominal reference from 8 starts (the resonance's also at
    tight tolerances) and, with_validation, OUT/validation/paper/ with POINTS points per case."""
    rng = np.random.default_rng(seed)
    rows = []
    for case in CASES:
        for start in range(STARTS):
            job = f"{case}/reference/hertz" + (f"/start={start}" if start else "")
            rows.append(row(job, case, response(case, None, rng), start=start, starts=STARTS))
    first = next(r for r in rows if r["job_id"] == "resonance/reference/hertz")
    tight = dict(first, job_id="resonance/reference/hertz/atol=1e-15;rtol=1e-12", options="atol=1e-15;rtol=1e-12",
                 ensemble_starts="1",
                 frame1_sensor_peak_acceleration_g=repr(float(first["frame1_sensor_peak_acceleration_g"]) + 0.02))
    rows.append(tight)
    os.makedirs(folder, exist_ok=True)
    write_csv(os.path.join(folder, "runs.csv"), rows, COLUMNS)
    if not with_validation:
        return
    sample_folder = os.path.join(folder, "validation", "paper")
    os.makedirs(sample_folder)
    names = [name for name, *_ in INPUTS]
    sample, runs, point_id = [], [], 0
    for case in CASES:
        for point in range(POINTS):
            inputs = draw_inputs(rng)
            scenario = f"{case}_p{point_id:03d}"
            point_id += 1
            sample.append({"case": case, "point": point, "scenario": scenario,
                           "scenario_file": f"OUT/validation/paper/scenarios/{scenario}.toml",
                           **{n: repr(inputs[n]) for n in names}})
            if (case, point) == NO_RUN:
                continue
            failed = (case, point) == FAILED
            values = ({k: math.nan for k in response(case, inputs, rng)} if failed else response(case, inputs, rng))
            runs.append(row(f"{scenario}/reference/hertz", scenario, values, verdict="failed" if failed else "ok",
                            reason="step size underflow" if failed else "", scenario_file=sample[-1]["scenario_file"]))
    write_csv(os.path.join(sample_folder, "sample.csv"), sample, ["case", "point", "scenario", "scenario_file"] + names)
    write_csv(os.path.join(sample_folder, "runs.csv"), runs, COLUMNS)
    with open(os.path.join(sample_folder, "inputs.json"), "w") as f:
        json.dump({"inputs_file": "scenarios/paper_inputs.toml", "design": "sobol", "points": POINTS, "inputs": [
            {"name": n, "keys": [n], "nominal": v, "distribution": d,
             ("half_width" if d == "uniform" else "standard_uncertainty"): s,
             "standard_deviation": s / math.sqrt(3) if d == "uniform" else s, "source": "test"}
            for n, v, d, s in INPUTS]}, f)


# ---- closed forms --------------------------------------------------------------------------------------------


class ClosedForms(unittest.TestCase):
    def test_a_linear_response_has_the_index_of_its_share_of_the_variance(self):
        """Y = a X1 + noise, X uniform on [0, 1]: S1 = a^2 Var(X1) / Var(Y) (Var(X1) = 1/12), at N = 512 within
        the estimator's error (over 300 seeds: mean error -0.002, standard deviation 0.021, largest 0.074); X2,
        which Y does not depend on, near 0 (below the noise floor the page uses)."""
        a, noise, n = 2.0, 0.4, 512
        expected = a ** 2 / 12 / (a ** 2 / 12 + noise ** 2)
        for seed in range(5):
            rng = np.random.default_rng(seed)
            x1, x2 = rng.uniform(size=n), rng.uniform(size=n)
            y = a * x1 + rng.normal(0, noise, n)
            self.assertAlmostEqual(validation.first_order_index(x1, y), expected, delta=0.08, msg=f"seed {seed}")
            self.assertLess(validation.first_order_index(x2, y), validation.index_noise_floor(n), f"seed {seed}")
        ranked = validation.ranked_indices({"x2": x2, "x1": x1}, y)
        self.assertEqual(ranked[0][0], "x1")

    def test_an_input_without_effect_averages_an_index_of_0(self):
        """The bias (B-1)/(N-1) taken off: over many samples an irrelevant input's index averages near 0 (it is
        clipped at 0, so its mean is a little above), and 95 % of them or more fall under the noise floor."""
        rng = np.random.default_rng(7)
        indices = [validation.first_order_index(rng.uniform(size=256), rng.normal(size=256)) for _ in range(200)]
        self.assertLess(np.mean(indices), 0.02)
        self.assertGreaterEqual(min(indices), 0.0)
        self.assertGreaterEqual(np.mean(np.asarray(indices) < validation.index_noise_floor(256)), 0.95)

    def test_a_response_that_does_not_vary_has_no_index(self):
        self.assertIsNone(validation.first_order_index(np.arange(10.0), np.ones(10)))

    def test_u_input_recovers_the_inputs_spread_under_chaos(self):
        """Y = X + chaos, X uniform +-h (standard deviation h / sqrt(3)), the chaos normal with sigma: u_input
        from the sample's variance and sigma is h / sqrt(3) within the variance estimate's error
        (sqrt(2 / N) relative, about 2 % at N = 4096)."""
        rng = np.random.default_rng(11)
        h, sigma, n = 0.3, 0.2, 4096
        y = rng.uniform(-h, h, n) + rng.normal(0, sigma, n)
        ensemble = rng.normal(0, sigma, 64)  # the nominal case's starts: the chaos alone
        sigma_chaos, starts = validation.chaos_scatter(ensemble)
        self.assertEqual(starts, 64)
        u = validation.input_uncertainty(np.var(y, ddof=1), sigma_chaos)
        self.assertAlmostEqual(u, h / math.sqrt(3), delta=0.1 * h / math.sqrt(3))
        # with the chaos known exactly, closer still
        self.assertAlmostEqual(validation.input_uncertainty(np.var(y, ddof=1), sigma), h / math.sqrt(3),
                               delta=0.05 * h / math.sqrt(3))
        self.assertEqual(validation.input_uncertainty(0.01, 0.2), 0.0)  # the chaos explains it all: clipped

    def test_the_verdicts_edge(self):
        """|E| exactly at 2 u_val is within; a hair above is not, and the model-form error is that hair."""
        # u_val = sqrt(0 + 0 + 0.5^2) = 0.5 exactly; E = 11 - 10 = 1 = 2 u_val
        at_edge = validation.compare(11.0, 10.0, 0.0, 0.0, 8, 0.0, 0.5, "g")
        self.assertEqual((at_edge.e, at_edge.u_val), (1.0, 0.5))
        self.assertEqual(at_edge.verdict, "within the validation uncertainty")
        self.assertIsNone(at_edge.model_form_error_at_least)
        above = validation.compare(math.nextafter(11.0, 12.0), 10.0, 0.0, 0.0, 8, 0.0, 0.5, "g")
        self.assertTrue(above.verdict.startswith("model-form error of at least"), above.verdict)
        self.assertGreater(above.model_form_error_at_least, 0.0)
        self.assertLess(above.model_form_error_at_least, 1e-14)
        below = validation.compare(9.0, 10.0, 0.0, 0.0, 8, 0.0, 0.5)  # the sign does not matter
        self.assertEqual(below.verdict, "within the validation uncertainty")

    def test_a_verdict_within_u_inputs_sampling_error_is_undecided(self):
        """u_input from N runs is good to u_input / sqrt(2 (N - 1)): |E| = 2 u_val + a hair is undecided at 16
        points (se 0.18 of u_input = 1) and a model-form error at 10^6 points."""
        u_val = math.sqrt(0.1 ** 2 + 1.0 ** 2 + 0.5 ** 2)
        e = -(2 * u_val + 0.05)
        few = validation.compare(e, 0.0, 0.0, 0.1, 0, 1.0, 0.5, "g", n_sample=16)
        self.assertTrue(few.verdict.startswith("undecided at 16 sample points"), few.verdict)
        self.assertIsNone(few.model_form_error_at_least)
        self.assertAlmostEqual(few.u_input_sampling_error, 1 / math.sqrt(30), places=12)
        many = validation.compare(e, 0.0, 0.0, 0.1, 0, 1.0, 0.5, "g", n_sample=10 ** 6)
        self.assertAlmostEqual(many.model_form_error_at_least, 0.05, places=9)
        far = validation.compare(-10 * u_val, 0.0, 0.0, 0.1, 0, 1.0, 0.5, "g", n_sample=16)
        self.assertGreater(far.model_form_error_at_least, 0)  # far beyond: decided whatever the sample

    def test_u_num_holds_the_solver_the_one_window_and_the_means_noise(self):
        c = validation.compare(5.0, 4.0, 0.03, 0.2, 8, 0.1, 0.25)
        self.assertAlmostEqual(c.u_num, math.sqrt(0.03 ** 2 + 0.2 ** 2 + 0.2 ** 2 / 8), places=15)
        self.assertAlmostEqual(c.u_val, math.sqrt(c.u_num ** 2 + 0.1 ** 2 + 0.25 ** 2), places=15)

    def test_the_measurements_uncertainty_is_experiment_tomls(self):
        experiment = data.read_experiment()
        q = {x.column: x for x in validation.QUANTITIES}
        d, u, source = validation.measurement(experiment, "resonance", q["frame1_sensor_peak_acceleration_g"])
        self.assertEqual((d, u), (11.95, 0.05 * 11.95))
        self.assertIn("assumed", source)
        d, u, _ = validation.measurement(experiment, "post_resonance", q["impacts_per_beat"])
        self.assertEqual((d, u), (8.0, 1 / math.sqrt(3)))
        self.assertIsNone(validation.measurement(experiment, "resonance", q["impacts_per_beat"]))
        self.assertIsNone(validation.measurement(experiment, "resonance", q["beat_period_s"]))


# ---- a study's report --------------------------------------------------------------------------------------------


def markdown_tables(text):
    """Every Markdown table of a text as [header, rows...], each row its cells."""
    tables, current = [], []
    for line in text.splitlines() + [""]:
        if line.startswith("| "):
            current.append([c.strip() for c in line.strip("|").split(" | ")])
        elif line.startswith("|---"):
            continue
        elif current:
            tables.append(current)
            current = []
    return tables


def section_of(markdown, title):
    start = markdown.index(f"## {title}")
    end = markdown.find("\n## ", start + 1)
    return markdown[start:end if end >= 0 else len(markdown)]


def check_pages_print_the_json(test, summary, markdown, page):
    """Every cell of each case's two tables, in both pages, is summary.json's number as the page formats it (four
    significant digits), written here from the JSON alone."""
    text = section_of(markdown, "The reference against the experiment")
    tables = markdown_tables(text)
    fmt = lambda x: "–" if x is None else f"{x:.4g}"  # noqa: E731
    cases = summary["validation"][0]["cases"]
    test.assertEqual(len(tables), 2 * len(cases))
    for case, verdicts, spread in zip(cases, tables[0::2], tables[1::2]):
        measured = [q for q in case["quantities"] if q["vv20"]]
        test.assertEqual(verdicts[0][:4], ["quantity", "measured D", "reference S", "E = S − D"])
        test.assertEqual(len(verdicts) - 1, len(measured))
        for q, cells in zip(measured, verdicts[1:]):
            v = q["vv20"]
            test.assertEqual(cells[1:], [fmt(v[k]) for k in ("d", "s", "e", "u_num", "u_input", "u_d", "u_val")]
                             + [v["verdict"]])
        test.assertEqual(len(spread) - 1, len(case["quantities"]))
        for q, cells in zip(case["quantities"], spread[1:]):
            s = q["sample"]
            test.assertEqual(cells[1:6], [fmt(s["mean"]), fmt(s["standard_deviation"]), fmt(s["p2_5"]),
                                          fmt(s["p97_5"]), str(s["runs_not_ok"])])
            floor = q["sensitivity"]["noise_floor"]
            ranked = [r for r in q["sensitivity"]["ranked"] if r["index"] is not None]
            top = [r for r in ranked if r["index"] > floor][:3]
            test.assertEqual(cells[6], ", ".join(f"{r['input']} {fmt(r['index'])}" for r in top)
                             or (f"none above {fmt(floor)}" if ranked else "–"))
            test.assertEqual(cells[7], fmt(q["chaos_share"]))
        for cells in verdicts[1:] + spread[1:]:  # the same cells in index.html
            test.assertIn("".join(f"<td>{html.escape(c)}</td>" for c in cells), page)


class StudyWithValidation(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.folder = tempfile.mkdtemp(prefix="impactbench_validation_test_")
        cls.study = os.path.join(cls.folder, "study")
        write_study(cls.study)
        cls.out = os.path.join(cls.study, "report")
        os.makedirs(cls.out)
        suite = data.read_runs(cls.study)
        document = {"suite": {"made": "2026-11-29 11:00 UTC"}, "cases": [], "ablation": []}
        suite_report.add_validation(document, suite, data.read_experiment())
        with open(os.path.join(cls.out, "summary.json"), "w") as f:
            json.dump(document, f, indent=1, allow_nan=False)  # as the report writes it: no NaN
        with open(os.path.join(cls.out, "summary.json")) as f:
            cls.summary = json.load(f)
        inputs = report_views.ViewInputs(cls.study, document, cls.out)
        sections = report_views.sections(report_views.AFTER_CASES, inputs)
        cls.titles = [s[0] for s in sections]
        cls.markdown = "\n".join(page_writer.sections_markdown(sections, cls.out))
        cls.html = "\n".join(page_writer.sections_html(sections, cls.out))

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.folder)

    def case(self, name):
        return next(c for c in self.summary["validation"][0]["cases"] if c["case"] == name)

    def quantity(self, case, column):
        return next(q for q in self.case(case)["quantities"] if q["quantity"] == column)

    def test_the_key_holds_the_sample_and_every_case(self):
        entry = self.summary["validation"][0]
        self.assertEqual((entry["name"], entry["design"], entry["sample_size"]), ("paper", "sobol", POINTS))
        self.assertEqual(entry["inputs_file"], "scenarios/paper_inputs.toml")
        self.assertEqual(entry["input_names"], [n for n, *_ in INPUTS])  # from sample.csv's header
        self.assertEqual([c["case"] for c in entry["cases"]], ["resonance", "post_resonance", "pre_resonance"])

    def test_the_numbers_are_the_folders(self):
        """The distribution, the chaos and u_input computed here again from the CSV files."""
        with open(os.path.join(self.study, "validation", "paper", "runs.csv")) as f:
            runs = {r["scenario"]: r for r in csv.DictReader(f)}
        with open(os.path.join(self.study, "validation", "paper", "sample.csv")) as f:
            points = [r for r in csv.DictReader(f) if r["case"] == "resonance"]
        y = [float(runs[p["scenario"]]["frame1_sensor_peak_acceleration_g"]) for p in points
             if p["scenario"] in runs and runs[p["scenario"]]["verdict"] == "ok"]
        with open(os.path.join(self.study, "runs.csv")) as f:
            nominal = [float(r["frame1_sensor_peak_acceleration_g"]) for r in csv.DictReader(f)
                       if r["scenario"] == "resonance" and r["options"] == ""]
        q = self.quantity("resonance", "frame1_sensor_peak_acceleration_g")
        self.assertEqual(q["sample"]["n"], len(y))
        self.assertAlmostEqual(q["sample"]["mean"], np.mean(y), places=12)
        self.assertAlmostEqual(q["sample"]["p97_5"], np.percentile(y, 97.5), places=12)
        self.assertEqual(q["nominal"]["n"], STARTS)
        self.assertAlmostEqual(q["nominal"]["sigma_chaos"], np.std(nominal, ddof=1), places=12)
        self.assertAlmostEqual(q["u_input"], math.sqrt(max(0, np.var(y, ddof=1) - np.var(nominal, ddof=1))), places=12)
        v = q["vv20"]
        self.assertAlmostEqual(v["s"], np.mean(nominal), places=12)
        self.assertAlmostEqual(v["u_solver"], 0.02, places=9)  # the tight rerun's difference
        self.assertEqual(v["e"], v["s"] - v["d"])

    def test_runs_not_ok_and_undefined_values_are_listed(self):
        q = self.quantity("resonance", "frame1_sensor_peak_acceleration_g")
        self.assertEqual([(r["point"], r["status"], r["reason"]) for r in q["runs_not_ok"]],
                         [(FAILED[1], "failed", "step size underflow")])
        self.assertEqual(q["sample"]["runs_not_ok"], 1)
        missing = self.quantity("pre_resonance", "frame1_sensor_peak_acceleration_g")["runs_not_ok"]
        self.assertEqual([(r["point"], r["status"]) for r in missing], [(NO_RUN[1], "no run")])
        beat = self.quantity("resonance", "beat_period_s")
        self.assertEqual(beat["sample"]["n"], 0)
        self.assertEqual(len(beat["not_defined"]), POINTS - 1)  # every ok run: no beating at resonance
        self.assertIn("point 3 (resonance_p003): failed, step size underflow", self.markdown)

    def test_only_measured_quantities_have_a_verdict(self):
        for case in self.summary["validation"][0]["cases"]:
            for q in case["quantities"]:
                measured = (q["quantity"] == "frame1_sensor_peak_acceleration_g"
                            or (q["quantity"] == "impacts_per_beat" and case["case"] == "post_resonance"))
                self.assertEqual(q["vv20"] is not None, measured, (case["case"], q["quantity"]))
                if not measured:
                    self.assertIn("not measured in the experiment: its distribution alone, no verdict", q["notes"])
        self.assertEqual(self.quantity("pre_resonance", "frame1_sensor_peak_acceleration_g")["vv20"]["u_solver_from"],
                         "taken as 0: the study did not rerun the reference at tighter tolerances")

    def test_the_gap_matters_most_to_frame_1s_peak(self):
        ranked = self.quantity("post_resonance", "frame1_sensor_peak_acceleration_g")["sensitivity"]["ranked"]
        self.assertEqual(ranked[0]["input"], "gap_m")

    def test_the_pages_print_the_jsons_numbers(self):
        self.assertEqual(self.titles[0], "The reference against the experiment")
        check_pages_print_the_json(self, self.summary, self.markdown, self.html)

    def test_the_reading_states_the_verdict_in_words(self):
        v = self.quantity("resonance", "frame1_sensor_peak_acceleration_g")["vv20"]
        said = f"the reference gives {v['s']:.4g} g, {abs(v['e']):.4g} g"
        self.assertIn(said, self.markdown)
        self.assertIn("docs/validation.md", self.markdown)
        self.assertTrue(os.path.exists(validation_page.DOC), "the page names docs/validation.md")

    def test_each_case_has_its_figure(self):
        section = section_of(self.markdown, "The reference against the experiment")
        figures = re.findall(r"!\[[^\]]*\]\(([^)]+)\)", section)
        self.assertEqual(len(figures), 3)
        for path in figures:
            ElementTree.parse(os.path.join(self.out, path))  # a parseable SVG
            self.assertIn(os.path.join("figures", "validation_paper_"), path)


class ReportOfTheStudy(unittest.TestCase):
    """The whole report (suite_report.make) of the synthetic study, with and without its validation folder: the files
    a reader opens."""

    def make(self, with_validation):
        folder = tempfile.mkdtemp(prefix="impactbench_validation_report_")
        self.addCleanup(shutil.rmtree, folder)
        study = os.path.join(folder, "study")
        write_study(study, with_validation)
        out = os.path.join(study, "report")
        os.makedirs(out)
        with contextlib.redirect_stdout(io.StringIO()), warnings.catch_warnings():
            # a study of reference runs alone leaves each case's error-against-cost figure without an engine's panel
            warnings.filterwarnings("ignore", "constrained_layout not applied", UserWarning)
            suite_report.make(study, out)
        with open(os.path.join(out, "summary.json")) as f:
            summary = json.load(f)
        with open(os.path.join(out, "summary.md")) as f:
            markdown = f.read()
        with open(os.path.join(out, "index.html")) as f:
            page = f.read()
        return out, summary, markdown, page

    def test_summary_json_holds_what_the_pages_print(self):
        out, summary, markdown, page = self.make(True)
        check_pages_print_the_json(self, summary, markdown, page)
        self.assertIn("<h2 id='the-reference-against-the-experiment'>The reference against the experiment</h2>", page)
        self.assertIn("href='#the-reference-against-the-experiment'", page)  # in the page's navigation

    def test_without_a_validation_folder_no_key_and_no_section(self):
        out, summary, markdown, page = self.make(False)
        self.assertNotIn("validation", summary)
        self.assertNotIn("The reference against the experiment", markdown)
        self.assertNotIn("The reference against the experiment", page)
        self.assertFalse([f for f in os.listdir(os.path.join(out, "figures")) if f.startswith("validation_")])


if __name__ == "__main__":
    unittest.main()
