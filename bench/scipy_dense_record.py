"""What bench/scipy_reference.py records from solve_ivp's dense output, the way the reference records
(reference/reference_solver.cpp, model/trajectory.h):

- samples at the output rate: tip displacement, velocity and acceleration of both frames, contact force,
  mechanical energy;
- the peak_* columns: the exact maximum of |tip acceleration| and of the contact force over each output
  interval (t_{k-1}, t_k] (the sample at t_{k-1} included). Exact as the reference's: every quantity is
  scanned on a grid of at least 8 points per period of the fastest mode (the reference's rule, so that its
  derivative changes sign at most once between grid points), through every integrator step end and every
  sample, and each sign change of the derivative (jerk, dF/dt) is located by bisection on the dense output
  to 2^-30 of a grid interval (the value at an extremum is flat in its location: an error e in the location
  changes it by order e^2); the maximum is taken over the grid values and these extrema;
- per contact episode: the largest force and the largest indentation, located the same way.

A solution piece is a Segment: one phase ([t_a, t_b], with or without the contact force) and its dense output.
"""
import math

import numpy as np

BISECTION_STEPS = 30
GRID_POINTS_PER_PERIOD = 8


class DenseOutput:
    """solve_ivp's OdeSolution evaluated at many instants at once. OdeSolution.__call__ loops over its
    steps in Python, far too slow for the extremum search; this stacks the interpolants of DOP853 and of
    the explicit Runge-Kutta methods (RK45, RK23) into arrays and evaluates them the way SciPy does
    (scipy/integrate/_ivp/rk.py), and falls back to OdeSolution for any other method."""

    def __init__(self, solution):
        self.solution = solution
        self.boundaries = np.asarray(solution.ts)
        interpolants = solution.interpolants
        kinds = {type(i).__name__ for i in interpolants}
        self.kind = kinds.pop() if len(kinds) == 1 else None
        if self.kind not in ("Dop853DenseOutput", "RkDenseOutput"):
            self.kind = None
            return
        self.t_old = np.array([i.t_old for i in interpolants])
        self.h = np.array([i.h for i in interpolants])
        self.y_old = np.array([i.y_old for i in interpolants])
        self.coefficients = np.array([i.F if self.kind == "Dop853DenseOutput" else i.Q.T for i in interpolants])

    def step_ends(self):
        return self.boundaries

    def __call__(self, t):
        """States at instants t (1-D array): shape (states, len(t))."""
        t = np.asarray(t, dtype=float)
        if self.kind is None:
            return self.solution(t)
        # the step of each instant, as OdeSolution chooses it (an instant on a step end: the earlier step)
        step = np.clip(np.searchsorted(self.boundaries, t, side="left") - 1, 0, len(self.h) - 1)
        x = ((t - self.t_old[step]) / self.h[step])[:, None]
        if self.kind == "Dop853DenseOutput":
            y = np.zeros((len(t), self.y_old.shape[1]))
            for i in range(self.coefficients.shape[1] - 1, -1, -1):  # SciPy's nested form, innermost first
                y += self.coefficients[step, i]
                y *= x if (self.coefficients.shape[1] - 1 - i) % 2 == 0 else 1 - x
        else:  # RkDenseOutput: y = y_old + h Q [x, x^2, ...]
            y = np.zeros((len(t), self.y_old.shape[1]))
            power = np.ones_like(x)
            for i in range(self.coefficients.shape[1]):
                power = power * x
                y += self.coefficients[step, i] * power
            y *= self.h[step][:, None]
        y += self.y_old[step]
        return y.T


class Segment:
    """One phase of the solution: [t_a, t_b], whether the contact force acts, and its dense output."""

    def __init__(self, t_a, t_b, contact, dense):
        self.t_a, self.t_b, self.contact, self.dense = t_a, t_b, contact, dense

    def kinematics(self, model, t):
        return model.kinematics(t, self.dense(t), self.contact)

    def grid(self, model, extra=()):
        """Scan instants: the segment's ends, every integrator step end inside it, the extra instants, and
        enough between them for GRID_POINTS_PER_PERIOD points per period of the fastest mode."""
        ends = self.dense.step_ends()
        knots = np.unique(np.concatenate(([self.t_a, self.t_b], ends[(ends > self.t_a) & (ends < self.t_b)])))
        spacing = model.fastest_period / GRID_POINTS_PER_PERIOD
        pieces = [knots[-1:]]
        for a, b in zip(knots[:-1], knots[1:]):
            n = max(1, math.ceil((b - a) / spacing))
            pieces.append(a + (b - a) * np.arange(n) / n)
        extra = np.asarray(extra, dtype=float)
        pieces.append(extra[(extra >= self.t_a) & (extra <= self.t_b)])
        return np.unique(np.concatenate(pieces))

    def _bisect(self, model, lo, hi, slope_lo, slope_of):
        """Roots of slope_of(kinematics) bracketed by [lo, hi], with its sign at lo; returns the kinematics there."""
        if lo.size == 0:
            return None
        lo, hi = lo.copy(), hi.copy()
        positive_lo = slope_lo > 0
        for _ in range(BISECTION_STEPS):
            mid = 0.5 * (lo + hi)
            same = (slope_of(self.kinematics(model, mid)) > 0) == positive_lo
            lo = np.where(same, mid, lo)
            hi = np.where(same, hi, mid)
        mid = 0.5 * (lo + hi)
        return mid, self.kinematics(model, mid)

    def peaks(self, model, extra=()):
        """The scan grid's kinematics plus every located extremum: (instants, |acceleration| per frame,
        force) for the series' peak columns, and the largest force and indentation of the segment."""
        times = self.grid(model, extra)
        k = self.kinematics(model, times)
        t_points = [times]
        acc = [np.abs(k["acceleration"])]
        force = [k["force"]]
        max_force, max_delta = k["force"].max(), k["delta"].max()
        for f in (0, 1):
            jerk = k["jerk"][f]
            change = np.nonzero(jerk[:-1] * jerk[1:] < 0)[0]
            found = self._bisect(model, times[change], times[change + 1], jerk[change], lambda kk, f=f: kk["jerk"][f])
            if found:
                t_points.append(found[0])
                acc.append(np.abs(found[1]["acceleration"]))
                force.append(found[1]["force"])
        if self.contact:
            for slope in ("force_rate", "delta_rate"):
                s = k[slope]
                change = np.nonzero(s[:-1] * s[1:] < 0)[0]
                found = self._bisect(model, times[change], times[change + 1], s[change], lambda kk, n=slope: kk[n])
                if found:
                    t_points.append(found[0])
                    acc.append(np.abs(found[1]["acceleration"]))
                    force.append(found[1]["force"])
                    max_force = max(max_force, found[1]["force"].max())
                    max_delta = max(max_delta, found[1]["delta"].max())
        return np.concatenate(t_points), np.hstack(acc), np.concatenate(force), max_force, max_delta


class SeriesRecorder:
    """The output series of model/trajectory.h: samples at rate_hz from start_s to end_s, and the exact
    maxima between them, fed one Segment at a time in time order."""

    COLUMNS = ("time_s,frame1_displacement_m,frame1_velocity_m_s,frame1_acceleration_m_s2,"
               "frame2_displacement_m,frame2_velocity_m_s,frame2_acceleration_m_s2,contact_force_n,"
               "frame1_peak_abs_acceleration_m_s2,frame2_peak_abs_acceleration_m_s2,peak_contact_force_n,"
               "mechanical_energy_j")

    def __init__(self, start_s, end_s, rate_hz):
        # the reference's sample count and times (SeriesRecorder in reference_solver.cpp)
        count = int(math.floor((end_s - start_s) * rate_hz + 1e-9)) + 1 if end_s >= start_s else 0
        self.start, self.rate = start_s, rate_hz
        self.time = start_s + np.arange(count) / rate_hz
        self.filled = np.zeros(count, dtype=bool)
        self.columns = {name: np.full(count, np.nan) for name in (
            "displacement1", "velocity1", "acceleration1", "displacement2", "velocity2", "acceleration2",
            "force", "energy")}
        self.peak_acc = np.zeros((2, count))     # max over each interval's interior
        self.peak_force = np.full(count, -np.inf)

    def wants(self, t_a, t_b):
        return len(self.time) > 0 and t_b >= self.start and t_a <= self.time[-1]

    def add(self, model, segment, peaks=None):
        """Samples and peaks from one segment; peaks: segment.peaks(model, self.time) when already computed."""
        if not self.wants(segment.t_a, segment.t_b):
            return
        # samples in (t_a, t_b] not taken yet (an instant on a boundary belongs to the earlier segment)
        take = np.nonzero(~self.filled & (self.time >= segment.t_a) & (self.time <= segment.t_b))[0]
        if take.size:
            k = segment.kinematics(model, self.time[take])
            for f in (0, 1):
                self.columns[f"displacement{f + 1}"][take] = k["displacement"][f]
                self.columns[f"velocity{f + 1}"][take] = k["velocity"][f]
                self.columns[f"acceleration{f + 1}"][take] = k["acceleration"][f]
            self.columns["force"][take] = k["force"]
            self.columns["energy"][take] = k["energy"]
            self.filled[take] = True
        times, acc, force, _, _ = peaks or segment.peaks(model, self.time)
        # interval k is (t_{k-1}, t_k]: an instant before the first sample belongs to none
        index = np.ceil((times - self.start) * self.rate - 1e-9).astype(np.int64)
        keep = (index >= 1) & (index < len(self.time))
        for f in (0, 1):
            np.maximum.at(self.peak_acc[f], index[keep], acc[f][keep])
        np.maximum.at(self.peak_force, index[keep], force[keep])

    def write_csv(self, path):
        if not self.filled.all():
            missing = np.nonzero(~self.filled)[0]
            raise RuntimeError(f"{path}: {missing.size} samples were not reached by the solution "
                               f"(first at t = {self.time[missing[0]]!r} s)")
        c = self.columns
        peak_acc = self.peak_acc.copy()
        peak_force = self.peak_force.copy()
        for f in (0, 1):
            a = np.abs(c[f"acceleration{f + 1}"])
            # the sample at t_{k-1} opens interval k, the sample at t_k closes it; sample 0 holds its own value
            peak_acc[f][1:] = np.maximum(peak_acc[f][1:], np.maximum(a[1:], a[:-1]))
            peak_acc[f][0] = a[0]
        peak_force[1:] = np.maximum(peak_force[1:], np.maximum(c["force"][1:], c["force"][:-1]))
        peak_force[:1] = c["force"][:1]
        rows = np.column_stack([self.time, c["displacement1"], c["velocity1"], c["acceleration1"], c["displacement2"],
                                c["velocity2"], c["acceleration2"], c["force"], peak_acc[0], peak_acc[1], peak_force,
                                c["energy"]])
        with open(path, "w", encoding="utf-8") as out:
            out.write(self.COLUMNS + "\n")
            for row in rows:
                out.write(",".join(number(v) for v in row) + "\n")


def number(value):
    """A value as the harness writes it: 17 significant digits, empty for NaN."""
    return "" if not math.isfinite(value) else "%.17g" % value


EVENT_COLUMNS = ("onset_time_s,end_time_s,duration_s,approach_velocity_m_s,rebound_velocity_m_s,restitution,"
                 "peak_force_n,impulse_n_s,max_indentation_m")


def write_events_csv(path, events):
    """events: dicts with the ContactEvent fields of model/trajectory.h."""
    with open(path, "w", encoding="utf-8") as out:
        out.write(EVENT_COLUMNS + "\n")
        for e in events:
            values = (e["onset"], e["end"], e["end"] - e["onset"], e["approach"], e["rebound"], e["restitution"],
                      e["peak_force"], e["impulse"], e["max_indentation"])
            out.write(",".join(number(v) for v in values) + "\n")
