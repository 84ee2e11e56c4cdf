"""What moved between two result folders, judged against the noise: each configuration's headline metrics
(and so its errors against the reference), its CPU cost, its verdicts; and the configurations that
appeared or disappeared.

The noise a metric's change is judged against, in this order:
- both folders ran the configuration as an ensemble: Welch's 95 % interval of the difference of the means;
- single runs of a case whose reference ran as an ensemble: the reference's scatter of one start (95 %
  prediction half-width) on each side, sqrt(2) of it for the difference of two single runs; but never a
  noise wider than the metric itself: where that noise exceeds |the base value|, or the metric is one the
  case needs an ensemble for (its one-start scatter above ENSEMBLE_NEED_FRACTION_OF_TOLERANCE of its
  default tolerance, ensembles.py's rule), the metric is "not judged" (listed, neither moved nor regressed);
- single runs and nothing measured: the runs are deterministic (the same build and inputs give the same
  numbers to the bit), so a change beyond rounding is a change.
The cost's noise: the spread of a run's repeated timings (--repeat) or of an ensemble's starts, and at least
COST_NOISE_FLOOR, the drift between identical runs on a shared machine; costs timed on other machines are
not comparable unless asked, and a run under MIN_TIMED_CPU_S is too short to time.

Before any of it: a configuration run otherwise in the two folders (alike.py) is not comparable, and one
unstable in both is compared by when and why (instability.py). After it: the per-impact distributions
(impacts.py), then each metric and configuration judged better or worse (judgement.py)."""

import math
from collections import Counter
from dataclasses import dataclass, field

from impactbench_report import ensemble_groups, ensembles, metric_catalog
from impactbench_report.ensembles import ENSEMBLE_NEED_FRACTION_OF_TOLERANCE, Interval

from . import alike, impacts, instability, judgement

# The relative drift of the same run's CPU time between two runs of a study on a shared machine: 15 to 30 %
# (docs/budgets.md). A smaller change of cost is not told apart from it without instruction counts.
COST_NOISE_FLOOR = 0.30
# A run shorter than this (CPU time of its stepping) is not timed well enough to judge its cost: the clock's
# resolution, start-up and caches weigh as much as the stepping.
MIN_TIMED_CPU_S = 0.1
# Two deterministic runs differ by rounding alone: a relative change below this is none.
ROUNDING = 1e-9
FAILING = ("unstable", "failed")


@dataclass
class MetricChange:
    label: str
    column: str
    kind: str  # "relative" (shown as a fraction of the base value) or "difference"
    base: float
    new: float
    change: float  # (new - base) / |base| for a relative metric, new - base for a difference
    noise: float  # the half-width the change is judged against, in the change's unit
    noise_method: str
    moved: bool
    not_judged: str = ""  # why the metric is not judged: a noise wider than itself (then not moved)
    base_errors: dict = field(default_factory=dict)  # {"beam", "own chain": signed error} (NaN where not defined)
    new_errors: dict = field(default_factory=dict)
    against: str = None  # the reference it is judged against (judgement.judged_against), None without an error
    judgement: str = ""  # judgement.judge_metric's


@dataclass
class CostChange:
    base_s_per_s: float  # CPU time per simulated second
    new_s_per_s: float
    ratio: float
    noise: float  # relative
    judgement: str  # "moved", "within the noise", or why it is not judged
    moved: bool = False


@dataclass
class ConfigurationChange:
    job_id: str  # member 0's: the configuration in both folders
    scenario: str
    law: str
    engine: str
    time_step_s: float
    options: str
    presence: str  # "both", "appeared" (in NEW only), "disappeared" (in BASE only)
    base_verdicts: dict = field(default_factory=dict)  # {verdict: members}
    new_verdicts: dict = field(default_factory=dict)
    newly_failing: bool = False
    metrics: list = field(default_factory=list)
    cost: CostChange = None
    not_comparable: list = field(default_factory=list)  # [(setting, base's, new's)] run otherwise (alike.py)
    instability: "instability.InstabilityChange" = None  # unstable in both folders: when and why
    impacts: list = field(default_factory=list)  # impacts.ImpactChange per per-impact distribution tested
    judgement: str = ""  # judgement.judge_configuration's
    why: str = ""  # why a configuration disappeared

    @property
    def moved_metrics(self):
        return [m for m in self.metrics if m.moved]

    @property
    def not_judged_metrics(self):
        return [m for m in self.metrics if m.not_judged]

    @property
    def moved_impacts(self):
        return [i for i in self.impacts if i.moved]

    @property
    def verdicts_changed(self):
        return self.presence == "both" and not self.not_comparable and self.base_verdicts != self.new_verdicts

    @property
    def moved(self):
        if self.not_comparable:
            return False
        return (self.presence != "both" or self.verdicts_changed or bool(self.moved_metrics)
                or (self.cost is not None and self.cost.moved) or bool(self.moved_impacts)
                or (self.instability is not None and self.instability.moved))


def metric_interval(run, column):
    """A configuration's metric: its ensemble's Interval, or the run's own value (a single run)."""
    ensemble = run.ensemble
    if ensemble is not None and ensemble.n > 1 and column in ensemble.metrics:
        return ensemble.metrics[column]
    return Interval(run.number(column), 1, "single run")


def case_noise(suite):
    """{(scenario, law): the case's beam reference intervals {metric column: Interval}}, read once per case."""
    cases = {}
    for run in suite.runs:
        key = (run["scenario"], run["law"])
        if key not in cases:
            cases[key] = ensemble_groups.reference_intervals(suite, *key)[1]
    return cases


@dataclass
class SingleRunNoise:
    half_width: float  # the reference's one-start scatter, absolute, around its mean
    needs_ensemble: bool  # the case needs an ensemble for this metric (ensembles.py's rule)


def single_run_noise(cases, run, metric):
    """The reference's one-start scatter of a metric in the run's case (cases: case_noise) as a
    SingleRunNoise; None when the case's reference ran once."""
    interval = cases.get((run["scenario"], run["law"]), {}).get(metric.column)
    half = ensembles.single_run_noise(interval, metric.kind) if interval is not None else None
    if half is None:
        return None
    tolerance = metric_catalog.DEFAULT_TOLERANCES.get(metric.tolerance_key, math.inf)
    needs = half > ENSEMBLE_NEED_FRACTION_OF_TOLERANCE * tolerance
    return SingleRunNoise(half * abs(interval.mean) if metric.kind == "relative" else half, needs)


def noise_text(kind, half_width):
    return f"±{100 * half_width:.3g} %" if kind == "relative" else f"±{half_width:.3g}"


def judge(label, column, kind, a, b, single_runs=()):
    """A metric's change from Interval a to Interval b against its noise (the module's rules, in order);
    single_runs: the cases' SingleRunNoise where the runs are single. None when neither has it."""
    if math.isnan(a.mean) and math.isnan(b.mean):
        return None
    if math.isnan(a.mean) != math.isnan(b.mean):  # measured in one folder only (impacts that stopped, say)
        return MetricChange(label, column, kind, a.mean, b.mean, math.nan, 0.0, "defined in one folder only", True)
    scale = abs(a.mean) if kind == "relative" and a.mean else 1.0
    change = (b.mean - a.mean) / scale
    difference = ensembles.welch_difference(b, a)
    single_runs = [s for s in single_runs if s is not None]
    if difference is not None:
        noise, method = difference.half_width / scale, "the ensembles' 95 % intervals (Welch)"
    elif single_runs:
        half = math.sqrt(2) * max(s.half_width for s in single_runs)
        noise, method = half / scale, "the reference's one-start scatter, for two single runs (95 %)"
        if half > abs(a.mean) or any(s.needs_ensemble for s in single_runs):  # a noise wider than the metric
            why = (f"not judged: a single run of a case that needs an ensemble (noise {noise_text(kind, noise)})"
                   if any(s.needs_ensemble for s in single_runs) else
                   f"not judged: a single run whose noise is wider than the metric (noise {noise_text(kind, noise)})")
            return MetricChange(label, column, kind, a.mean, b.mean, change, noise, method, False, why)
    else:
        noise = ROUNDING * max(abs(a.mean), abs(b.mean)) / scale
        method = "none measured: deterministic single runs, any change beyond rounding"
    return MetricChange(label, column, kind, a.mean, b.mean, change, noise, method, abs(change) > noise)


def judge_metric(base_cases, base_run, new_cases, new_run, metric):
    a, b = metric_interval(base_run, metric.column), metric_interval(new_run, metric.column)
    single_runs = (single_run_noise(base_cases, base_run, metric), single_run_noise(new_cases, new_run, metric))
    change = judge(metric.label, metric.column, metric.kind, a, b, single_runs)
    if change is not None:
        change.base_errors = judgement.errors(base_run, metric.error_column)
        change.new_errors = judgement.errors(new_run, metric.error_column)
        change.against = judgement.judged_against(change.base_errors, change.new_errors)
    return change


def run_cost(suite, run):
    """(CPU time per simulated second, the CPU time of the stepping, the relative spread of its timings:
    repeated timings of the run, or the ensemble's starts; 0 when it was timed once)."""
    value = run.number("cpu_time_per_simulated_s")
    spread = 0.0
    low, high = run.number("cpu_time_min_s"), run.number("cpu_time_max_s")
    if run.number("timed_runs") >= 2 and low > 0 and high >= low:
        spread = (high - low) / low
    members = [m.number("cpu_time_per_simulated_s") for m in suite.members.get(run["job_id"], [run])]
    members = [m for m in members if m > 0]
    if len(members) >= 2:
        spread = max(spread, (max(members) - min(members)) / min(members))
    return value, run.number("cpu_time_s"), spread


def judge_cost(base, new, comparable, floor):
    """The cost's change from base to new, each (CPU s per simulated s, CPU s, relative spread)."""
    (a, cpu_a, spread_a), (b, cpu_b, spread_b) = base, new
    if not (a > 0 and b > 0):
        return CostChange(a, b, math.nan, math.nan, "not timed in both folders")
    if min(cpu_a, cpu_b) < MIN_TIMED_CPU_S:
        return CostChange(a, b, b / a, math.nan, f"too short to time (under {MIN_TIMED_CPU_S:g} s of CPU)")
    noise = max(spread_a, spread_b, floor)
    ratio = b / a
    if not comparable:
        return CostChange(a, b, ratio, noise, "not comparable: timed on other machines (--cost-across-machines compares them)")
    moved = abs(ratio - 1) > noise
    return CostChange(a, b, ratio, noise, "moved" if moved else "within the noise", moved)


def verdict_counts(suite, run):
    return dict(Counter(m["verdict"] for m in suite.members.get(run["job_id"], [run])))


def configuration(run, presence):
    return ConfigurationChange(run["job_id"], run["scenario"], run["law"], run["engine"], run.number("time_step_s"),
                               run["options"], presence)


ORDER = {judgement.REGRESSED: 0, judgement.IMPROVED: 1, judgement.MOVED: 2, "appeared": 2, "not comparable": 3}


def compare(base, new, comparable_cost, cost_floor=COST_NOISE_FLOOR):
    """Every configuration of either folder (folders.ResultFolder) as a ConfigurationChange, judged: the
    regressed first, then the improved, the other moves, the not comparable, the rest. The suite's runs,
    then each sweep's rows."""
    settings = alike.Settings(base, new)
    found = compare_runs(base, new, comparable_cost, cost_floor, settings) if base.suite and new.suite else []
    for prefix in sorted(set(base.sweeps) | set(new.sweeps)):
        a, b = base.sweeps.get(prefix), new.sweeps.get(prefix)
        not_comparable = settings.of_sweeps(a, b) if a and b else []
        found += compare_sweep_rows(prefix, a, b, comparable_cost, cost_floor, not_comparable)
    judgement.judge_all(found, new)
    found.sort(key=lambda c: (ORDER.get(c.judgement, 4), c.job_id))
    return found


def sweep_cost(row):
    """A sweep row's (CPU s per simulated s, CPU s, spread): timed once."""
    return (row["cpu_time_s"] / row["duration_s"] if row["duration_s"] > 0 else math.nan), row["cpu_time_s"], 0.0


def sweep_verdict(row):
    return {f"{row['verdict']}, {row['regime'] or 'no regime'}": 1} if row else {}


def compare_sweep_rows(prefix, base_sweep, new_sweep, comparable, floor, not_comparable):
    """Each row of a sweep (an id: configuration, start and ratio) as a ConfigurationChange; its regime is part
    of its verdict (a row that changed regime moved). Its metrics are sweep.csv's measured numbers
    (metric_catalog.SWEEP): single, deterministic runs continued from ratio to ratio."""
    rows_a = {r["id"]: r for r in base_sweep.rows} if base_sweep else {}
    rows_b = {r["id"]: r for r in new_sweep.rows} if new_sweep else {}
    found = []
    for row_id in sorted(set(rows_a) | set(rows_b)):
        a, b = rows_a.get(row_id), rows_b.get(row_id)
        row = a or b
        presence = "both" if a and b else ("disappeared" if a else "appeared")
        change = ConfigurationChange(prefix + row_id, row["scenario"], row["law"], row["engine"], row["time_step_s"],
                                     row["options"], presence)
        change.base_verdicts, change.new_verdicts = sweep_verdict(a), sweep_verdict(b)
        change.newly_failing = bool(b) and b["verdict"] in FAILING and not (a and a["verdict"] in FAILING)
        change.not_comparable = list(not_comparable) if a and b else []
        if a and b and not change.not_comparable:
            metrics = (judge(m.label, m.column, m.kind, Interval(a.get(m.column, math.nan), 1, "single run"),
                             Interval(b.get(m.column, math.nan), 1, "single run")) for m in metric_catalog.SWEEP)
            change.metrics = [m for m in metrics if m is not None]
            change.cost = judge_cost(sweep_cost(a), sweep_cost(b), comparable, floor)
        found.append(change)
    return found


def one_side(base, new, a, b):
    """A configuration in one folder only."""
    change = configuration(a or b, "disappeared" if b is None else "appeared")
    if a is not None:
        change.base_verdicts = verdict_counts(base.suite, a)
    if b is not None:
        change.new_verdicts = verdict_counts(new.suite, b)
        change.newly_failing = any(v in FAILING for v in change.new_verdicts)
    return change


def stable_members(suite, run):
    """The members whose impacts mean something: every member of a reference, the stable ones of an engine."""
    return [m for m in suite.members.get(run["job_id"], [run]) if run["engine"] == "reference" or m.stable]


def in_both(base, new, a, b, cases, comparable_cost, cost_floor):
    """A configuration in both folders, run alike: its metrics, instability and cost judged against their noise."""
    change = configuration(a, "both")
    change.base_verdicts, change.new_verdicts = verdict_counts(base.suite, a), verdict_counts(new.suite, b)
    change.newly_failing = (sum(n for v, n in change.new_verdicts.items() if v in FAILING) >
                            sum(n for v, n in change.base_verdicts.items() if v in FAILING))
    change.instability = instability.compare(base.suite.members.get(a["job_id"], [a]),
                                             new.suite.members.get(b["job_id"], [b]))
    if a.stable or b.stable or a["engine"] == "reference":
        metrics = (judge_metric(cases[0], a, cases[1], b, m) for m in metric_catalog.SCORED)
        change.metrics = [m for m in metrics if m is not None]
    change.cost = judge_cost(run_cost(base.suite, a), run_cost(new.suite, b), comparable_cost, cost_floor)
    return change


def compare_runs(base, new, comparable_cost, cost_floor, settings):
    """Each suite configuration of either folder; the per-impact distributions of those stable in both."""
    base_runs = {r["job_id"]: r for r in base.suite.runs if r["engine"]}
    new_runs = {r["job_id"]: r for r in new.suite.runs if r["engine"]}
    cases = case_noise(base.suite), case_noise(new.suite)
    found, impact_pairs = [], []
    for job_id in sorted(set(base_runs) | set(new_runs)):
        a, b = base_runs.get(job_id), new_runs.get(job_id)
        if a is None or b is None:
            found.append(one_side(base, new, a, b))
            continue
        not_comparable = settings.of_runs(a, b)
        if not_comparable:
            change = configuration(a, "both")
            change.base_verdicts, change.new_verdicts = verdict_counts(base.suite, a), verdict_counts(new.suite, b)
            change.not_comparable = not_comparable
            found.append(change)
            continue
        found.append(in_both(base, new, a, b, cases, comparable_cost, cost_floor))
        members = stable_members(base.suite, a), stable_members(new.suite, b)
        if all(members):
            impact_pairs.append((found[-1], *members))
    impacts.compare(base, new, impact_pairs)
    return found
