"""The observed order of convergence of the fronts' lines (reports/impactbench_report/front_order.py) on runs whose
errors are chosen: errors exactly C h^p give p, two steps give no order, a noisy case or an error within its
interval gives no number, errors that do not fall with the step are called a poor fit, and the table on both pages
of a report made from a synthetic runs.csv shows the numbers its summary.json holds.

    /usr/bin/python3 reports/tests/test_front_order.py
"""

import csv
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import types
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from impactbench_report import data, front_order, fronts, metric_catalog  # noqa: E402
from impactbench_report.ensembles import Interval  # noqa: E402

MAKE_REPORT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "make_report.py")
TOLERANCES = metric_catalog.DEFAULT_TOLERANCES
PEAK = "frame1_sensor_peak_relative_error"
STEPS_S = (2e-4, 1e-4, 5e-5, 2.5e-5)
NOISY = {"needed": True, "single_run_noise": {PEAK: [0.05, 11]}}  # one reference start scatters by +-5 %


def run(job_id, step_s, chain_error, engine="engine_a", options="contact=matched", verdict="ok"):
    """A run whose only scored error is frame 1's sensor peak against its own chain (and the beam, 1 % further)."""
    return data.Run({"job_id": job_id, "engine": engine, "options": options, "same_run_as": "", "verdict": verdict,
                     "time_step_s": step_s, "cpu_time_per_simulated_s": 1e-5 / step_s, "chain_links": 8.0,
                     "vs_reference_" + PEAK: chain_error + 0.01, "vs_chain_reference_" + PEAK: chain_error})


def power_law_line(order, steps_s=STEPS_S, constant=0.2, engine="engine_a"):
    """Runs whose errors are exactly constant (h / h_0)^order."""
    return [run(f"{engine}/dt={h:g}", h, constant * (h / steps_s[0]) ** order, engine) for h in steps_s]


def orders(runs, need=None):
    return front_order.observed_orders(fronts.points(runs, TOLERANCES), need)


class ObservedOrder(unittest.TestCase):
    def test_errors_exactly_c_h_to_the_p_give_order_p(self):
        for order in (1, 2):
            with self.subTest(order=order):
                [line] = orders(power_law_line(order))
                self.assertAlmostEqual(line["observed_order"], order, places=9)
                self.assertEqual(line["status"], "measured")
                self.assertAlmostEqual(line["fit_r_squared"], 1.0, places=12)
                self.assertEqual(line["time_steps_s"], list(STEPS_S))  # coarsest first
                self.assertEqual(line["job_ids"], [f"engine_a/dt={h:g}" for h in STEPS_S])
                for step_s, error in zip(line["time_steps_s"], line["errors"]):
                    self.assertAlmostEqual(error, 0.2 * (step_s / STEPS_S[0]) ** order, places=15)

    def test_a_line_with_two_steps_gives_no_order(self):
        [line] = orders(power_law_line(1, STEPS_S[:2]))
        self.assertIsNone(line["observed_order"])
        self.assertEqual(line["status"], "no order")
        self.assertIn("3 needed", line["remark"])

    def test_an_unstable_step_does_not_count(self):
        runs = power_law_line(1, STEPS_S[:3])
        runs[0].values["verdict"] = "unstable"
        [line] = orders(runs)
        self.assertEqual((line["status"], line["time_steps_s"]), ("no order", list(STEPS_S[1:3])))

    def test_a_single_step_is_no_line(self):
        self.assertEqual(orders(power_law_line(1, STEPS_S[:1])), [])

    def test_a_line_in_a_noisy_case_is_not_measurable(self):
        runs = power_law_line(1)
        [line] = orders(runs, NOISY)
        self.assertIsNone(line["observed_order"])
        self.assertEqual(line["status"], "not measurable")
        self.assertTrue(line["remark"].startswith("not measurable: errors within the noise"), line["remark"])
        self.assertEqual(orders(runs)[0]["status"], "measured", "the same errors in a quiet case give an order")

    def test_ensembles_give_an_order_unless_an_error_is_within_its_interval(self):
        runs = power_law_line(1)
        for r, half_width in zip(runs, (0.01, 0.01, 0.01, 0.01)):  # every error above its +-1 %
            error = r.number("vs_chain_reference_" + PEAK)
            r.ensemble = types.SimpleNamespace(n=4, errors={"vs_chain_reference_" + PEAK: Interval(
                error, 4, "Welch", half_width / 2, 6, half_width)})
        self.assertAlmostEqual(orders(runs, NOISY)[0]["observed_order"], 1.0, places=9)
        runs[-1].ensemble.errors["vs_chain_reference_" + PEAK].half_width = 0.03  # 2.5 % within +-3 %
        [line] = orders(runs, NOISY)
        self.assertEqual((line["status"], line["observed_order"]), ("not measurable", None))
        self.assertIn("2.5e-05 s", line["remark"])

    def test_errors_that_do_not_fall_with_the_step_are_a_poor_fit(self):
        [line] = orders(power_law_line(-1))  # the error grows as the step shrinks
        self.assertLess(line["observed_order"], 0)
        self.assertEqual(line["status"], "poor fit")
        self.assertIn("do not fall with the step", line["remark"])

    def test_errors_that_level_off_are_a_poor_fit(self):
        """A slope well above 0 but below half an order: errors that level off at a bias (-41 % at every step)."""
        [line] = orders([run(f"engine_a/dt={h:g}", h, e) for h, e in ((1e-4, -0.412), (5e-5, -0.407), (2.5e-5, -0.406))])
        self.assertEqual(line["status"], "poor fit")
        self.assertIn("do not fall with the step", line["remark"])
        self.assertLess(line["observed_order"], front_order.SLOWEST_ORDER)

    def test_errors_that_follow_no_one_power_are_a_poor_fit(self):
        runs = [run(f"a/dt={h:g}", h, e) for h, e in zip(STEPS_S, (0.2, 0.01, 0.012, 0.009))]
        [line] = orders(runs)
        self.assertLess(line["fit_r_squared"], front_order.POOR_FIT_R_SQUARED)
        self.assertEqual(line["status"], "poor fit")
        self.assertIn("R²", line["remark"])

    def test_each_configuration_and_chain_is_its_own_line(self):
        first = power_law_line(1)
        second = [run(f"native/dt={h:g}", h, 0.3 * (h / STEPS_S[0]) ** 2, options="contact=native") for h in STEPS_S]
        finer = power_law_line(1)
        for r in finer:
            r.values.update(job_id=r["job_id"] + "/k16", chain_links=16.0)
        found = {(line["configuration"], line["chain_links"]): line["observed_order"]
                 for line in orders(first + second + finer)}
        self.assertEqual(set(found), {("engine_a [contact=matched]", 8), ("engine_a [contact=native]", 8),
                                      ("engine_a [contact=matched]", 16)})
        self.assertAlmostEqual(found[("engine_a [contact=native]", 8)], 2.0, places=9)

    def test_least_squares_on_a_known_line(self):
        slope, r_squared, standard_error = front_order.least_squares([0.0, 1.0, 2.0], [1.0, 3.0, 5.0])
        self.assertEqual((slope, r_squared, standard_error), (2.0, 1.0, 0.0))
        slope, r_squared, _ = front_order.least_squares([0.0, 1.0, 2.0], [0.0, 1.0, 0.0])
        self.assertEqual((slope, r_squared), (0.0, 0.0))


COLUMNS = ("job_id", "scenario", "law", "engine", "time_step_s", "options", "contact_path", "law_simulated",
           "same_run_as", "chain_links", "verdict", "reason", "duration_s", "window_start_s", "window_end_s",
           "vs_reference_" + PEAK, "vs_chain_reference_" + PEAK, "cpu_time_per_simulated_s", "scenario_file",
           "engine_version")


class TableOnThePages(unittest.TestCase):
    """A report made from a synthetic runs.csv: a first-order line, a second-order one, a two-step one."""

    def setUp(self):
        self.folder = tempfile.mkdtemp(prefix="impactbench_front_order_")
        rows = [dict(job_id="s/reference/hertz", engine="reference", time_step_s=0, cpu_time_per_simulated_s=1.0)]
        for engine, order, steps_s in (("engine_a", 1, STEPS_S[:3]), ("engine_b", 2, STEPS_S[:3]),
                                       ("engine_c", 1, STEPS_S[:2])):
            rows += [dict(job_id=f"s/{engine}/hertz/dt={h:g}", engine=engine, time_step_s=h, options="contact=matched",
                          contact_path="matched", chain_links=8, cpu_time_per_simulated_s=1e-5 / h,
                          **{"vs_chain_reference_" + PEAK: 0.3 * (h / STEPS_S[0]) ** order,
                             "vs_reference_" + PEAK: 0.3 * (h / STEPS_S[0]) ** order + 0.01}) for h in steps_s]
        with open(os.path.join(self.folder, "runs.csv"), "w", newline="") as f:
            writer = csv.DictWriter(f, COLUMNS, restval="")
            writer.writeheader()
            for row in rows:
                writer.writerow(dict(scenario="s", law="hertz", verdict="ok", duration_s=0.3, window_start_s=0,
                                     window_end_s=0.3) | row)
        made = subprocess.run([sys.executable, MAKE_REPORT, self.folder], capture_output=True, text=True)
        self.assertEqual(made.returncode, 0, made.stderr)
        report = os.path.join(self.folder, "report")
        with open(os.path.join(report, "summary.json")) as f:
            self.summary = json.load(f)
        with open(os.path.join(report, "summary.md")) as f:
            self.markdown = f.read()
        with open(os.path.join(report, "index.html")) as f:
            self.page = f.read()

    def tearDown(self):
        shutil.rmtree(self.folder)

    def test_the_table_shows_the_numbers_in_summary_json(self):
        engines = self.summary["cases"][0]["fronts"]["engines"]
        lines = {engine: entry["observed_orders"][0] for engine, entry in engines.items()}
        self.assertAlmostEqual(lines["engine_a"]["observed_order"], 1.0, places=9)
        self.assertAlmostEqual(lines["engine_b"]["observed_order"], 2.0, places=9)
        self.assertIsNone(lines["engine_c"]["observed_order"])
        table = self.page[self.page.index("<div id='front-orders'>"):]
        table = table[:table.index("</div>")]
        for engine, line in lines.items():
            if line["status"] == "no order":  # counted under the table, not listed
                self.assertNotIn(line["configuration"], table)
                continue
            cells = [f"{s:.3g}" for s in line["time_steps_s"]] + [f"{100 * e:+.3g} %" for e in line["errors"]]
            order = "–" if line["observed_order"] is None else f"{line['observed_order']:.2f}"
            row = next(r for r in self.markdown.splitlines() if r.startswith("| s, hertz | " + line["configuration"]))
            html_row = next(r for r in table.split("<tr>") if line["configuration"] in r)
            for text in cells + [order, line["remark"]]:
                self.assertIn(text, row, engine)
                self.assertIn(text, html_row, engine)
        note = "1 line with fewer than 3 stable steps gives no order (summary.json)."
        self.assertIn(note, table)
        self.assertIn("\n" + note, self.markdown)
        self.assertIn("| 1.00 ± 0.00 |", self.markdown)
        self.assertIn("<td>2.00 ± 0.00</td>", table)
        self.assertTrue(math.isclose(lines["engine_b"]["errors"][-1], 0.3 / 16))


if __name__ == "__main__":
    unittest.main()
