"""Fronts and operating points (reports/impactbench_report/fronts.py) on runs whose errors and costs are
chosen: a point beaten on both cost and error is off the front, an unstable point is never on it, the most
accurate point names the points the noise cannot tell from it, and a point whose interval reaches past
a tolerance is not called within it.

    /usr/bin/python3 reports/tests/test_fronts.py
"""

import json
import os
import shutil
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from impactbench_report import data, engines, fronts, metric_catalog  # noqa: E402

TOLERANCES = metric_catalog.DEFAULT_TOLERANCES
PEAK = "frame1_sensor_peak_relative_error"


def run(job_id, step_s, cost_s_per_s, peak_error, verdict="ok", engine="engine_a", options="contact=matched",
        chain_error=None):
    """A run whose only scored error is frame 1's sensor peak (against the beam and its own chain)."""
    return data.Run({"job_id": job_id, "engine": engine, "options": options, "same_run_as": "", "verdict": verdict,
                     "time_step_s": step_s, "cpu_time_per_simulated_s": cost_s_per_s,
                     "vs_reference_" + PEAK: peak_error,
                     "vs_chain_reference_" + PEAK: peak_error if chain_error is None else chain_error})


def ids(points):
    return [p.run["job_id"] for p in points]


class Front(unittest.TestCase):
    def test_a_point_beaten_on_cost_and_error_is_off_the_front(self):
        runs = [run("coarse", 1e-4, 0.1, 0.30), run("fine", 5e-5, 0.2, 0.05),
                run("costly_and_worse", 7e-5, 0.15, 0.40), run("finest", 2.5e-5, 0.4, 0.05)]
        front = fronts.pareto(fronts.points(runs, TOLERANCES))
        # "finest" ties "fine" on error at twice the cost: dominated too
        self.assertEqual(ids(front), ["coarse", "fine"])

    def test_an_unstable_point_is_never_on_the_front_however_cheap(self):
        runs = [run("diverged", 2e-4, 0.01, 0.0, verdict="unstable"), run("ok", 1e-4, 0.1, 0.2)]
        self.assertEqual(ids(fronts.pareto(fronts.points(runs, TOLERANCES))), ["ok"])

    def test_the_references_and_repeated_runs_are_not_points(self):
        runs = [run("beam", 1e-4, 0.01, 0.0, engine="reference"), run("a", 1e-4, 0.1, 0.2)]
        repeated = run("a_again", 1e-4, 0.1, 0.2)
        repeated.values["same_run_as"] = "a"
        self.assertEqual(ids(fronts.points(runs + [repeated], TOLERANCES)), ["a"])

    def test_the_front_against_the_own_chain_is_its_own(self):
        # against the beam "fine" beats "coarse" only at a cost; against its chain it is also the cheaper
        # in error terms: both fronts are drawn from the same points, each with its own scores
        runs = [run("coarse", 1e-4, 0.1, 0.30, chain_error=0.02), run("fine", 5e-5, 0.2, 0.05, chain_error=0.01)]
        every = fronts.points(runs, TOLERANCES)
        self.assertEqual(ids(fronts.pareto(every)), ["coarse", "fine"])
        self.assertEqual(ids(fronts.pareto(every, "own chain")), ["coarse", "fine"])
        runs[1].values["vs_chain_reference_" + PEAK] = 0.03
        self.assertEqual(ids(fronts.pareto(fronts.points(runs, TOLERANCES), "own chain")), ["coarse"])


class OperatingPoints(unittest.TestCase):
    def test_single_runs_most_accurate_and_cheapest_within(self):
        runs = [run("coarse", 1e-4, 0.1, 0.12), run("middle", 7e-5, 0.15, 0.08), run("fine", 5e-5, 0.2, 0.01)]
        chosen = fronts.operating_points(fronts.points(runs, TOLERANCES), TOLERANCES, need=None)
        self.assertEqual(chosen["most_accurate"]["job_id"], "fine")
        self.assertEqual(chosen["cheapest_within_tolerance_vs_beam"]["job_id"], "middle")
        self.assertAlmostEqual(chosen["cheapest_within_tolerance_vs_beam"]["score_vs_beam"], 0.8)

    def test_no_point_within_says_so(self):
        runs = [run("coarse", 1e-4, 0.1, 0.5), run("fine", 5e-5, 0.2, 0.2)]
        chosen = fronts.operating_points(fronts.points(runs, TOLERANCES), TOLERANCES, need=None)
        self.assertIsNone(chosen["cheapest_within_tolerance_vs_beam"])
        self.assertIn("no stable run with every error within", chosen["cheapest_within_tolerance_vs_beam_why_none"])
        self.assertEqual(chosen["most_accurate"]["job_id"], "fine")

    def test_with_noise_the_most_accurate_names_the_points_it_cannot_be_told_from(self):
        # one reference start scatters the error by +-5 %: 0.21 and 0.20 cannot be told apart, 0.40 can
        need = {"needed": True, "single_run_noise": {PEAK: [0.05, 11]}}
        runs = [run("cheap", 1e-4, 0.1, 0.21), run("costly", 5e-5, 0.2, 0.20), run("far", 2e-4, 0.05, 0.40)]
        chosen = fronts.operating_points(fronts.points(runs, TOLERANCES), TOLERANCES, need)
        self.assertEqual(chosen["most_accurate"]["job_id"], "costly")
        self.assertEqual(chosen["most_accurate"]["tied_with_job_ids"], ["cheap"])
        # without the noise nothing is tied
        plain = fronts.operating_points(fronts.points(runs, TOLERANCES), TOLERANCES, need=None)
        self.assertEqual((plain["most_accurate"]["job_id"], plain["most_accurate"]["tied_with_job_ids"]), ("costly", []))

    def test_with_noise_a_point_whose_interval_reaches_past_the_tolerance_is_not_within(self):
        need = {"needed": True, "single_run_noise": {PEAK: [0.05, 11]}}
        runs = [run("near_the_line", 1e-4, 0.1, 0.08), run("clear", 5e-5, 0.2, 0.03)]
        chosen = fronts.operating_points(fronts.points(runs, TOLERANCES), TOLERANCES, need)
        self.assertEqual(chosen["cheapest_within_tolerance_vs_beam"]["job_id"], "clear")
        plain = fronts.operating_points(fronts.points(runs, TOLERANCES), TOLERANCES, need=None)
        self.assertEqual(plain["cheapest_within_tolerance_vs_beam"]["job_id"], "near_the_line")

    def test_a_points_error_bar_is_its_errors_half_width_in_tolerance_multiples(self):
        need = {"needed": True, "single_run_noise": {PEAK: [0.05, 11]}}
        entry = fronts.point_entry(fronts.points([run("a", 1e-4, 0.1, 0.08)], TOLERANCES)[0], TOLERANCES, need)
        # a single run: its noise is the reference's single-start scatter, written as such (as a run object's)
        self.assertIsNone(entry["largest_error_vs_beam"]["half_width"])
        half_width = entry["largest_error_vs_beam"]["single_run_noise"]
        self.assertGreater(half_width, 0)
        self.assertAlmostEqual(entry["score_half_width"], half_width / TOLERANCES["sensor_peak_relative_error"])
        plain = fronts.point_entry(fronts.points([run("a", 1e-4, 0.1, 0.08)], TOLERANCES)[0], TOLERANCES, None)
        self.assertIsNone(plain["score_half_width"])

    def test_case_fronts_name_every_engine_with_its_own_front(self):
        runs = [run("a1", 1e-4, 0.1, 0.3), run("a2", 5e-5, 0.2, 0.05),
                run("b1", 1e-4, 0.05, 0.5, engine="engine_b"), run("b2", 5e-5, 0.3, 0.02, engine="engine_b")]
        case = fronts.case_fronts(runs, TOLERANCES, need=None)
        self.assertEqual(case["pareto_front_job_ids"], ["b1", "a1", "a2", "b2"])
        self.assertEqual(sorted(case["engines"]), ["engine_a", "engine_b"])
        self.assertEqual(case["engines"]["engine_b"]["front_job_ids"], ["b1", "b2"])
        self.assertEqual(case["engines"]["engine_b"]["cheapest_within_tolerance_vs_beam"]["job_id"], "b2")


class Recommended(unittest.TestCase):
    """The recommended configuration's point: the run with its options at its step, from engines.json."""

    def setUp(self):
        self.folder = tempfile.mkdtemp(prefix="impactbench_fronts_test_")
        settings = [{"setting": "contact=matched", "value_is": "v", "why": "w", "source": "https://example.org", "words": ""}]
        document = {"simulators": [{"name": "engine_a", "recommended": {
            "laws": {"hertz": {"options": {"contact": "matched", "knob": "2"}, "time_step_s": 5e-5}},
            "settings": settings}}]}
        with open(os.path.join(self.folder, "engines.json"), "w") as f:
            json.dump(document, f)
        engines.use(self.folder)

    def tearDown(self):
        engines.use(tempfile.gettempdir())  # no engines.json there: the next test's names are bare
        shutil.rmtree(self.folder)

    def test_the_run_with_the_options_at_the_step_is_the_recommended_one(self):
        runs = [run("plain", 5e-5, 0.2, 0.05), run("coarse", 1e-4, 0.1, 0.2, options="contact=matched;knob=2"),
                run("it", 5e-5, 0.2, 0.08, options="knob=2;contact=matched")]
        case = fronts.case_fronts(runs, TOLERANCES, need=None, law="hertz")
        recommended = case["engines"]["engine_a"]["recommended"]
        self.assertEqual(recommended["job_id"], "it")
        self.assertEqual(recommended["settings"][0]["source"], "https://example.org")

    def test_a_law_without_one_or_a_suite_without_its_run_says_why(self):
        runs = [run("plain", 5e-5, 0.2, 0.05)]
        newton = fronts.case_fronts(runs, TOLERANCES, need=None, law="newton")["engines"]["engine_a"]
        self.assertIsNone(newton["recommended"])
        self.assertIn("names no recommended configuration", newton["recommended_why_none"])
        hertz = fronts.case_fronts(runs, TOLERANCES, need=None, law="hertz")["engines"]["engine_a"]
        self.assertEqual(hertz["recommended_why_none"], "not run in this suite")


if __name__ == "__main__":
    unittest.main()
