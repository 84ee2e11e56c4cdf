"""The settings behind a configuration's name ("<engine> [contact=matched]"): what its contact path means
and what the engine used, read from the run's diagnostics in runs.jsonl (each adapter reports the
settings it applied, so nothing here restates an adapter's defaults) through the keys its descriptor
documents (engines.json; docs/diagnostics.md)."""

import math

from . import engines

PATHS = {
    "matched": "matched: the scenario's contact law in the engine's own contact parameters where it has a "
               "form for it, else the law's force applied at the tips (docs/engines.md)",
    "injected": "injected: impactbench computes the law's force from the tip states and applies it; the "
                "engine's collision is off",
    "native": "native: the engine's own contact with its defaults, as a user would leave it (the law's "
              "parameters are not used)",
}


def number(value, unit=""):
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "?"
    return f"{value:.4g}" + (f" {unit}" if unit else "")


def engine_items(descriptor, d):
    """[(label, text)] of the documented diagnostics keys (the engine's descriptor, docs/diagnostics.md)
    that a run wrote, in the descriptor's order; a flag or code shown as the descriptor's text for its
    value, a number with its unit. Keys sharing a label (an engine with one flag per integrator) make one item."""
    items = {}
    for key in descriptor.get("diagnostics", []):
        if key.get("key") not in d:
            continue
        value = d[key["key"]]
        text = key.get("values", {}).get(number(value), number(value, key.get("unit", "")))
        label = key.get("label") or key["key"]
        items[label] = f"{items[label]}, {text}" if label in items else text
    return list(items.items())


def describe(engine, path, diagnostics):
    """[(setting, value)] for a configuration, from one of its runs' diagnostics."""
    items = [("contact path", PATHS.get(path, path))]
    if "chain_links" in diagnostics:
        # "hinge" was three engines' word in folders written before the one vocabulary (docs/diagnostics.md)
        # and before the joints were tuned to the beam's first two frequencies: one stiffness for every joint
        stiffness = diagnostics.get("frame1_root_joint_stiffness_n_m_per_rad",
                                    diagnostics.get("frame1_joint_stiffness_n_m_per_rad",
                                                    diagnostics.get("frame1_hinge_stiffness_n_m_per_rad")))
        items.append(("chain", f"{number(diagnostics['chain_links'])} rigid links per frame, root joint stiffness "
                               f"{number(stiffness, 'N m/rad')} "
                               f"(frame 1), first frequency {number(diagnostics.get('frame1_chain_first_frequency_hz'), 'Hz')}"))
    items += engine_items(engines.descriptor(engine), diagnostics)
    return items


def merged(per_law):
    """One configuration's settings over the laws it ran: {setting: text}, a setting that differs between
    laws (the matched path maps each law's parameters) written per law."""
    names = []
    for items in per_law.values():
        names += [name for name, _ in items if name not in names]
    out = {}
    for name in names:
        values = {law: dict(items).get(name) for law, items in per_law.items()}
        distinct = {v for v in values.values() if v is not None}
        out[name] = distinct.pop() if len(distinct) == 1 and None not in values.values() else \
            "; ".join(f"{law}: {v}" for law, v in values.items() if v is not None)
    return out
