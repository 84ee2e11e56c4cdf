"""Error against run time as fronts: every run of an engine in a case is a point (its CPU time per simulated
second, its score: the largest headline error in multiples of its tolerance, analysis.score); the Pareto
front is the stable points no other stable point beats on both; each engine's two operating points are
the most accurate point and the cheapest point within the verdict tolerances.

Where a case needed an ensemble (significance.case_need), scores are intervals: the most accurate point names
the points whose score cannot be told from its own (ensembles.compare), and a point is within the tolerances
only where every error's interval is (ensembles.verdict); a single run without a measured noise is within
where its score is at most 1."""

import math
from dataclasses import dataclass

from . import analysis, engines, ensembles, front_order, significance


@dataclass
class Point:
    """One run of an engine in a case, as a front draws it."""
    run: object  # data.Run
    cost_s_per_s: float  # CPU time per simulated second
    score: float  # vs the beam, tolerance multiples (inf: no error defined)
    score_vs_chain: float  # vs the engine's own chain
    metric: str = None  # the metric of the score vs the beam, and its signed error
    error: float = math.nan
    skip: tuple = ()  # metric labels the case's chain convergence flags: they rank no point

    @property
    def passes(self):
        """Whether the run passes its own verdict (ok: stable and every metric within its tolerance of the
        reference it is judged against, its own chain where it has one)."""
        return self.run["verdict"] == "ok"

    @property
    def engine(self):
        return self.run["engine"]

    @property
    def stable(self):
        return self.run.stable

    @property
    def scored(self):
        return self.stable and not math.isinf(self.score) and not math.isnan(self.cost_s_per_s)


def points(runs, tolerances, skip=()):
    """The engine runs of a case (no reference, no run that only repeats another), as Points; `skip`: the
    metric labels that rank nothing in this case."""
    found = []
    skip = tuple(skip)
    for run in runs:
        if run["engine"] in ("reference", "") or run["same_run_as"]:
            continue
        score, metric, error = analysis.score(run, tolerances, "beam", skip)
        found.append(Point(run, run.number("cpu_time_per_simulated_s"), score,
                           analysis.score(run, tolerances, "own chain", skip)[0], metric, error, skip))
    return found


def passing_first(candidates):
    """The points that pass their own verdict where there is one, else all: no answer names a run that fails
    its verdict while one that passes exists."""
    passing = [p for p in candidates if p.passes]
    return passing or list(candidates)


def dominates(a, b, against="beam"):
    """Whether point a is at most as costly and at most as far off as b, and better in one of the two."""
    sa, sb = (a.score, b.score) if against == "beam" else (a.score_vs_chain, b.score_vs_chain)
    return a.cost_s_per_s <= b.cost_s_per_s and sa <= sb and (a.cost_s_per_s < b.cost_s_per_s or sa < sb)


def pareto(candidates, against="beam"):
    """The stable, scored points no other such point dominates, cheapest first."""
    scored = [p for p in candidates if p.scored]
    front = [p for p in scored if not any(dominates(q, p, against) for q in scored if q is not p)]
    return sorted(front, key=lambda p: (p.cost_s_per_s, p.score))


def within_tolerances(point, tolerances, need, against="beam"):
    """Whether a point's errors are within the verdict tolerances: by their intervals where it has them,
    else by its score."""
    verdict = significance.verdict(point.run, tolerances, need, against, point.skip)
    if verdict is not None:
        return verdict == "within"
    score = point.score if against == "beam" else point.score_vs_chain
    return score <= 1


def most_accurate(candidates, tolerances, need):
    """(the point with the smallest score against its own chain among those that pass their verdict where one
    does, the cheaper first among equal scores; the other such points whose score the noise cannot tell from
    it), or (None, []) without a scored point. The error against the beam is the total a user sees, not what
    ranks the engine: the chain's share is the same for every engine on that chain."""
    scored = passing_first([p for p in candidates if p.scored])
    if not scored:
        return None, []
    best = min(scored, key=lambda p: (analysis.engine_score(p.score_vs_chain, p.score)[0], p.cost_s_per_s))
    against = analysis.engine_score(best.score_vs_chain, best.score)[1]
    best_interval = significance.score_interval(best.run, tolerances, need, against, best.skip)
    tied = []
    for p in scored:
        if p is best:
            continue
        other = significance.score_interval(p.run, tolerances, need, against, p.skip)
        if (other is not None and significance.like_with_like(best_interval, other)
                and ensembles.compare(best_interval[0], other[0]) == "tie"):
            tied.append(p)
    return best, sorted(tied, key=lambda p: p.cost_s_per_s)


def cheapest_within(candidates, tolerances, need, against="beam"):
    """The cheapest stable point within the tolerances against the beam or the own chain, or None; a point
    that fails its own verdict only where no point passes (its errors may offset the chain's by chance)."""
    scored = [p for p in candidates if p.scored]
    pool = [p for p in scored if p.passes] if any(p.passes for p in scored) else scored
    within = [p for p in pool if within_tolerances(p, tolerances, need, against)]
    return min(within, key=lambda p: (p.cost_s_per_s, p.score), default=None)


def point_entry(point, tolerances, need, budgets=None):
    """A point as summary.json names it: its runs.csv row's job id, configuration, step and cost, and the
    scores derived from that row (or its ensemble); the largest error vs the beam with its interval's
    half-width, and the score's half-width in tolerance multiples, where it has one; its error budget
    (budget.py) where `budgets` ({job id: budget}) holds one."""
    run = point.run
    scored = significance.score_interval(run, tolerances, need, "beam", point.skip) if point.metric is not None else None
    own = significance.score_interval(run, tolerances, need, "own chain", point.skip)
    step = run.number("time_step_s")
    return {"job_id": run["job_id"], "configuration": run.config, "engine": point.engine,
            "options": run["options"], "time_step_s": None if math.isnan(step) else step,
            "verdict": run["verdict"],
            "cpu_time_per_simulated_s": None if math.isnan(point.cost_s_per_s) else point.cost_s_per_s,
            "score_vs_beam": None if math.isinf(point.score) else point.score,
            "score_half_width": None if scored is None else scored[0].half_width,
            "largest_error_vs_beam": None if point.metric is None else error_entry(point.metric, point.error, scored),
            "score_vs_own_chain": None if math.isinf(point.score_vs_chain) else point.score_vs_chain,
            "score_vs_own_chain_half_width": None if own is None else own[0].half_width,
            "largest_error_vs_own_chain": None if own is None else error_entry(own[1], own[2].mean, own),
            "chain_links": None if math.isnan(run.number("chain_links")) or run.number("chain_links") <= 0
            else int(run.number("chain_links")),
            "passes_its_verdict": point.passes,
            "within_tolerances_vs_beam": point.scored and within_tolerances(point, tolerances, need, "beam"),
            "budget": (budgets or {}).get(run["job_id"])}


def error_entry(metric, error, scored):
    """{metric, error, half_width, interval_method, single_run_noise} as answer.run_entry writes a largest error:
    the half-width of an interval of more than one start, else the reference's single-start scatter as the noise."""
    interval = None if scored is None else scored[2]
    several = interval is not None and interval.n > 1
    return {"metric": metric, "error": error, "half_width": interval.half_width if several else None,
            "interval_method": None if interval is None else interval.method,
            "single_run_noise": interval.half_width if interval is not None and not several else None}


def operating_points(candidates, tolerances, need, budgets=None):
    """An engine's two operating points in a case, each its point entry or null with why."""
    accurate, tied = most_accurate(candidates, tolerances, need)
    result = {"most_accurate": None if accurate is None else
              point_entry(accurate, tolerances, need, budgets) | {"tied_with_job_ids": [p.run["job_id"] for p in tied]}}
    if accurate is None:
        result["most_accurate_why_none"] = "no stable run with a scored error"
    for against, key in (("beam", "cheapest_within_tolerance_vs_beam"),
                         ("own chain", "cheapest_within_tolerance_vs_own_chain")):
        point = cheapest_within(candidates, tolerances, need, against)
        result[key] = None if point is None else point_entry(point, tolerances, need, budgets)
        if point is None:
            result[key + "_why_none"] = (f"no stable run with every error within its verdict tolerance of the "
                                         f"{against}" + (" (with its interval)" if need and need.get("needed") else ""))
    return result


def is_recommended(run, configuration):
    """Whether a run is the recommended configuration {options, time_step_s} of its engine for its law: the
    same options (the contact path among them) at the same step."""
    options = analysis.options_of(run["options"])
    step = run.number("time_step_s")
    return options == configuration.get("options") and math.isclose(step, configuration.get("time_step_s", math.nan),
                                                                     rel_tol=1e-9)


def recommended_entry(own, law, tolerances, need, budgets=None):
    """The engine's recommended configuration in this case: its point and the settings with their sources
    (engines.recommended), or null with why."""
    recommended = engines.recommended(own[0].engine) if own else {}
    configuration = recommended.get("laws", {}).get(law)
    if configuration is None:
        return {"recommended": None, "recommended_why_none": "the engine's descriptor names no recommended configuration"
                                                              f" for the {law} law"}
    point = next((p for p in own if is_recommended(p.run, configuration)), None)
    if point is None:
        return {"recommended": None, "recommended_why_none": "not run in this suite"}
    return {"recommended": point_entry(point, tolerances, need, budgets) | {"settings": recommended.get("settings", [])}}


def case_fronts(runs, tolerances, need, law=None, skip=(), budgets=None):
    """A case's fronts as summary.json holds them: the Pareto front over every engine (job ids, cheapest
    first), and per engine its points, its own front, its operating points and its recommended
    configuration's point (`law`: the case's), and the observed order of convergence of each of its
    configurations' lines (front_order.py); `skip`: the metrics that rank nothing in the case; `budgets`:
    {job id: error budget} for every point."""
    every = points(runs, tolerances, skip)
    result = {"pareto_front_job_ids": [p.run["job_id"] for p in pareto(every)], "engines": {}}
    for engine in dict.fromkeys(p.engine for p in every):
        own = [p for p in every if p.engine == engine]
        result["engines"][engine] = {
            "points": [point_entry(p, tolerances, need, budgets)
                       for p in sorted(own, key=lambda p: (p.run.config, -p.run.number("time_step_s")))],
            "front_job_ids": [p.run["job_id"] for p in pareto(own)],
            **operating_points(own, tolerances, need, budgets), **recommended_entry(own, law, tolerances, need, budgets),
            "observed_orders": front_order.observed_orders(own, need)}
    return result


LEAD_CASE = ("resonance", "hertz")  # the case the first screen and the engines' lines give operating points for


def lead_case(cases):
    """The case whose operating points the first screen gives (summary.json's cases): the resonance with
    Hertz contact where it ran, else the first case with engine runs; None without one."""
    found = with_runs(cases)
    return next((c for c in found if (c["scenario"], c["law"]) == LEAD_CASE), found[0] if found else None)


def with_runs(cases):
    """The cases (summary.json's) whose fronts hold an engine run."""
    return [c for c in cases if c.get("fronts") and c["fronts"]["engines"]]


def settings_text(point):
    """'matched' or 'matched; length_unit=cm': the options a user sets for a point, the contact path by its
    name; 'defaults' without any."""
    options = [o.split("=", 1)[1] if o.startswith("contact=") else o for o in point["options"].split(";") if o]
    return "; ".join(options) or "defaults"
