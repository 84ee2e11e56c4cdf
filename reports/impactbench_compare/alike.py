"""Like with like: whether two folders, and each configuration in both, were run the same way, so that what
differs between their numbers is the engine's doing and not the settings'.

Two folders of different kinds (a suite's or a study's folder, with runs.csv, against a sweep's folder) are
not compared at all: refuse() raises a CompareInputError naming both kinds. A configuration in both folders
that was run differently is "not comparable": it is listed with each setting that differs and its two values,
and counts as neither moved nor regressed. The settings, and where each is recorded:

- duration_s, the simulated time (runs.csv, after a --duration cut);
- window_s, the scoring window's length (runs.csv: window_end_s - window_start_s);
- ensemble, the configuration's members (runs.csv rows of one configuration) and the reference ensemble,
  the members of its case's beam reference: ensembles' means are not single runs, nor other ensembles;
- output_rate_hz, the rate the series is sampled and measured at (runs.csv);
- sensor_rate_hz and merge_window_s, how the sensor peaks and the impacts are read (suite.jsonl's settings
  record of the part whose scenario_files hold the run's scenario file).

A sweep's rows share their sweep's settings (sweep.json): the durations, window, reference ensemble and
rates above. series_rate_hz is not among them: it thins the series file a run keeps, never runs.csv."""

import json
import math
import os

from .folders import CompareInputError

# sweep.json's keys that decide a sweep's numbers (harness/sweep/sweep_runner.cpp, settings_record)
SWEEP_SETTINGS = ("continuation_duration_s", "rest_duration_s", "window_s", "reference_ensemble_starts",
                  "output_rate_hz", "sensor_rate_hz", "merge_window_s")
# suite.jsonl's keys, per part, that decide how a run is measured and that runs.csv does not hold
PART_SETTINGS = ("sensor_rate_hz", "merge_window_s")
# two numbers read back from text are the same setting when they agree to this (runs.csv keeps 9 digits)
SAME = 1e-9


def kind_of(folder):
    return "a sweep's folder (sweep.json)" if folder.suite is None else "a suite's or a study's folder (runs.csv)"


def refuse(base, new):
    """CompareInputError (exit 2) for folders of different kinds: their configurations are of other kinds."""
    if (base.suite is None) != (new.suite is None):
        raise CompareInputError(f"{base.path} is {kind_of(base)}, {new.path} is {kind_of(new)}: folders of different "
                                "kinds are not comparable (compare a suite with a suite, a sweep with a sweep)")


def part_settings(folder):
    """{scenario file: its part's settings record} from suite.jsonl (a later part's record of a file wins, as
    the suite's own resume does); {} without suite.jsonl. A line cut short by a kill is skipped."""
    path = os.path.join(folder.path, "suite.jsonl")
    found = {}
    if not os.path.exists(path):
        return found
    with open(path) as f:
        lines = f.read().split("\n")[:-1]  # the part after the last line break is cut short
    for line in lines:
        try:
            record = json.loads(line)
        except json.JSONDecodeError:
            continue  # folders.read_folder has named a damaged line already
        settings = record.get("settings", {}) if isinstance(record, dict) else {}
        for name in settings.get("scenario_files", {}) or {}:
            found[name] = settings
    return found


def members(suite, run):
    return len(suite.members.get(run["job_id"], [run]))


def reference_members(suite, run):
    """The members of the run's case's beam reference ensemble, 0 without one."""
    reference = suite.beam_reference(run["scenario"], run["law"])
    return 0 if reference is None else members(suite, reference)


def run_settings(folder, parts, run):
    """{setting: value} of a suite's run as alike compares them (the module's list)."""
    settings = {"duration_s": run.number("duration_s"),
                "window_s": run.number("window_end_s") - run.number("window_start_s"),
                "ensemble members": members(folder.suite, run),
                "reference ensemble": reference_members(folder.suite, run),
                "output_rate_hz": run.number("output_rate_hz")}
    part = parts.get(run["scenario_file"], {}) if "scenario_file" in run.values else {}
    settings.update({key: part[key] for key in PART_SETTINGS if key in part})
    return settings


def same(a, b):
    if isinstance(a, (int, float)) and isinstance(b, (int, float)):
        if math.isnan(a) and math.isnan(b):
            return True
        return abs(a - b) <= SAME * max(abs(a), abs(b))
    return a == b


def value_text(x):
    if isinstance(x, float):
        return "none" if math.isnan(x) else f"{x:g}"
    return str(x)


def differing(a, b):
    """[(setting, base's, new's)] of the settings two dicts both record with other values; a setting one of
    them does not record (an older folder) is not a difference."""
    return [(key, value_text(a[key]), value_text(b[key])) for key in a if key in b and not same(a[key], b[key])]


class Settings:
    """Each folder's settings, read once, and the differences of a configuration in both."""

    def __init__(self, base, new):
        self.base, self.new = base, new
        self.base_parts, self.new_parts = part_settings(base), part_settings(new)

    def of_runs(self, a, b):
        return differing(run_settings(self.base, self.base_parts, a), run_settings(self.new, self.new_parts, b))

    def of_sweeps(self, base_sweep, new_sweep):
        a = {key: base_sweep.settings[key] for key in SWEEP_SETTINGS if key in base_sweep.settings}
        b = {key: new_sweep.settings[key] for key in SWEEP_SETTINGS if key in new_sweep.settings}
        if "window_s" in a or "window_s" in b:  # absent: the scenario's, which the digests compare
            a.setdefault("window_s", None)
            b.setdefault("window_s", None)
        if "reference_ensemble_starts" in a or "reference_ensemble_starts" in b:  # absent: a single start
            a.setdefault("reference_ensemble_starts", 1)
            b.setdefault("reference_ensemble_starts", 1)
        return differing(a, b)


def differences_text(found):
    """'duration_s 1 vs 0.2; reference ensemble 3 vs 1'."""
    return "; ".join(f"{what} {a} vs {b}" for what, a, b in found)


def folder_differences(changes):
    """What differs in how the folders were run, over their configurations in both: [(what, base's, new's)]
    with how many configurations each difference holds for, for the list of what differs between the folders
    (a whole folder run otherwise must not read "made alike")."""
    both = [c for c in changes if c.presence == "both"]
    counts = {}
    for c in both:
        for difference in c.not_comparable:
            counts[difference] = counts.get(difference, 0) + 1
    return [(f"run differently: {what} (" + ("every configuration" if n == len(both) else f"{n} of {len(both)} "
                                             "configurations") + ")", a, b)
            for (what, a, b), n in sorted(counts.items(), key=lambda kv: -kv[1])]


def nothing_alike(changes):
    """Whether the folders share configurations and none of them was run alike: a whole folder run otherwise
    (every run 1 s against 0.2 s), which compare refuses after listing it."""
    both = [c for c in changes if c.presence == "both"]
    return bool(both) and all(c.not_comparable for c in both)
