"""Better or worse: each moved metric judged by its error before and after, and each configuration by
what moved in it.

A metric is judged on what the engine controls: its error against the reference on its own chain where the
run has one (its contact handling and time stepping alone), else against the beam (the reference engine,
a run without a chain). A metric that moved beyond its noise is
- improved when |error| fell, regressed when it rose,
- "moved, error as large" when the change of |error| is itself within the noise (the error crossed zero:
  -3 % -> +3 %);
one that did not move is "unchanged within the noise". A metric without an error (a sweep's row, or one
defined in one folder only) moved without a judgement of its own: "moved".

A configuration regressed when any of these did: a metric regressed; more members fail or are unstable
(newly failing), or more are inaccurate; the instability comes earlier; the CPU cost rose beyond its noise;
it disappeared (it is in BASE only: why, named). It improved when something improved and nothing regressed.
It appeared: neither. Anything else that moved (a per-impact distribution, a regime, an error as large) is
"moved"; nothing moved: "unchanged"; run otherwise: "not comparable"."""

import math

from impactbench_report import analysis

IMPROVED, REGRESSED, AS_LARGE, UNCHANGED, MOVED = ("improved", "regressed", "moved, error as large",
                                                    "unchanged within the noise", "moved")
FAILING = ("unstable", "failed")


def errors(run, error_column):
    """{against: signed error} of a run's metric, against the beam and against its own chain (NaN where not
    defined; a sweep's row has neither)."""
    if run is None or isinstance(run, dict):
        return {"beam": math.nan, "own chain": math.nan}
    return {against: analysis.signed_error(run, error_column, against) for against in ("beam", "own chain")}


def judged_against(base_errors, new_errors):
    """The reference the engine is judged against: its own chain where both folders' runs have an error
    against it, else the beam; None without either."""
    for against in ("own chain", "beam"):
        if not (math.isnan(base_errors[against]) or math.isnan(new_errors[against])):
            return against
    return None


def error_noise(m, base_error):
    """The metric's noise in the error's unit: a relative change c of the value moves a relative error by
    c (1 + error) (error = value / reference - 1); a difference moves it by itself."""
    if m.kind != "relative":
        return m.noise
    return m.noise * abs(1 + base_error)


def judge_metric(m):
    """The metric's judgement (the module's rule) from its moved flag and its errors."""
    if m.not_judged:
        return m.not_judged
    if not m.moved:
        return UNCHANGED
    if m.against is None:
        return MOVED
    before, after = m.base_errors[m.against], m.new_errors[m.against]
    change = abs(after) - abs(before)
    if abs(change) <= error_noise(m, before):
        return AS_LARGE
    return IMPROVED if change < 0 else REGRESSED


def failing(verdicts):
    return sum(n for v, n in verdicts.items() if v.split(",")[0] in FAILING)


def inaccurate(verdicts):
    return sum(n for v, n in verdicts.items() if v.split(",")[0] == "inaccurate")


def verdict_judgement(c):
    """REGRESSED / IMPROVED / MOVED / None from the members' verdicts: failing first, then inaccurate; a
    change of a sweep row's regime alone is MOVED."""
    if not c.verdicts_changed:
        return None
    for count in (failing, inaccurate):
        a, b = count(c.base_verdicts), count(c.new_verdicts)
        if a != b:
            return REGRESSED if b > a else IMPROVED
    return MOVED


def parts(c):
    """The judgements of what moved in a configuration compared in both folders."""
    found = [m.judgement for m in c.metrics]
    found.append(verdict_judgement(c))
    if c.instability is not None and c.instability.moved:
        found.append(c.instability.judgement)
    if c.cost is not None and c.cost.moved:
        found.append(REGRESSED if c.cost.ratio > 1 else IMPROVED)
    found += [MOVED for i in c.impacts if i.moved]
    return found


def judge_configuration(c):
    if c.not_comparable:
        return "not comparable"
    if c.presence != "both":
        return REGRESSED if c.presence == "disappeared" else "appeared"
    found = parts(c)
    if REGRESSED in found:
        return REGRESSED
    if IMPROVED in found:
        return IMPROVED
    return MOVED if c.moved else "unchanged"


def why_disappeared(c, new):
    """Why a configuration of BASE is not in NEW, as far as NEW's configurations tell."""
    runs = list(new.configurations.values())
    for key, what in (("engine", "its engine"), ("scenario", "its scenario"), ("law", "its law")):
        if not any(r[key] == getattr(c, key) for r in runs):
            return f"{what} ({getattr(c, key)}) is not in NEW"
    return "its step or options are not in NEW (not run, or its run was lost)"


def judge_all(changes, new):
    """Each metric's and configuration's judgement, and why each disappeared configuration did."""
    for c in changes:
        for m in c.metrics:
            m.judgement = judge_metric(m)
        c.judgement = judge_configuration(c)
        if c.presence == "disappeared":
            c.why = why_disappeared(c, new)


def regressed(changes):
    return any(c.judgement == REGRESSED for c in changes)
