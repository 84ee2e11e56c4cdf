"""The settings behind a configuration's name ("mujoco [contact=matched]"): what its contact path means
and what the engine used, read from the run's diagnostics in runs.jsonl (each adapter reports the
settings it applied, so nothing here restates an adapter's defaults)."""

import math

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


def _mujoco(d):
    items = [("integrator", "RK4" if d.get("integrator_rk4") == 1 else "Euler (MuJoCo's default)")]
    if "native_solref_timeconst_s" in d:
        items.append(("contact solref", f"time constant {number(d['native_solref_timeconst_s'], 's')}, "
                                        f"damping ratio {number(d.get('native_solref_dampratio'))}"))
        items.append(("contact solimp", f"dmin {number(d.get('native_solimp_dmin'))}, "
                                        f"dmax {number(d.get('native_solimp_dmax'))}"))
        items.append(("contact condim", number(d.get("native_condim"))))
    return items


def _ode(d):
    stepper = (f"dWorldQuickStep, {number(d['quick_step_iterations'])} iterations" if "quick_step_iterations" in d
               else "dWorldStep (direct LCP, ODE's default)")
    items = [("stepper", stepper), ("world ERP, CFM", f"{number(d.get('world_erp'))}, {number(d.get('world_cfm'))}"),
             ("hinge springs", "joint stops with ERP/CFM from the joint's stiffness and damping "
                               f"(frame 1: ERP {number(d.get('frame1_hinge_stop_erp'))})")]
    if "contact_soft_erp" in d:
        items.append(("contact soft ERP", number(d["contact_soft_erp"])))
    if "contact_soft_cfm_m_per_n_s" in d:
        items.append(("contact soft CFM", number(d["contact_soft_cfm_m_per_n_s"], "m/(N s)")))
    if "contact_bounce" in d:
        items.append(("contact bounce", f"{number(d['contact_bounce'])} above "
                                        f"{number(d.get('contact_bounce_threshold_m_s'), 'm/s')}"))
    return items


def _bullet(d):
    articulation = ("btMultiBody (reduced coordinates, Featherstone)" if d.get("articulation_multibody") == 1
                    else "rigid bodies joined by hinge constraints")
    items = [("articulation", articulation),
             ("solver", f"{number(d.get('solver_iterations'))} iterations, split impulse "
                        f"{'on' if d.get('split_impulse') == 1 else 'off'}, contact ERP2 {number(d.get('contact_erp2'))}")]
    if "contact_restitution" in d:
        items.append(("contact", f"restitution {number(d['contact_restitution'])}, friction "
                                 f"{number(d.get('contact_friction'))}, restitution threshold "
                                 f"{number(d.get('restitution_velocity_threshold_m_s'), 'm/s')}"))
    return items


ENGINE_SETTINGS = {"mujoco": _mujoco, "ode": _ode, "bullet": _bullet}


def describe(engine, path, diagnostics):
    """[(setting, value)] for a configuration, from one of its runs' diagnostics."""
    items = [("contact path", PATHS.get(path, path))]
    if "chain_links" in diagnostics:
        items.append(("chain", f"{number(diagnostics['chain_links'])} rigid links per frame, joint stiffness "
                               f"{number(diagnostics.get('frame1_joint_stiffness_n_m_per_rad', diagnostics.get('frame1_hinge_stiffness_n_m_per_rad')), 'N m/rad')} "
                               f"(frame 1), first frequency {number(diagnostics.get('frame1_chain_first_frequency_hz'), 'Hz')}"))
    items += ENGINE_SETTINGS.get(engine, lambda d: [])(diagnostics)
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
