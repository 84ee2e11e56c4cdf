"""The report's answer, as data: for each case and law the best configuration out of the box (native
contact, the engine's defaults) and the best tuned one (matched or injected contact), each with its
errors against the beam and its own chain, its largest stable step and its CPU cost per simulated second;
one standing per engine; the settings behind every configuration; what ran, where and under what load.

It is report/summary.json (schema: docs/summary-json.md). Every number of a run is copied from its row of
runs.csv under the same column name beside the row's job_id; the few derived numbers (the score, the
error against the experiment) are computed from such numbers by the formulas the schema states. Where a
configuration ran from several starts (an ensemble), its run object is member 0's row and carries the
ensemble's intervals beside it, each naming the job ids of the members it was computed from."""

import math

from . import ablation, analysis, answer_sentence, budget, chain_convergence, data, engines, ensemble_groups, fronts, \
    metric_catalog, settings, significance
from .tables import percent

SCHEMA_VERSION = 4

RUN_COLUMNS = ["time_step_s", "verdict", "reason", "same_run_as", "chain_links", "duration_s", "window_start_s",
               "window_end_s", "frame1_sensor_peak_acceleration_g", "frame2_sensor_peak_acceleration_g",
               "contact_duration_mean_s", "impacts_per_cycle", "frame1_log_decrement", "cpu_time_s",
               "cpu_time_per_simulated_s", "wall_time_s", "load_average"]


def value(run, column):
    """A runs.csv cell as JSON: text as text, a number as a number, an empty cell as null."""
    cell = run.values.get(column)
    if isinstance(cell, float):
        return None if math.isnan(cell) else cell
    return cell


def run_entry(run, tolerances, experiment_peak_g=None, need=None, skip=()):
    """One run as the summary names it: its job_id, its runs.csv values, its errors against each
    reference, its score (over the metrics but `skip`, the case's flagged ones) and (where the experiment
    measured one) its error against the measured peak; with an ensemble, its intervals (`ensemble`); `need`:
    the case's ensemble_need."""
    entry = {"job_id": run["job_id"], "configuration": run.config, "engine": run["engine"], "options": run["options"]}
    if run["engine"] != "reference":
        entry["contact_path"] = analysis.contact_path(run)
    entry["runs_csv"] = {c: value(run, c) for c in RUN_COLUMNS if c in run.values}
    for name, prefix in analysis.AGAINST.items():
        errors = {prefix + m.error_column: value(run, prefix + m.error_column) for m in metric_catalog.SCORED
                  if prefix + m.error_column in run.values}
        entry["errors_vs_" + name.replace(" ", "_")] = errors
    for against in analysis.AGAINST:
        multiple, label, error = analysis.score(run, tolerances, against, skip)
        entry["largest_error_vs_" + against.replace(" ", "_")] = None if label is None else {
            "metric": label, "error": error, "tolerance": tolerance_of(label, tolerances), "tolerance_multiple": multiple,
            **largest_error_interval(run, tolerances, need, against, skip)}
    entry["ensemble"] = ensemble_entry(run)
    peak = run.number("frame1_sensor_peak_acceleration_g")
    if experiment_peak_g and not math.isnan(peak):
        entry["vs_experiment_frame1_peak_relative_error"] = (peak - experiment_peak_g) / experiment_peak_g
    return entry


def largest_error_interval(run, tolerances, need, against, skip=()):
    """The largest error's interval: half_width (null for a single run without a measured noise), method,
    and the verdict against the tolerances over every scored error (within / beyond / undecided, null for
    such a single run)."""
    scored = significance.score_interval(run, tolerances, need, against, skip)
    error = scored[2] if scored else None
    interval = error is not None and error.n > 1
    return {"half_width": error.half_width if interval else None,
            "interval_method": None if error is None else error.method,
            "single_run_noise": error.half_width if error is not None and not interval else None,
            "verdict": significance.verdict(run, tolerances, need, against, skip)}


def ensemble_entry(run):
    """A run's ensemble: its members' job ids and starts, each metric's and each error's interval; null
    when neither it nor its references ran from more than one start."""
    ensemble = run.ensemble
    if ensemble is None:
        return None
    entry = {"starts": ensemble.n, "job_ids": ensemble.job_ids,
             "initial_displacement_offsets_m": [value(m, "initial_displacement_offset_m") for m in ensemble.members],
             "unstable_members": [m["job_id"] for m in ensemble.members if m not in ensemble.stable_members],
             "metrics": {c: i.json() | {"job_ids": list(i.job_ids)} for c, i in ensemble.metrics.items()
                         if i.n > 0}}
    for name, prefix in analysis.AGAINST.items():
        entry["errors_vs_" + name.replace(" ", "_")] = {
            c: i.json() | {"job_ids": list(i.job_ids)} for c, i in ensemble.errors.items() if c.startswith(prefix)}
    return entry


def tolerance_of(label, tolerances):
    return tolerances[metric_catalog.by_label(label).tolerance_key]


def step_limit(suite, steps, scenario, law, config):
    """The configuration's largest stable step in this case: the step search's (steps.csv) when it ran,
    else the largest stable step the suite tried, with what bounds it."""
    runs = [r for r in suite.runs_of(scenario, law) if r.config == config]
    for row in data.steps_of(steps, scenario, law):
        if row.config == config and not math.isnan(row.number("largest_stable_step_s")):
            return {"largest_stable_step_s": row.number("largest_stable_step_s"), "bounded_by": "step search",
                    "smallest_unstable_step_s": none_if_nan(row.number("smallest_unstable_step_s")),
                    "steps_csv_group_id": row["group_id"]}
    largest, smallest_unstable = analysis.step_limits(runs, config)
    if largest is None:
        return {"largest_stable_step_s": None, "bounded_by": "no stable run",
                "smallest_unstable_step_s": none_if_nan(smallest_unstable)}
    step = largest.number("time_step_s")
    unstable_above = not math.isnan(smallest_unstable) and smallest_unstable > step
    return {"largest_stable_step_s": step, "job_id": largest["job_id"],
            "bounded_by": "a larger step was unstable" if unstable_above else "largest step tried (a lower bound)",
            "smallest_unstable_step_s": none_if_nan(smallest_unstable)}


def none_if_nan(x):
    return None if x is None or (isinstance(x, float) and math.isnan(x)) else x


def case_answer(suite, steps, scenario, law, experiment, tolerances):
    runs = suite.runs_of(scenario, law)
    measured = experiment.get(scenario, {}).get("frame1_peak_acceleration_g")
    reference = suite.beam_reference(scenario, law)
    need = significance.case_need(suite, scenario, law, tolerances)
    convergence = chain_convergence.case_convergence(suite, scenario, law, tolerances)
    flagged = chain_convergence.flagged_metrics(convergence)
    skip = tuple(flagged)
    any_run = reference or next((r for r in runs if r["engine"]), None)
    case = {"scenario": scenario, "law": law,
            "duration_s": value(any_run, "duration_s") if any_run else None,
            "window_start_s": value(any_run, "window_start_s") if any_run else None,
            "window_end_s": value(any_run, "window_end_s") if any_run else None,
            "contact_stiffness": contact_stiffness(any_run, law),
            "restitution": restitution(any_run, law),
            "experiment_frame1_peak_acceleration_g": measured,
            "reference": run_entry(reference, tolerances, measured) if reference else None,
            "ensemble_need": need, "chain_convergence": convergence,
            "reference_numerical_error": budget.reference_numerical_error(suite, scenario, law),
            "metrics_not_ranked": [{"metric": m, "why": "; ".join(w)} for m, w in flagged.items()],
            "configurations": []}
    best, chosen_runs = {}, {}
    for config in analysis.configurations(runs):
        config_runs = analysis.runs_of_config(runs, config)
        chosen = analysis.best_run(config_runs, tolerances, skip)
        entry = {"configuration": config, "runs": len(config_runs),
                 "unstable_runs": sum(r["verdict"] == "unstable" for r in config_runs),
                 "failed_runs": sum(r["verdict"] == "failed" for r in config_runs),
                 "best_run": run_entry(chosen, tolerances, measured, need, skip) if chosen else None,
                 "step_limit": step_limit(suite, steps, scenario, law, config)}
        case["configurations"].append(entry)
        if chosen:
            kind = "out_of_box" if analysis.contact_path(chosen) == analysis.NATIVE else "tuned"
            incumbent = best.get(kind)
            if incumbent is None or analysis.ranking_key(chosen, tolerances, skip) < analysis.ranking_key(incumbent[0], tolerances, skip):
                best[kind] = (chosen, entry)
        if chosen:
            chosen_runs[config] = chosen
    index = ensemble_groups.reference_index(suite.runs)
    budgets = {r["job_id"]: budget.run_budget(suite, index, r, need) for r in runs
               if r["engine"] not in ("reference", "") and not r["same_run_as"]}
    case["fronts"] = fronts.case_fronts(runs, tolerances, need, law, skip, budgets)
    for kind in ("out_of_box", "tuned"):
        if kind in best:
            run, entry = best[kind]
            others = [(c, r) for c, r in chosen_runs.items() if c != entry["configuration"]
                      and (analysis.contact_path(r) == analysis.NATIVE) == (kind == "out_of_box")]
            # ties are judged against what ranked it (analysis.engine_score): its own chain, or the beam where its
            # chain reference gave no score
            against = analysis.engine_score_of(run, tolerances, skip)[1]
            tied, significant = significance.ties(run, others, tolerances, need, against, skip)
            case["best_" + kind] = {"configuration": entry["configuration"], "job_id": run["job_id"],
                                    "ranked_by": f"error vs {against}, a run that passes its verdict first",
                                    "tied_with": tied,
                                    "tied_with_job_ids": [chosen_runs[c]["job_id"] for c in tied],
                                    "significant": significant, "test": significance.TEST}
        else:
            ran = any((analysis.contact_path(r) == analysis.NATIVE) == (kind == "out_of_box")
                      for r in runs if r["engine"] not in ("reference", ""))
            case["best_" + kind] = {"configuration": None,
                                    "why": "no stable run" if ran else "not run in this suite"}
    case["answer"] = answer_sentence.case_answer(case)
    return case


def contact_stiffness(run, law):
    if run is None:
        return None
    k = data.contact_stiffness(data.read_scenario(run["scenario_file"]), law)
    if math.isnan(k):
        return None
    return {"value": k, "unit": "N/m" if law == "viscoelastic" else "N/m^1.5"}


def restitution(run, law):
    """The Newton law's coefficient of restitution in the scenario file; None for the other laws."""
    if run is None or law != "newton":
        return None
    return data.read_scenario(run["scenario_file"]).get("contact", {}).get("newton", {}).get("restitution")


def engine_standing(engine, cases, tolerances, runs=()):
    """One engine across the cases: per contact kind, how many of its runs (`runs`: the suite's) took that
    contact path, in how many cases its best run is within the verdict tolerances of the beam, its worst
    case, its CPU cost; and how many of its runs were unstable."""
    standing = {"engine": engine}
    for kind, paths in (("tuned", analysis.TUNED), ("out_of_box", (analysis.NATIVE,))):
        ran = sum(r["engine"] == engine and not r["same_run_as"] and analysis.contact_path(r) in paths for r in runs)
        bests = []
        for case in cases:
            entries = [c["best_run"] for c in case["configurations"] if c["best_run"]
                       and c["best_run"]["engine"] == engine and c["best_run"]["contact_path"] in paths]
            if entries:
                bests.append((case, min(entries, key=lambda e: e["largest_error_vs_beam"]["tolerance_multiple"]
                                        if e["largest_error_vs_beam"] else math.inf)))
        scored = [(c, e) for c, e in bests if e["largest_error_vs_beam"]]
        within = [1 for _, e in scored if e["largest_error_vs_beam"]["tolerance_multiple"] <= 1]
        worst = max(scored, key=lambda ce: ce[1]["largest_error_vs_beam"]["tolerance_multiple"], default=None)
        costs = sorted(e["runs_csv"]["cpu_time_per_simulated_s"] for _, e in scored
                       if e["runs_csv"].get("cpu_time_per_simulated_s") is not None)
        standing[kind] = {
            "runs": ran, "cases_with_a_stable_run": len(bests), "cases_within_tolerance_vs_beam": len(within),
            "worst": None if worst is None else {"scenario": worst[0]["scenario"], "law": worst[0]["law"],
                                                 "job_id": worst[1]["job_id"], **worst[1]["largest_error_vs_beam"]},
            "cpu_time_per_simulated_s_median": costs[len(costs) // 2] if costs else None}
    return standing


def lead_operating_points(cases, engine):
    """The engine's two operating points in the lead case (fronts.lead_case): {scenario, law,
    most_accurate, cheapest_within_tolerance_vs_beam} with the points' job ids, or None."""
    case = fronts.lead_case(cases)
    entry = None if case is None else case["fronts"]["engines"].get(engine)
    if entry is None:
        return None
    return {"scenario": case["scenario"], "law": case["law"], "most_accurate": entry["most_accurate"],
            "cheapest_within_tolerance_vs_beam": entry["cheapest_within_tolerance_vs_beam"]}


def summarise(suite, steps, experiment, tolerances, provenance):
    cases = [case_answer(suite, steps, s, l, experiment, tolerances) for s, l in suite.cases()]
    engines = sorted({r["engine"] for r in suite.runs if r["engine"] not in ("reference", "")})
    standings = []
    for engine in engines:
        standing = engine_standing(engine, cases, tolerances, suite.runs)
        runs = [r for r in suite.runs if r["engine"] == engine and not r["same_run_as"]]
        unstable = [r for r in runs if r["verdict"] == "unstable"]
        standing["runs"] = len(runs)
        standing["unstable_runs"] = len(unstable)
        standing["failed_runs"] = sum(r["verdict"] == "failed" for r in runs)
        standing["first_unstable"] = None if not unstable else {"job_id": unstable[0]["job_id"],
                                                                "reason": unstable[0]["reason"]}
        standing["version"] = next((r["engine_version"] for r in runs if r["engine_version"]), "")
        standing["operating_points"] = lead_operating_points(cases, engine)
        standing["line"] = standing_line(standing)
        standings.append(standing)
    configurations = {}
    # a configuration's settings are described from its first run per law, a published case's first: the
    # step search's extreme cases map their own laws (restitution 0) and would misstate the configuration
    published_first = sorted(suite.runs, key=lambda r: "/paper/" not in (r.values.get("scenario_file") or ""))
    for run in published_first:
        if run["engine"] in ("reference", "") or run["same_run_as"]:
            continue
        entry = configurations.setdefault(run.config, {
            "engine": run["engine"], "options": run["options"], "contact_path": analysis.contact_path(run),
            "per_law": {}, "settings_from_job_ids": []})
        if run["law"] not in entry["per_law"]:
            entry["per_law"][run["law"]] = settings.describe(run["engine"], analysis.contact_path(run),
                                                             suite.diagnostics(run))
            entry["settings_from_job_ids"].append(run["job_id"])
    for entry in configurations.values():
        entry["settings"] = settings.merged(entry.pop("per_law"))
    return {"schema_version": SCHEMA_VERSION, "schema": "docs/summary-json.md", "suite": provenance,
            "verdict_tolerances": tolerances, "warnings": warnings(suite), "cases": cases, "engines": standings,
            "configurations": configurations, "ablation": ablation.engine_ablation(cases)}


def warnings(suite):
    """What the suite warned about its runs (runs.jsonl "warnings"), one entry per warning with the runs
    it concerns, in the runs' order: [{"warning", "job_ids"}]."""
    found = {}
    for run in suite.runs:
        for text in suite.warnings(run):
            found.setdefault(text, []).append(run["job_id"])
    return [{"warning": text, "job_ids": ids} for text, ids in found.items()]


def warning_lines(entries, most=10, unit="runs"):
    """The report's "Warnings" list: one line per warning with how many runs it concerns, at most `most`
    lines and a last one counting the rest (a sweep's rows from rest can each carry their own)."""
    lines = [f"{e['warning']} ({len(e['job_ids'])} {unit if len(e['job_ids']) != 1 else unit.rstrip('s')})"
             for e in entries[:most]]
    if len(entries) > most:
        lines.append(f"and {len(entries) - most} more warnings (runs.jsonl, sweep.jsonl: \"warnings\")")
    return lines


def error_text(largest):
    """'frame 1 sensor peak -6.5 %' or 'impacts per cycle +0.12'; with an ensemble's interval,
    'frame 1 sensor peak -6.5 % ± 1.2 %'."""
    if not largest:
        return "no error defined"
    kind = metric_catalog.by_label(largest["metric"]).kind
    text = f"{largest['metric']} " + (percent(largest["error"]) if kind == "relative" else f"{largest['error']:+.3g}")
    if largest.get("half_width") is not None:
        text += " " + half_width_text(largest["half_width"], kind)
    return text


def error_cell(largest, intervals_exist=True):
    """What a table prints of a largest error, the same in every table: error_text, then for a single run where
    intervals exist its noise or that it has none: '(single run; noise ± 2.1 %)', '(single run (12 vs 1 starts))'."""
    text = error_text(largest)
    if not largest or largest.get("half_width") is not None or not intervals_exist or not largest.get("interval_method"):
        return text
    kind = metric_catalog.by_label(largest["metric"]).kind
    if largest.get("single_run_noise") is not None:
        return text + f" (single run; noise {half_width_text(largest['single_run_noise'], kind)})"
    return text + " (" + largest["interval_method"].split(";")[0] + ")"


def half_width_text(half_width, kind):
    """'± 1.2 %' (a relative error's) or '± 0.031'."""
    return f"± {100 * half_width:.2g} %" if kind == "relative" else f"± {half_width:.2g}"


def standing_line(s):
    name = engines.display_name(s["engine"])
    parts = []
    for kind, label in (("tuned", "tuned"), ("out_of_box", "native contact")):
        k = s[kind]
        # "no stable run" only where runs of this kind exist: a suite without --paths native never ran one
        if k.get("runs", 1) == 0:
            parts.append(f"{label}: not run")
            continue
        if k["cases_with_a_stable_run"] == 0:
            parts.append(f"{label}: no stable run")
            continue
        text = (f"{label} within tolerance of the beam in {k['cases_within_tolerance_vs_beam']} of "
                f"{k['cases_with_a_stable_run']} cases")
        if k["worst"] and k["worst"]["tolerance_multiple"] > 1:
            text += f" (worst {k['worst']['scenario']}, {k['worst']['law']}: {error_text(k['worst'])})"
        if k["cpu_time_per_simulated_s_median"] is not None:
            text += f" at {k['cpu_time_per_simulated_s_median']:.2g} s CPU/s"
        parts.append(text)
    points = s.get("operating_points")
    if points:
        parts.append(operating_points_text(points))
    parts.append(f"{s['unstable_runs']} of {s['runs']} runs unstable, {s['failed_runs']} failed")
    return f"{name}: " + "; ".join(parts) + "."


def point_text(point):
    """'matched at 5e-5 s, 0.16 s CPU/s' for a front's point."""
    step = point["time_step_s"]
    cost = point["cpu_time_per_simulated_s"]
    return (fronts.settings_text(point) + (f" at {step:g} s" if step else "")
            + (f", {cost:.2g} s CPU/s" if cost is not None else ""))


def operating_points_text(points):
    """'resonance, hertz: most accurate matched at 5e-5 s, ...; cheapest within the tolerances ...'."""
    accurate, cheapest = points["most_accurate"], points["cheapest_within_tolerance_vs_beam"]
    text = f"{points['scenario']}, {points['law']}: most accurate " + (point_text(accurate) if accurate else "none")
    if cheapest is None:
        return text + ", none within every tolerance of the beam"
    if accurate and cheapest["job_id"] == accurate["job_id"]:
        return text + ", also the cheapest within every tolerance of the beam"
    return text + "; cheapest within every tolerance of the beam " + point_text(cheapest)
