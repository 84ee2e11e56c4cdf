"""The reference's ensemble of starts from rest in a sweep (harness/sweep: --reference-ensemble; docs/sweeps.md,
"Multistable ratios"): the starts reaching each regime at each ratio, the multistable ratios (more than one
regime reached: which attractor one start reaches is chance there), and an engine's regime judged against
them. sweep.py reads the sweep and uses these."""

import math


def ratio_text(ratio):
    return f"{ratio:.3f}".rstrip("0").rstrip(".") if not math.isnan(ratio) else "?"


def regime_of(row):
    """What a row reached: its regime, or its verdict when it is not ok (unstable, failed)."""
    return row["regime"] if row["verdict"] == "ok" and row["regime"] else row["verdict"]


def ensemble_member(row):
    """An ensemble's start K >= 1 (a sweep recorded before ensembles has no such column: every row is start 0)."""
    start = row.get("ensemble_start", 0)
    return isinstance(start, float) and not math.isnan(start) and start >= 1


def start_ensembles(rows):
    """The reference's starts from rest at each ratio where it ran more than one: {(law, ratio): {regime: count}},
    the ratio rounded to 1e-6, regimes in the order first reached (start 0 first)."""
    by_ratio = {}
    for r in sorted(rows, key=lambda r: r.get("ensemble_start", 0)):
        if r["engine"] == "reference" and r["start"] == "rest":  # a sweep's one reference (its options, if any)
            by_ratio.setdefault((r["law"], round(r["ratio"], 6)), []).append(regime_of(r))
    found = {}
    for key, regimes in sorted(by_ratio.items()):
        if len(regimes) > 1:
            found[key] = {}
            for regime in regimes:
                found[key][regime] = found[key].get(regime, 0) + 1
    return found


def share_start_ensembles(sweeps):
    """A study's sweeps ([(name, Sweep)]): a sweep without an ensemble of its own takes the reference's starts
    from a sibling of the same scenario (the study's reference sweep), so that the engines' regime agreement at a
    multistable ratio is judged against the regimes the reference's starts reach. The same reference only: the
    same scenario and the reference's options (another mode count is another model)."""
    def reference_of(s):
        return s.settings.get("scenario"), next((r["options"] for r in s.rows if r["engine"] == "reference"), None)

    for name, s in sweeps:
        if s.start_ensembles:
            continue
        for other_name, other in sweeps:
            if other is not s and other.start_ensembles and reference_of(other) == reference_of(s):
                s.start_ensembles = dict(other.start_ensembles)
                s.start_ensembles_from = f"sweep {other_name}"
                break


def multistable(counts):
    """More than one regime reached by the starts: which attractor one start reaches is chance."""
    return counts is not None and len(counts) > 1


def fractions_text(counts):
    """ "no impact 5 of 8, irregular 3 of 8": each regime the starts reach, with how many of them."""
    total = sum(counts.values())
    return ", ".join(f"{regime} {n} of {total}" for regime, n in counts.items())


def impacting_count(counts):
    return sum(n for regime, n in counts.items() if regime not in ("no impact", "unstable", "failed"))


def start_ensemble_table(sweep, law):
    """Per ensemble ratio of one law: [ratio, starts, regimes reached (count of starts), impacting, multistable]."""
    rows = []
    for (row_law, ratio), counts in sorted(sweep.start_ensembles.items()):
        if row_law != law:
            continue
        total = sum(counts.values())
        rows.append({"ratio": ratio, "starts": total, "regimes": dict(counts), "impacting": impacting_count(counts),
                     "multistable": multistable(counts)})
    return rows


START_ENSEMBLE_HEADER = ["ratio", "starts", "regimes reached (starts of all)", "impacting", "multistable"]


def start_ensemble_rows(table):
    return [[ratio_text(t["ratio"]), str(t["starts"]), fractions_text(t["regimes"]),
             f"{t['impacting']} of {t['starts']}", "yes" if t["multistable"] else "no"] for t in table]


def multistable_sentence(sweep):
    """The reference's multistable ratios in words, per law ("" without an ensemble)."""
    parts = []
    for law in sweep.laws() or sorted({law for law, _ in sweep.start_ensembles}):
        table = start_ensemble_table(sweep, law)
        if not table:
            continue
        found = [t for t in table if t["multistable"]]
        starts = sorted({t["starts"] for t in table})
        runs = f"the reference from {'/'.join(str(n) for n in starts)} starts from rest at {len(table)} ratios"
        if found:
            parts.append(f"{law}: {runs} is multistable at r = " +
                         "; ".join(f"{ratio_text(t['ratio'])} ({fractions_text(t['regimes'])})" for t in found))
        else:
            parts.append(f"{law}: {runs} reaches one regime at each (no multistable ratio found)")
    where = "" if sweep.start_ensembles_from in ("", "this sweep") else f" ({sweep.start_ensembles_from})"
    return ("Multistable ratios" + where + ": " + "; ".join(parts) + ".") if parts else ""


def regime_agrees(row, reference_row, counts):
    """An engine's row against the reference's row at the same ratio and start; at a multistable ratio (counts:
    the regimes the reference's starts from rest reach there, more than one) also against every regime they
    reach: which attractor one start reaches is chance there, so any one the reference reaches is the
    reference's. A row not ok disagrees."""
    if row["verdict"] != "ok":
        return False
    return row["regime"] == reference_row["regime"] or (multistable(counts) and row["regime"] in counts)
