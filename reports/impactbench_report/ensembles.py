"""Ensembles: a configuration run from N starts (frame 1's initial tip displacement offset by K x the
study's step, K = 0..N-1), its metrics as means with 95 % intervals, its errors as differences of two
ensembles, and what is significant.

A chaotic case's metric is a random variable: two starts a micrometre apart give sensor peaks several
per cent apart. One run's error against one reference run then mixes the engine's error with that
scatter; the difference of two ensembles' means, with its interval, separates them.

The interface (runs.csv, runs.jsonl): `ensemble_start` (K), `ensemble_starts` (N; 1 outside an ensemble),
`initial_displacement_offset_m`; member 0 keeps a single run's job id, member K >= 1 has `/start=K`
appended. A folder without these columns is one of single runs (N = 1 everywhere).

Methods (docs/results.md, "Ensembles and intervals"):
- a metric: the mean over the members, Student's t interval t(0.975, n-1) s / sqrt(n);
- an error vs a reference ensemble: engine mean - reference mean (a difference), or that over the
  reference mean (a relative error); Welch-Satterthwaite interval, the relative error's variance by the
  delta method: var(me/mr - 1) = var(me)/mr^2 + (me/mr^2)^2 var(mr);
- one side a single run: no interval from it. Where the reference's scatter is measured, a single run's
  noise is the reference's 95 % prediction half-width t s sqrt(1 + 1/n) (the assumption: the engine's
  chain scatters as the beam does), stated as "differences below +-X are not significant", never as
  the engine's interval;
- "better": Welch's interval of the difference of two configurations' scores (largest |error| in
  tolerance multiples) excludes 0; otherwise a tie;
- a verdict: within when every error's interval lies inside its tolerance, beyond when one lies outside,
  else undecided."""

import math
from dataclasses import dataclass

from scipy import stats

CONFIDENCE = 0.95

# A case needs an ensemble when a single reference run's 95 % scatter (the prediction half-width of one
# more start) in any verdict metric exceeds this fraction of the metric's verdict tolerance: the answer
# ranks configurations whose errors differ by a tenth of a tolerance (1 to 2 % in a sensor peak), so a
# scatter above that makes single-run rankings a draw of the starts (docs/results.md).
ENSEMBLE_NEED_FRACTION_OF_TOLERANCE = 0.1


@dataclass
class Interval:
    """A mean with its 95 % interval: half_width None where there is none (a single run)."""
    mean: float
    n: int
    method: str
    standard_error: float = math.nan
    dof: float = math.nan
    half_width: float = None
    job_ids: tuple = ()
    engine_side: "Interval" = None  # an error against a single reference run: the engine ensemble's part alone

    def json(self):
        out = {"mean": none_if_nan(self.mean), "half_width": self.half_width, "n": self.n, "method": self.method}
        if self.half_width is not None:
            out["standard_error"] = self.standard_error
            out["degrees_of_freedom"] = none_if_nan(self.dof)  # null: infinite (no scatter on either side)
        return out


def none_if_nan(x):
    """JSON's null for NaN and infinity (summary.json holds finite numbers only)."""
    return None if x is None or (isinstance(x, float) and not math.isfinite(x)) else x


def t_quantile(dof):
    return float(stats.t.ppf(0.5 + CONFIDENCE / 2, dof))


def t_interval(values, job_ids=()):
    """Mean and Student t interval of a sample; a single value: "single run", no interval."""
    values = [v for v in values if not math.isnan(v)]
    n = len(values)
    if n == 0:
        return Interval(math.nan, 0, "none", job_ids=tuple(job_ids))
    mean = sum(values) / n
    if n == 1:
        return Interval(mean, 1, "single run", job_ids=tuple(job_ids))
    # equal values (a metric the starts do not change) have no scatter, not a rounding error's
    variance = 0.0 if max(values) == min(values) else sum((v - mean) ** 2 for v in values) / (n - 1)
    se = math.sqrt(variance / n)
    return Interval(mean, n, f"Student t, {100 * CONFIDENCE:g} %", se, n - 1, t_quantile(n - 1) * se, tuple(job_ids))


def standard_deviation(interval):
    return interval.standard_error * math.sqrt(interval.n)


def combine(parts, mean, method):
    """An interval of `mean` from independent parts [(variance, dof)]: Welch-Satterthwaite's dof."""
    variance = sum(v for v, _ in parts)
    if variance == 0:
        return mean, 0.0, math.inf, 0.0
    dof = variance ** 2 / sum(v ** 2 / d for v, d in parts if v > 0)
    se = math.sqrt(variance)
    return mean, se, dof, t_quantile(dof) * se


def welch_difference(a, b, method="Welch-Satterthwaite"):
    """a.mean - b.mean with Welch's interval; None when either side has no interval."""
    if a.half_width is None or b.half_width is None:
        return None
    mean, se, dof, half = combine([(a.standard_error ** 2, a.dof), (b.standard_error ** 2, b.dof)],
                                  a.mean - b.mean, method)
    return Interval(mean, min(a.n, b.n), method, se, dof, half, a.job_ids + b.job_ids)


def ensemble_error(engine, reference, kind):
    """The error of an engine ensemble against a reference ensemble: a difference, or relative to the
    reference mean (delta method). With a single run on either side: the value, "single run", no interval."""
    if math.isnan(engine.mean) or math.isnan(reference.mean) or (kind == "relative" and reference.mean == 0):
        return None
    n = f"{engine.n} vs {reference.n}"
    if kind != "relative":
        value = engine.mean - reference.mean
        interval = welch_difference(engine, reference)
    else:
        ratio = engine.mean / reference.mean
        value = ratio - 1
        interval = None
        if engine.half_width is not None and reference.half_width is not None:
            parts = [(engine.standard_error ** 2 / reference.mean ** 2, engine.dof),
                     ((ratio / reference.mean) ** 2 * reference.standard_error ** 2, reference.dof)]
            _, se, dof, half = combine(parts, value, "")
            interval = Interval(value, min(engine.n, reference.n), "", se, dof, half)
    if interval is None:
        error = Interval(value, min(engine.n, reference.n), f"single run ({n} starts)",
                         job_ids=engine.job_ids + reference.job_ids)
        if engine.half_width is not None:  # what two engines compared against the same reference run share
            scale = 1 / abs(reference.mean) if kind == "relative" else 1.0
            error.engine_side = Interval(value, engine.n, "the engine ensemble's alone (the reference ran once)",
                                         engine.standard_error * scale, engine.dof, engine.half_width * scale)
        return error
    method = ("Welch-Satterthwaite, delta method for the reference mean" if kind == "relative"
              else "Welch-Satterthwaite") + f", {100 * CONFIDENCE:g} % ({n} starts)"
    return Interval(value, interval.n, method, interval.standard_error, interval.dof, interval.half_width,
                    engine.job_ids + reference.job_ids)


def single_run_noise(reference, kind):
    """How far one run of a case scatters from its ensemble mean (95 % prediction half-width of one more
    start, t s sqrt(1 + 1/n)) as the reference measured it, relative to its mean for a relative error;
    None when the reference ran once."""
    if reference is None or reference.half_width is None:
        return None
    half = t_quantile(reference.dof) * standard_deviation(reference) * math.sqrt(1 + 1 / reference.n)
    if kind == "relative":
        return half / abs(reference.mean) if reference.mean else None
    return half


def compare(a, b):
    """Whether score a (an Interval of tolerance multiples) is below score b beyond the intervals:
    "better", "worse" or "tie" (Welch's interval of a - b contains 0); "single runs" when either has no
    interval (then the plain order decides, as for single runs it always has)."""
    if a.half_width is None and b.half_width is None and a.engine_side and b.engine_side:
        a, b = a.engine_side, b.engine_side  # both against one reference run, its value common to both
    difference = welch_difference(a, b)
    if difference is None:
        return "single runs"
    if difference.mean + difference.half_width < 0:
        return "better"
    if difference.mean - difference.half_width > 0:
        return "worse"
    return "tie"


def verdict(errors, tolerance_of):
    """within / beyond / undecided for a run's errors [(label, Interval)] against their tolerances; None
    when no error has an interval (a single run's verdict is its row's)."""
    if not any(e.half_width is not None for _, e in errors):
        return None
    result = "within"
    for label, e in errors:
        half = e.half_width or 0.0
        tolerance = tolerance_of(label)
        if abs(e.mean) - half > tolerance:
            return "beyond"
        if abs(e.mean) + half > tolerance:
            result = "undecided"
    return result
