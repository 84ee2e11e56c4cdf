"""An engine run's error against the beam split into what it is made of (issue 46):

- the chain: the reference on the run's own K-link chain against the beam (the model's share, the same for every
  engine on that chain; chain_convergence.py says how it falls with K);
- the engine: the run against that chain (contact handling and time stepping), in the beam's units so that the
  parts add: (E - C) / B = (E / C - 1) (C / B) for a relative error, E - C for a difference;
- the noise: the total's 95 % half-width (an ensemble's interval, or the reference's single-start scatter for a
  single run of a case that needed an ensemble); null where nothing measured it.

With E, C and B the run's, its chain's and the beam's values (an ensemble's means where there is one), chain +
engine = total exactly; `residual` keeps what rounding leaves, and `why_not_additive` says why where a part is
missing. The reference's own numerical error sits beside them (reference_numerical_error)."""

import math

from . import analysis, ensemble_groups, metric_catalog, significance

# Residual, relative to the largest part (at least one), below which the parts are said to add up: runs.csv
# writes each error with nine significant digits (harness/records/number_text.h), so three agree to about 1e-9.
ADDITIVE_TOLERANCE = 1e-8


def adds_up(total, chain, engine):
    return abs(total - chain - engine) <= ADDITIVE_TOLERANCE * max(1.0, abs(total), abs(chain), abs(engine))


def none_if_nan(x):
    return None if x is None or (isinstance(x, float) and math.isnan(x)) else x


def metric_budget(run, chain_run, column, kind, noise):
    """One scored metric's budget for a run; None where the run has no error against the beam in it."""
    total = analysis.signed_error(run, column, "beam")
    if math.isnan(total):
        return None
    # The chain's share from the same values as the run's total: the ensembles' means where the run's error is
    # an ensemble's, else the rows of the same start (an unstable run has no ensemble statistics)
    from_means = analysis.error_interval(run, column, "beam") is not None
    if chain_run is None:
        chain = math.nan
    elif from_means:
        chain = analysis.signed_error(chain_run, column, "beam")
    else:
        chain = chain_run.number(analysis.AGAINST["beam"] + column)
    own = analysis.signed_error(run, column, "own chain")
    engine = own * (1 + chain) if kind == "relative" else own
    entry = {"total": total, "chain": none_if_nan(chain), "engine": none_if_nan(engine),
             "engine_vs_own_chain": none_if_nan(own)}
    interval = significance.error_with_interval(run, column, "beam", noise)
    entry["noise_half_width"] = interval.half_width
    entry["noise_method"] = interval.method
    if math.isnan(chain) or math.isnan(own):
        entry["residual"] = None
        entry["why_not_additive"] = ("no reference on the run's own chain" if chain_run is None or math.isnan(chain)
                                     else "no error against the run's own chain")
    else:
        entry["residual"] = total - chain - engine
        if not adds_up(total, chain, engine):
            entry["why_not_additive"] = ("the run's errors and its chain's are measured against different values of "
                                         "the references (an ensemble's means on one side, a row on the other)")
    return entry


def run_budget(suite, index, run, need):
    """A run's budget over the scored metrics: {chain_links, chain_reference_job_id, metrics: {label: ...}}."""
    chain_run = ensemble_groups.reference_of(index, run, "own chain")
    noise = significance.noise_of(run, need)
    metrics = {}
    for m in metric_catalog.SCORED:
        entry = metric_budget(run, chain_run, m.error_column, m.kind, noise)
        if entry is not None:
            metrics[m.label] = {"kind": m.kind, **entry}
    links = run.number("chain_links")
    return {"chain_links": None if math.isnan(links) or links <= 0 else int(links),
            "chain_reference_job_id": chain_run["job_id"] if chain_run is not None else None, "metrics": metrics}



def tight_reference(suite, scenario, law):
    """The case's beam reference rerun at tighter tolerances (options rtol and atol only), or None."""
    for run in suite.runs_of(scenario, law):
        options = analysis.options_of(run["options"])
        if run["engine"] == "reference" and options and set(options) <= {"rtol", "atol"} and run["verdict"] == "ok":
            return run
    return None


def reference_numerical_error(suite, scenario, law):
    """The beam reference's own numerical error per scored metric: its first start's value against the same start
    at tighter tolerances (relative, or a difference for impacts per cycle); None without that rerun."""
    beam, tight = suite.beam_reference(scenario, law), tight_reference(suite, scenario, law)
    if beam is None or tight is None:
        return None
    metrics = {}
    for label, column, kind in ((m.label, m.column, m.kind) for m in metric_catalog.SCORED):
        value, exact = beam.number(column), tight.number(column)
        if math.isnan(value) or math.isnan(exact) or (kind == "relative" and exact == 0):
            continue
        metrics[label] = {"kind": kind, "error": value / exact - 1 if kind == "relative" else value - exact}
    return {"against_job_id": tight["job_id"], "against": f"the beam reference at {tight['options'].replace(';', ', ')}",
            "beam_job_id": beam["job_id"], "metrics": metrics}
