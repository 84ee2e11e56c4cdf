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


def _dart(d):
    unit = {1: "m", 100: "cm", 1000: "mm"}.get(d.get("length_unit_per_m"), number(d.get("length_unit_per_m")) + " per m")
    items = [("model length unit", unit),
             ("LCP solver", "PGS" if d.get("lcp_pgs") == 1 else "Dantzig (DART's default)"),
             ("joint springs", "DART's implicit joint springs and dampers")]
    if d.get("contact_force_from_tip_states") == 1:
        items.append(("contact", "the law's force from the tip states (DART has no compliant rigid contact)"))
    if "restitution_of_pair" in d:
        detector = "analytic sphere-sphere (DARTCollisionDetector)" if d.get("collision_detector_analytic") == 1 \
            else "FCL (DART's default, spheres as meshes)"
        items.append(("contact", f"{detector}, restitution {number(d['restitution_of_pair'])} for the pair, friction "
                                 f"{number(d.get('friction_coefficient'))}; no bounce below "
                                 f"{number(d.get('bounce_threshold_m_s'), 'm/s')} (e v), bounce capped at "
                                 f"{number(d.get('max_bounce_velocity_m_s'), 'm/s')}"))
    return items


def _simbody(d):
    if "rigid_constraint_tolerance_m" in d:
        items = [("stepping", "SemiExplicitEulerTimeStepper (rigid contact)"),
                 ("contact", f"rigid, Newton restitution {number(d.get('rigid_contact_newton_restitution'))}, "
                             f"constraint tolerance {number(d['rigid_constraint_tolerance_m'], 'm')}, capture speed "
                             f"{number(d.get('rigid_impact_capture_speed_m_s'), 'm/s')}")]
    else:
        integrator = next((k[len("integrator_"):] for k in d if k.startswith("integrator_") and k not in
                           ("integrator_steps", "integrator_steps_attempted")), "?")
        stepping = (f"error-controlled {integrator}, accuracy {number(d.get('accuracy'))}, steps "
                    f"{number(d.get('smallest_step_s'), 's')} to {number(d.get('largest_step_s'), 's')}"
                    if d.get("error_controlled") == 1 else f"fixed-step {integrator}")
        items = [("stepping", stepping)]
        if "hunt_crossley_material_stiffness_pa" in d:
            items.append(("contact", f"Hunt-Crossley, material stiffness {number(d['hunt_crossley_material_stiffness_pa'], 'Pa')}, "
                                     f"dissipation {number(d.get('hunt_crossley_dissipation_s_per_m'), 's/m')}"))
        if d.get("spring_dashpot_force_element") == 1:
            items.append(("contact", "the spring-dashpot law as a force element"))
    items.append(("hinge springs", "explicit forces (mobility springs and dampers); stable below "
                                   f"{number(d.get('explicit_spring_step_limit_s'), 's')} with semi-explicit Euler"))
    return items


ENGINE_SETTINGS = {"mujoco": _mujoco, "ode": _ode, "bullet": _bullet, "dart": _dart, "simbody": _simbody}


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
