"""Whether two runs had the same impact events, to a stated tolerance: the accuracy criterion of
bench/reference_cvode_scipy.py ("equal accuracy": each solver's events against a tight reference's) and of
the CVODE comparator's test. Reads events.csv in the harness's format (harness/records/run_files.h).

The errors, each over all events matched in order (the i-th against the i-th):
- event_count_difference: the number of events, minus the truth's (the criterion needs 0);
- onset_error_s, end_error_s: the largest |t - t_truth| of the onsets and of the ends [s];
- velocity_error: the largest |v - v_truth| of the approach and rebound velocities, over the truth's largest
  approach velocity [-] (relative to the scale of the impacts, so that a grazing contact does not divide
  by nearly zero);
- impulse_error: the largest |J - J_truth| over the truth's largest impulse [-] (shown, not in the criterion).
"""
import csv
import math


def read_events(path):
    """events.csv as a list of dicts of floats (NaN for an empty field)."""
    with open(path, encoding="utf-8", newline="") as f:
        rows = list(csv.DictReader(f))
    return [{k: float(v) if v != "" else math.nan for k, v in row.items()} for row in rows]


def errors(events, truth):
    """The errors above; the time and velocity ones are None when the counts differ (nothing to match)."""
    result = {"events": len(events), "events_truth": len(truth), "event_count_difference": len(events) - len(truth),
              "onset_error_s": None, "end_error_s": None, "velocity_error": None, "impulse_error": None}
    if len(events) != len(truth):
        return result
    if not truth:
        result.update(onset_error_s=0.0, end_error_s=0.0, velocity_error=0.0, impulse_error=0.0)
        return result
    speed = max(abs(e["approach_velocity_m_s"]) for e in truth) or 1.0
    impulse = max(abs(e["impulse_n_s"]) for e in truth) or 1.0
    result["onset_error_s"] = max(abs(a["onset_time_s"] - b["onset_time_s"]) for a, b in zip(events, truth))
    result["end_error_s"] = max(abs(a["end_time_s"] - b["end_time_s"]) for a, b in zip(events, truth))
    result["velocity_error"] = max(max(abs(a["approach_velocity_m_s"] - b["approach_velocity_m_s"]),
                                       abs(a["rebound_velocity_m_s"] - b["rebound_velocity_m_s"]))
                                   for a, b in zip(events, truth)) / speed
    result["impulse_error"] = max(abs(a["impulse_n_s"] - b["impulse_n_s"]) for a, b in zip(events, truth)) / impulse
    return result


def meets(error, time_tolerance_s, velocity_tolerance):
    """The criterion: the same number of events, every onset and end within time_tolerance_s, every approach
    and rebound velocity within velocity_tolerance of the impacts' scale."""
    return (error["event_count_difference"] == 0 and error["onset_error_s"] <= time_tolerance_s
            and error["end_error_s"] <= time_tolerance_s and error["velocity_error"] <= velocity_tolerance)
