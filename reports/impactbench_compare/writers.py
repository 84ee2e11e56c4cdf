"""A comparison as text: the short summary printed first, Markdown, and JSON (its keys: docs/compare.md)."""

import math

from impactbench_report.ensembles import none_if_nan

SUMMARY_LINES = 20  # moved configurations named in the printed summary; the rest are in the files


def change_text(m):
    if math.isnan(m.change):
        return f"{m.label}: {number(m.base)} -> {number(m.new)} ({m.noise_method})"
    change = f"{100 * m.change:+.3g} %" if m.kind == "relative" else f"{m.change:+.3g}"
    if m.noise_method.startswith("none measured"):
        return f"{m.label} {change} (deterministic runs: no noise but rounding)"
    noise = f"±{100 * m.noise:.2g} %" if m.kind == "relative" else f"±{m.noise:.2g}"
    return f"{m.label} {change} (noise {noise})"


def number(x):
    return "n/a" if x is None or (isinstance(x, float) and math.isnan(x)) else f"{x:.4g}"


def verdicts_text(counts):
    return ", ".join(f"{v} x{n}" if n > 1 else v for v, n in sorted(counts.items())) or "none"


def what_moved(c):
    """One line per moved configuration: its job and what moved in it."""
    if c.presence == "appeared":
        return f"{c.job_id}: appeared ({verdicts_text(c.new_verdicts)})"
    if c.presence == "disappeared":
        return f"{c.job_id}: disappeared (was {verdicts_text(c.base_verdicts)})"
    parts = []
    if c.verdicts_changed:
        parts.append(f"verdict {verdicts_text(c.base_verdicts)} -> {verdicts_text(c.new_verdicts)}"
                     + (" (newly failing)" if c.newly_failing else ""))
    parts += [change_text(m) for m in c.moved_metrics]
    if c.cost is not None and c.cost.moved:
        parts.append(f"CPU cost x{c.cost.ratio:.3g} (noise ±{100 * c.cost.noise:.2g} %)")
    return f"{c.job_id}: " + "; ".join(parts)


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
    if not moved:
        lines.append(f"nothing moved beyond the noise ({len(changes)} configurations, {compared} metrics compared)")
        return lines
    lines.append(f"moved beyond the noise: {len(moved)} of {len(changes)} configurations")
    lines += ["  " + what_moved(c) for c in moved[:SUMMARY_LINES]]
    if len(moved) > SUMMARY_LINES:
        lines.append(f"  and {len(moved) - SUMMARY_LINES} more (in the files)")
    return lines


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
    out += ["", "## Every configuration", "",
            "| job | presence | verdicts (base -> new) | metric changes (noise) | CPU s per simulated s (base -> new) | cost |",
            "|---|---|---|---|---|---|"]
    for c in changes:
        metrics = "; ".join(change_text(m) + (" **moved**" if m.moved else "") for m in c.metrics) or "-"
        cost = c.cost
        cost_cells = (f"{number(cost.base_s_per_s)} -> {number(cost.new_s_per_s)} | {cost.judgement}" if cost else "- | -")
        out.append(f"| {c.job_id} | {c.presence} | {verdicts_text(c.base_verdicts)} -> {verdicts_text(c.new_verdicts)} | "
                   f"{metrics} | {cost_cells} |")
    return "\n".join(out) + "\n"


def metric_json(m):
    return {"metric": m.label, "column": m.column, "kind": m.kind, "base": none_if_nan(m.base), "new": none_if_nan(m.new),
            "change": none_if_nan(m.change), "noise_half_width": none_if_nan(m.noise), "noise": m.noise_method,
            "moved": m.moved, "base_error_vs_beam": none_if_nan(m.base_error), "new_error_vs_beam": none_if_nan(m.new_error)}


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
        "configurations": [{
            "job_id": c.job_id, "scenario": c.scenario, "law": c.law, "engine": c.engine,
            "time_step_s": none_if_nan(c.time_step_s), "options": c.options, "presence": c.presence, "moved": c.moved,
            "base_verdicts": c.base_verdicts, "new_verdicts": c.new_verdicts, "verdicts_changed": c.verdicts_changed,
            "newly_failing": c.newly_failing, "metrics": [metric_json(m) for m in c.metrics], "cost": cost_json(c.cost),
        } for c in changes],
    }
