"""What the report picks from the runs: how the headline errors (metric_catalog.py) are scored, each configuration's
best run and largest stable step, and which configuration answers a case best out of the box and tuned.

One error convention (issue 16): every error is named by what it is measured against, the BEAM (the
continuous-beam reference: the physical question, the whole error a user sees) or the engine's OWN
CHAIN (the reference solved on the engine's K-link chain: the engine's contact handling and time stepping
alone). runs.csv names them vs_reference_* and vs_chain_reference_*."""

import math

from . import metric_catalog

AGAINST = {"beam": "vs_reference_", "own chain": "vs_chain_reference_"}

NATIVE, TUNED = "native", ("matched", "injected")


def options_of(text):
    """An options text as runs.csv and the configurations' names write it ('contact=matched;length_unit=cm')
    as {name: value}: the one reader of that text."""
    return dict(o.split("=", 1) for o in text.split(";") if "=" in o)


def contact_path_of(options_text):
    """The contact path an options text names: matched, injected or native (matched by default)."""
    return options_of(options_text).get("contact", "matched")


def contact_path(run):
    """The contact path of an engine run: matched, injected or native (options contact=...; matched by
    default)."""
    return contact_path_of(run["options"])


def signed_error(run, column, against="beam"):
    """A signed error of a run against the beam or its own chain (NaN where not defined); `against` may
    also be the column prefix itself (vs_reference_, vs_chain_reference_). Where the run stands for an
    ensemble (or its reference does), the difference of the two ensembles' means (ensembles.py)."""
    name = AGAINST.get(against, against) + column
    ensemble = getattr(run, "ensemble", None)
    if ensemble is not None and name in ensemble.errors:
        return ensemble.errors[name].mean
    return run.number(name)


def error_interval(run, column, against="beam"):
    """The ensembles.Interval of a signed error where the run has an ensemble statistic for it, else None."""
    ensemble = getattr(run, "ensemble", None)
    return None if ensemble is None else ensemble.errors.get(AGAINST.get(against, against) + column)


def error(run, column, against="vs_reference_"):
    """|signed_error|, as the log-log figures draw it."""
    return abs(signed_error(run, column, against))


def score(run, tolerances, against="beam", skip=()):
    """(largest |error| / tolerance over the headline metrics but those in `skip` (labels: a case's metrics its
    chain convergence flags, chain_convergence.py), that metric's label, its signed error): errors of different
    kinds compare through their tolerances. (inf, None, NaN) without any error."""
    worst = (math.inf, None, math.nan)
    for metric in metric_catalog.SCORED:
        if metric.label in skip:
            continue
        value = signed_error(run, metric.error_column, against)
        if math.isnan(value):
            continue
        multiple = abs(value) / tolerances[metric.tolerance_key]
        if worst[1] is None or multiple > worst[0]:
            worst = (multiple, metric.label, value)
    return worst


def configurations(runs):
    """Engine configurations (engine + options) other than the references, in first-seen order."""
    seen = []
    for r in runs:
        if r["engine"] not in ("reference", "") and r.config not in seen:
            seen.append(r.config)
    return seen


def runs_of_config(runs, config):
    return sorted((r for r in runs if r.config == config), key=lambda r: r.number("time_step_s"))


def engine_score(score_vs_own_chain, score_vs_beam):
    """(the score that ranks an engine's run, what it is against): the error the engine controls, its score against
    its own chain, or the beam's where it has no chain (issue 46)."""
    if math.isinf(score_vs_own_chain):
        return score_vs_beam, "beam"
    return score_vs_own_chain, "own chain"


def engine_score_of(run, tolerances, skip=()):
    """engine_score of a run: (its score against its own chain, or the beam's where it has none; which)."""
    return engine_score(score(run, tolerances, "own chain", skip)[0], score(run, tolerances, "beam", skip)[0])


def ranking_key(run, tolerances, skip=()):
    """How runs of an engine are ranked: a run that passes its own verdict before one that fails it, then its
    engine_score, then the cheaper."""
    return (run["verdict"] != "ok", engine_score_of(run, tolerances, skip)[0], run.number("cpu_time_per_simulated_s"))


def best_run(runs, tolerances, skip=()):
    """The best stable, scored run by ranking_key; None when no run is stable or scored."""
    scored = [r for r in runs if r.stable and not math.isinf(score(r, tolerances, "beam", skip)[0])]
    if not scored:
        return None
    return min(scored, key=lambda r: ranking_key(r, tolerances, skip))


def step_limits(runs, config):
    """(largest stable step tried [s], the run at it, smallest unstable step tried [s] or NaN, whether a
    larger step was tried and was unstable) over a configuration's fixed-step runs in the suite."""
    ordered = [r for r in runs_of_config(runs, config) if r.number("time_step_s") > 0]
    stable = [r for r in ordered if r.stable]
    unstable = [r for r in ordered if r["verdict"] == "unstable"]
    largest = max(stable, key=lambda r: r.number("time_step_s")) if stable else None
    smallest_unstable = min((r.number("time_step_s") for r in unstable), default=math.nan)
    return largest, smallest_unstable


def largest_stable_step(runs, config):
    largest, _ = step_limits(runs, config)
    return largest
