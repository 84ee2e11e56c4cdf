"""The observed order of convergence of each front line: per configuration (engine and options, the contact path
among them) and chain in a case, with stable runs at three or more fixed time steps, the least-squares slope p of
log|error| against log(time step), error ~ C h^p.

Which error: frame 1's sensor peak against the engine's OWN CHAIN (runs.csv's vs_chain_reference_ column; an
ensemble's mean difference where the run stands for one). Against its own chain because that error is the
engine's time stepping and contact handling alone and tends to 0 with the step; the error against the beam tends
to the chain's own error instead, and its log flattens at small steps whatever the engine's order. Frame 1's sensor
peak rather than the fronts' score because the score is the LARGEST error over the headline metrics in tolerance
multiples (analysis.score): which metric it is can change from one step to the next (the contact duration at a
coarse step, the sensor peak at a fine one), and the slope of such an envelope is no metric's order; the impacts per
cycle move in jumps of counts, and the log decrement is left out of the scores in cases whose chain convergence
flags it. Frame 1's sensor peak is the first headline metric, a relative error that moves continuously with the
step, and the one the step search already judges steps by; where the case's chain convergence flags it (it ranks
no engine there), no order is given.

What is said instead of a number:
- "not measurable: errors within the noise": where the case needed an ensemble (significance.case_need) and a run
  of the line is a single run (its error is one start's draw, the slope would fit the scatter), or where one of the
  line's errors lies within its noise band (|error| at most its 95 % half-width: its ensemble interval, or the
  reference's single-start scatter where the case needed an ensemble; significance.error_with_interval); an error
  of exactly 0 (below the printed digits) counts as within;
- "poor fit": where the errors do not fall with the step (p below SLOWEST_ORDER: they level off at a bias the step
  does not remove) or do not follow one power of it (R² below POOR_FIT_R_SQUARED); the slope is still given, with
  that remark;
- "no order": fewer than MINIMUM_STEPS stable steps with an error."""

import html
import math

from . import metric_catalog, significance
from .tables import html_table
from .tables import markdown as markdown_table

ORDER_METRIC = "frame1_sensor_peak"  # metric_catalog name of the error whose order is fitted
AGAINST = "own chain"
MINIMUM_STEPS = 3  # two points always lie on a line: a slope through them says nothing of its fit
# Below this share of log|error|'s variance explained by the line, the errors do not follow one power of the step
# (a first-order method's errors at 2e-4, 1e-4, 5e-5 s explain over 0.99 of it; a kink from a change of regime
# brings it under 0.9).
POOR_FIT_R_SQUARED = 0.9
# Below this slope the errors do not fall with the step: every consistent time-stepping scheme converges at least at
# first order (half of it allows for a contact's whole-step timing), so a flatter line is an error the step does not
# remove (an engine that makes every impact plastic: -41 % at every step).
SLOWEST_ORDER = 0.5


def least_squares(x, y):
    """(slope, R², slope's standard error or None with fewer than three points) of y against x; R² is 1 where y
    does not vary (a flat line explains it whole)."""
    n = len(x)
    mean_x, mean_y = sum(x) / n, sum(y) / n
    sxx = sum((a - mean_x) ** 2 for a in x)
    sxy = sum((a - mean_x) * (b - mean_y) for a, b in zip(x, y))
    syy = sum((b - mean_y) ** 2 for b in y)
    slope = sxy / sxx
    residual = max(syy - slope * sxy, 0.0)
    r_squared = 1.0 if syy == 0 else 1.0 - residual / syy
    standard_error = math.sqrt(residual / (n - 2) / sxx) if n > 2 else None
    return slope, r_squared, standard_error


def line_key(point):
    """(configuration, chain links or None): one line; a run on another chain has another chain's error."""
    links = point.run.number("chain_links")
    return point.run.config, None if math.isnan(links) or links <= 0 else int(links)


def fixed_step(point):
    step_s = point.run.number("time_step_s")
    return step_s if step_s > 0 else None  # NaN or 0: an adaptive run, on no step axis


def line_samples(points, need):
    """[(step [s], job id, error as an ensembles.Interval)] of a line's stable runs with an error, coarsest step
    first, one per step (the first run at a step)."""
    metric = metric_catalog.by_name(ORDER_METRIC)
    samples, seen = [], set()
    for point in sorted(points, key=lambda p: -fixed_step(p)):
        step_s = fixed_step(point)
        if step_s in seen or not point.stable:
            continue
        noise = significance.noise_of(point.run, need)
        error = significance.error_with_interval(point.run, metric.error_column, AGAINST, noise)
        if math.isnan(error.mean):
            continue
        seen.add(step_s)
        samples.append((step_s, point.run["job_id"], error))
    return samples


def noise_reason(samples, need):
    """Why the line's errors are within the noise, or None where they are above it."""
    single = [job for _, job, e in samples if e.n <= 1]
    if need and need.get("needed") and single:
        return ("the case needed an ensemble and " + ("every run" if len(single) == len(samples) else "a run")
                + " of this line ran once: its error is one start's draw")
    within = [(step_s, e) for step_s, _, e in samples
              if e.mean == 0 or (e.half_width is not None and abs(e.mean) <= e.half_width)]
    if within:
        step_s, e = within[0]
        return (f"at {step_s:g} s the error {100 * e.mean:+.2g} % is within its ± {100 * (e.half_width or 0):.2g} %"
                if e.mean != 0 else f"at {step_s:g} s the error is 0 at the printed digits")
    return None


def fit_status(order, r_squared):
    """(status, remark) of a measured slope."""
    if order < SLOWEST_ORDER:
        return "poor fit", "poor fit: the errors do not fall with the step"
    if r_squared < POOR_FIT_R_SQUARED:
        return "poor fit", f"poor fit: R² = {r_squared:.2f}, the errors follow no one power of the step"
    return "measured", ""


def line_order(points, need):
    """A line's entry in summary.json (see observed_orders)."""
    configuration, links = line_key(points[0])
    samples = line_samples(points, need)
    label = metric_catalog.by_name(ORDER_METRIC).label
    entry = {"configuration": configuration, "engine": points[0].engine, "chain_links": links,
             "metric": label, "against": AGAINST,
             "time_steps_s": [s for s, _, _ in samples], "errors": [e.mean for _, _, e in samples],
             "half_widths": [e.half_width for _, _, e in samples], "job_ids": [j for _, j, _ in samples],
             "observed_order": None, "order_standard_error": None, "fit_r_squared": None}
    noise = noise_reason(samples, need)
    if label in points[0].skip:
        status, remark = "not measurable", f"not measurable: the case's chain convergence flags the {label}"
    elif len(samples) < MINIMUM_STEPS:
        status, remark = "no order", (f"no order: {len(samples)} stable step(s) with an error, "
                                      f"{MINIMUM_STEPS} needed")
    elif noise is not None:
        status, remark = "not measurable", "not measurable: errors within the noise (" + noise + ")"
    else:
        order, r_squared, standard_error = least_squares([math.log(s) for s, _, _ in samples],
                                                         [math.log(abs(e.mean)) for _, _, e in samples])
        entry.update(observed_order=order, order_standard_error=standard_error, fit_r_squared=r_squared)
        status, remark = fit_status(order, r_squared)
    return entry | {"status": status, "remark": remark}


def observed_orders(points, need):
    """summary.json's `observed_orders` of an engine in a case: one entry per line of its points (fronts.Point:
    configuration and chain) run at two or more fixed steps: {configuration, engine, chain_links, metric, against,
    time_steps_s (coarsest first), errors (signed, relative), half_widths (95 %, null without one), job_ids,
    observed_order (null where none is given), order_standard_error, fit_r_squared, status (measured, poor fit,
    not measurable, no order), remark (the page's words)}."""
    lines = {}
    for point in points:
        if fixed_step(point) is not None:
            lines.setdefault(line_key(point), []).append(point)
    return [line_order(own, need) for own in lines.values() if len({fixed_step(p) for p in own}) >= 2]


HEADER = ["case, law", "configuration", "time steps [s]", "frame 1 sensor peak error vs own chain",
          "observed order", "remark"]
INTRO = ("Observed order of convergence of each configuration's line in the fronts: the least-squares slope p of "
         "log|error| against log(time step) (error ~ C h^p) over its stable runs, the error that of frame 1's "
         "sensor peak against the engine's own chain (its time stepping and contact handling alone), ± the slope's "
         f"standard error; {MINIMUM_STEPS} steps or more. A case that needed an ensemble, or an error within its "
         "noise, gives no number; a poor fit is named. summary.json: each engine's fronts.observed_orders.")


def order_text(entry):
    """'1.02 ± 0.03' (the slope and its standard error), or '–' where no order is given."""
    if entry["observed_order"] is None:
        return "–"
    spread = entry["order_standard_error"]
    return f"{entry['observed_order']:.2f}" + (f" ± {spread:.2f}" if spread is not None else "")


def every_line(cases):
    """[(case, line)] over summary.json's cases, every engine's lines in the fronts' order."""
    return [(case, line) for case in cases for entry in ((case.get("fronts") or {}).get("engines") or {}).values()
            for line in entry.get("observed_orders", [])]


def rows(cases):
    """The table's rows: the lines with three stable steps or more (a line of fewer is counted under the table, not
    listed: in a default study most cases' lines have one or two steps, and a table of "no order" says nothing)."""
    found = []
    for case, line in every_line(cases):
        if line["status"] != "no order":
            name = line["configuration"] + (f", {line['chain_links']} links" if line["chain_links"] else "")
            found.append([f"{case['scenario']}, {case['law']}", name,
                          ", ".join(f"{s:.3g}" for s in line["time_steps_s"]),
                          ", ".join(f"{100 * e:+.3g} %" for e in line["errors"]),
                          order_text(line), line["remark"]])
    return found


def too_few_note(cases):
    """'4 lines with fewer than 3 stable steps give no order (summary.json).', '' without one."""
    count = sum(line["status"] == "no order" for _, line in every_line(cases))
    if not count:
        return ""
    return (f"{count} line{'s' if count > 1 else ''} with fewer than {MINIMUM_STEPS} stable steps "
            f"give{'' if count > 1 else 's'} no order (summary.json).")


def html_section(document):
    """The table under the fronts (id "front-orders") and the count of the lines too short for one, '' without a
    line of two steps."""
    cases = document.get("cases", [])
    found, note = rows(cases), too_few_note(cases)
    if not found and not note:
        return ""
    table = html_table(HEADER, found) if found else ""
    return (f"<p class='lede'>{html.escape(INTRO)}</p><div id='front-orders'>{table}"
            + (f"<p class='notes'>{html.escape(note)}</p>" if note else "") + "</div>")


def markdown(document):
    """The same in Markdown, '' without a line."""
    cases = document.get("cases", [])
    found, note = rows(cases), too_few_note(cases)
    if not found and not note:
        return ""
    return "\n\n".join([INTRO] + ([markdown_table(HEADER, found)] if found else []) + ([note] if note else []))
