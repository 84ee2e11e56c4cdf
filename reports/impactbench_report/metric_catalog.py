"""The metrics a run is scored on: the one list the report (impactbench_report) and compare (impactbench_compare)
read them from. Each is named as runs.csv names it (docs/results.md) and as the harness scores it
(harness/scoring/metrics.h, verdict.h):

- label: its name in the tables, the sentences and summary.json ("frame 1 sensor peak");
- column, unit: runs.csv's column of the metric (sweep.csv's too, where a sweep measures it) and its unit;
- error_column: runs.csv's column of its error, without the vs_reference_ / vs_chain_reference_ prefix
  (analysis.AGAINST);
- kind: how two values are compared: "relative" ((run - reference) / |reference|, a fraction) or "difference"
  (run - reference, absolute, in the metric's unit);
- tolerance_key: its tolerance's key in commands.jsonl's verdict_tolerances (verdict.h's AccuracyTolerances);
- better: which way is better; for every scored metric, the smaller |error| whatever its sign (the metric
  itself has no better direction: a larger peak is not better, a peak nearer the reference's is);
- figure_label: its panel's title in the error-against-cost figures, "" where it has no panel (HEADLINE);
- step_prefix: steps.csv's column prefix where the step search (--find-steps) searches its largest accurate
  step, "" where it does not (STEP_SEARCHED)."""

from dataclasses import dataclass

SMALLER_ERROR = "smaller |error|"


@dataclass(frozen=True)
class Metric:
    label: str
    column: str
    unit: str
    error_column: str
    kind: str
    tolerance_key: str
    better: str = SMALLER_ERROR
    figure_label: str = ""
    step_prefix: str = ""

    @property
    def step_tolerance_column(self):
        """steps.csv's column of the tolerance the step search judged this metric with."""
        return self.error_column + "_tolerance"


FRAME1_SENSOR_PEAK = Metric("frame 1 sensor peak", "frame1_sensor_peak_acceleration_g", "g",
                            "frame1_sensor_peak_relative_error", "relative", "sensor_peak_relative_error",
                            figure_label="sensor peak, frame 1", step_prefix="frame1_sensor_peak")
FRAME2_SENSOR_PEAK = Metric("frame 2 sensor peak", "frame2_sensor_peak_acceleration_g", "g",
                            "frame2_sensor_peak_relative_error", "relative", "sensor_peak_relative_error")
CONTACT_DURATION = Metric("contact duration", "contact_duration_mean_s", "s", "contact_duration_relative_error",
                          "relative", "contact_duration_relative_error", figure_label="contact duration",
                          step_prefix="contact_duration")
IMPACTS_PER_CYCLE = Metric("impacts per cycle", "impacts_per_cycle", "-", "impacts_per_cycle_difference",
                           "difference", "impacts_per_cycle_difference", figure_label="impacts per cycle",
                           step_prefix="impacts_per_cycle")
FRAME1_LOG_DECREMENT = Metric("frame 1 log decrement", "frame1_log_decrement", "-",
                              "frame1_log_decrement_relative_error", "relative", "log_decrement_relative_error")

# Every scored metric, in the order the tables, summary.json and compare list them.
SCORED = (FRAME1_SENSOR_PEAK, FRAME2_SENSOR_PEAK, CONTACT_DURATION, IMPACTS_PER_CYCLE, FRAME1_LOG_DECREMENT)
# The headline errors the error-against-cost figures draw, one panel each.
HEADLINE = tuple(m for m in SCORED if m.figure_label)
# The metrics whose largest accurate step the step search finds (steps.csv).
STEP_SEARCHED = tuple(m for m in SCORED if m.step_prefix)
# The metrics a frequency sweep measures (sweep.csv's columns, in its order): single, deterministic runs
# continued from ratio to ratio, without an error of their own (docs/sweeps.md).
SWEEP = (IMPACTS_PER_CYCLE, FRAME1_SENSOR_PEAK, FRAME2_SENSOR_PEAK, CONTACT_DURATION)

# The harness's verdict tolerances (harness/scoring/verdict.h), used only for a results folder that predates
# commands.jsonl (which states the tolerances its verdicts used).
DEFAULT_TOLERANCES = {"sensor_peak_relative_error": 0.10, "contact_duration_relative_error": 0.10,
                      "impacts_per_cycle_difference": 0.10, "log_decrement_relative_error": 0.10}


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

