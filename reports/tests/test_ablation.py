"""The ablation (reports/impactbench_report/ablation.py) on fronts whose points are chosen: a step is paired
with the next smaller step of its own configuration only, an option is read from its default to its value,
two points that differ in two settings are no pair, and each change is the median over its cases.

    /usr/bin/python3 reports/tests/test_ablation.py
"""

import os
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from impactbench_report import ablation  # noqa: E402


def point(job_id, step_s, cost, score, options="contact=matched", verdict="ok", chain_score=None):
    return {"job_id": job_id, "options": options, "time_step_s": step_s, "verdict": verdict,
            "cpu_time_per_simulated_s": cost, "score_vs_beam": score,
            "score_vs_own_chain": score if chain_score is None else chain_score}


def case(name, points, engine="engine_a"):
    return {"scenario": name, "law": "hertz", "fronts": {"engines": {engine: {"points": points}}}}


def row(rows, setting, to):
    return next(r for r in rows if r["setting"] == setting and r["to"] == to)


class Ablation(unittest.TestCase):
    def test_a_step_pairs_with_the_next_smaller_step_only(self):
        points = [point("a4", 4e-4, 0.05, 3.0), point("a2", 2e-4, 0.1, 1.0), point("a1", 1e-4, 0.2, 0.5)]
        rows = ablation.engine_ablation([case("c", points)])
        halving = row(rows, ablation.SETTING_STEP, "÷2")
        self.assertEqual(halving["job_id_pairs"], [["a4", "a2"], ["a2", "a1"]])
        self.assertAlmostEqual(halving["score_vs_beam_change_median"], (-2.0 - 0.5) / 2)
        self.assertAlmostEqual(halving["cost_ratio_median"], 2.0)
        self.assertEqual(len(rows), 1)  # no 4e-4 -> 1e-4 pair: 2e-4 stands between

    def test_points_in_any_order_make_each_pair_once(self):
        # smallest step first: a pair read backwards must not change which run the next pairs start from
        points = [point("a1", 1e-4, 0.2, 0.5), point("a2", 2e-4, 0.1, 1.0), point("a4", 4e-4, 0.05, 3.0),
                  point("b1", 1e-4, 0.4, 0.4, "contact=matched;integrator=rk4")]
        rows = ablation.engine_ablation([case("c", points)])
        self.assertEqual(sorted(row(rows, ablation.SETTING_STEP, "÷2")["job_id_pairs"]), [["a2", "a1"], ["a4", "a2"]])
        self.assertEqual(row(rows, "integrator", "rk4")["job_id_pairs"], [["a1", "b1"]])

    def test_an_option_reads_from_its_default_and_two_changes_are_no_pair(self):
        points = [point("m", 1e-4, 0.1, 0.8), point("cm", 1e-4, 0.1, 0.2, "contact=matched;length_unit=cm"),
                  point("cm_fine", 5e-5, 0.2, 0.1, "contact=matched;length_unit=cm"),
                  point("native_fine", 5e-5, 0.15, 9.0, "contact=native")]
        rows = ablation.engine_ablation([case("c", points)])
        unit = row(rows, "length_unit", "cm")
        self.assertEqual((unit["from"], unit["job_id_pairs"]), ("default", [["m", "cm"]]))
        self.assertAlmostEqual(unit["score_vs_beam_change_median"], -0.6)
        # native_fine differs from m in contact and step, from cm_fine in contact and length_unit: no pair
        self.assertFalse(any(r["setting"] == "contact" for r in rows))

    def test_unstable_points_make_no_pair_and_changes_are_medians_over_cases(self):
        rows = ablation.engine_ablation([
            case("c1", [point("a", 1e-4, 0.1, 1.0), point("b", 5e-5, 0.2, 0.4)]),
            case("c2", [point("a", 1e-4, 0.1, 1.0), point("b", 5e-5, 0.2, 0.8)]),
            case("c3", [point("a", 1e-4, 0.1, 1.0), point("b", 5e-5, 0.3, 0.1)]),
            case("c4", [point("a", 1e-4, 0.1, 1.0, verdict="unstable"), point("b", 5e-5, 0.2, 0.1)])])
        halving = row(rows, ablation.SETTING_STEP, "÷2")
        self.assertEqual((halving["pairs"], halving["cases"]), (3, ["c1, hertz", "c2, hertz", "c3, hertz"]))
        self.assertAlmostEqual(halving["score_vs_beam_change_median"], -0.6)
        for got, expected in zip(halving["score_vs_beam_change_range"], [-0.9, -0.2]):
            self.assertAlmostEqual(got, expected)
        self.assertAlmostEqual(halving["cost_ratio_median"], 2.0)
        # c4's pair moved no score, but the smaller step made its run stable: counted, and named
        self.assertEqual((halving["pairs_made_stable"], halving["pairs_made_unstable"]), (1, 0))
        self.assertEqual(halving["stability_job_id_pairs"], [["a", "b"]])

    def test_a_setting_that_makes_every_run_unstable_has_its_row(self):
        points = [point("plain_coarse", 1e-4, 0.1, 1.0), point("plain_fine", 5e-5, 0.2, 0.5),
                  point("rk4_coarse", 1e-4, 0.3, None, "contact=matched;integrator=rk4", verdict="unstable"),
                  point("rk4_fine", 5e-5, 0.6, None, "contact=matched;integrator=rk4", verdict="unstable")]
        rows = ablation.engine_ablation([case("c", points)])
        rk4 = row(rows, "integrator", "rk4")
        self.assertEqual((rk4["pairs"], rk4["pairs_made_unstable"], rk4["pairs_made_stable"]), (0, 2, 0))
        self.assertIsNone(rk4["score_vs_beam_change_median"])
        self.assertEqual(rk4["stability_job_id_pairs"], [["plain_coarse", "rk4_coarse"], ["plain_fine", "rk4_fine"]])
        # two unstable runs a step apart are no pair: only the plain steps' halving is
        self.assertEqual(row(rows, ablation.SETTING_STEP, "÷2")["job_id_pairs"], [["plain_coarse", "plain_fine"]])
        self.assertIn("2 made unstable", ablation.table_rows(rows)[[r["setting"] for r in rows].index("integrator")][-1])


if __name__ == "__main__":
    unittest.main()
