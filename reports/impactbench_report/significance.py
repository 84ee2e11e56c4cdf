"""What is significant in a case: whether it needed an ensemble (the reference's scatter over its starts),
each configuration's score with its interval, ties between configurations, and verdicts against the
tolerances that an interval leaves undecided. The statistics themselves: ensembles.py."""

import math

from . import analysis, ensemble_groups, ensembles, metric_catalog
from .ensembles import ENSEMBLE_NEED_FRACTION_OF_TOLERANCE, Interval


def metric_text(kind, value):
    return f"{100 * value:.2g} %" if kind == "relative" else f"{value:.2g}"


def case_need(suite, scenario, law, tolerances):
    """Whether a case needed an ensemble, by the rule of ensembles.ENSEMBLE_NEED_FRACTION_OF_TOLERANCE, from
    its beam reference's starts: {needed (None when unmeasured), why, reference_job_ids, spread (per
    metric), engines_ran_once, single_run_noise ({error column: [half-width, dof]}), note}."""
    ensemble, intervals = ensemble_groups.reference_intervals(suite, scenario, law)
    if ensemble is None:
        return {"needed": None, "why": "no beam reference run: its scatter is not measured"}
    if ensemble.n <= 1:
        return {"needed": None, "reference_starts": 1, "reference_job_ids": ensemble.job_ids,
                "why": "the reference ran once: its scatter over starts is not measured"}
    spread, noise, above = {}, {}, []
    for m in metric_catalog.SCORED:
        label, column, error_column, kind, key = m.label, m.column, m.error_column, m.kind, m.tolerance_key
        interval = intervals[column]
        half = ensembles.single_run_noise(interval, kind)
        if half is None:
            continue
        threshold = ENSEMBLE_NEED_FRACTION_OF_TOLERANCE * tolerances[key]
        spread[column] = {"mean": interval.mean, "standard_deviation": ensembles.standard_deviation(interval),
                          "n": interval.n, "mean_half_width": interval.half_width,
                          "single_run_half_width": half, "kind": kind, "tolerance": tolerances[key],
                          "threshold": threshold, "exceeds": half > threshold}
        noise[error_column] = [half, interval.dof]
        if half > threshold:
            above.append((f"±{metric_text(kind, half)} in {label}", metric_text(kind, threshold)))
    engine_runs = [r for r in suite.runs_of(scenario, law) if r["engine"] not in ("reference", "")]
    ran_once = bool(engine_runs) and all(len(suite.members.get(r["job_id"], [r])) <= 1 for r in engine_runs)
    need = {"needed": bool(above), "reference_starts": ensemble.n, "reference_job_ids": ensemble.job_ids,
            "rule": f"a single reference start's 95 % scatter in a verdict metric above "
                    f"{ENSEMBLE_NEED_FRACTION_OF_TOLERANCE:g} of that metric's tolerance",
            "spread": spread, "engines_ran_once": ran_once, "single_run_noise": noise}
    labels = {m.column: m.label for m in metric_catalog.SCORED}
    if above:
        thresholds = ", ".join(dict.fromkeys(t for _, t in above))
        need["why"] = (f"one reference start scatters {', '.join(a for a, _ in above)} (95 %, {ensemble.n} starts), "
                       f"above {ENSEMBLE_NEED_FRACTION_OF_TOLERANCE:g} of the verdict tolerance: {thresholds}")
    else:
        largest = max(spread.items(), key=lambda kv: kv[1]["single_run_half_width"] / kv[1]["tolerance"], default=None)
        need["why"] = ("one reference start scatters less than " f"{ENSEMBLE_NEED_FRACTION_OF_TOLERANCE:g} of the verdict "
                       "tolerance in every verdict metric" +
                       (f" (most: ±{metric_text(largest[1]['kind'], largest[1]['single_run_half_width'])} in "
                        f"{labels[largest[0]]}, {ensemble.n} starts)" if largest else ""))
    need["note"] = single_runs_note(need) if above and ran_once else ""
    return need


def single_runs_note(need):
    """'single runs: differences below ±6 % (frame 1 sensor peak) are not significant', per metric that
    needed the ensemble."""
    labels = {m.column: m.label for m in metric_catalog.SCORED}
    parts = [f"±{metric_text(s['kind'], s['single_run_half_width'])} ({labels[column]})"
             for column, s in need["spread"].items() if s["exceeds"]]
    return "single runs: differences below " + ", ".join(parts) + " are not significant"


def noise_of(run, need):
    """The single-run noise {error column: [half-width, dof]} that applies to a run: a case that needed an
    ensemble, an engine that ran once; {} otherwise."""
    if not need or not need.get("needed") or run.ensemble is not None and run.ensemble.n > 1:
        return {}
    return need.get("single_run_noise", {})


def error_with_interval(run, column, against, noise):
    """A signed error as an Interval: the ensembles' where there is one, a single run with the reference's
    scatter as its noise where the case needed an ensemble, else a single run without an interval."""
    interval = analysis.error_interval(run, column, against)
    if interval is not None and interval.half_width is not None:
        return interval
    value = analysis.signed_error(run, column, against)
    if column in noise:
        half, dof = noise[column]
        return Interval(value, 1, "single run; noise: the reference's single-start scatter", half / ensembles.t_quantile(dof),
                        dof, half)
    return interval if interval is not None else Interval(value, 1, "single run")


def score_interval(run, tolerances, need=None, against="beam", skip=()):
    """(score as an Interval of tolerance multiples, its metric's label, its error as an Interval), or None
    when the run has no scored error; `skip`: metric labels left out (analysis.score)."""
    multiple, label, _ = analysis.score(run, tolerances, against, skip)
    if label is None:
        return None
    metric = metric_catalog.by_label(label)
    column, key = metric.error_column, metric.tolerance_key
    error = error_with_interval(run, column, against, noise_of(run, need))
    tolerance = tolerances[key]
    if error.half_width is None:
        score = Interval(multiple, 1, error.method)
        if error.engine_side is not None:
            side = error.engine_side
            score.engine_side = Interval(multiple, side.n, side.method, side.standard_error / tolerance, side.dof,
                                         side.half_width / tolerance)
        return score, label, error
    return (Interval(multiple, error.n, error.method, error.standard_error / tolerance, error.dof,
                     error.half_width / tolerance), label, error)


def verdict(run, tolerances, need=None, against="beam", skip=()):
    """within / beyond / undecided against the tolerances over every scored error but those in `skip`, from
    the intervals; None for a single run without a measured noise (its ✗ is its error's own)."""
    noise = noise_of(run, need)
    errors = []
    for m in metric_catalog.SCORED:
        if m.label in skip:
            continue
        if math.isnan(analysis.signed_error(run, m.error_column, against)):
            continue
        errors.append((m.label, error_with_interval(run, m.error_column, against, noise)))
    tolerance_of = {m.label: tolerances[m.tolerance_key] for m in metric_catalog.SCORED}.get
    return ensembles.verdict(errors, tolerance_of)


TEST = ("Welch's 95 % interval of the difference of the two configurations' scores (largest |error| vs the engine's own "
        "chain in tolerance multiples) excludes 0")


def like_with_like(a, b):
    """Two engine ensembles scored against one single reference run compare on their own intervals only
    where the reference's value cancels: the same metric, errors of the same sign."""
    if a[0].half_width is not None or b[0].half_width is not None:
        return True
    return a[1] == b[1] and math.copysign(1, a[2].mean) == math.copysign(1, b[2].mean)


def ties(best_run, others, tolerances, need, against="beam", skip=()):
    """(configurations [(name, run)] whose score `against` is not distinguishable from best_run's, whether the
    best is significant: True, False, or None when no comparison had intervals)."""
    best = score_interval(best_run, tolerances, need, against, skip)
    if best is None:
        return [], None
    tied, decided = [], []
    for name, run in others:
        other = score_interval(run, tolerances, need, against, skip)
        if other is None:
            continue
        if not like_with_like(best, other):
            decided.append(False)
            continue
        result = ensembles.compare(best[0], other[0])
        if result == "tie":
            tied.append(name)
        decided.append(result != "single runs")
    significant = None if not any(decided) else not tied
    return tied, significant
