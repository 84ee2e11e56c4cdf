"""The runs a case's detail figures draw: the ones its answers name (summary.json), so that a reader sees the runs
the first screen speaks of. Each configuration's best run (its best_run: a run that passes its verdict first, then
the smallest error against its own chain), and the run the answer sentence names where it is another run of its
configuration (another step), under the name '<configuration> at <step> s'."""

from .tables import step_text


def drawn_runs(suite, case):
    """{name: run} for the figures of one case of summary.json (answer.case_answer), runs from `suite`."""
    by_id = {r["job_id"]: r for r in suite.runs_of(case["scenario"], case["law"])}
    chosen = {}
    for entry in case["configurations"]:
        best = entry.get("best_run")
        if best and best["job_id"] in by_id:
            chosen[entry["configuration"]] = by_id[best["job_id"]]
    named = by_id.get((case.get("answer") or {}).get("job_id"))
    if named is not None and all(run is not named for run in chosen.values()):
        chosen[f"{named.config} at {step_text(named.number('time_step_s'))} s"] = named
    return chosen
