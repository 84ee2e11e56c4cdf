"""The ablation: per engine, which setting moved the error or the cost and by how much, from the fronts'
points alone. Two runs of an engine in one case that differ in one setting only (the time step, the contact
path, or one option) are a pair; a setting's change (from one value to another) is summarised over its pairs
in every case: the median change of the score (largest |error| in tolerance multiples, vs the beam and vs
the engine's own chain) and the median ratio of the CPU cost, with the job ids of every pair."""

import html
import math
import statistics

from . import engines, tables

SETTING_STEP = "time step [s]"


def settings_of(point):
    """A point's settings as {name: value}: its time step, its contact path and every other option."""
    options = dict(o.split("=", 1) for o in point["options"].split(";") if "=" in o)
    options.setdefault("contact", "matched")
    options[SETTING_STEP] = f"{point['time_step_s']:g}" if point["time_step_s"] is not None else ""
    return options


def step_ratio_text(larger_s, smaller_s):
    """'÷2', '÷1.4': how much a step was cut, as the ladders cut it (octaves, half-octaves)."""
    return f"÷{larger_s / smaller_s:.2g}"


def pairs(points):
    """[(setting, from value, to value, point a, point b)] for every two stable, scored points that differ in
    exactly one setting. A time step is compared with the next smaller one of the same configuration only
    (from the larger to the smaller: 'time step [s]', '÷2', ...); any other setting from its default (or
    the first of its two values by name) to the other value."""
    found = []
    usable = [p for p in points if p["verdict"] in ("ok", "inaccurate") and p["score_vs_beam"] is not None
              and p["cpu_time_per_simulated_s"]]
    for i, a in enumerate(usable):
        for b in usable[i + 1:]:
            sa, sb = settings_of(a), settings_of(b)
            differ = [k for k in set(sa) | set(sb) if sa.get(k, "default") != sb.get(k, "default")]
            if len(differ) != 1:
                continue
            name = differ[0]
            va, vb = sa.get(name, "default"), sb.get(name, "default")
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
    cost_ratio_median, job_id_pairs}] over summary.json's cases (their fronts), largest score change first per
    engine."""
    grouped = {}
    for case in cases:
        for engine, entry in (case.get("fronts") or {}).get("engines", {}).items():
            for name, va, vb, a, b in pairs(entry["points"]):
                key = (engine, name, va, vb)
                grouped.setdefault(key, []).append((case, a, b))
    rows = []
    for (engine, name, va, vb), found in grouped.items():
        beam = [b["score_vs_beam"] - a["score_vs_beam"] for _, a, b in found]
        chain = [b["score_vs_own_chain"] - a["score_vs_own_chain"] for _, a, b in found
                 if a["score_vs_own_chain"] is not None and b["score_vs_own_chain"] is not None]
        cost = [b["cpu_time_per_simulated_s"] / a["cpu_time_per_simulated_s"] for _, a, b in found]
        rows.append({"engine": engine, "setting": name, "from": va, "to": vb, "pairs": len(found),
                     "cases": sorted({f"{c['scenario']}, {c['law']}" for c, _, _ in found}),
                     "score_vs_beam_change_median": statistics.median(beam),
                     "score_vs_beam_change_range": [min(beam), max(beam)],
                     "score_vs_own_chain_change_median": statistics.median(chain) if chain else None,
                     "cost_ratio_median": statistics.median(cost),
                     "job_id_pairs": [[a["job_id"], b["job_id"]] for _, a, b in found]})
    rows.sort(key=lambda r: (r["engine"], -abs(r["score_vs_beam_change_median"]), r["setting"]))
    return rows


HEADER = ["engine", "setting: from → to", "pairs (cases)", "score vs beam: median change [range]",
          "score vs own chain: median change", "CPU cost: median ratio"]


def table_rows(rows):
    """The report's ablation table: one row per engine and setting change."""
    def signed(x):
        return "–" if x is None or math.isnan(x) else f"{x:+.2g}"
    return [[engines.display_name(r["engine"]),
             f"{r['setting']}: {r['to']}" if r["setting"] == SETTING_STEP else f"{r['setting']}: {r['from']} → {r['to']}",
             f"{r['pairs']} ({len(r['cases'])})",
             f"{signed(r['score_vs_beam_change_median'])} [{signed(r['score_vs_beam_change_range'][0])}, "
             f"{signed(r['score_vs_beam_change_range'][1])}]",
             signed(r["score_vs_own_chain_change_median"]), f"×{r['cost_ratio_median']:.2g}"] for r in rows]


NOTE = ("Two runs of an engine in one case that differ in one setting only are a pair: a time step and the next "
        "smaller one of the same configuration, or one option changed. Each row: how the score (largest |error| in "
        "multiples of its tolerance) and the CPU cost per simulated second changed over its pairs, medians over every "
        "case where the pair ran (summary.json: ablation, with each pair's job ids).")


def section(rows):
    """The report's section: (title, Markdown, HTML, no figures)."""
    body = table_rows(rows)
    return ("Ablation: which setting moved the error or the cost",
            NOTE + "\n\n" + tables.markdown(HEADER, body), f"<p>{html.escape(NOTE)}</p>" + tables.html_table(HEADER, body), [])
