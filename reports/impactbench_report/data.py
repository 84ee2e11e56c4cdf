"""Reading a suite's results: runs.csv rows as plain records, the series of a run, the experiment."""

import csv
import gzip
import io
import json
import math
import os
import tomllib
from dataclasses import dataclass, field

import numpy as np

from . import engines, metric_catalog

G = 9.80665  # standard gravity [m/s^2]
# The verdicts of a run that gave a usable trajectory (an unstable or failed one did not).
STABLE_VERDICTS = ("ok", "inaccurate")

# runs.csv columns that are text; every other column is a number (empty: not applicable).
TEXT_COLUMNS = {"job_id", "scenario", "law", "engine", "options", "contact_path", "law_simulated", "same_run_as", "verdict",
                "reason", "scenario_file", "engine_version"}


@dataclass
class Record:
    """One row of a results CSV with numbers as floats (NaN where empty)."""
    values: dict

    def __getitem__(self, name):
        return self.values[name]

    def number(self, name):
        value = self.values.get(name, math.nan)
        return value if isinstance(value, float) else math.nan

    @property
    def config(self):
        """The engine and its options: one curve of the error-against-cost plots."""
        options = self.values["options"]
        return self.values["engine"] + (f" [{options}]" if options else "")


class Run(Record):
    """One row of runs.csv; `ensemble` (ensemble_groups.Ensemble) where it stands for an ensemble's members."""
    ensemble = None

    @property
    def is_beam_reference(self):
        return self.values["engine"] == "reference" and self.values["options"] == ""

    @property
    def stable(self):
        return self.values["verdict"] in STABLE_VERDICTS


@dataclass
class Suite:
    folder: str
    runs: list = field(default_factory=list)  # one run per configuration: an ensemble's member 0
    members: dict = field(default_factory=dict)  # a run's job id -> its ensemble's members, by start
    _records: dict = None  # runs.jsonl by job id, read on first use

    def record(self, run):
        """A run's full record from runs.jsonl (its diagnostics: the settings the engine used, the
        reference's frequencies and energy ledger), or {} when runs.jsonl does not hold it."""
        if self._records is None:
            self._records = {}
            path = os.path.join(self.folder, "runs.jsonl")
            if os.path.exists(path):
                with open(path) as f:
                    for line in f:
                        try:
                            record = json.loads(line)
                        except json.JSONDecodeError:
                            continue  # a cut last line: runs.csv is the report's source of truth
                        self._records[record.get("job_id", "")] = record
        return self._records.get(run["job_id"], {})

    def diagnostics(self, run):
        return self.record(run).get("diagnostics") or {}

    def warnings(self, run):
        """What the suite warned about a run (runs.jsonl "warnings": a scoring window inside the start-up
        transient), [] when nothing (or a runs.jsonl older than the field)."""
        return [w for w in self.record(run).get("warnings") or [] if isinstance(w, str)]

    def motor_frequency_hz(self, scenario):
        """The motor's frequency in a case (the beam reference reports it), NaN without a motor or a
        reference run."""
        for law in sorted({r["law"] for r in self.runs if r["scenario"] == scenario}):
            reference = self.beam_reference(scenario, law)
            if reference is not None:
                value = self.diagnostics(reference).get("motor_frequency_hz")
                return float(value) if value else math.nan
        return math.nan

    def has_series(self, run, name="series.csv"):
        """Whether a run kept its series (a step-search probe or --series none keeps none)."""
        path = os.path.join(self.folder, "runs", run["job_id"], name)
        return os.path.exists(path + ".gz") or os.path.exists(path)

    def events(self, run):
        """A run's contact episodes (events.csv: onset, end, duration, approach and rebound velocity,
        restitution, peak force, impulse, indentation) as a dict of column -> list of floats; None when
        the run kept none."""
        path = os.path.join(self.folder, "runs", run["job_id"], "events.csv")
        return read_series(path) if os.path.exists(path) else None

    def cases(self):
        """(scenario, law) pairs in a stable order: published cases first."""
        order = ["resonance", "post_resonance", "pre_resonance", "free_vibration"]
        # a law the scenario has no parameters for is recorded with no engine: not a case to draw
        pairs = sorted({(r["scenario"], r["law"]) for r in self.runs if r["scenario"] and r["law"] and r["engine"]},
                       key=lambda p: (order.index(p[0]) if p[0] in order else len(order), p[0], p[1]))
        return pairs

    def runs_of(self, scenario, law):
        return [r for r in self.runs if r["scenario"] == scenario and r["law"] == law]

    def beam_reference(self, scenario, law):
        for r in self.runs_of(scenario, law):
            if r.is_beam_reference:
                return r
        return None

    def series(self, run, name="series.csv"):
        """A run's sampled series (series.csv.gz, or series.csv in older folders), or its strongest impact
        finely resolved (impact.csv.gz); None when the run kept none (--series none, a step-search probe)."""
        path = os.path.join(self.folder, "runs", run["job_id"], name)
        for candidate in (path + ".gz", path):
            if os.path.exists(candidate):
                return read_series(candidate)
        return None


class ResultsError(ValueError):
    """A runs.csv the report cannot read: the message names the file, the line, the column and the value."""


def read_runs(folder):
    """The rows of runs.csv, sorted by job id: the report does not depend on the order in which jobs
    finished (parallel workers, a suite interrupted and resumed)."""
    path = os.path.join(folder, "runs.csv")
    engines.use(folder)  # the names, colours and settings keys of the engines that made these runs
    try:
        metric_catalog.use(folder)  # and the metrics they were scored on (metrics.json)
    except metric_catalog.MetricsFileError as e:
        raise ResultsError(str(e)) from None
    suite = Suite(folder)
    seen = {}  # job id -> line
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        if not reader.fieldnames or "job_id" not in reader.fieldnames:
            raise ResultsError(f"{path}:1: no header with job_id (is this a suite's runs.csv?)")
        for row in reader:
            line = reader.line_num
            if None in row or any(text is None for text in row.values()):
                raise ResultsError(f"{path}:{line}: not the header's {len(reader.fieldnames)} columns: a cut or "
                                   "garbled row (`impactbench suite ... --resume` rebuilds runs.csv from runs.jsonl)")
            values = {}
            for name, text in row.items():
                if name in TEXT_COLUMNS:
                    values[name] = text
                    continue
                try:
                    values[name] = float(text) if text != "" else math.nan
                except ValueError:
                    raise ResultsError(f"{path}:{line}: {name} = '{text}': not a number") from None
            if values["job_id"] in seen:
                raise ResultsError(f"{path}:{line}: job {values['job_id']} recorded again (line {seen[values['job_id']]} "
                                   "too): one record per job (`impactbench suite ... --resume` repairs the folder)")
            seen[values["job_id"]] = line
            suite.runs.append(Run(values))
    from . import ensemble_groups
    suite.runs, suite.members = ensemble_groups.split(suite.runs)
    suite.runs.sort(key=lambda r: r["job_id"])
    ensemble_groups.attach(suite, suite.members)
    return suite


def read_series(path):
    """series.csv (plain, or gzipped when the name ends in .gz) as a dict of column name -> numpy array of
    floats (NaN where a value is empty). numpy parses the usual file at once; a file it refuses (an empty
    value, a cut or garbled row) is read again row by row, which names the line and the column at fault."""
    opener = gzip.open if path.endswith(".gz") else open
    with opener(path, "rt", newline="") as f:
        text = f.read()
    first_line, _, body = text.partition("\n")
    header = next(csv.reader([first_line]), None) if first_line.strip() else None
    if not header:
        raise ResultsError(f"{path}: empty (no header); the run's series is damaged: run the job again "
                           "(`impactbench suite ... --resume` after removing its row, or `impactbench run`)")
    if not body.strip():
        return {name: np.empty(0) for name in header}
    try:
        values = np.loadtxt(io.StringIO(body), delimiter=",", ndmin=2, dtype=float)
    except ValueError:
        values = None
    if values is not None and values.shape[1] == len(header):
        return dict(zip(header, values.T.copy()))
    return read_series_rows(path, text)


def read_series_rows(path, text):
    """read_series row by row: what a faulty file's error names (its line, its column) or empty values."""
    reader = csv.reader(io.StringIO(text, newline=""))
    header = next(reader)
    columns = {name: [] for name in header}
    for row in reader:
        if len(row) != len(header):
            raise ResultsError(f"{path}:{reader.line_num}: {len(row)} values, expected {len(header)}")
        for name, text_value in zip(header, row):
            try:
                columns[name].append(float(text_value) if text_value != "" else math.nan)
            except ValueError:
                raise ResultsError(f"{path}:{reader.line_num}: {name} = '{text_value}': not a number") from None
    return {name: np.asarray(values, float) for name, values in columns.items()}


# The experiment's measurements (rig.md section 7), each with its source: data shown beside the simulators.
EXPERIMENT_FILE = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "experiment.toml")


def read_experiment(path=EXPERIMENT_FILE):
    """experiment.toml: {case: {motor_ratio_to_f1, frame1_peak_acceleration_g, impacts_per_beat, observations}}, each
    case with what was measured in it."""
    with open(path, "rb") as f:
        return tomllib.load(f)


def experiment_ratios(experiment):
    """The motor speed ratios (to f_1) the experiment ran at, ascending: the operating points a sweep marks."""
    return tuple(sorted(case["motor_ratio_to_f1"] for case in experiment.values() if "motor_ratio_to_f1" in case))


def read_scenario(path):
    """The scenario file a run names, or {} when it cannot be read (moved since)."""
    try:
        with open(path, "rb") as f:
            return tomllib.load(f)
    except (OSError, tomllib.TOMLDecodeError):
        return {}


def contact_stiffness(scenario, law):
    """The contact law's stiffness from a scenario file [N/m or N/m^n]; NaN for the Newton law."""
    contact = scenario.get("contact", {})
    if law == "hertz":
        return float(contact.get("hertz", {}).get("stiffness", math.nan))
    if law == "viscoelastic":
        return float(contact.get("viscoelastic", {}).get("stiffness_n_per_m", math.nan))
    return math.nan


class StepRow(Record):
    """One row of steps.csv: one engine configuration's step search."""


def read_steps(folder):
    """steps.csv's rows, or None when the suite ran no step search. Columns ending in _s, _tolerance,
    and the counts are numbers; the rest text. A later row of the same group and settings (a search
    repeated) replaces an earlier one."""
    path = os.path.join(folder, "steps.csv")
    if not os.path.exists(path):
        return None
    numeric = ("_s", "_tolerance", "_at_largest_step")
    rows = {}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            values = {}
            for name, text in row.items():
                if name.endswith(numeric) or name in ("chain_links", "grid_points_per_octave", "probes"):
                    values[name] = float(text) if text not in ("", None) else math.nan
                else:
                    values[name] = text or ""
            key = (values["group_id"], values["step_range_min_s"], values["step_range_max_s"],
                   tuple(values[m.step_tolerance_column] for m in metric_catalog.STEP_SEARCHED))
            rows[key] = StepRow(values)
    return list(rows.values())


def steps_of(steps, scenario, law):
    return [s for s in (steps or []) if s["scenario"] == scenario and s["law"] == law]
