"""The chain-convergence table, from summary.json's cases (chain_convergence.py): per case and scored metric, the
chain's error against the beam at each K tried with its 95 % interval, the smallest K from which it stays within
its share of the tolerance, and why a metric ranks no engine. Rendered in HTML and Markdown."""

import html

from .tables import html_table, signed_text
from .tables import markdown as markdown_table


def error_cell(row, kind):
    """'-3.7 % ± 1.6 %' or '+0.014 ± 0.02', with ✓ within the chain's share of the tolerance, ✗ beyond, ? undecided."""
    value = signed_text(row["error"], kind)
    if row.get("half_width"):
        value += f" ± {100 * row['half_width']:.2g} %" if kind == "relative" else f" ± {row['half_width']:.2g}"
    return value + {"within": " ✓", "beyond": " ✗", "undecided": " ?"}[row["status"]]


def numerical_text(case, label):
    """The beam reference's own numerical error in a metric (budget.reference_numerical_error), or '–'."""
    entry = ((case.get("reference_numerical_error") or {}).get("metrics") or {}).get(label)
    if not entry:
        return "–"
    return f"{100 * entry['error']:+.1e} %" if entry["kind"] == "relative" else f"{entry['error']:+.1e}"


def settled_text(metric):
    """'32', 'none tried', or 'undecided (noise ± 2.9 %)' where only the noise keeps it from settling."""
    if metric["settled_links"] is not None:
        return str(metric["settled_links"])
    if not metric["flags"] and metric["noise_exceeds_share_at_links"]:
        return "undecided: the noise exceeds the share"
    return "none tried"


def rows_and_header(cases):
    """(header, rows, notes) over every case with a convergence; ([], [], []) without one."""
    with_convergence = [c for c in cases if c.get("chain_convergence")]
    if not with_convergence:
        return [], [], []
    links = sorted({k for c in with_convergence for k in c["chain_convergence"]["links_tried"]})
    header = (["case, law", "metric"] + [f"K = {k}" for k in links] +
              ["settled from K", "ranks engines", "the reference's own numerical error"])
    rows, notes = [], []
    for case in with_convergence:
        convergence = case["chain_convergence"]
        for label, metric in convergence["metrics"].items():
            by_links = {r["links"]: r for r in metric["errors_vs_beam"]}
            cells = [error_cell(by_links[k], metric["kind"]) if k in by_links else "–" for k in links]
            if metric["flags"]:
                notes.append(f"[{len(notes) + 1}] {case['scenario']}, {case['law']}, {label}: " + "; ".join(metric["flags"]))
            rows.append([f"{case['scenario']}, {case['law']}", label] + cells +
                         [settled_text(metric),
                          f"no [{len(notes)}]" if metric["flags"] else "yes", numerical_text(case, label)])
    return header, rows, notes


def intro(cases):
    share = next(c["chain_convergence"]["share_of_tolerance"] for c in cases if c.get("chain_convergence"))
    return (f"The chain's own error against the beam at K rigid links per frame: the reference alone on each chain, "
            f"from the same starts as the beam's (± its 95 % interval). ✓: within {share:g} of the metric's verdict "
            "tolerance, the share left to the chain; ✗ beyond; ? the interval straddles it. Settled from K: the "
            "smallest K from which every finer chain tried stays within. A metric that does not settle, or whose "
            "chain error swings in sign between two K beyond that share (ill-conditioned in its window), ranks no "
            "engine in that case. The last column: the beam reference against itself at tolerances a thousand times "
            "tighter (its first start), the error its own tolerances leave; in a chaotic case it is what they seed, "
            "within the scatter of one start.")


def section(document):
    """(title, markdown, html) of the chain-convergence section, or None without a convergence."""
    header, rows, notes = rows_and_header(document["cases"])
    if not rows:
        return None
    text = intro(document["cases"])
    markdown = "\n".join([text, "", markdown_table(header, rows), ""] + notes)
    page = (f"<p class='lede'>{html.escape(text)}</p><div id='convergence'>{html_table(header, rows)}</div>"
            + "".join(f"<p class='notes'>{html.escape(n)}</p>" for n in notes))
    return "The chain's resolution", markdown, page
