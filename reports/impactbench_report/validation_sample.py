"""What a validation of the reference against the experiment is made from (docs/validation.md), read from a
study's results:

- its input sample, one folder per [[validation]] part, OUT/validation/NAME/: sample.csv (one row per sample
  point and published case: the point's uncertain inputs, SI units, one column each, named as
  scenarios/paper_inputs.toml names them; the variant scenario it ran as), inputs.json (each input's nominal
  value, distribution and source) and runs.csv (one reference run per variant scenario, a single start, scored
  over the case's window);
- the nominal reference of each published case from several starts, in the same folder's runs.csv (the part runs
  it beside the sample, cut and scored alike; else the study's own runs.csv, read by data.py): the chaotic scatter
  the sample's single starts carry as well, and the same reference rerun at tolerances a thousand times tighter,
  the reference's own numerical error.

The input columns are read from sample.csv's header, never named here: the C++ side decides their names (with
their units). Nothing is dropped: a sample point without a run, or with a run that is not ok, is kept with
its point, so that the analysis (validation.py) lists it."""

import csv
import json
import math
import os
from dataclasses import dataclass, field

from . import budget, data, ensemble_groups

# sample.csv's columns that are not inputs
POINT_COLUMNS = ("case", "point", "scenario", "scenario_file")
# the published cases in the page's order (data.Suite.cases's)
CASE_ORDER = ("resonance", "post_resonance", "pre_resonance")
OK = "ok"


@dataclass(frozen=True)
class Quantity:
    """A response the validation reads from runs.csv: its column, a name for people, its unit, and the key of
    reports/experiment.toml that holds its measurement, if the paper measured it."""
    column: str
    label: str
    unit: str
    measured_key: str = None


QUANTITIES = (
    Quantity("frame1_sensor_peak_acceleration_g", "frame 1 peak acceleration", "g", "frame1_peak_acceleration_g"),
    Quantity("frame2_sensor_peak_acceleration_g", "frame 2 peak acceleration", "g"),
    Quantity("impacts_per_cycle", "impacts per motor cycle", "-"),
    Quantity("impacts_per_beat", "impacts per beat", "-", "impacts_per_beat"),
    Quantity("beat_period_s", "beat period", "s"),
)


@dataclass
class SamplePoint:
    """One sample point of one case: its inputs {name: value} and its reference run's row (None: no run)."""
    case: str
    point: int
    scenario: str
    inputs: dict
    run: dict = None

    @property
    def status(self):
        """The run's verdict ("ok" for a usable reference run), "no run" where runs.csv has none."""
        if self.run is None:
            return "no run"
        return self.run.get("verdict") or self.run.get("status") or "?"

    def value(self, column):
        """The run's value of a quantity, NaN where the run is not ok or does not define it."""
        if self.status != OK:
            return math.nan
        return self.run.get(column, math.nan)


@dataclass
class ValidationSample:
    """One [[validation]] part's folder, read."""
    name: str
    folder: str
    inputs_file: str
    design: str
    points_declared: int
    inputs: list           # inputs.json's entries, for the names sample.csv's header gives
    input_names: list      # sample.csv's input columns, in its order
    points: list = field(default_factory=list)
    law: str = "hertz"     # the law its runs used (the nominal ensemble is that law's)
    # the published cases' own runs in the folder: the nominal ensemble's starts and the tight rerun
    nominal_rows: list = field(default_factory=list)

    def cases(self):
        present = {p.case for p in self.points}
        return [c for c in CASE_ORDER if c in present] + sorted(present - set(CASE_ORDER))

    def of_case(self, case):
        return sorted((p for p in self.points if p.case == case), key=lambda p: p.point)

    def input_entry(self, name):
        return next((i for i in self.inputs if i.get("name") == name), {})


def validation_folders(study_folder):
    """OUT/validation/NAME/ folders holding a sample.csv, by name; [] for a study without [[validation]]."""
    root = os.path.join(study_folder, "validation")
    if not os.path.isdir(root):
        return []
    return [os.path.join(root, n) for n in sorted(os.listdir(root))
            if os.path.exists(os.path.join(root, n, "sample.csv"))]


def number(text, path, line, column):
    try:
        return float(text) if text not in ("", None) else math.nan
    except ValueError:
        raise data.ResultsError(f"{path}:{line}: {column} = '{text}': not a number") from None


def read_validation_runs(folder):
    """runs.csv of a validation folder, the reference's rows in the file's order, numbers as floats (NaN where
    empty), text columns (data.TEXT_COLUMNS, and `status` should the C++ side name the verdict so) as text, each
    with the line it was read from."""
    path = os.path.join(folder, "runs.csv")
    if not os.path.exists(path):
        return []
    rows = []
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        for row in reader:
            if row.get("engine", "reference") != "reference":
                continue
            values = {name: text if name in data.TEXT_COLUMNS or name == "status" else
                      number(text, path, reader.line_num, name) for name, text in row.items()}
            rows.append((reader.line_num, values))
    return rows


def split_runs(folder, rows, variants):
    """The sample's runs, {variant scenario: row}, and the rest: the published cases' own (their nominal
    ensemble's starts and tight rerun). A variant run twice is an error, not a choice the report makes."""
    runs, nominal = {}, []
    for line, values in rows:
        if values["scenario"] not in variants:
            nominal.append(values)
            continue
        if values["scenario"] in runs:
            raise data.ResultsError(f"{os.path.join(folder, 'runs.csv')}:{line}: scenario {values['scenario']} "
                                    "recorded again: one reference run per variant scenario")
        runs[values["scenario"]] = values
    return runs, nominal


def read_sample(folder):
    """A validation folder as a ValidationSample; data.ResultsError for a sample.csv the report cannot read."""
    path = os.path.join(folder, "sample.csv")
    meta = {}
    if os.path.exists(os.path.join(folder, "inputs.json")):
        with open(os.path.join(folder, "inputs.json")) as f:
            try:
                meta = json.load(f)
            except json.JSONDecodeError as error:
                raise data.ResultsError(f"{os.path.join(folder, 'inputs.json')}: not JSON ({error})") from None
    all_runs = read_validation_runs(folder)
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        header = reader.fieldnames or []
        missing = [c for c in POINT_COLUMNS if c not in header]
        if missing:
            raise data.ResultsError(f"{path}:1: no column {', '.join(missing)} (is this a validation sample?)")
        names = [c for c in header if c not in POINT_COLUMNS]
        rows = [(reader.line_num, row) for row in reader]
    runs, nominal_rows = split_runs(folder, all_runs, {row["scenario"] for _, row in rows})
    points = []
    for line, row in rows:
        point = number(row["point"], path, line, "point")
        if math.isnan(point):
            raise data.ResultsError(f"{path}:{line}: point is empty")
        points.append(SamplePoint(row["case"], int(point), row["scenario"],
                                  {n: number(row[n], path, line, n) for n in names}, runs.get(row["scenario"])))
    laws = {r.get("law") for r in runs.values() if r.get("law")}
    sample = ValidationSample(os.path.basename(os.path.normpath(folder)), folder, meta.get("inputs_file", ""),
                              meta.get("design", ""), int(meta.get("points", 0) or 0), meta.get("inputs", []), names,
                              points, law=laws.pop() if len(laws) == 1 else "hertz")
    sample.nominal_rows = [data.Run(r) for r in nominal_rows]
    return sample


@dataclass
class NominalEnsemble:
    """A published case's nominal reference from its starts: the members (data.Run, by start), and the first
    start rerun at tighter tolerances (None where the study did not)."""
    case: str
    law: str
    members: list
    tight: object = None

    def values(self, column):
        """[(job id, value)] of the members that ran ok and define the quantity."""
        out = []
        for run in self.members:
            value = run.number(column)
            if run["verdict"] in data.STABLE_VERDICTS and not math.isnan(value):
                out.append((run["job_id"], value))
        return out

    def left_out(self, column):
        """The members whose value is not used, with why: [{job_id, start, why}]."""
        used = {j for j, _ in self.values(column)}
        return [{"job_id": r["job_id"], "start": ensemble_groups.start_of(r),
                 "why": r["verdict"] if r["verdict"] not in data.STABLE_VERDICTS else "not defined"}
                for r in self.members if r["job_id"] not in used]

    @property
    def first_start(self):
        return self.members[0] if self.members else None


def nominal_ensemble(suite, case, law, sample=None):
    """The case's nominal reference from all its starts (start 0 first) and its tight rerun: the validation
    folder's own (a [[validation]] part runs them beside its sample, cut and scored as the sample is) where it
    holds them, else the study's beam reference; None without either."""
    if sample is not None:
        own = [r for r in sample.nominal_rows if r["scenario"] == case and r["law"] == law]
        members = sorted((r for r in own if not r["options"]), key=ensemble_groups.start_of)
        tight = [r for r in own if "rtol" in r["options"] and r["verdict"] in data.STABLE_VERDICTS]
        if members:
            return NominalEnsemble(case, law, members, tight[0] if tight else None)
    reference = suite.beam_reference(case, law)
    if reference is None:
        return None
    members = suite.members.get(reference["job_id"], [reference])
    return NominalEnsemble(case, law, members, budget.tight_reference(suite, case, law))
