"""The metrics a run is scored on, as the folder's metrics.json lists them: the one list the report
(impactbench_report) and compare (impactbench_compare) read them from. The harness writes metrics.json into every
suite and sweep folder from its catalog (harness/scoring/metric_catalog.h, docs/results.md#metricsjson); each
metric is named as runs.csv names it:

- name: its key ("frame1_sensor_peak"), steps.csv's column prefix where the step search searches it;
- label: its name in the tables, the sentences and summary.json ("frame 1 sensor peak");
- column, unit: runs.csv's column of the metric (sweep.csv's too, where a sweep measures it) and its unit;
- error_column: runs.csv's column of its error, without the reference's prefix (vs_reference_ for the beam,
  vs_chain_reference_ for the engine's own chain: scored_against, analysis.AGAINST);
- kind: how two values are compared: "relative" ((run - reference) / |reference|, a fraction) or "difference"
  (run - reference, absolute, in the metric's unit);
- tolerance_key, default_tolerance: its tolerance's key in commands.jsonl's verdict_tolerances (which holds the
  tolerances each command judged with) and the harness's default;
- better: which way is better; for every scored metric, the smaller |error| whatever its sign;
- step_searched: whether the step search (--find-steps) searches its largest accurate step (steps.csv).

Presentation stays here: figure_label, its panel's title in the error-against-cost figures ("" where it has no
panel, HEADLINE), and SWEEP_NAMES, the scored metrics sweep.csv holds, in its order.

use(folder) makes a folder's catalog the one every later call reads (the report reads one folder; compare the
metrics every folder has); before any use(), and for a folder made before metrics.json, the catalog is
CATALOG_OF_FOLDERS_WITHOUT_METRICS_JSON."""

import json
import os
from dataclasses import dataclass

SMALLER_ERROR = "smaller |error|"


@dataclass(frozen=True)
class Metric:
    name: str
    label: str
    column: str
    unit: str
    error_column: str
    kind: str
    tolerance_key: str
    default_tolerance: float
    better: str = SMALLER_ERROR
    scored_against: tuple = ("beam", "own chain")
    step_searched: bool = False
    figure_label: str = ""

    @property
    def step_prefix(self):
        """steps.csv's column prefix of the metric's search, "" where it is not searched."""
        return self.name if self.step_searched else ""

    @property
    def step_tolerance_column(self):
        """steps.csv's column of the tolerance the step search judged this metric with."""
        return self.error_column + "_tolerance"


# The one fallback, for a folder made before metrics.json existed: the metrics.json the harness would have written
# into it, its metrics the ones such a folder was scored on (reports/tests/test_metrics_file.py checks it against
# what the current binary writes; a metric added since is in no such folder, and is not listed here).
CATALOG_OF_FOLDERS_WITHOUT_METRICS_JSON = {
    "tolerances": "default_tolerance is the harness's default; the tolerances each command's verdicts used are its "
                  "line's verdict_tolerances in commands.jsonl",
    "references": [
        {"name": "beam", "error_prefix": "vs_reference_",
         "meaning": "the analytical reference on the beam (reference/): the whole error a user sees"},
        {"name": "own chain", "error_prefix": "vs_chain_reference_",
         "meaning": "the reference on the engine's own K-link chain: the engine's contact handling and time stepping "
                    "alone; the verdict judges against it where there is one, against the beam otherwise"}],
    "metrics": [
        {"name": "frame1_sensor_peak", "label": "frame 1 sensor peak", "column": "frame1_sensor_peak_acceleration_g",
         "unit": "g", "error_column": "frame1_sensor_peak_relative_error", "kind": "relative",
         "tolerance_key": "sensor_peak_relative_error", "default_tolerance": 0.1, "better": SMALLER_ERROR,
         "scored_against": ["beam", "own chain"], "step_searched": True},
        {"name": "frame2_sensor_peak", "label": "frame 2 sensor peak", "column": "frame2_sensor_peak_acceleration_g",
         "unit": "g", "error_column": "frame2_sensor_peak_relative_error", "kind": "relative",
         "tolerance_key": "sensor_peak_relative_error", "default_tolerance": 0.1, "better": SMALLER_ERROR,
         "scored_against": ["beam", "own chain"], "step_searched": False},
        {"name": "contact_duration", "label": "contact duration", "column": "contact_duration_mean_s", "unit": "s",
         "error_column": "contact_duration_relative_error", "kind": "relative",
         "tolerance_key": "contact_duration_relative_error", "default_tolerance": 0.1, "better": SMALLER_ERROR,
         "scored_against": ["beam", "own chain"], "step_searched": True},
        {"name": "impacts_per_cycle", "label": "impacts per cycle", "column": "impacts_per_cycle", "unit": "-",
         "error_column": "impacts_per_cycle_difference", "kind": "difference",
         "tolerance_key": "impacts_per_cycle_difference", "default_tolerance": 0.1, "better": SMALLER_ERROR,
         "scored_against": ["beam", "own chain"], "step_searched": True},
        {"name": "frame1_log_decrement", "label": "frame 1 log decrement", "column": "frame1_log_decrement",
         "unit": "-", "error_column": "frame1_log_decrement_relative_error", "kind": "relative",
         "tolerance_key": "log_decrement_relative_error", "default_tolerance": 0.1, "better": SMALLER_ERROR,
         "scored_against": ["beam", "own chain"], "step_searched": False}]}

# Presentation: each headline metric's panel title in the error-against-cost figures.
FIGURE_LABELS = {"frame1_sensor_peak": "sensor peak, frame 1", "contact_duration": "contact duration",
                 "impacts_per_cycle": "impacts per cycle"}
# The scored metrics a frequency sweep measures (sweep.csv's columns, in its order): single, deterministic runs
# continued from ratio to ratio, without an error of their own (docs/sweeps.md).
SWEEP_NAMES = ("impacts_per_cycle", "frame1_sensor_peak", "frame2_sensor_peak", "contact_duration")


class MetricsFileError(ValueError):
    """A metrics.json that cannot be read: the message names the file and what is wrong."""


def metrics_of(document):
    """The Metric records of a metrics.json document, in its order."""
    return tuple(Metric(m["name"], m["label"], m["column"], m["unit"], m["error_column"], m["kind"],
                        m["tolerance_key"], float(m["default_tolerance"]), m["better"], tuple(m["scored_against"]),
                        bool(m["step_searched"]), FIGURE_LABELS.get(m["name"], ""))
                 for m in document["metrics"])


def load(folder):
    """The scored metrics of a result folder: its metrics.json's, or the fallback's for a folder without one;
    MetricsFileError for a metrics.json that cannot be read (a wrong vocabulary must not score silently)."""
    path = os.path.join(folder, "metrics.json")
    if not os.path.exists(path):
        return metrics_of(CATALOG_OF_FOLDERS_WITHOUT_METRICS_JSON)
    try:
        with open(path) as f:
            return metrics_of(json.load(f))
    except (OSError, ValueError, KeyError, TypeError) as e:
        raise MetricsFileError(f"{path}: not a metrics.json the report can read ({type(e).__name__}: {e})") from None


SCORED = HEADLINE = STEP_SEARCHED = SWEEP = ()
DEFAULT_TOLERANCES = {}


def _set(metrics):
    """Every scored metric in the order the tables, summary.json and compare list them, and the views of it: the
    headline errors the error-against-cost figures draw (HEADLINE), the step search's (STEP_SEARCHED), the sweep's
    (SWEEP), and the default tolerances, used for a folder whose commands.jsonl states none."""
    global SCORED, HEADLINE, STEP_SEARCHED, SWEEP, DEFAULT_TOLERANCES
    SCORED = tuple(metrics)
    HEADLINE = tuple(m for m in SCORED if m.figure_label)
    STEP_SEARCHED = tuple(m for m in SCORED if m.step_searched)
    SWEEP = tuple(m for name in SWEEP_NAMES for m in SCORED if m.name == name)
    DEFAULT_TOLERANCES = {m.tolerance_key: m.default_tolerance for m in SCORED}


def use(*folders):
    """Makes the metrics every folder's catalog has (in the first's order) the ones every later call reads."""
    catalogs = [load(folder) for folder in folders]
    common = [m for m in catalogs[0] if all(any(o.name == m.name for o in c) for c in catalogs[1:])]
    _set(common)


_set(metrics_of(CATALOG_OF_FOLDERS_WITHOUT_METRICS_JSON))


def by_name(name):
    """The scored metric of a name ("impacts_per_cycle"); KeyError for another."""
    found = next((m for m in SCORED if m.name == name), None)
    if found is None:
        raise KeyError(f"no scored metric is called {name!r} in this folder's metrics.json")
    return found


def by_label(label):
    """The scored metric of a label; KeyError for another."""
    found = next((m for m in SCORED if m.label == label), None)
    if found is None:
        raise KeyError(f"no scored metric is called {label!r}")
    return found


def by_error_column(column):
    """The scored metric of an error column (with or without its vs_reference_ / vs_chain_reference_ prefix);
    None for another column."""
    return next((m for m in SCORED if column.endswith(m.error_column)), None)
