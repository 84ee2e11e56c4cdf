"""The reference's modal model as `impactbench export SCENARIO --engine reference` writes it (JSON), read
for SciPy: the equations of rig.md section 2 in stacked modal form,

    q'' + 2 zeta omega q' + omega^2 q = p F_m(t) - b F_c,   delta = b . q - gap,   F_m = A cos(Omega t),

the chosen contact law (rig.md section 3) and the kinematics the harness records (tip displacement,
velocity, acceleration and its rate of each frame, contact force and its rate). Modal coordinates in
m sqrt(kg), SI units everywhere else. Vectorised over time: every function takes arrays of instants.
"""
import json
import math

import numpy as np


class ModelError(ValueError):
    """A model file that cannot be used; the message names the file, the key, the value and what is allowed."""


def _get(data, key, path, where=""):
    if key not in data:
        raise ModelError(f"{path}: missing key '{where}{key}'")
    return data[key]


def _number(data, key, path, where="", positive=False, non_negative=False):
    value = _get(data, key, path, where)
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise ModelError(f"{path}: '{where}{key}' = {value!r}: allowed: a finite number")
    if positive and not value > 0:
        raise ModelError(f"{path}: '{where}{key}' = {value!r}: allowed: a number > 0")
    if non_negative and not value >= 0:
        raise ModelError(f"{path}: '{where}{key}' = {value!r}: allowed: a number >= 0")
    return float(value)


def _vector(data, key, path, size, where=""):
    value = _get(data, key, path, where)
    if not isinstance(value, list) or len(value) != size or not all(
            isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x) for x in value):
        raise ModelError(f"{path}: '{where}{key}': allowed: a list of {size} finite numbers (one per stacked mode)")
    return np.array(value, dtype=float)


class ContactLaw:
    """F_c(delta, delta') of one law, continued smoothly to delta < 0 as the reference does inside a contact
    phase (physics/contact_laws.h): the phase ends where delta returns to 0, so the continuation is never
    applied, but it keeps the right-hand side smooth across the step that crosses the separation."""

    def __init__(self, data, path):
        self.name = _get(data, "name", path, "contact_law.")
        w = "contact_law."
        if self.name == "hertz":
            self.stiffness = _number(data, "stiffness_n_per_m_pow_n", path, w, positive=True)  # k [N/m^n]
            self.exponent = _number(data, "exponent", path, w, positive=True)                 # n [-]
            self.damping = _number(data, "damping_n_s_per_m_pow_n_plus_1", path, w, non_negative=True)  # c [N s/m^(n+1)]
            self.clipped = True
        elif self.name == "viscoelastic":
            self.stiffness = _number(data, "stiffness_n_per_m", path, w, positive=True)   # k [N/m]
            self.damping = _number(data, "damping_n_s_per_m", path, w, non_negative=True)  # c [N s/m]
            self.clipped = _get(data, "clip_tension", path, w)
            if not isinstance(self.clipped, bool):
                raise ModelError(f"{path}: 'contact_law.clip_tension' = {self.clipped!r}: allowed: true or false")
        elif self.name == "newton":
            self.restitution = _number(data, "restitution", path, w, non_negative=True)  # e [-]
            if self.restitution > 1:
                raise ModelError(f"{path}: 'contact_law.restitution' = {self.restitution}: allowed: 0 <= e <= 1")
            self.clipped = False
        else:
            raise ModelError(f"{path}: 'contact_law.name' = {self.name!r}: allowed: hertz, viscoelastic, newton")
        self.instantaneous = self.name == "newton"

    def _power(self, delta):  # sign(delta) |delta|^n and its derivative
        magnitude = np.abs(delta)
        return np.copysign(magnitude ** self.exponent, delta), self.exponent * magnitude ** (self.exponent - 1)

    def unclipped(self, delta, rate):
        """The law's expression before clipping at zero [N]."""
        if self.name == "hertz":
            return self.stiffness * self._power(delta)[0] * (1 + self.damping / self.stiffness * rate)
        return self.stiffness * delta + self.damping * rate

    def force(self, delta, rate):
        """Contact force [N] inside a contact phase (continued to delta < 0)."""
        if self.name == "hertz":
            return self.stiffness * self._power(delta)[0] * np.maximum(0.0, 1 + self.damping / self.stiffness * rate)
        f = self.stiffness * delta + self.damping * rate
        return np.maximum(0.0, f) if self.clipped else f

    def force_rate(self, delta, rate, acceleration):
        """dF_c/dt [N/s] along a motion with indentation delta, delta' and delta''."""
        if self.name == "hertz":
            factor = 1 + self.damping / self.stiffness * rate
            power, d_power = self._power(delta)
            value = self.stiffness * d_power * factor * rate + self.damping * power * acceleration
            return np.where(factor > 0, value, 0.0)
        value = self.stiffness * rate + self.damping * acceleration
        if self.clipped:
            value = np.where(self.stiffness * delta + self.damping * rate > 0, value, 0.0)
        return value

    def elastic_energy(self, delta):
        """Energy stored in the contact spring [J]; zero without overlap."""
        d = np.maximum(delta, 0.0)
        if self.name == "hertz":
            return self.stiffness * d ** (self.exponent + 1) / (self.exponent + 1)
        return 0.5 * self.stiffness * d * d


class ModalModel:
    def __init__(self, path):
        try:
            with open(path, encoding="utf-8") as f:
                data = json.load(f)
        except OSError as error:
            raise ModelError(f"{path}: cannot read: {error.strerror}") from None
        except json.JSONDecodeError as error:
            raise ModelError(f"{path}:{error.lineno}: not JSON: {error.msg}") from None
        if data.get("format") != "impactbench modal model 1":
            raise ModelError(f"{path}: 'format' = {data.get('format')!r}: allowed: 'impactbench modal model 1' "
                             "(write it with: impactbench export SCENARIO --engine reference --law LAW --out FILE)")
        self.path = path
        self.scenario = str(data.get("scenario", ""))
        self.omega = np.array(_get(data, "omega_rad_s", path), dtype=float)  # [rad/s]
        m = self.modes = len(self.omega)
        if m == 0 or not np.all(np.isfinite(self.omega)) or np.any(self.omega <= 0):
            raise ModelError(f"{path}: 'omega_rad_s': allowed: a non-empty list of frequencies > 0 rad/s")
        self.zeta = _vector(data, "zeta", path, m)
        self.b = _vector(data, "contact_lever_per_sqrt_kg", path, m)   # delta = b . q - gap
        self.p = _vector(data, "motor_lever_per_sqrt_kg", path, m)     # motor force's modal lever
        recorded = _get(data, "recorded", path)
        self.tip = np.vstack([_vector(recorded, f"frame{f}_tip_lever_per_sqrt_kg", path, m, "recorded.") for f in (1, 2)])
        self.gap = _number(data, "gap_m", path)
        motor = data.get("motor")
        self.motor_amplitude = _number(motor, "amplitude_n", path, "motor.") if motor else 0.0   # [N]
        self.motor_omega = _number(motor, "omega_rad_s", path, "motor.", non_negative=True) if motor else 0.0  # [rad/s]
        self.law = ContactLaw(_get(data, "contact_law", path), path)
        initial = _get(data, "initial", path)
        self.q0 = _vector(initial, "q_m_sqrt_kg", path, m, "initial.")
        self.v0 = _vector(initial, "v_m_s_sqrt_kg", path, m, "initial.")
        self.duration = _number(data, "duration_s", path, positive=True)
        self.series_start = _number(data, "series_start_s", path, non_negative=True)
        self.output_rate = _number(data, "output_rate_hz", path, positive=True)
        self.window = (_number(data, "scoring_window_start_s", path), _number(data, "scoring_window_end_s", path))
        settings = _get(data, "reference_settings", path)
        self.rtol = _number(settings, "rtol", path, "reference_settings.", positive=True)
        self.atol = _number(settings, "atol_m_sqrt_kg", path, "reference_settings.", positive=True)
        self.accumulation_time = _number(settings, "accumulation_time_s", path, "reference_settings.", non_negative=True)
        self.damping_rate = 2 * self.zeta * self.omega   # 2 zeta omega [1/s]
        self.stiffness = self.omega ** 2                  # omega^2 [1/s^2]
        self.lever_norm2 = float(self.b @ self.b)         # 1 / effective mass of the relative tip motion [1/kg]
        # the fastest motion in the model: sets the scan grid for extrema (the reference's 8 per period)
        self.fastest_period = 2 * math.pi / max(self.omega.max(), self.motor_omega)

    def motor(self, t):
        """F_m(t) [N] and dF_m/dt [N/s]."""
        phase = self.motor_omega * t
        return self.motor_amplitude * np.cos(phase), -self.motor_amplitude * self.motor_omega * np.sin(phase)

    def acceleration_without_contact(self, t, q, v):
        """q'' [m sqrt(kg)/s^2] with no contact force; q, v: (modes,) or (modes, points)."""
        fm = self.motor(t)[0]
        if q.ndim == 2:
            return np.outer(self.p, fm) - self.damping_rate[:, None] * v - self.stiffness[:, None] * q
        return self.p * fm - self.damping_rate * v - self.stiffness * q

    def kinematics(self, t, y, contact):
        """Everything recorded at instants t (array) from states y (2 M or more rows, one column per instant);
        contact: whether the contact force acts (inside a contact phase)."""
        m = self.modes
        q, v = y[:m], y[m:2 * m]
        fm, fm_rate = self.motor(t)
        k = {"delta": self.b @ q - self.gap, "delta_rate": self.b @ v}
        free = self.acceleration_without_contact(t, q, v)
        if contact:
            k["force"] = self.law.force(k["delta"], k["delta_rate"])
            acc = free - np.outer(self.b, k["force"])
            k["force_rate"] = self.law.force_rate(k["delta"], k["delta_rate"], self.b @ acc)
            k["energy"] = 0.5 * np.sum(v * v + self.stiffness[:, None] * q * q, axis=0) + self.law.elastic_energy(k["delta"])
        else:
            k["force"] = k["force_rate"] = np.zeros_like(t)
            acc = free
            k["energy"] = 0.5 * np.sum(v * v + self.stiffness[:, None] * q * q, axis=0)
        jerk = np.outer(self.p, fm_rate) - self.damping_rate[:, None] * acc - self.stiffness[:, None] * v \
            - np.outer(self.b, k["force_rate"])
        k["displacement"] = self.tip @ q      # (2, points): frame 1, frame 2 [m]
        k["velocity"] = self.tip @ v          # [m/s]
        k["acceleration"] = self.tip @ acc    # [m/s^2]
        k["jerk"] = self.tip @ jerk           # [m/s^3]
        return k
