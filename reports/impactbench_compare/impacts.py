"""Per-impact comparison: the distributions of each impact's contact duration, restitution and peak force,
not only their means and peaks. Two runs can agree on runs.csv's aggregates while their impacts differ
(a restitution that moved up in some impacts and down in others), and runs.csv would not say so.

Each run folder keeps events.csv (runs/<job id>/events.csv: onset_time_s, duration_s, restitution,
peak_force_n, ...; docs/results.md). For each configuration compared in both folders (stable in both, run
alike), the impacts with their onset in the scoring window, pooled over the ensemble's members, are compared
with the two-sample Kolmogorov-Smirnov test. A rerun of a chaotic case draws other impacts from the same
distribution, so every test of the comparison together is held to a family-wise error of FAMILY_ALPHA
(Holm's step-down over all of them): a distribution moved when its test is rejected. Values are compared
to ROUND_DIGITS significant digits, what events.csv's text holds of a number, so that deterministic reruns
(the same events to the bit) give no move whatever the last digit's rounding.

A moved distribution is a move, neutral: that impacts are now shorter is not by itself better or worse."""

import math
import os
from dataclasses import dataclass

import numpy as np
from scipy import stats

from impactbench_report import data

FAMILY_ALPHA = 0.01
ROUND_DIGITS = 9
# events.csv's columns compared, with their label
QUANTITIES = (("duration_s", "contact duration", "s"), ("restitution", "restitution", ""),
              ("peak_force_n", "peak force", "N"))


@dataclass
class ImpactChange:
    column: str
    label: str
    unit: str
    base_median: float
    new_median: float
    base_impacts: int
    new_impacts: int
    p_value: float
    tests: int = 0  # how many tests the family held (Holm)
    moved: bool = False

    def text(self):
        unit = f" {self.unit}" if self.unit else ""
        return (f"per-impact {self.label}: median {self.base_median:.4g} -> {self.new_median:.4g}{unit} "
                f"({self.base_impacts} -> {self.new_impacts} impacts; KS p = {self.p_value:.2g}, Holm over "
                f"{self.tests} tests at {FAMILY_ALPHA:g}): moved")


def rounded(values):
    values = np.asarray(values, float)
    values = values[np.isfinite(values)]
    if values.size == 0:
        return values
    scale = 10.0 ** (ROUND_DIGITS - 1 - np.floor(np.log10(np.where(values == 0, 1.0, np.abs(values)))))
    return np.round(values * scale) / scale


def window_events(folder, members):
    """{column: values} of the impacts with their onset in each member's scoring window, pooled; None when a
    member kept no events.csv."""
    pooled = {column: [] for column, _, _ in QUANTITIES}
    for run in members:
        path = os.path.join(folder.path, "runs", run["job_id"], "events.csv")
        if not os.path.exists(path):
            return None
        try:
            events = data.read_series(path)
        except data.ResultsError:
            return None  # a damaged events.csv: the aggregates in runs.csv are compared still
        onset = events.get("onset_time_s", np.empty(0))
        inside = (onset >= run.number("window_start_s")) & (onset <= run.number("window_end_s"))
        for column in pooled:
            if column in events:
                pooled[column].extend(events[column][inside])
    return {column: rounded(values) for column, values in pooled.items()}


def test_pair(base_events, new_events):
    """An ImpactChange per quantity both folders measured (p-values before Holm)."""
    found = []
    for column, label, unit in QUANTITIES:
        a, b = base_events[column], new_events[column]
        if a.size == 0 or b.size == 0:
            continue  # no impacts (or none with a peak force: a Newton impact) on a side
        same = a.size == b.size and np.array_equal(np.sort(a), np.sort(b))
        p = 1.0 if same else float(stats.ks_2samp(a, b).pvalue)
        found.append(ImpactChange(column, label, unit, float(np.median(a)), float(np.median(b)), a.size, b.size, p))
    return found


def holm(changes, alpha=FAMILY_ALPHA):
    """Marks the changes whose tests Holm's step-down rejects at family-wise `alpha`."""
    ordered = sorted(changes, key=lambda c: c.p_value)
    for c in changes:
        c.tests = len(changes)
    for i, c in enumerate(ordered):
        if math.isnan(c.p_value) or c.p_value > alpha / (len(ordered) - i):
            break
        c.moved = True


def compare(base, new, pairs):
    """pairs: [(ConfigurationChange, base members, new members)] compared; sets each change's `impacts` to
    its ImpactChanges and applies Holm over all of them."""
    every = []
    for change, base_members, new_members in pairs:
        a, b = window_events(base, base_members), window_events(new, new_members)
        if a is None or b is None:
            continue
        change.impacts = test_pair(a, b)
        every += change.impacts
    holm(every)
