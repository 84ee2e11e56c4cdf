"""The page's section "The reference against the experiment": per published case, what the sampled inputs make of
each response, the verdict of ASME V&V 20 where the paper measured it, the inputs that matter, and a figure of
each measured quantity's sample against the measurement. Every number printed is summary.json's `validation`
(validation.py), formatted by `number`; the figures read the sample's values again from its folder."""

import html
import math
import os

import numpy as np

from . import tables, validation_sample
from .validation import TOP_INPUTS
from .figures import REPOSITORY, plt, proxy, save
from .page_writer import figure_html, markdown_figure

TITLE = "The reference against the experiment"
DOC = os.path.join(REPOSITORY, "docs", "validation.md")  # what the section names: tested to exist


def number(value):
    """Every number of the section, four significant digits (the measured peaks have four); '–' where none."""
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return "–"
    return f"{value:.4g}"


def with_unit(quantity):
    return quantity["label"] + ("" if quantity["unit"] == "-" else f" [{quantity['unit']}]")


def unit_text(quantity):
    return "" if quantity["unit"] == "-" else f" {quantity['unit']}"


VERDICT_HEADER = ["quantity", "measured D", "reference S", "E = S − D", "u_num", "u_input", "u_D", "u_val", "verdict"]
SPREAD_HEADER = ["quantity", "sample mean", "sample std. dev.", "2.5 %", "97.5 %", "runs not ok",
                 "inputs that matter most (index)", "chaos share", "against the experiment"]


def verdict_rows(case):
    rows = []
    for q in case["quantities"]:
        v = q["vv20"]
        if v is None:
            continue
        rows.append([with_unit(q)] + [number(v[k]) for k in ("d", "s", "e", "u_num", "u_input", "u_d", "u_val")]
                    + [v["verdict"]])
    return rows


def above_floor(quantity):
    """The ranked indices above the noise floor, the largest first."""
    floor = quantity["sensitivity"]["noise_floor"]
    return [r for r in quantity["sensitivity"]["ranked"] if r["index"] is not None and r["index"] > floor]


def top_inputs(quantity):
    """The (at most) three largest indices above the noise floor, named; what else where none is."""
    if not any(r["index"] is not None for r in quantity["sensitivity"]["ranked"]):
        return "–"
    above = above_floor(quantity)[:TOP_INPUTS]
    return (", ".join(f"{r['input']} {number(r['index'])}" for r in above)
            or f"none above {number(quantity['sensitivity']['noise_floor'])}")


def spread_rows(case):
    rows = []
    for q in case["quantities"]:
        s = q["sample"]
        against = ("verdict above" if q["vv20"] else "measured, no simulated value" if q["measured"]
                   else "not measured: no verdict")
        rows.append([with_unit(q), number(s["mean"]), number(s["standard_deviation"]), number(s["p2_5"]),
                     number(s["p97_5"]), str(s["runs_not_ok"]), top_inputs(q), number(q["chaos_share"]), against])
    return rows


def reading(case):
    """What the case's numbers say, one sentence per measured quantity."""
    lines = []
    for q in case["quantities"]:
        v, unit = q["vv20"], unit_text(q)
        if v is None:
            if q["measured"]:
                lines.append(f"{q['label'].capitalize()}: measured {number(q['measured']['d'])}{unit}, but "
                             f"{q['notes'][-1]}.")
            continue
        side = (f"{number(abs(v['e']))}{unit} {'above' if v['e'] > 0 else 'below'}" if v["e"] else "equal to")
        text = (f"{q['label'].capitalize()}: the reference gives {number(v['s'])}{unit}, {side} the measured "
                f"{number(v['d'])}{unit}, against a validation uncertainty u_val of {number(v['u_val'])}{unit}")
        if v["verdict"].startswith("undecided"):
            text += (f" — at the edge of twice it, closer than u_input's own sampling error "
                     f"(+-{number(v['u_input_sampling_error'])}{unit}) allows: a larger sample decides.")
        elif v["model_form_error_at_least"] is None:
            text += " — within it: these uncertainties can explain the difference."
        else:
            text += (f" — beyond twice it: a model-form error of at least {number(v['model_form_error_at_least'])}"
                     f"{unit} that the inputs, the chaos, the solver and the measurement do not explain.")
        top = above_floor(q)[:1]
        if q["u_input"] is not None:
            text += (f" The rig's tolerances move it by u_input = {number(q['u_input'])}{unit}"
                     + "".join(f", most through {r['input']} (index {number(r['index'])})" for r in top)
                     + ("" if q["chaos_share"] is None else
                        f"; one start's chaos makes a share {number(q['chaos_share'])} of the sample's variance") + ".")
        lines.append(text)
    return lines


def listed(case):
    """The runs not ok and the quantities some runs leave undefined, named (nothing is dropped silently)."""
    lines = []
    floors = [q["sensitivity"]["noise_floor"] for q in case["quantities"] if q["sensitivity"]["noise_floor"]]
    if floors:
        lines.append(f"An index below {number(max(floors))} (twice an index's noise at this sample size) is not told "
                     "apart from no effect and is not listed.")
    bad = case["quantities"][0]["runs_not_ok"] if case["quantities"] else []
    if bad:
        lines.append("Runs not ok, left out of every quantity: " + "; ".join(
            f"point {r['point']} ({r['scenario']}): {r['status']}" + (f", {r['reason']}" if r["reason"] else "")
            for r in bad) + ".")
    # a note every quantity has (no nominal reference) is said once
    common = set.intersection(*(set(q["notes"]) for q in case["quantities"])) if case["quantities"] else set()
    lines += [f"Every quantity: {note}." for note in sorted(common)]
    for q in case["quantities"]:
        if q["not_defined"] and q["sample"]["n"]:  # where no run defines it, its note says so
            lines.append(f"{q['label'].capitalize()}: not defined in {len(q['not_defined'])} of {case['points']} runs "
                         f"({', '.join(q['not_defined'][:8])}{', …' if len(q['not_defined']) > 8 else ''}).")
        for note in q["notes"]:
            if not note.startswith("not measured") and note not in common:
                lines.append(f"{q['label'].capitalize()}: {note}.")
    return lines


def intro(entry, named=False):
    """What the section shows, for a reader who knows the rig, and where its method is written."""
    text = ((f"Sample {entry['name']}: each" if named else "Each") +
            f" published case ran at {entry['sample_size']} points of the rig's uncertain inputs "
            f"({entry['inputs_file'] or 'inputs file not recorded'}, {entry['design'] or 'design not recorded'} "
            "design), one start each, beside the nominal reference from several starts. u_input is how far the rig's "
            "tolerances move a response, the chaos share the part of the sample's spread that one start's chaotic "
            "scatter makes, an input's index the share of the spread it explains by itself. The verdict is ASME V&V "
            "20's: the difference E is a model-form error only beyond twice the validation uncertainty u_val.")
    # named, as the other sections name the project's docs: a link relative to this report would hold on the
    # machine that made it only
    return (text + " Method and assumptions: docs/validation.md.",
            html.escape(text) + " Method and assumptions: docs/validation.md.")


def case_text(entry, case, named=False):
    """(markdown, html) of one case; `named`: the sample's name in its heading (a study with several)."""
    heading = (f"{case['case']}" + (f", sample {entry['name']}" if named else "") +
               f" ({case['points']} sample points, nominal reference: {len(case['nominal_job_ids'])} starts)")
    said = reading(case)
    others = listed(case)
    md = [f"### {heading}", ""] + [line for s in said for line in (s, "")]  # a paragraph each
    page = [f"<h3>{html.escape(heading)}</h3>"] + [f"<p>{html.escape(s)}</p>" for s in said]
    rows = verdict_rows(case)
    if rows:
        md += [tables.markdown(VERDICT_HEADER, rows), ""]
        page.append(tables.html_table(VERDICT_HEADER, rows))
    spread = spread_rows(case)
    md += [tables.markdown(SPREAD_HEADER, spread), ""] + [f"- {s}" for s in others]
    page.append(tables.html_table(SPREAD_HEADER, spread))
    page += [f"<p class='notes'>{html.escape(s)}</p>" for s in others]
    return "\n".join(md), "".join(page)


def case_figure(entry, case, sample, folder, stamp):
    """Each measured quantity's sample (one dot per run, ok and defined), its 2.5-97.5 % range, the nominal
    ensemble's starts and mean, the measured value with its +-2 u_D band; None without a measured quantity."""
    measured = [q for q in case["quantities"] if q["measured"]]
    if not measured or sample is None:
        return None
    figure, axes = plt.subplots(len(measured) + 1, 1, figsize=(7.5, 1.7 * len(measured) + 0.9), constrained_layout=True,
                                gridspec_kw={"height_ratios": [3] * len(measured) + [1]})
    rng = np.random.default_rng(0)  # the dots' vertical jitter only: the same figure every time
    for ax, q in zip(axes, measured):
        y = np.asarray([p.value(q["quantity"]) for p in sample.of_case(case["case"])], float)
        y = y[np.isfinite(y)]
        ax.scatter(y, 1 + rng.uniform(-0.25, 0.25, len(y)), s=9, color="#1f77b4", alpha=0.7)
        s = q["sample"]
        if s["p2_5"] is not None:
            ax.plot([s["p2_5"], s["p97_5"]], [1.5, 1.5], color="#1f77b4", linewidth=2)
        nominal = q["nominal"]
        ax.scatter(nominal["values"], [0] * len(nominal["values"]), marker="|", s=120, color="black")
        if nominal["mean"] is not None:
            ax.plot([nominal["mean"]], [0], marker="D", color="black", markersize=6)
        d, u_d = q["measured"]["d"], q["measured"]["u_d"]
        ax.axvspan(d - 2 * u_d, d + 2 * u_d, color="#2ca02c", alpha=0.18)
        ax.axvline(d, color="#2ca02c", linewidth=1.5)
        ax.set_yticks([0, 1])
        ax.set_yticklabels([f"nominal,\n{nominal['n']} starts", f"sample,\n{s['n']} runs"], fontsize=7)
        ax.set_ylim(-0.6, 1.8)
        ax.set_xlabel(with_unit(q), fontsize=8)
        ax.tick_params(labelsize=7)
        ax.grid(True, axis="x", linewidth=0.3)
    axes[-1].axis("off")
    axes[-1].legend(handles=[proxy("sample runs (one start each)", marker="o", color="#1f77b4"),
                             proxy("sample's 2.5-97.5 %", color="#1f77b4", linewidth=2, linestyle="-"),
                             proxy("nominal reference: starts (|), mean (◆)", marker="D", color="black"),
                             proxy("measured", color="#2ca02c", linewidth=1.5, linestyle="-"),
                             proxy("measured ± 2 u_D (assumed)", color="#2ca02c", linewidth=7, alpha=0.25,
                                   linestyle="-")],
                    loc="upper left", ncol=2, fontsize=7, frameon=False)
    caption = (f"{case['case']}: each measured quantity over the sampled inputs ({entry['name']}, "
               f"{case['points']} points) "
               f"beside the nominal reference's starts and the measurement with twice its assumed standard "
               f"uncertainty (reports/experiment.toml); {stamp}")
    return save(figure, folder, f"validation_{entry['name']}_{case['case']}", caption)


def section(document, suite_folder, out):
    """(title, markdown, html, [figure paths]) of the section, or None without summary.json's `validation`."""
    entries = document.get("validation")
    if not entries:
        return None
    stamp = f"impactbench, {document.get('suite', {}).get('made', '')}"
    folder = os.path.join(out, "figures")
    os.makedirs(folder, exist_ok=True)
    md, page = [], []
    for entry in entries:
        text, text_html = intro(entry, named=len(entries) > 1)
        md += [text, ""]
        page.append(f"<p class='lede'>{text_html}</p>")
        path = os.path.join(suite_folder, "validation", entry["name"])
        sample = validation_sample.read_sample(path) if os.path.isdir(path) else None
        for case in entry["cases"]:
            case_md, case_html = case_text(entry, case, named=len(entries) > 1)
            md += [case_md, ""]
            page.append(case_html)
            figure = case_figure(entry, case, sample, folder, stamp)
            if figure:  # under its case's tables, not at the section's end with the others
                md += [markdown_figure(figure, out), ""]
                page.append(figure_html(figure, out))
    return TITLE, "\n".join(md).rstrip(), "".join(page), []
