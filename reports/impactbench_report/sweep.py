"""A frequency sweep's results (impactbench sweep: sweep.csv, poincare.csv) read, measured against the
reference and put in words: which regime each simulator reaches at each motor speed ratio, where the up
and down sweeps disagree (coexisting branches), and how far each engine's regimes are from the reference's.
The figures are sweep_figures.py's."""

import csv
import json
import math
import os

from . import data, engines, metric_catalog
from .sweep_starts import (START_ENSEMBLE_HEADER, ensemble_member, multistable, multistable_sentence, ratio_text,
                           regime_agrees, regime_of, start_ensemble_rows, start_ensemble_table, start_ensembles)

EXPERIMENT = data.read_experiment()  # experiment.toml: the published operating points (rig.md section 7)
EXPERIMENT_RATIOS = data.experiment_ratios(EXPERIMENT)
POST_RESONANCE = EXPERIMENT["post_resonance"]  # its ratio, and the impacts per beat the experiment counted there
STARTS = ("up", "down", "rest")


def configuration_key(row):
    """A row's configuration: its id without start and ratio, and without an ensemble start's /start=K
    (harness/sweep: "<configuration>/<start>/r=<ratio>[/start=K]")."""
    head, _, last = row["id"].rpartition("/")
    return (head if last.startswith("start=") else row["id"]).rsplit("/", 2)[0]


class Sweep:
    """A sweep folder read: its rows (dicts, numbers as floats where the column is numeric), the
    Poincare samples of each row id and the warnings of each row id (sweep.jsonl). start_ensembles: the
    reference's starts from rest, {(law, ratio): {regime: starts}} at each ratio where it ran more than one
    (its own, or a sibling sweep's of the same scenario in a study: share_start_ensembles)."""

    def __init__(self, folder, rows, samples, settings, warnings=None):
        self.folder, self.rows, self.samples, self.settings = folder, rows, samples, settings
        self.warnings = warnings or {}
        self.start_ensembles = start_ensembles(rows)
        self.start_ensembles_from = "this sweep" if self.start_ensembles else ""

    def warning_entries(self):
        """The rows' warnings as the report lists them (answer.warning_lines): [{"warning", "job_ids"}]."""
        found = {}
        for r in self.rows:
            for text in self.warnings.get(r["id"], []):
                found.setdefault(text, []).append(r["id"])
        return [{"warning": text, "job_ids": ids} for text, ids in found.items()]

    def simulators(self):
        """Configurations (engine, options, time step) in the order they first appear, the reference first.
        A configuration is its rows' id without start and ratio (the time step a run that never started
        could not report is its chain's)."""
        seen = []
        for r in self.rows:
            if configuration_key(r) not in [k for k, _ in seen]:
                seen.append((configuration_key(r), r))
        steps = {}
        for r in self.rows:
            if not math.isnan(r["time_step_s"]) and r["time_step_s"] > 0:
                steps[configuration_key(r)] = r["time_step_s"]
        configs = [(r["engine"], r["options"], steps.get(key, 0.0) if r["engine"] != "reference" else 0.0, key)
                   for key, r in seen]
        return sorted(configs, key=lambda c: (c[0] != "reference", configs.index(c)))

    def laws(self):
        return sorted({r["law"] for r in self.rows}, key=lambda law: ["hertz", "viscoelastic", "newton"].index(law)
                      if law in ("hertz", "viscoelastic", "newton") else 9)

    def rows_of(self, config, law, start, members=False):
        """A configuration's rows of one law and start by ratio; the reference's ensemble starts K >= 1 from
        rest only with members (start 0 is the row from rest every configuration has)."""
        return sorted((r for r in self.rows if configuration_key(r) == config[3] and r["law"] == law
                       and r["start"] == start and (members or not ensemble_member(r))),
                      key=lambda r: (r["ratio"], r.get("ensemble_start", 0)))

    def all_ratios(self):
        return sorted({r["ratio"] for r in self.rows})


def label(config):
    engine, options, step, _ = config
    if engine == "reference":
        return "reference" + (f" ({options})" if options else "")
    return f"{engine} {options or 'default'}, dt {step:g} s"


def numbers():
    """sweep.csv's numeric columns, in its order; a quantity runs.csv has too carries runs.csv's name and unit
    (docs/sweeps.md), the scored metrics among them the folder's metric catalog's (metric_catalog.SWEEP)."""
    column = {name: metric_catalog.by_name(name).column for name in metric_catalog.SWEEP_NAMES}
    return ("ratio", "ensemble_start", "ensemble_starts", "initial_displacement_offset_m", "time_step_s",
            "motor_frequency_hz", "duration_s", "window_s", "impacts", column["impacts_per_cycle"], "period_n",
            "impacts_per_period", column["frame1_sensor_peak"], column["frame2_sensor_peak"],
            "frame1_peak_displacement_m", "frame2_peak_displacement_m", "mean_approach_velocity_m_s",
            column["contact_duration"], "poincare_samples", "steps", "cpu_time_s", "wall_time_s", "load_average")


def number(text, path, line, column):
    if text == "":
        return math.nan
    try:
        return float(text)
    except ValueError:
        raise data.ResultsError(f"{path} line {line}: column {column} is {text!r}, not a number") from None


def is_sweep(folder):
    return os.path.isfile(os.path.join(folder, "sweep.json"))


def use_metrics(folder):
    """The folder's metric catalog (metric_catalog.use), its error as a data.ResultsError."""
    try:
        metric_catalog.use(folder)
    except metric_catalog.MetricsFileError as e:
        raise data.ResultsError(str(e)) from None


def read(folder):
    """The sweep in folder; data.ResultsError naming the file, line and column for what cannot be read."""
    engines.use(folder)  # the names and colours of the engines that made the sweep (engines.json)
    use_metrics(folder)  # and the metrics it measured (metrics.json)
    path = os.path.join(folder, "sweep.csv")
    if not os.path.isfile(path):
        raise data.ResultsError(f"{path}: no such file (a sweep's folder holds one once a ratio has ended)")
    rows = []
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        missing = [c for c in ("id", "engine", "law", "start", "ratio", "verdict", "regime") if c not in (reader.fieldnames or [])]
        if missing:
            raise data.ResultsError(f"{path}: columns {', '.join(missing)} missing (not a sweep.csv of this build?)")
        columns = numbers()
        for line, row in enumerate(reader, start=2):
            for column in columns:
                if column in row:
                    row[column] = number(row[column] or "", path, line, column)
            if math.isnan(row["ratio"]):
                raise data.ResultsError(f"{path} line {line}: column ratio is empty")
            rows.append(row)
    samples = {}
    samples_path = os.path.join(folder, "poincare.csv")
    if os.path.isfile(samples_path):
        with open(samples_path, newline="") as f:
            for line, row in enumerate(csv.DictReader(f), start=2):
                samples.setdefault(row["id"], []).append(number(row.get("frame1_tip_displacement_m", ""), samples_path,
                                                                line, "frame1_tip_displacement_m"))
    settings = {}
    try:
        with open(os.path.join(folder, "sweep.json")) as f:
            settings = json.load(f)
    except (OSError, json.JSONDecodeError):
        pass  # the tables say what ran; the settings only add the scenario's name
    return Sweep(folder, rows, samples, settings, read_warnings(os.path.join(folder, "sweep.jsonl")))


def read_warnings(path):
    """Each row id's warnings from sweep.jsonl (a list per row: sweep.csv has no column for a list); {}
    without the file. A line that is not JSON is skipped: sweep.csv, read before, is the rows' source."""
    warnings = {}
    if not os.path.isfile(path):
        return warnings
    with open(path) as f:
        for line in f:
            try:
                row = json.loads(line)
            except json.JSONDecodeError:
                continue
            if isinstance(row, dict) and isinstance(row.get("warnings"), list):
                warnings[row.get("id", "")] = [w for w in row["warnings"] if isinstance(w, str)]
    return warnings


def impacts(row):
    return row["verdict"] == "ok" and row["regime"] not in ("", "no impact")


def ranges_text(ratios, grid):
    """Ratios as runs of neighbours on the sweep's grid: "0.94 to 1.08, 1.1 to 1.13"."""
    index = {round(r, 6): i for i, r in enumerate(grid)}
    runs = []
    for r in sorted(ratios):
        if runs and index.get(round(r, 6), -9) == index.get(round(runs[-1][-1], 6), -99) + 1:
            runs[-1].append(r)
        else:
            runs.append([r])
    return ", ".join(ratio_text(run[0]) if len(run) == 1 else f"{ratio_text(run[0])} to {ratio_text(run[-1])}" for run in runs)


def branch_facts(sweep, law):
    """The reference's sweep of one law in words and numbers: the largest ratio the up sweep still impacts at,
    whether each experiment ratio impacts sweeping up, the ratios where up and down differ in regime."""
    reference = next((c for c in sweep.simulators() if c[0] == "reference"), None)
    if reference is None:
        return None
    up, down = sweep.rows_of(reference, law, "up"), sweep.rows_of(reference, law, "down")
    rest = sweep.rows_of(reference, law, "rest")
    facts = {"law": law, "ratios": len({r["ratio"] for r in up + down + rest})}
    if up:
        impacting = [r["ratio"] for r in up if impacts(r)]
        facts["up_last_impacting_ratio"] = max(impacting) if impacting else None
        at = {round(r["ratio"], 6): r for r in up}
        facts["up_at_experiment"] = {x: at.get(round(x, 6)) for x in EXPERIMENT_RATIOS}
    if down:
        impacting = [r["ratio"] for r in down if impacts(r)]
        facts["down_last_impacting_ratio"] = max(impacting) if impacting else None
    if up and down:
        down_at = {round(r["ratio"], 6): r for r in down}
        facts["coexisting"] = [(r["ratio"], r["regime"] or r["verdict"], down_at[round(r["ratio"], 6)]["regime"] or
                                down_at[round(r["ratio"], 6)]["verdict"])
                               for r in up if round(r["ratio"], 6) in down_at and
                               impacts(r) != impacts(down_at[round(r["ratio"], 6)])]
    if rest:
        facts["rest_impacting"] = [r["ratio"] for r in rest if impacts(r)]
    return facts


def answer_sentences(sweep):
    """The measured answer to "does a sweep up reach the experiment's post-resonance ratio (1.17 f_1) still
    impacting?", one sentence per law."""
    sentences = []
    for law in sweep.laws():
        f = branch_facts(sweep, law)
        if not f or "up_last_impacting_ratio" not in f:
            continue
        last = f["up_last_impacting_ratio"]
        end = max(r["ratio"] for r in sweep.rows if r["start"] == "up")
        text = f"{law}: sweeping up, the reference " + (
            "never impacts" if last is None else f"impacts up to the sweep's end, r = {ratio_text(last)}" if last >= end
            else f"keeps impacting up to r = {ratio_text(last)}")
        if f.get("down_last_impacting_ratio") is not None:
            text += f" (sweeping down, it first impacts at r = {ratio_text(f['down_last_impacting_ratio'])})"
        ratio = POST_RESONANCE["motor_ratio_to_f1"]
        post = f["up_at_experiment"].get(ratio)
        if post is not None:
            if impacts(post):
                per_cycle = post[metric_catalog.by_name("impacts_per_cycle").column]
                text += f"; at {ratio:g} f_1 it impacts, {per_cycle:.2f} impacts per cycle ({post['regime']})"
            else:
                text += (f"; at {ratio:g} f_1 (the experiment's post-resonance, about "
                         f"{POST_RESONANCE['impacts_per_beat']:g} impacts per beat) it has no impact")
        coexisting = f.get("coexisting", [])
        if coexisting:
            text += ("; up and down differ at r = " + ", ".join(f"{ratio_text(r)} ({u} up, {d} down)" for r, u, d in coexisting))
        if f.get("rest_impacting"):
            text += "; from rest it impacts at r = " + ranges_text(f["rest_impacting"], sweep.all_ratios())
        sentences.append(text + ".")
    return sentences


def agreement(sweep):
    """Per engine configuration, law and start: how often its regime is the reference's at the same ratio
    (regime_agrees: at a multistable ratio, any regime the reference's starts reach), where not, the error of
    impacts per cycle and of frame 1's sensor peak where both impact, and its CPU time. Rows whose verdict is
    not ok disagree. multistable: (ratio, engine's regime, {regime: starts}) at each multistable ratio."""
    reference = next((c for c in sweep.simulators() if c[0] == "reference"), None)
    table = []
    for config in sweep.simulators():
        if config[0] == "reference" or reference is None:
            continue
        for law in sweep.laws():
            for start in STARTS:
                rows = sweep.rows_of(config, law, start)
                ref = {round(r["ratio"], 6): r for r in sweep.rows_of(reference, law, start)}
                paired = [(r, ref[round(r["ratio"], 6)]) for r in rows if round(r["ratio"], 6) in ref]
                if not paired:
                    continue
                reached = {id(r): sweep.start_ensembles.get((law, round(r["ratio"], 6))) for r, _ in paired}
                same = [(r, q) for r, q in paired if regime_agrees(r, q, reached[id(r)])]
                differ = [(r, q) for r, q in paired if not regime_agrees(r, q, reached[id(r)])]
                count, peak = (metric_catalog.by_name(n).column for n in ("impacts_per_cycle", "frame1_sensor_peak"))  # a difference, a relative error
                ipc = [abs(r[count] - q[count]) for r, q in paired
                       if r["verdict"] == "ok" and not math.isnan(r[count]) and not math.isnan(q[count])]
                peaks = sorted(abs(r[peak] / q[peak] - 1)
                               for r, q in paired
                               if impacts(r) and impacts(q) and q[peak] > 0)
                table.append({
                    "configuration": label(config), "law": law, "start": start, "ratios": len(paired),
                    "agreement": len(same) / len(paired),
                    "differ": [(r["ratio"], regime_of(r), q["regime"] or q["verdict"]) for r, q in differ],
                    "multistable": [(r["ratio"], regime_of(r), reached[id(r)]) for r, _ in paired
                                    if multistable(reached[id(r)])],
                    "impacts_per_cycle_mean_abs_error": sum(ipc) / len(ipc) if ipc else math.nan,
                    "sensor_peak_median_relative_error": peaks[len(peaks) // 2] if peaks else math.nan,
                    "cpu_time_s": sum(r["cpu_time_s"] for r in rows if not math.isnan(r["cpu_time_s"])),
                })
    return table


AGREEMENT_HEADER = ["configuration", "law", "start", "ratios", "regime as the reference", "where it differs (engine vs reference)",
                    "at multistable ratios (engine: reference's starts reaching it)", "impacts/cycle mean |error|",
                    "frame 1 sensor peak median |error|", "CPU [s]"]


def agreement_rows(table):
    def differ_text(items):
        shown = [f"{ratio_text(r)} ({e} vs {q})" for r, e, q in items[:8]]
        return ", ".join(shown) + (f", and {len(items) - 8} more" if len(items) > 8 else "") if items else "none"

    def multistable_text(items):
        return ", ".join(f"{ratio_text(r)} ({e}: {counts.get(e, 0)} of {sum(counts.values())})" for r, e, counts in items) or "none"

    def fmt(value, percent=False):
        if math.isnan(value):
            return "n/a"
        return f"{100 * value:.1f} %" if percent else f"{value:.3f}"

    return [[t["configuration"], t["law"], t["start"], str(t["ratios"]), f"{100 * t['agreement']:.0f} %",
             differ_text(t["differ"]), multistable_text(t.get("multistable", [])), fmt(t["impacts_per_cycle_mean_abs_error"]),
             fmt(t["sensor_peak_median_relative_error"], percent=True), f"{t['cpu_time_s']:.1f}"] for t in table]


def summary_sentence(sweep):
    """One opening line: the reference's branches and the engines' agreement, from the data."""
    parts = answer_sentences(sweep)
    if sweep.start_ensembles_from == "this sweep":
        parts.append(multistable_sentence(sweep))
    table = agreement(sweep)
    if table:
        by_config = {}
        for t in table:
            by_config.setdefault(t["configuration"], []).append(t)
        parts.append("Regime as the reference's: " + "; ".join(
            f"{name} {100 * sum(t['agreement'] * t['ratios'] for t in ts) / sum(t['ratios'] for t in ts):.0f} % of "
            f"{sum(t['ratios'] for t in ts)} ratios" for name, ts in by_config.items()) + ".")
    return " ".join(parts)


def sections(data, figures_folder, stamp, title):
    """The report's sections of one sweep: (title, markdown, html, figure paths) per law, its answer first."""
    from . import sweep_figures, tables  # the figures need matplotlib; reading a sweep does not
    found = []
    lede = summary_sentence(data)
    table = agreement(data)
    for law in data.laws():
        slug = "".join(c if c.isalnum() else "_" for c in f"{title}_{law}")
        paths = [sweep_figures.bifurcation(data, law, figures_folder, stamp, f"sweep_{slug}_bifurcation"),
                 sweep_figures.response(data, law, figures_folder, stamp, f"sweep_{slug}_response")]
        rows = agreement_rows([t for t in table if t["law"] == law])
        text = lede if law == data.laws()[0] else ""
        markdown_text, html_text = text, f"<p>{text}</p>" if text else ""
        ensemble = start_ensemble_rows(start_ensemble_table(data, law)) if data.start_ensembles_from == "this sweep" else []
        if ensemble:
            note = ("The reference from an ensemble of starts from rest (start K: frame 1's tip displaced K x the "
                    "ensemble's step): how many starts reach each regime, and whether more than one is reached "
                    "(multistable: which attractor one start reaches is chance; the engines' regimes are judged "
                    "against every regime reached).")
            markdown_text += "\n\n" + note + "\n\n" + tables.markdown(START_ENSEMBLE_HEADER, ensemble)
            html_text += f"<p>{note}</p>" + tables.html_table(START_ENSEMBLE_HEADER, ensemble)
        if rows:
            note = ("Each engine's regime against the reference's at the same ratio and start (no impact, period-n, "
                    "irregular; a run not ok disagrees; at a multistable ratio, against every regime the reference's "
                    "starts from rest reach" + (f", from {data.start_ensembles_from}" if data.start_ensembles_from not in
                                                ("", "this sweep") else "") + "), the error of impacts per cycle, the median error of frame 1's "
                    "sensor peak where both impact, and the engine's CPU time for the sweep.")
            markdown_text += "\n\n" + note + "\n\n" + tables.markdown(AGREEMENT_HEADER, rows)
            html_text += f"<p>{note}</p>" + tables.html_table(AGREEMENT_HEADER, rows)
        found.append((f"{title}, {law}", markdown_text, html_text, [p for p in paths if p]))
    return found
