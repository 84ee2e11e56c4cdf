"""The reference against the experiment (issue 50; the method and its assumptions: docs/validation.md).

For each published case and response quantity:
- the distribution the uncertain inputs give it: the sample's values (validation_sample.py), with every run that
  is not ok, or that does not define the quantity, listed rather than dropped;
- the chaotic scatter, kept apart: sigma_chaos, the standard deviation over the nominal reference's starts. Each
  sample point ran from one start, so the sample's variance holds both; the inputs' own share is
  u_input = sqrt(max(0, var_sample - sigma_chaos^2));
- which inputs matter: first-order global sensitivity indices from the same sample (the correlation ratio,
  binned, its bias removed), beside the chaos share sigma_chaos^2 / var_sample;
- where the paper measured the quantity, ASME V&V 20: E = S - D against the validation uncertainty u_val.

Plain functions on numbers and the sample; summarise() is what summary.json's `validation` holds."""

import math
from dataclasses import asdict, dataclass

import numpy as np

from . import validation_sample
from .validation_sample import QUANTITIES

# V&V 20's coverage factor: |E| within K u_val is within the validation uncertainty (about 95 % for a normal E)
COVERAGE = 2.0
PERCENTILES = (2.5, 50.0, 97.5)
TOP_INPUTS = 3  # the inputs the page names per quantity


def finite(values):
    return np.asarray([v for v in values if v is not None and math.isfinite(v)], float)


@dataclass
class Distribution:
    """A quantity over the sample's runs that ran ok and define it; count and standard deviation over those."""
    n: int
    mean: float
    standard_deviation: float
    p2_5: float
    p50: float
    p97_5: float


def distribution(values):
    """Distribution of the finite values; NaNs (and a standard deviation of one value) where too few."""
    y = finite(values)
    if len(y) == 0:
        return Distribution(0, math.nan, math.nan, math.nan, math.nan, math.nan)
    low, mid, high = (float(p) for p in np.percentile(y, PERCENTILES))
    sd = float(np.std(y, ddof=1)) if len(y) > 1 else math.nan
    return Distribution(len(y), float(np.mean(y)), sd, low, mid, high)


def chaos_scatter(values):
    """(sigma_chaos, n): the sample standard deviation over a case's starts (NaN from fewer than two)."""
    y = finite(values)
    return (float(np.std(y, ddof=1)) if len(y) > 1 else math.nan), len(y)


def input_uncertainty(sample_variance, sigma_chaos):
    """u_input: the part of the sample's variance the chaotic scatter does not explain. A sample point's single
    start scatters as a start of the nominal ensemble does (the assumption: the scatter does not change over the
    inputs' range), so var_sample = u_input^2 + sigma_chaos^2; clipped at 0 where the sample's estimate falls
    below the chaos's."""
    chaos = 0.0 if math.isnan(sigma_chaos) else sigma_chaos ** 2
    return math.sqrt(max(0.0, sample_variance - chaos))


def bin_count(n):
    """sqrt(N) equal-count bins, at least two: the correlation ratio's bias and its resolution balanced."""
    return max(2, int(round(math.sqrt(n))))


def first_order_index(x, y):
    """First-order sensitivity index of Y to one input X from a given sample (x, y), the correlation ratio:
    sort by x, split into B = sqrt(N) bins of equal count, eta^2 = sum n_b (mean_b - mean)^2 / sum (y - mean)^2
    estimates Var(E[Y|X]) / Var(Y). Each bin mean carries its own noise, so that eta^2 averages S + c (1 - S)
    with c = (B-1)/(N-1), c alone where Y does not depend on X: the index is (eta^2 - c) / (1 - c), clipped at 0.
    (Taking c off alone, without the division, would leave a bias of -c S: -0.03 for S = 0.68 at N = 512.)
    None where Y does not vary or the sample is too small."""
    x, y = np.asarray(x, float), np.asarray(y, float)
    keep = np.isfinite(x) & np.isfinite(y)
    x, y = x[keep], y[keep]
    n = len(y)
    if n < 4:
        return None
    total = float(np.sum((y - y.mean()) ** 2))
    if total <= 0:
        return None
    bins = bin_count(n)
    order = np.argsort(x, kind="stable")
    between = sum(len(b) * (float(np.mean(b)) - y.mean()) ** 2 for b in np.array_split(y[order], bins))
    bias = (bins - 1) / (n - 1)
    return max(0.0, (between / total - bias) / (1 - bias))


def index_noise_floor(n):
    """Twice the standard deviation of an index's estimate for an input Y does not depend on: below it an index is
    not told apart from none. Without dependence (Y normal) eta^2 is Beta((B-1)/2, (N-B)/2), of variance
    2 (B-1) (N-B) / ((N-1)^2 (N+1)), which the bias correction divides by (1 - c)^2."""
    if n < 4:
        return None
    bins = bin_count(n)
    bias = (bins - 1) / (n - 1)
    return 2 * math.sqrt(2 * (bins - 1) * (n - bins) / ((n - 1) ** 2 * (n + 1))) / (1 - bias)


def ranked_indices(inputs, y):
    """[(input name, index)] over {name: x values}, the largest first (None indices last, in input order)."""
    indices = [(name, first_order_index(x, y)) for name, x in inputs.items()]
    return sorted(indices, key=lambda item: -1.0 if item[1] is None else -item[1])


def standard_uncertainty(entry, value):
    """A measurement's standard uncertainty from experiment.toml's [CASE.uncertainty.KEY] (or an inputs.json
    entry): normal with standard_uncertainty or relative_standard_uncertainty, uniform with half_width / sqrt(3)."""
    if "standard_uncertainty" in entry:
        return float(entry["standard_uncertainty"])
    if "relative_standard_uncertainty" in entry:
        return abs(value) * float(entry["relative_standard_uncertainty"])
    if "half_width" in entry:
        return float(entry["half_width"]) / math.sqrt(3)
    raise ValueError(f"an uncertainty needs standard_uncertainty, relative_standard_uncertainty or half_width: {entry}")


def measurement(experiment, case, quantity):
    """(D, u_D, source) where the paper measured the quantity in the case, else None. A measurement without a
    stated uncertainty has u_D = 0, said so in the source."""
    if quantity.measured_key is None:
        return None
    entry = experiment.get(case, {})
    if quantity.measured_key not in entry:
        return None
    value = float(entry[quantity.measured_key])
    stated = entry.get("uncertainty", {}).get(quantity.measured_key)
    if stated is None:
        return value, 0.0, "no uncertainty stated in reports/experiment.toml: taken as 0"
    return value, standard_uncertainty(stated, value), stated.get("source", "")


def unit_text(unit):
    return "" if unit in ("", "-") else f" {unit}"


def verdict(e, u_val, unit=""):
    """V&V 20's reading of E against u_val: (words, the model-form error's lower bound or None).
    |E| <= 2 u_val: the model's error is not resolved from the uncertainties; beyond: at least |E| - 2 u_val."""
    excess = abs(e) - COVERAGE * u_val
    if excess <= 0:
        return "within the validation uncertainty", None
    return f"model-form error of at least {excess:.4g}{unit_text(unit)}", excess


@dataclass
class Comparison:
    """ASME V&V 20 for one measured quantity. S: the nominal ensemble's mean; E = S - D; u_num from the solver's
    tolerance (u_solver), the chaotic scatter of the one window the experiment recorded (sigma_chaos) and the
    ensemble mean's own noise (sigma_chaos / sqrt(n)); u_val = sqrt(u_num^2 + u_input^2 + u_D^2)."""
    d: float
    s: float
    e: float
    u_solver: float
    u_num: float
    u_input: float
    u_d: float
    u_val: float
    verdict: str
    model_form_error_at_least: float = None
    u_input_sampling_error: float = 0.0  # u_input's own standard error from the sample's size (0: not estimated)


def undecided(e, u_num, u_input, u_d, sampling_error):
    """Whether the verdict turns within u_input's own sampling error: 2 u_val computed with u_input - se and with
    u_input + se on either side of |E|."""
    def u_val(u):
        return math.sqrt(u_num ** 2 + max(0.0, u) ** 2 + u_d ** 2)
    return (abs(e) > COVERAGE * u_val(u_input - sampling_error)) != (abs(e) > COVERAGE * u_val(u_input + sampling_error))


def compare(s, d, u_solver, sigma_chaos, n_starts, u_input, u_d, unit="", n_sample=0):
    """V&V 20 for one quantity. n_sample (the sample's runs, >= 2): u_input is a standard deviation estimated from
    them, good to about u_input / sqrt(2 (n_sample - 1)); where the verdict turns within that, it is undecided at
    this sample size, and says so, rather than naming a side."""
    chaos = 0.0 if math.isnan(sigma_chaos) else sigma_chaos
    u_num = math.sqrt(u_solver ** 2 + chaos ** 2 + (chaos ** 2 / n_starts if n_starts else 0.0))
    u_val = math.sqrt(u_num ** 2 + u_input ** 2 + u_d ** 2)
    e = s - d
    words, excess = verdict(e, u_val, unit)
    sampling_error = u_input / math.sqrt(2 * (n_sample - 1)) if n_sample >= 2 else 0.0
    if sampling_error > 0 and undecided(e, u_num, u_input, u_d, sampling_error):
        words, excess = (f"undecided at {n_sample} sample points: the verdict turns within u_input's sampling error "
                         f"(+-{sampling_error:.4g}{unit_text(unit)})"), None
    return Comparison(d, s, e, u_solver, u_num, u_input, u_d, u_val, words, excess, sampling_error)


def none_if_nan(x):
    return None if x is None or (isinstance(x, float) and not math.isfinite(x)) else x


def clean(value):
    """NaN and infinity as JSON's null, through dicts and lists (summary.json is written with allow_nan=False)."""
    if isinstance(value, dict):
        return {k: clean(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [clean(v) for v in value]
    return none_if_nan(value)


def solver_uncertainty(ensemble, column):
    """(u_solver, what it is): |tight reference - nominal first start| where the tight run exists and defines the
    quantity, else 0 with the reason."""
    first = ensemble.first_start
    if ensemble.tight is None:
        return 0.0, "taken as 0: the study did not rerun the reference at tighter tolerances"
    tight, nominal = ensemble.tight.number(column), first.number(column)
    if math.isnan(tight) or math.isnan(nominal):
        return 0.0, "taken as 0: the tight rerun or the first start does not define the quantity"
    return abs(tight - nominal), f"|{ensemble.tight['job_id']} - {first['job_id']}|"


def sample_part(points, column):
    """The sample's side of a quantity: its values (NaN where a run is not ok or does not define it), and the entry's
    distribution, runs not ok and runs that leave it undefined."""
    y = np.asarray([p.value(column) for p in points], float)
    not_ok = [{"point": p.point, "scenario": p.scenario, "status": p.status, "reason": (p.run or {}).get("reason", "")}
              for p in points if p.status != validation_sample.OK]
    dist = distribution(y)
    return y, dist, {"sample": {**asdict(dist), "runs_not_ok": len(not_ok)}, "runs_not_ok": not_ok,
                     "not_defined": [p.scenario for p, v in zip(points, y) if p.status == validation_sample.OK
                                     and math.isnan(v)]}


def nominal_part(ensemble, column):
    """The nominal reference's side: its starts' values, their mean and sigma_chaos."""
    values = ensemble.values(column) if ensemble else []
    sigma, n = chaos_scatter([v for _, v in values])
    return {"law": ensemble.law if ensemble else None, "starts": len(ensemble.members) if ensemble else 0, "n": n,
            "mean": float(np.mean([v for _, v in values])) if values else None, "sigma_chaos": sigma,
            "values": [v for _, v in values], "job_ids": [j for j, _ in values],
            "left_out": ensemble.left_out(column) if ensemble else []}


def sensitivity_part(sample, points, y):
    """The inputs' first-order indices over the runs that define the quantity, ranked, with B and the noise floor."""
    defined = [i for i in range(len(points)) if math.isfinite(y[i])]
    inputs = {name: np.asarray([points[i].inputs[name] for i in defined]) for name in sample.input_names}
    ranked = ranked_indices(inputs, y[defined]) if len(defined) >= 4 else []
    return {"bins": bin_count(len(defined)) if ranked else None, "noise_floor": index_noise_floor(len(defined)),
            "ranked": [{"input": name, "index": index} for name, index in ranked]}


def limits(entry, dist, has_ensemble):
    """What the numbers cannot say, once each, the most telling reason first."""
    nominal = entry["nominal"]
    if not has_ensemble:
        return ["no nominal reference of this case in the study's runs.csv: the chaos is not separated"]
    if dist.n == 0:
        return ["no run of the sample defines it" + ("" if nominal["n"] else ", nor does the nominal reference")]
    if dist.n > 1 and dist.standard_deviation == 0:
        return ["the same value in every run of the sample: no input moves it"]
    notes = []
    if nominal["n"] < 2:
        notes.append("the nominal reference defines it in fewer than two starts: its chaotic scatter is not measured, "
                     "and u_input holds it")
    if entry["u_input"] == 0.0:
        notes.append("the sample spreads no more than one start's chaotic scatter: the inputs' effect is not resolved")
    if all(r["index"] is None for r in entry["sensitivity"]["ranked"]):
        notes.append("no sensitivity indices: fewer than four runs define it")
    return notes


def quantity_entry(sample, case, quantity, ensemble, experiment):
    """One case's quantity: the sample's distribution, the chaos kept apart, the indices, V&V 20 where measured."""
    points = sample.of_case(case)
    y, dist, entry = sample_part(points, quantity.column)
    entry = {"quantity": quantity.column, "label": quantity.label, "unit": quantity.unit, **entry,
             "nominal": nominal_part(ensemble, quantity.column)}
    sigma, n = entry["nominal"]["sigma_chaos"], entry["nominal"]["n"]
    variance = dist.standard_deviation ** 2 if dist.n > 1 else math.nan
    entry["u_input"] = input_uncertainty(variance, sigma) if dist.n > 1 else None
    entry["chaos_share"] = sigma ** 2 / variance if dist.n > 1 and variance > 0 and not math.isnan(sigma) else None
    entry["sensitivity"] = sensitivity_part(sample, points, y)
    notes = limits(entry, dist, ensemble is not None)
    measured = measurement(experiment, case, quantity)
    entry["measured"] = entry["vv20"] = None
    if measured is None:
        notes.append("not measured in the experiment: its distribution alone, no verdict")
    else:
        d, u_d, source = measured
        entry["measured"] = {"d": d, "u_d": u_d, "source": source}
        if entry["nominal"]["mean"] is None:
            notes.append(("the nominal reference does not define it" if ensemble else "no nominal reference") +
                         ": no simulated value to compare, no verdict")
        else:
            u_solver, solver_note = solver_uncertainty(ensemble, quantity.column)
            comparison = compare(entry["nominal"]["mean"], d, u_solver, sigma, n, entry["u_input"] or 0.0, u_d,
                                 quantity.unit, entry["sample"]["n"])
            entry["vv20"] = {**asdict(comparison), "u_solver_from": solver_note, "coverage": COVERAGE}
    entry["notes"] = notes
    return entry


def summarise_sample(sample, suite, experiment):
    """One validation folder's entry of summary.json's `validation`."""
    cases = []
    for case in sample.cases():
        ensemble = validation_sample.nominal_ensemble(suite, case, sample.law, sample)
        cases.append({"case": case, "points": len(sample.of_case(case)),
                      "nominal_job_ids": [r["job_id"] for r in ensemble.members] if ensemble else [],
                      "tight_job_id": ensemble.tight["job_id"] if ensemble and ensemble.tight is not None else None,
                      "quantities": [quantity_entry(sample, case, q, ensemble, experiment) for q in QUANTITIES]})
    return clean({"name": sample.name, "inputs_file": sample.inputs_file, "design": sample.design,
                  "sample_size": sample.points_declared or max((c["points"] for c in cases), default=0),
                  "law": sample.law, "inputs": sample.inputs, "input_names": sample.input_names, "cases": cases})


def summarise(suite, experiment):
    """summary.json's `validation`: one entry per OUT/validation/NAME/ folder; [] for a study without one (the
    report then adds no key)."""
    return [summarise_sample(validation_sample.read_sample(folder), suite, experiment)
            for folder in validation_sample.validation_folders(suite.folder)]
