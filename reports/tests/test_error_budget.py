"""The error budget and the answers that follow it (issue 46), on runs whose errors are chosen:

- an engine's contact handling is ranked by its error against its own chain, not against the beam (whose error
  is mostly the chain's, the same for every engine on it, and rewards an engine error that offsets it);
- no answer names a run that fails its own verdict while one that passes exists;
- a budget's parts (the chain's share, the engine's) add up to the error against the beam;
- the chain's convergence settles where its error stays within its share of the tolerance, and flags a metric
  whose chain error swings in sign between two K (ill-conditioned in its window).

    /usr/bin/python3 reports/tests/test_error_budget.py
"""

import os
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from impactbench_report import analysis, answer_sentence, budget, chain_convergence, data, fronts, metric_catalog, tables  # noqa: E402

TOLERANCES = metric_catalog.DEFAULT_TOLERANCES
PEAK = "frame1_sensor_peak_relative_error"


def run(job_id, cost_s_per_s, beam_error, own_chain_error, verdict="ok", engine="engine_a", step_s=5e-5):
    """An engine run whose only scored error is frame 1's sensor peak, against the beam and its own chain."""
    return data.Run({"job_id": job_id, "engine": engine, "options": "contact=matched", "same_run_as": "",
                     "verdict": verdict, "time_step_s": step_s, "cpu_time_per_simulated_s": cost_s_per_s,
                     "chain_links": 8.0, "vs_reference_" + PEAK: beam_error, "vs_chain_reference_" + PEAK: own_chain_error})


class RankedByTheEnginesOwnError(unittest.TestCase):
    """The chain alone is -9 % from the beam. `offsets` is +8 % from its chain, so -1.7 % from the beam; `faithful`
    is -0.5 % from its chain, so -9.5 % from the beam. The beam would name `offsets`; the engine's own error names
    `faithful`."""

    def setUp(self):
        self.runs = [run("offsets", 0.2, -0.0172, 0.08), run("faithful", 0.2, -0.0946, -0.005)]

    def test_the_most_accurate_point_is_the_smallest_error_against_its_own_chain(self):
        chosen, _ = fronts.most_accurate(fronts.points(self.runs, TOLERANCES), TOLERANCES, None)
        self.assertEqual(chosen.run["job_id"], "faithful")

    def test_the_best_run_of_a_configuration_too(self):
        self.assertEqual(analysis.best_run(self.runs, TOLERANCES)["job_id"], "faithful")

    def test_a_metric_the_case_does_not_rank_on_is_left_out(self):
        skip = ("frame 1 sensor peak",)
        self.assertEqual(analysis.score(self.runs[0], TOLERANCES, "own chain", skip)[1], None)


class NoFailingRunOverAPassingOne(unittest.TestCase):
    """`cancels` is cheap and within the beam's tolerance only because its -15 % from its chain offsets the chain's
    +13 %: it fails its own verdict. `passes` costs more, and is within both."""

    def setUp(self):
        self.runs = [run("cancels", 0.1, -0.02, -0.15, verdict="inaccurate"), run("passes", 0.3, 0.06, -0.03)]

    def test_the_cheapest_within_the_beams_tolerances_passes_its_verdict(self):
        points = fronts.points(self.runs, TOLERANCES)
        self.assertEqual(fronts.cheapest_within(points, TOLERANCES, None, "beam").run["job_id"], "passes")

    def test_the_most_accurate_passes_its_verdict(self):
        # `fails` is closer to its chain in the one metric here, and inaccurate in another (its verdict says so)
        runs = [run("fails", 0.1, -0.02, -0.01, verdict="inaccurate"), self.runs[1]]
        chosen, _ = fronts.most_accurate(fronts.points(runs, TOLERANCES), TOLERANCES, None)
        self.assertEqual(chosen.run["job_id"], "passes")
        self.assertEqual(analysis.best_run(runs, TOLERANCES)["job_id"], "passes")

    def test_a_failing_run_is_named_only_where_none_passes(self):
        failing = [self.runs[0], run("worse", 0.2, -0.03, -0.2, verdict="inaccurate")]
        points = fronts.points(failing, TOLERANCES)
        self.assertEqual(fronts.cheapest_within(points, TOLERANCES, None, "beam").run["job_id"], "cancels")

    def test_the_answer_sentence_names_the_passing_run(self):
        case = fronts.case_fronts(self.runs, TOLERANCES, None, "hertz")
        document_case = {"scenario": "resonance", "law": "hertz", "fronts": case, "metrics_not_ranked": []}
        answer = answer_sentence.case_answer(document_case)
        self.assertEqual(answer["job_id"], "passes")
        self.assertTrue(answer["within_every_tolerance_vs_beam"])
        self.assertIn("within every tolerance of the beam", answer["sentence"])


class TheAnswerSentence(unittest.TestCase):
    def case(self, runs):
        return {"scenario": "resonance", "law": "hertz", "fronts": fronts.case_fronts(runs, TOLERANCES, None, "hertz"),
                "metrics_not_ranked": []}

    def test_it_names_every_run_tied_with_it_in_cost(self):
        runs = [run("cheapest", 0.10, 0.02, 0.01), run("close", 0.12, 0.01, 0.01, engine="engine_b"),
                run("costly", 0.5, 0.0, 0.0, engine="engine_c")]
        answer = answer_sentence.case_answer(self.case(runs))
        self.assertEqual((answer["job_id"], answer["tied_with_job_ids"]), ("cheapest", ["close"]))
        self.assertIn("tied in cost with", answer["sentence"])

    def test_without_a_run_within_it_gives_the_closest_with_its_budget(self):
        runs = [run("far", 0.1, 0.25, 0.01), run("farther", 0.2, 0.4, 0.2)]
        case = self.case(runs)
        for entry in case["fronts"]["engines"].values():
            for point in entry["points"]:
                point["budget"] = {"chain_links": 8, "metrics": {"frame 1 sensor peak": {
                    "kind": "relative", "total": point["largest_error_vs_beam"]["error"], "chain": 0.24, "engine": 0.01}}}
        answer = answer_sentence.case_answer(case)
        self.assertFalse(answer["within_every_tolerance_vs_beam"])
        self.assertEqual(answer["job_id"], "far")
        self.assertIn("no run is within every tolerance of the beam", answer["sentence"])
        self.assertIn("the 8-link chain's +24 %", answer["sentence"])


class TheBudgetAddsUp(unittest.TestCase):
    def test_relative_errors_add_in_the_beams_units(self):
        beam, chain_value, engine_value = 10.0, 9.1, 9.4
        chain = data.Run({"job_id": "chain", "engine": "reference", "options": "links=8;modes=chain",
                          "vs_reference_" + PEAK: chain_value / beam - 1})
        engine = run("e", 0.1, engine_value / beam - 1, engine_value / chain_value - 1)
        entry = budget.metric_budget(engine, chain, PEAK, "relative", {})
        self.assertAlmostEqual(entry["chain"], -0.09, places=12)
        self.assertAlmostEqual(entry["engine"], (engine_value - chain_value) / beam, places=12)
        self.assertAlmostEqual(entry["chain"] + entry["engine"], entry["total"], places=12)
        self.assertLess(abs(entry["residual"]), budget.ADDITIVE_TOLERANCE)
        self.assertNotIn("why_not_additive", entry)

    def test_a_missing_chain_says_why_the_parts_do_not_add(self):
        entry = budget.metric_budget(run("e", 0.1, 0.05, 0.02), None, PEAK, "relative", {})
        self.assertIsNone(entry["residual"])
        self.assertEqual(entry["why_not_additive"], "no reference on the run's own chain")


def chains(errors_by_links, half_width=0.001):
    """{K: a reference run on the K-link chain whose frame 1 log decrement is off the beam's by the error}."""
    column = "frame1_log_decrement_relative_error"
    return {k: data.Run({"job_id": f"chain{k}", "engine": "reference", "options": f"links={k};modes=chain",
                         "vs_reference_" + column: e}) for k, e in errors_by_links.items()}


class TheChainsConvergence(unittest.TestCase):
    COLUMN = "frame1_log_decrement_relative_error"

    def test_a_monotone_fall_settles_where_it_stays_within_its_share(self):
        result = chain_convergence.metric_convergence(chains({4: 0.07, 8: 0.03, 16: 0.02, 32: 0.01, 64: 0.005}),
                                                      self.COLUMN, "relative", 0.10)
        self.assertEqual((result["settled_links"], result["flags"]), (16, []))

    def test_a_swing_in_sign_beyond_the_share_is_ill_conditioned(self):
        # the free vibration's frame 1 log decrement over 3 s: -22 %, +25 %, -7.3 %, -1.9 %, -0.5 %
        result = chain_convergence.metric_convergence(
            chains({4: -0.22, 8: 0.25, 16: -0.073, 32: -0.019, 64: -0.005}), self.COLUMN, "relative", 0.10)
        self.assertEqual(result["settled_links"], 32)
        self.assertEqual(len(result["flags"]), 1)
        self.assertIn("ill-conditioned", result["flags"][0])

    def test_a_chain_still_beyond_at_the_finest_k_does_not_settle(self):
        result = chain_convergence.metric_convergence(chains({4: 0.2, 8: 0.15, 16: 0.1}), self.COLUMN, "relative", 0.10)
        self.assertIsNone(result["settled_links"])
        self.assertIn("does not settle within 16 links", result["flags"][0])

    def test_at_the_edge_of_its_share_it_is_within(self):
        share = chain_convergence.CHAIN_SHARE_OF_TOLERANCE * 0.10
        result = chain_convergence.metric_convergence(chains({8: share, 16: share}), self.COLUMN, "relative", 0.10)
        self.assertEqual(result["settled_links"], 8)
        beyond = chain_convergence.metric_convergence(chains({8: share * 1.001, 16: share}), self.COLUMN, "relative", 0.10)
        self.assertEqual(beyond["settled_links"], 16)


class ASignedError(unittest.TestCase):
    """The budget's parts as the sentences write them: a sign for a direction, none for an exact zero."""

    def test_a_direction_is_signed_and_a_zero_is_not(self):
        self.assertEqual(tables.signed_text(0.025, "relative"), "+2.5 %")
        self.assertEqual(tables.signed_text(-0.14, "difference"), "-0.14")
        self.assertEqual(tables.signed_text(0.0, "difference"), "0")
        self.assertEqual(tables.signed_text(-0.0, "relative"), "0 %")
        self.assertEqual(tables.signed_text(float("nan"), "relative"), "n/a")


if __name__ == "__main__":
    unittest.main()
