"""The ablation: per engine, which setting moved the error or the cost and by how much, from the fronts'
points alone. Two runs of an engine in one case that differ in one setting only (the time step, the contact
path, or one option) are a pair; a setting's change (from one value to another) is summarised over its pairs
in every case: over the pairs of two stable runs, the median change of the score (largest |error| in
tolerance multiples, vs the beam and vs the engine's own chain) and the median ratio of the CPU cost; and how
many pairs it made unstable or stable (a setting that makes every run unstable moves no score, but it is
what the setting did). Every pair is named by its job ids."""

import html
import math
import statistics

from . import analysis, data, engines, tables

SETTING_STEP = "time step [s]"


def settings_of(point):
    """A point's settings as {name: value}: its time step, its contact path and every other option."""
    options = analysis.options_of(point["options"])
    options.setdefault("contact", "matched")
    options[SETTING_STEP] = f"{point['time_step_s']:g}" if point["time_step_s"] is not None else ""
    return options


def step_ratio_text(larger_s, smaller_s):
    """'÷2', '÷1.4': how much a step was cut, as the ladders cut it (octaves, half-octaves)."""
    return f"÷{larger_s / smaller_s:.2g}"


def stable(point):
    return point["verdict"] in data.STABLE_VERDICTS


def scored(point):
    """A stable point with a score and a cost: one a change of score and cost can be read from."""
    return stable(point) and point["score_vs_beam"] is not None and bool(point["cpu_time_per_simulated_s"])


def pairs(points):
    """[(setting, from value, to value, point a, point b)] for every two points that differ in exactly one
    setting, at least one of them scored (the other scored too, or unstable or failed). A time step is
    compared with the next smaller one of the same configuration only (from the larger to the smaller:
    'time step [s]', '÷2', ...); any other setting from its default (or the first of its two values by
    name) to the other value."""
    found = []
    usable = [p for p in points if scored(p) or (not stable(p) and p["time_step_s"] is not None)]
    for i, first in enumerate(usable):
        for second in usable[i + 1:]:
            if not (scored(first) or scored(second)):
                continue  # unstable either way: nothing moved that a pair could show
            sa, sb = settings_of(first), settings_of(second)
            differ = [k for k in set(sa) | set(sb) if sa.get(k, "default") != sb.get(k, "default")]
            if len(differ) != 1:
                continue
            name = differ[0]
            va, vb = sa.get(name, "default"), sb.get(name, "default")
            # a: the run before the change, b: after it (the smaller step; the option's value off its default)
            a, b = first, second
            if name == SETTING_STEP:
                if float(va) < float(vb):
                    a, b, va, vb = b, a, vb, va
                between = [p for p in usable if p is not a and p is not b and float(vb) < p["time_step_s"] < float(va)
                           and {k: v for k, v in settings_of(p).items() if k != SETTING_STEP}
                           == {k: v for k, v in sa.items() if k != SETTING_STEP}]
                if between:
                    continue  # not adjacent: the steps between stand for it
                found.append((name, "", step_ratio_text(float(va), float(vb)), a, b))
                continue
            if vb == "default" or (va != "default" and va > vb):
                a, b, va, vb = b, a, vb, va
            found.append((name, va, vb, a, b))
    return found


def engine_ablation(cases):
    """[{engine, setting, from, to, pairs, cases, score_vs_beam_change_median, score_vs_own_chain_change_median,
    cost_ratio_median, job_id_pairs, pairs_made_unstable, pairs_made_stable, stability_job_id_pairs}] over
    summary.json's cases (their fronts), largest score change first per engine. `pairs`, `cases`, the
    medians and `job_id_pairs` are those of the pairs of two scored runs (the medians null without one)."""
    grouped = {}
    for case in cases:
        for engine, entry in (case.get("fronts") or {}).get("engines", {}).items():
            for name, va, vb, a, b in pairs(entry["points"]):
                key = (engine, name, va, vb)
                grouped.setdefault(key, []).append((case, a, b))
    rows = []
    for (engine, name, va, vb), every in grouped.items():
        found = [(c, a, b) for c, a, b in every if scored(a) and scored(b)]
        flipped = [(c, a, b) for c, a, b in every if stable(a) != stable(b)]
        beam = [b["score_vs_beam"] - a["score_vs_beam"] for _, a, b in found]
        chain = [b["score_vs_own_chain"] - a["score_vs_own_chain"] for _, a, b in found
                 if a["score_vs_own_chain"] is not None and b["score_vs_own_chain"] is not None]
        cost = [b["cpu_time_per_simulated_s"] / a["cpu_time_per_simulated_s"] for _, a, b in found]
        rows.append({"engine": engine, "setting": name, "from": va, "to": vb, "pairs": len(found),
                     "cases": sorted({f"{c['scenario']}, {c['law']}" for c, _, _ in found}),
                     "score_vs_beam_change_median": statistics.median(beam) if beam else None,
                     "score_vs_beam_change_range": [min(beam), max(beam)] if beam else None,
                     "score_vs_own_chain_change_median": statistics.median(chain) if chain else None,
                     "cost_ratio_median": statistics.median(cost) if cost else None,
                     "job_id_pairs": [[a["job_id"], b["job_id"]] for _, a, b in found],
                     "pairs_made_unstable": sum(1 for _, a, _ in flipped if stable(a)),
                     "pairs_made_stable": sum(1 for _, a, _ in flipped if not stable(a)),
                     "stability_job_id_pairs": [[a["job_id"], b["job_id"]] for _, a, b in flipped]})
    rows.sort(key=lambda r: (r["engine"], -abs(r["score_vs_beam_change_median"] or 0), r["setting"]))
    return rows


HEADER = ["engine", "setting: from → to", "pairs (cases)", "score vs beam: median change [range]",
          "score vs own chain: median change", "CPU cost: median ratio", "stability: pairs it changed"]


def table_rows(rows):
    """The report's ablation table: one row per engine and setting change."""
    def signed(x):
        return "–" if x is None or math.isnan(x) else f"{x:+.2g}"

    def stability(r):
        made = [f"{n} made {what}" for n, what in ((r["pairs_made_unstable"], "unstable"),
                                                   (r["pairs_made_stable"], "stable")) if n]
        return ", ".join(made) or "none"

    def row(r):
        low, high = r["score_vs_beam_change_range"] or (None, None)  # none without a pair of two stable runs
        return [engines.display_name(r["engine"]),
                f"{r['setting']}: {r['to']}" if r["setting"] == SETTING_STEP else f"{r['setting']}: {r['from']} → {r['to']}",
                f"{r['pairs']} ({len(r['cases'])})",
                f"{signed(r['score_vs_beam_change_median'])} [{signed(low)}, {signed(high)}]",
                signed(r["score_vs_own_chain_change_median"]),
                "–" if r["cost_ratio_median"] is None else f"×{r['cost_ratio_median']:.2g}", stability(r)]
    return [row(r) for r in rows]


NOTE = ("Two runs of an engine in one case that differ in one setting only are a pair: a time step and the next "
        "smaller one of the same configuration, or one option changed. Each row: how the score (largest |error| in "
        "multiples of its tolerance) and the CPU cost per simulated second changed over its pairs of two stable runs, "
        "medians over every case where the pair ran, and how many pairs the change made unstable or stable "
        "(summary.json: ablation, with each pair's job ids).")


def section(rows):
    """The report's section: (title, Markdown, HTML, no figures)."""
    body = table_rows(rows)
    return ("Ablation: which setting moved the error or the cost",
            NOTE + "\n\n" + tables.markdown(HEADER, body), f"<p>{html.escape(NOTE)}</p>" + tables.html_table(HEADER, body), [])
