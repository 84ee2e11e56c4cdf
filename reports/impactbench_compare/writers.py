"""A comparison as text: the short summary printed first, Markdown, and JSON (its keys: docs/compare.md)."""

import math

from impactbench_report.ensembles import none_if_nan

from . import alike, judgement

SUMMARY_LINES = 20  # moved configurations named in the printed summary; the rest are in the files


def amount(kind, x, sign="+"):
    return "n/a" if math.isnan(x) else (f"{100 * x:{sign}.3g} %" if kind == "relative" else f"{x:{sign}.3g}")


def noise_text(m, half_width):
    if m.noise_method.startswith("none measured"):
        return "deterministic runs: no noise but rounding"
    return "noise ±" + amount(m.kind, half_width, "")


def errors_text(m):
    """'error vs own chain -0.50 % -> +7.46 % (vs beam -4.2 % -> +3.1 %)', the judged reference first."""
    if m.against is None:
        return ""
    others = [a for a in ("own chain", "beam") if a != m.against and not math.isnan(m.base_errors[a])
              and not math.isnan(m.new_errors[a])]
    text = f"error vs {m.against} {amount(m.kind, m.base_errors[m.against])} -> {amount(m.kind, m.new_errors[m.against])}"
    return text + "".join(f" (vs {a} {amount(m.kind, m.base_errors[a])} -> {amount(m.kind, m.new_errors[a])})"
                          for a in others)


def change_text(m):
    """'contact duration +30 %: error vs own chain ... -> ...: regressed (noise ±0.1 %)'; the noise in the
    error's unit where the error judges it."""
    if m.not_judged:
        return f"{m.label}: {m.not_judged}"
    if math.isnan(m.change):
        return f"{m.label}: {number(m.base)} -> {number(m.new)} ({m.noise_method}): {m.judgement}"
    errors = errors_text(m)
    noise = judgement.error_noise(m, m.base_errors[m.against]) if errors else m.noise
    return f"{m.label} {amount(m.kind, m.change)}" + (f": {errors}" if errors else "") + \
        f": {m.judgement} ({noise_text(m, noise)})"


def number(x):
    return "n/a" if x is None or (isinstance(x, float) and math.isnan(x)) else f"{x:.4g}"


def verdicts_text(counts):
    return ", ".join(f"{v} x{n}" if n > 1 else v for v, n in sorted(counts.items())) or "none"


def what_moved(c):
    """One line per moved (or not comparable) configuration: its job, its judgement and what moved in it."""
    if c.not_comparable:
        return f"{c.job_id}: not comparable: {alike.differences_text(c.not_comparable)}"
    if c.presence == "appeared":
        return f"{c.job_id}: appeared ({verdicts_text(c.new_verdicts)})"
    if c.presence == "disappeared":
        return f"{c.job_id}: regressed: disappeared (was {verdicts_text(c.base_verdicts)}; {c.why})"
    parts = []
    if c.verdicts_changed:
        parts.append(f"verdict {verdicts_text(c.base_verdicts)} -> {verdicts_text(c.new_verdicts)}"
                     + (" (newly failing)" if c.newly_failing else ""))
    parts += [change_text(m) for m in c.moved_metrics]
    if c.instability is not None and c.instability.moved:
        parts.append(c.instability.text())
    if c.cost is not None and c.cost.moved:
        parts.append(f"CPU cost x{c.cost.ratio:.3g} (noise ±{100 * c.cost.noise:.2g} %): "
                     + (judgement.REGRESSED if c.cost.ratio > 1 else judgement.IMPROVED))
    parts += [i.text() for i in c.moved_impacts]
    return f"{c.job_id}: {c.judgement}: " + "; ".join(parts)


def not_judged_lines(changes):
    return [f"{c.job_id}: {change_text(m)}" for c in changes for m in c.not_judged_metrics]


def counted(changes, what):
    n = sum(c.judgement == what for c in changes)
    return f"{n} {what}" if n else ""


def summary_lines(base, new, differences, changes):
    lines = [f"compare: {base.path} -> {new.path}"]
    if differences:
        lines.append("what differs between the folders (before what moved):")
        lines += [f"  {what}: {a} -> {b}" for what, a, b in differences]
    else:
        lines.append("made alike: the same build, machine, engine versions and scenario files" if base.provenance
                     else "made alike as far as the folders say (no provenance.json: folders of an older build)")
    moved = [c for c in changes if c.moved]
    compared = sum(len(c.metrics) for c in changes)
    alike_count = sum(not c.not_comparable for c in changes)
    if not moved:
        lines.append(f"nothing moved beyond the noise ({alike_count} configurations compared alike, {compared} metrics "
                     "compared)" if alike_count else "nothing compared: every configuration was run otherwise")
    else:
        tally = ", ".join(t for t in (counted(changes, judgement.REGRESSED), counted(changes, judgement.IMPROVED)) if t)
        lines.append(f"moved beyond the noise: {len(moved)} of {len(changes)} configurations" + (f" ({tally})" if tally else ""))
        lines += ["  " + what_moved(c) for c in moved[:SUMMARY_LINES]]
        if len(moved) > SUMMARY_LINES:
            lines.append(f"  and {len(moved) - SUMMARY_LINES} more (in the files)")
    lines += listed("not comparable (run otherwise: not counted as moved):", [what_moved(c) for c in changes if c.not_comparable])
    lines += listed("not judged (a noise wider than the metric: not counted as moved):", not_judged_lines(changes))
    return lines


def listed(title, lines):
    if not lines:
        return []
    return [title] + ["  " + line for line in lines[:SUMMARY_LINES]] + (
        [f"  and {len(lines) - SUMMARY_LINES} more (in the files)"] if len(lines) > SUMMARY_LINES else [])


def markdown(base, new, differences, changes):
    out = ["# Comparison", "", f"Base: `{base.path}`, new: `{new.path}`.", ""]
    out += ["## What differs between the folders", ""]
    if differences:
        out += ["| what | base | new |", "|---|---|---|"]
        out += [f"| {what} | {a} | {b} |" for what, a, b in differences]
    else:
        out.append("Nothing: the same build, machine, engine versions and scenario files (as far as the folders say).")
    out += ["", "## What moved beyond the noise", ""]
    moved = [c for c in changes if c.moved]
    out += [f"- {what_moved(c)}" for c in moved] or ["Nothing."]
    out += ["", "## Not comparable (run otherwise)", ""]
    out += [f"- {what_moved(c)}" for c in changes if c.not_comparable] or ["None."]
    out += ["", "## Not judged (a noise wider than the metric)", ""]
    out += [f"- {line}" for line in not_judged_lines(changes)] or ["None."]
    out += ["", "## Every configuration", "",
            "| job | judgement | presence | verdicts (base -> new) | metric changes (noise) | CPU s per simulated s (base -> new) | cost |",
            "|---|---|---|---|---|---|---|"]
    for c in changes:
        metrics = "; ".join(change_text(m) + (" **moved**" if m.moved else "") for m in c.metrics) or "-"
        cost = c.cost
        cost_cells = (f"{number(cost.base_s_per_s)} -> {number(cost.new_s_per_s)} | {cost.judgement}" if cost else "- | -")
        out.append(f"| {c.job_id} | {c.judgement} | {c.presence} | {verdicts_text(c.base_verdicts)} -> "
                   f"{verdicts_text(c.new_verdicts)} | {metrics} | {cost_cells} |")
    return "\n".join(out) + "\n"


def metric_json(m):
    return {"metric": m.label, "column": m.column, "kind": m.kind, "base": none_if_nan(m.base), "new": none_if_nan(m.new),
            "change": none_if_nan(m.change), "noise_half_width": none_if_nan(m.noise), "noise": m.noise_method,
            "moved": m.moved, "base_error_vs_beam": none_if_nan(m.base_errors.get("beam", math.nan)),
            "new_error_vs_beam": none_if_nan(m.new_errors.get("beam", math.nan)),
            "base_error_vs_own_chain": none_if_nan(m.base_errors.get("own chain", math.nan)),
            "new_error_vs_own_chain": none_if_nan(m.new_errors.get("own chain", math.nan)),
            "judged_against": m.against, "judgement": m.judgement}


def instability_json(i):
    if i is None:
        return None
    return {"base_time_s": none_if_nan(i.base_time_s), "new_time_s": none_if_nan(i.new_time_s), "start": i.start,
            "base_reason": i.base_reason, "new_reason": i.new_reason, "slack_s": i.slack_s,
            "judgement": i.judgement, "moved": i.moved}


def impact_json(i):
    return {"quantity": i.column, "label": i.label, "base_median": none_if_nan(i.base_median),
            "new_median": none_if_nan(i.new_median), "base_impacts": i.base_impacts, "new_impacts": i.new_impacts,
            "p_value": none_if_nan(i.p_value), "tests": i.tests, "moved": i.moved}


def cost_json(cost):
    if cost is None:
        return None
    return {"base_cpu_time_per_simulated_s": none_if_nan(cost.base_s_per_s),
            "new_cpu_time_per_simulated_s": none_if_nan(cost.new_s_per_s), "ratio": none_if_nan(cost.ratio),
            "noise_relative": none_if_nan(cost.noise), "judgement": cost.judgement, "moved": cost.moved}


def json_object(base, new, differences, changes):
    return {
        "base": base.path, "new": new.path,
        "differences": [{"what": what, "base": a, "new": b} for what, a, b in differences],
        "moved": any(c.moved for c in changes),
        "regressed": judgement.regressed(changes),
        "configurations": [{
            "job_id": c.job_id, "scenario": c.scenario, "law": c.law, "engine": c.engine,
            "time_step_s": none_if_nan(c.time_step_s), "options": c.options, "presence": c.presence, "moved": c.moved,
            "base_verdicts": c.base_verdicts, "new_verdicts": c.new_verdicts, "verdicts_changed": c.verdicts_changed,
            "newly_failing": c.newly_failing, "metrics": [metric_json(m) for m in c.metrics], "cost": cost_json(c.cost),
            "judgement": c.judgement, "why": c.why or None,
            "not_comparable": [{"setting": what, "base": a, "new": b} for what, a, b in c.not_comparable],
            "instability": instability_json(c.instability), "impacts": [impact_json(i) for i in c.impacts],
        } for c in changes],
    }
