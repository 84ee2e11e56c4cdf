"""Runs.csv's ensemble members grouped into their configurations, and each configuration's statistics
(ensembles.py) attached to the run that stands for it.

A configuration is (scenario, law, engine, time step, options); its members differ in `ensemble_start`.
The report's tables, figures and picks see one run per configuration, member 0 (the job id a single run
has), carrying `ensemble`: its members, each headline metric's interval and each error's interval against
the reference ensemble of its kind (the beam, or the reference on the engine's own chain)."""

import math
from dataclasses import dataclass, field

from . import analysis, ensembles, metric_catalog


def start_of(run):
    value = run.number("ensemble_start")
    return 0 if math.isnan(value) else int(value)


def base_job_id(run):
    """The job id of member 0: member K >= 1 is it + '/start=K'."""
    job_id = run["job_id"]
    suffix = f"/start={start_of(run)}"
    return job_id[:-len(suffix)] if start_of(run) and job_id.endswith(suffix) else job_id


def configuration_key(run):
    """What an ensemble's members share (with member 0's job id: two suite parts that ran the same
    configuration stay two); a run outside an ensemble is its own configuration (its job id is its base's).
    Member 0 belongs with its starts even where it says N = 1: a study part without the ensemble planned it
    first (a job two parts plan runs once, with the first part's settings)."""
    return (run["scenario"], run["law"], run["engine"], run.number("time_step_s"), run["options"], base_job_id(run))


@dataclass
class Ensemble:
    """A configuration's members (by start) and their statistics: metrics {runs.csv column: Interval},
    errors {error column with its prefix: Interval}."""
    members: list
    metrics: dict = field(default_factory=dict)
    errors: dict = field(default_factory=dict)

    @property
    def n(self):
        return len(self.members)

    @property
    def job_ids(self):
        return [m["job_id"] for m in self.members]

    @property
    def stable_members(self):
        engine = self.members[0]["engine"]
        return [m for m in self.members if engine == "reference" or m.stable]


def split(runs):
    """(one run per configuration: its member of the lowest start, {that run's job id: its members})."""
    groups = {}
    for run in runs:
        groups.setdefault(configuration_key(run), []).append(run)
    representatives, members = [], {}
    for group in groups.values():
        group.sort(key=start_of)
        representatives.append(group[0])
        members[group[0]["job_id"]] = group
    return representatives, members


def metric_interval(ensemble, column):
    runs = ensemble.stable_members
    return ensembles.t_interval([r.number(column) for r in runs], [r["job_id"] for r in runs])


def chain_damping(run):
    """The chain damping a run's options name (an engine's and its chain reference's alike), "modal" by default:
    two chains of one K damped otherwise are two references."""
    return analysis.options_of(run["options"]).get("chain_damping", "modal")


def reference_index(runs):
    """{(scenario, law, "beam") or (scenario, law, chain links, chain damping): the reference run}: what
    reference_of looks up."""
    index = {}
    for r in runs:
        if r["engine"] != "reference":
            continue
        if r["options"] == "":
            index.setdefault((r["scenario"], r["law"], "beam"), r)
        elif "modes=chain" in r["options"]:
            index.setdefault((r["scenario"], r["law"], r.number("chain_links"), chain_damping(r)), r)
    return index


def reference_of(index, run, against):
    """The representative of the reference ensemble a run's errors `against` ("beam", "own chain") are
    measured against (the beam's, or the chain's with the run's links and chain damping), or None."""
    if against == "beam":
        return index.get((run["scenario"], run["law"], "beam"))
    return index.get((run["scenario"], run["law"], run.number("chain_links"), chain_damping(run)))


def attach(suite, members):
    """Every configuration's Ensemble on its representative (run.ensemble), where it or a reference it is
    measured against has more than one member; None elsewhere (single runs: the rows' own values)."""
    ensembles_by_id = {job_id: Ensemble(group) for job_id, group in members.items()}
    index = reference_index(suite.runs)
    for run in suite.runs:
        run.ensemble = None
    for run in suite.runs:
        ensemble = ensembles_by_id[run["job_id"]]
        if run["engine"] != "reference":
            references = {against: reference_of(index, run, against) for against in analysis.AGAINST}
        else:  # the reference on a chain is measured against the beam; the beam's reference is itself
            references = {"beam": reference_of(index, run, "beam")} if "modes=chain" in run["options"] else {}
        if ensemble.n <= 1 and all(r is None or ensembles_by_id[r["job_id"]].n <= 1 for r in references.values()):
            continue
        for m in metric_catalog.SCORED:
            ensemble.metrics[m.column] = metric_interval(ensemble, m.column)
        for against, reference in references.items():
            if reference is None:
                continue
            reference_ensemble = ensembles_by_id[reference["job_id"]]
            for column, error_column, kind in ((m.column, m.error_column, m.kind) for m in metric_catalog.SCORED):
                if math.isnan(run.number(analysis.AGAINST[against] + error_column)):
                    continue  # not defined for this run (no motor, a reference that failed): as the row says
                error = ensembles.ensemble_error(ensemble.metrics[column], metric_interval(reference_ensemble, column),
                                                 kind)
                if error is not None:
                    ensemble.errors[analysis.AGAINST[against] + error_column] = error
        run.ensemble = ensemble


def reference_intervals(suite, scenario, law):
    """The beam reference ensemble of a case: (its members, {metric column: Interval}), or (None, {})."""
    reference = suite.beam_reference(scenario, law)
    if reference is None:
        return None, {}
    group = suite.members.get(reference["job_id"], [reference])
    ensemble = Ensemble(group)
    return ensemble, {m.column: metric_interval(ensemble, m.column) for m in metric_catalog.SCORED}
