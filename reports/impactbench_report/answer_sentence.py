"""One sentence per case and law that a person can act on, from summary.json's case (its fronts' points, their
error budgets and the chain's convergence): which run to use, why, at what cost, and with which runs it is tied.

The run it names is the cheapest that passes its own verdict and is within every verdict tolerance of the beam
(over the metrics the case ranks on); a run that fails its verdict is named only where none passes. Runs tied
with it are the others that qualify at a cost this machine's drift cannot tell from its cost. Where no run
qualifies, the sentence names the closest run that passes its verdict and says, with its budget, how much of its
largest error is the chain's and how many links would settle it."""

from . import analysis, data, engines
from .tables import signed_text, step_text

# Two CPU costs closer than this (relative) are not told apart: this machine's speed drifts 15 to 30 % between
# identical runs (docs/budgets.md), the same floor `impactbench compare` judges cost against.
COST_DRIFT = 0.30


def every_point(case):
    return [p for entry in case["fronts"]["engines"].values() for p in entry["points"]]


def stable(point):
    return point["verdict"] in data.STABLE_VERDICTS and point["cpu_time_per_simulated_s"] is not None


def qualifying(case):
    """The points that are within every tolerance of the beam, those passing their own verdict where one does."""
    within = [p for p in every_point(case) if stable(p) and p.get("within_tolerances_vs_beam")]
    passing = [p for p in within if p.get("passes_its_verdict")]
    if passing:
        return passing
    return within if not any(p.get("passes_its_verdict") for p in every_point(case)) else []


def run_words(point):
    """'<engine>, matched contact, 7e-5 s, 8 links', or with the run's other options: '<engine>, matched contact,
    accuracy=1e-3, 1e-4 s, 8 links'."""
    options = analysis.options_of(point["options"])
    words = [engines.display_name(point["engine"]), f"{analysis.contact_path(point)} contact"]
    words += [f"{name}={value}" for name, value in options.items() if name not in ("contact", "links")]
    if point.get("time_step_s"):
        words.append(f"{step_text(point['time_step_s'])} s")
    if point.get("chain_links"):
        words.append(f"{point['chain_links']} links")
    return ", ".join(words)


def cost_text(point):
    return f"{point['cpu_time_per_simulated_s']:.2g} s of CPU per simulated second"


def budget_words(point):
    """'frame 1 log decrement +25 % from the beam: the 8-link chain's +25 %, the engine's -0.2 %' for a point's
    largest error against the beam."""
    largest = point.get("largest_error_vs_beam")
    budget = point.get("budget") or {}
    if not largest:
        return "no error defined"
    entry = budget.get("metrics", {}).get(largest["metric"])
    if not entry:
        return f"{largest['metric']} {largest['error']:+.3g} from the beam"
    kind = entry["kind"]
    text = f"{largest['metric']} {signed_text(entry['total'], kind)} from the beam"
    if entry.get("chain") is not None:
        text += (f": the {budget.get('chain_links')}-link chain's {signed_text(entry['chain'], kind)}, "
                 f"the engine's {signed_text(entry['engine'], kind)}")
    return text


def settle_words(case, metric):
    """' (the chain's error in it is within a quarter of its tolerance from 32 links)' or ''."""
    convergence = (case.get("chain_convergence") or {}).get("metrics", {}).get(metric)
    if not convergence:
        return ""
    if convergence["settled_links"] is None:
        return f"; no chain tried (up to {convergence['errors_vs_beam'][-1]['links']} links) settles it"
    return (f"; the chain's error in it is within {case['chain_convergence']['share_of_tolerance']:g} of its "
            f"tolerance from {convergence['settled_links']} links")


def not_ranked_words(case):
    flagged = case.get("metrics_not_ranked") or []
    if not flagged:
        return ""
    return " Not judged here: " + "; ".join(f"{f['metric']} ({f['why']})" for f in flagged) + "."


def case_answer(case):
    """{sentence, job_id, tied_with_job_ids, within_every_tolerance_vs_beam} for a case of summary.json; the
    sentence names no run where the case has no engine run."""
    title = f"{case['scenario']}, {case['law']}"
    if not case.get("fronts") or not every_point(case):
        return {"sentence": f"{title}: no engine ran.", "job_id": None, "tied_with_job_ids": [],
                "within_every_tolerance_vs_beam": None}
    candidates = qualifying(case)
    if candidates:
        chosen = min(candidates, key=lambda p: (p["cpu_time_per_simulated_s"], p["score_vs_beam"]))
        limit = chosen["cpu_time_per_simulated_s"] * (1 + COST_DRIFT)
        tied = sorted((p for p in candidates if p is not chosen and p["cpu_time_per_simulated_s"] <= limit),
                      key=lambda p: p["cpu_time_per_simulated_s"])
        verdict = "" if chosen.get("passes_its_verdict") else " (no run passes its own verdict)"
        sentence = (f"{title}: use {run_words(chosen)}: within every tolerance of the beam{verdict} at "
                    f"{cost_text(chosen)}")
        sentence += ("; tied in cost with " + "; ".join(f"{run_words(p)} ({p['cpu_time_per_simulated_s']:.2g} s/s)"
                                                      for p in tied) if tied else "; no other run within 30 % of its cost")
        return {"sentence": sentence + "." + not_ranked_words(case), "job_id": chosen["job_id"],
                "tied_with_job_ids": [p["job_id"] for p in tied], "within_every_tolerance_vs_beam": True}
    scored = [p for p in every_point(case) if stable(p) and p["score_vs_beam"] is not None]
    pool = [p for p in scored if p.get("passes_its_verdict")] or scored
    if not pool:
        return {"sentence": f"{title}: no engine run is stable.", "job_id": None, "tied_with_job_ids": [],
                "within_every_tolerance_vs_beam": False}
    closest = min(pool, key=lambda p: (p["score_vs_beam"], p["cpu_time_per_simulated_s"]))
    metric = (closest.get("largest_error_vs_beam") or {}).get("metric")
    sentence = (f"{title}: no run is within every tolerance of the beam. Closest: {run_words(closest)} at "
                f"{cost_text(closest)}, {budget_words(closest)}{settle_words(case, metric)}.")
    return {"sentence": sentence + not_ranked_words(case), "job_id": closest["job_id"], "tied_with_job_ids": [],
            "within_every_tolerance_vs_beam": False}
