"""The chain's own error against the beam at each resolution K (rigid links per frame): the model's share of every
engine's error, measured by the reference alone on K-link chains (a suite's --reference-chains, a study's
reference_chains), scored against the beam reference of the same starts.

Per case and scored metric: the chain's error at each K with its 95 % interval, and the smallest K from which every
finer chain tried stays within CHAIN_SHARE_OF_TOLERANCE of the metric's verdict tolerance (by its mean: in a chaotic
case the interval of a few starts is as wide as that share, and says so in `noise_exceeds_share`). A metric is flagged,
and ranks no engine in that case (budget.sound_metrics), when
- it does not settle: no K tried gets it there, and the finest chain's interval lies beyond (where only the noise
  keeps it from settling, `settled_links` is null and the metric still ranks); or
- it is ill-conditioned in its window: its chain error changes sign between successive K while both sides are
  beyond that share (a log decrement read from 3 s and a few impacts swings from -27 % to +25 % and back): the
  metric answers to details of the model finer than its convergence, so an engine's error in it says little."""

import math

from . import analysis, metric_catalog
from .tables import signed_text

# How much of a tolerance the chain may take for its resolution to count as settled: a quarter leaves three
# quarters of every tolerance to the engine and the noise.
CHAIN_SHARE_OF_TOLERANCE = 0.25


def links_of(run):
    """K of a reference run on a chain with the default damping (its options are exactly links and modes=chain),
    else None: a chain damped otherwise answers another engine option, not the resolution."""
    options = analysis.options_of(run["options"])
    if run["engine"] != "reference" or options.get("modes") != "chain" or set(options) != {"links", "modes"}:
        return None
    return int(options["links"])


def chain_references(suite, scenario, law):
    """{K: the reference run on the K-link chain (an ensemble's member 0)} of a case, by increasing K."""
    found = {}
    for run in suite.runs_of(scenario, law):
        links = links_of(run)
        if links is not None and run["verdict"] == "ok":
            found.setdefault(links, run)
    return dict(sorted(found.items()))


def status(error, half_width, allowed):
    """'within' (the whole interval inside +-allowed), 'beyond' (the whole interval outside), else 'undecided'."""
    half = half_width or 0.0
    if abs(error) + half <= allowed:
        return "within"
    if abs(error) - half > allowed:
        return "beyond"
    return "undecided"


def metric_convergence(references, column, kind, tolerance):
    """One metric's chain errors against the beam over K, the smallest settled K and its flags."""
    allowed = CHAIN_SHARE_OF_TOLERANCE * tolerance
    rows = []
    for links, run in references.items():
        error = analysis.signed_error(run, column, "beam")
        if math.isnan(error):
            continue
        interval = analysis.error_interval(run, column, "beam")
        half_width = interval.half_width if interval is not None else None
        rows.append({"links": links, "error": error, "half_width": half_width, "job_id": run["job_id"],
                     "status": status(error, half_width, allowed)})
    settled = None
    for i, row in enumerate(rows):
        if all(abs(r["error"]) <= allowed for r in rows[i:]):
            settled = row["links"]
            break
    flags = []
    # Not settled because the finest chain tried is provably beyond the share: flagged. Not settled because the
    # noise cannot tell (a chaotic case's few starts): said, not flagged; the engines are ranked on their own chains.
    if rows and settled is None and rows[-1]["status"] == "beyond":
        flags.append(f"does not settle within {rows[-1]['links']} links: its chain error stays beyond "
                     f"{share_text(allowed, kind)}")
    for a, b in zip(rows, rows[1:]):
        if abs(a["error"]) > allowed and abs(b["error"]) > allowed and a["error"] * b["error"] < 0:
            flags.append(f"ill-conditioned in its window: its chain error swings from {signed_text(a['error'], kind)} "
                         f"at {a['links']} links to {signed_text(b['error'], kind)} at {b['links']}")
            break
    noisy = [r["links"] for r in rows if (r["half_width"] or 0) > allowed]
    return {"errors_vs_beam": rows, "allowed_chain_error": allowed, "settled_links": settled, "flags": flags,
            "noise_exceeds_share_at_links": noisy}


def share_text(allowed, kind):
    return f"{100 * allowed:.3g} %" if kind == "relative" else f"{allowed:.3g}"


def case_convergence(suite, scenario, law, tolerances):
    """A case's chain convergence as summary.json holds it: {links_tried, share_of_tolerance, metrics: {label:
    metric_convergence + kind, tolerance}}; None without two or more chains."""
    references = chain_references(suite, scenario, law)
    if len(references) < 2:
        return None
    metrics = {}
    for label, column, kind, key in ((m.label, m.error_column, m.kind, m.tolerance_key) for m in metric_catalog.SCORED):
        entry = metric_convergence(references, column, kind, tolerances[key])
        if entry["errors_vs_beam"]:
            metrics[label] = {"error_column": analysis.AGAINST["beam"] + column, "kind": kind,
                              "tolerance": tolerances[key], **entry}
    return {"links_tried": list(references), "share_of_tolerance": CHAIN_SHARE_OF_TOLERANCE, "metrics": metrics}


def flagged_metrics(convergence):
    """{metric label: its flags} of the metrics that rank no engine in this case."""
    if not convergence:
        return {}
    return {label: m["flags"] for label, m in convergence["metrics"].items() if m["flags"]}


def settled_links(convergence):
    """The smallest K at which every sound metric of the case has settled, or None (no convergence, or a sound
    metric that did not settle)."""
    if not convergence:
        return None
    values = [m["settled_links"] for m in convergence["metrics"].values() if not m["flags"]]
    if not values or any(v is None for v in values):
        return None
    return max(values)
