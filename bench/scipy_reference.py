#!/usr/bin/python3
"""The reference's modal equations integrated with SciPy's solve_ivp, as a competent user would, for
comparison with the reference (bench/reference_vs_scipy.py).

    impactbench export SCENARIO --engine reference --law LAW --out model.json
    /usr/bin/python3 bench/scipy_reference.py model.json --out DIR [--method DOP853] [--rtol R] [--atol A]
    impactbench score DIR --scenario SCENARIO

Writes DIR/series.csv and DIR/events.csv in the harness's format (harness/records/run_files.h), so that
`impactbench score` measures them exactly as every simulator's run, and DIR/scipy_run.json with the cost.

How it integrates (the choices a user would make; the README's "The reference against SciPy"):
- The whole run with solve_ivp, free flight included (the reference propagates free flight in closed
  form; a user of solve_ivp integrates it). Method DOP853 by default: at rtol 1e-9 an 8th-order method
  takes far fewer steps than RK45's 5th order (SciPy's documentation recommends it for high precision);
  the system is not stiff (lightly damped oscillators, contact frequencies below the fastest mode's), so
  an implicit method (Radau, BDF, LSODA) only adds Jacobian work. rtol and atol default to the
  reference's (the model file's reference_settings).
- Events, restarting solve_ivp at each: contact onset is delta = b . q - gap crossing 0 upward (terminal);
  a compliant contact (Hertz, spring-dashpot) is integrated with the contact force until delta returns to 0
  (terminal, downward). Inside a contact the law is continued smoothly to delta < 0, as in the reference,
  so that the step that crosses the separation sees a smooth right-hand side. For the laws clipped at zero
  two non-terminal events find where the unclipped force turns negative and positive again: an episode
  whose force ended before the overlap did ends there, as in the reference. The impulse of each contact is
  integrated as one more state.
- Newton: the reference's modal impulse map at each onset, q' -= b (1 + e) delta' / (b . b). When the
  impacts would accumulate (the reference's bouncing-ball estimate against its accumulation time) the
  reference makes the tips stick; sticking is NOT implemented here: the run stops with a message.
- solve_ivp's events are seen at step ends only: a contact that starts and ends within one step would be
  missed (the reference checks the indentation's interior maxima). The raw onset counts show it.
- Dense output only where the output needs it (the output window, and every contact for its peak force
  and indentation); before the window solve_ivp keeps no steps (t_eval at the end). In the window the free
  flight is solved in chunks (--chunk) so that the dense output of one chunk is processed and dropped.

Timing: time.perf_counter around each solve_ivp call (and the impulse map), summed: the integration
(integration_time_s; its CPU time, time.process_time, beside it: less sensitive to a shared machine).
Recording the series and peaks from the dense output is timed apart (output_time_s): the reference does
both in its wall time, so the integration time alone flatters SciPy.
"""
import argparse
import json
import math
import os
import platform
import sys
import time

try:
    import numpy as np
    import scipy
    from scipy.integrate import solve_ivp
except ImportError as missing:
    sys.exit(f"scipy_reference: {missing}: needs NumPy and SciPy (Debian's python3-scipy); run with /usr/bin/python3")

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from scipy_dense_record import DenseOutput, Segment, SeriesRecorder, write_events_csv  # noqa: E402
from scipy_modal_model import ModalModel, ModelError  # noqa: E402


class RunStopped(RuntimeError):
    """The run cannot go on (an integrator failure, or Newton sticking, which is not implemented)."""


class ScipySolver:
    def __init__(self, model, method, rtol, atol, chunk_s):
        self.model, self.method, self.rtol, self.atol, self.chunk = model, method, rtol, atol, chunk_s
        self.recorder = SeriesRecorder(model.series_start, model.duration, model.output_rate)
        self.events = []
        self.integration_time = self.integration_cpu_time = self.output_time = 0.0
        self.rhs_evaluations = self.solve_calls = 0
        m = model.modes
        law = model.law

        def free_rhs(t, y):
            q, v = y[:m], y[m:]
            return np.concatenate((v, model.p * (model.motor_amplitude * math.cos(model.motor_omega * t))
                                   - model.damping_rate * v - model.stiffness * q))

        def contact_rhs(t, y):  # y = [q, v, impulse]
            q, v = y[:m], y[m:2 * m]
            force = law.force(model.b @ q - model.gap, model.b @ v)
            acc = model.p * (model.motor_amplitude * math.cos(model.motor_omega * t)) \
                - model.damping_rate * v - model.stiffness * q - model.b * force
            return np.concatenate((v, acc, (force,)))

        def onset(t, y):  # delta crossing 0 upward
            return model.b @ y[:m] - model.gap

        def separation(t, y):  # delta crossing 0 downward
            return model.b @ y[:m] - model.gap

        def force_ends(t, y):  # the unclipped force crossing 0 downward
            return law.unclipped(model.b @ y[:m] - model.gap, model.b @ y[m:2 * m])

        def force_returns(t, y):  # and upward
            return force_ends(t, y)

        onset.terminal, onset.direction = True, 1
        separation.terminal, separation.direction = True, -1
        force_ends.terminal, force_ends.direction = False, -1
        force_returns.terminal, force_returns.direction = False, 1
        self.free_rhs, self.contact_rhs = free_rhs, contact_rhs
        self.free_events = [onset]
        self.contact_events = [separation] + ([force_ends, force_returns] if law.clipped else [])

    def _solve(self, rhs, t0, t1, y0, events, dense):
        start, cpu_start = time.perf_counter(), time.process_time()
        # t_eval at the end only: solve_ivp then keeps no step it does not need
        sol = solve_ivp(rhs, (t0, t1), y0, method=self.method, rtol=self.rtol, atol=self.atol, events=events,
                        dense_output=dense, t_eval=[t1])
        self.integration_time += time.perf_counter() - start
        self.integration_cpu_time += time.process_time() - cpu_start
        self.rhs_evaluations += sol.nfev
        self.solve_calls += 1
        if sol.status < 0:
            raise RunStopped(f"solve_ivp failed at t in [{t0}, {t1}] s: {sol.message}")
        return sol

    def _record(self, segment):
        start = time.perf_counter()
        self.recorder.add(self.model, segment)
        self.output_time += time.perf_counter() - start

    def run(self):
        model = self.model
        t, y = 0.0, np.concatenate((model.q0, model.v0))
        delta, rate = model.b @ model.q0 - model.gap, model.b @ model.v0
        in_contact = delta > 0 or (delta == 0 and rate > 0)
        if in_contact and model.law.instantaneous:
            if delta > 0:
                raise RunStopped(f"the Newton law cannot start with the tips interpenetrating (delta = {delta} m)")
            y = self._newton_impact(t, y)
            in_contact = False
        while t < model.duration:
            if in_contact:
                t, y = self._contact_phase(t, y)
                in_contact = False
            else:
                t, y, onset = self._free_phase(t, y)
                if onset and model.law.instantaneous:
                    start = time.perf_counter()
                    y = self._newton_impact(t, y)
                    self.integration_time += time.perf_counter() - start
                else:
                    in_contact = onset

    def _free_phase(self, t, y):
        """Free flight to the next onset, the output window's start, the end of a chunk or of the run."""
        model = self.model
        dense = t >= model.series_start
        t_stop = min(t + self.chunk, model.duration) if dense else min(model.series_start, model.duration)
        if t_stop <= t:  # the window starts at t: nothing to integrate before it
            t_stop, dense = min(t + self.chunk, model.duration), True
        sol = self._solve(self.free_rhs, t, t_stop, y, self.free_events, dense)
        onset = sol.status == 1
        t_end, y_end = (sol.t_events[0][0], sol.y_events[0][0]) if onset else (t_stop, sol.y[:, -1])
        if dense:
            self._record(Segment(t, t_end, False, DenseOutput(sol.sol)))
        return t_end, y_end, onset

    def _contact_phase(self, t, y):
        """A compliant contact from its onset to the separation (or the end of the run), recorded as one
        contact episode."""
        model, m = self.model, self.model.modes
        sol = self._solve(self.contact_rhs, t, model.duration, np.append(y, 0.0), self.contact_events, True)
        separated = sol.t_events[0].size > 0
        t_end, y_end = (sol.t_events[0][0], sol.y_events[0][0]) if separated else (model.duration, sol.y[:, -1])
        start = time.perf_counter()
        segment = Segment(t, t_end, True, DenseOutput(sol.sol))
        peaks = segment.peaks(model, self.recorder.time)
        self.recorder.add(model, segment, peaks)
        peak_force, max_delta = peaks[3], peaks[4]
        approach = model.b @ y[m:2 * m]
        end, rebound = t_end, -(model.b @ y_end[m:2 * m])
        if model.law.clipped and sol.t_events[1].size:
            # the force ended before the overlap did, and stayed zero: the episode ends there
            last_end = sol.t_events[1][-1]
            if sol.t_events[2].size == 0 or sol.t_events[2][-1] < last_end:
                end, rebound = last_end, -(model.b @ sol.y_events[1][-1][m:2 * m])
        self.events.append({"onset": t, "end": end, "approach": approach, "rebound": rebound,
                            "restitution": rebound / approach if approach > 0 else 0.0,
                            "peak_force": max(peak_force, 0.0), "impulse": y_end[2 * m],
                            "max_indentation": max(max_delta, 0.0)})
        self.output_time += time.perf_counter() - start
        return t_end, y_end[:2 * m]

    def _newton_impact(self, t, y):
        """The reference's impulse map; stops the run where the reference would make the tips stick."""
        model, m = self.model, self.model.modes
        e = model.law.restitution
        q, v = y[:m], y[m:].copy()
        approach = max(0.0, model.b @ v)
        impulse = (1 + e) * approach / model.lever_norm2
        v -= model.b * impulse
        self.events.append({"onset": t, "end": t, "approach": approach, "rebound": e * approach,
                            "restitution": e if approach > 0 else 0.0, "peak_force": math.nan,
                            "impulse": impulse, "max_indentation": 0.0})
        closing = model.b @ model.acceleration_without_contact(t, q, v)
        rebound = -(model.b @ v)
        if closing > 0 and e < 1 and 2 * rebound / ((1 - e) * closing) < model.accumulation_time:
            raise RunStopped(f"Newton impacts accumulate at t = {t!r} s (the reference makes the tips stick "
                             "there); sticking is not implemented in this SciPy solver: choose a case without it")
        return np.concatenate((q, v))


def versions():
    return {"python": platform.python_version(), "numpy": np.__version__, "scipy": scipy.__version__}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("model", help="the JSON of `impactbench export SCENARIO --engine reference`")
    parser.add_argument("--out", required=True, help="folder for series.csv, events.csv, scipy_run.json")
    parser.add_argument("--method", default="DOP853", choices=["DOP853", "RK45", "RK23", "Radau", "BDF", "LSODA"],
                        help="solve_ivp method (default DOP853)")
    parser.add_argument("--rtol", type=float, help="relative tolerance (default: the model's reference rtol)")
    parser.add_argument("--atol", type=float, help="absolute tolerance [m sqrt(kg)] (default: the model's reference atol)")
    parser.add_argument("--chunk", type=float, default=0.25,
                        help="free flight in the output window is solved in chunks this long [s] (default 0.25)")
    args = parser.parse_args()
    try:
        model = ModalModel(args.model)
    except ModelError as error:
        sys.exit(f"scipy_reference: {error}")
    for name in ("rtol", "atol", "chunk"):
        value = getattr(args, name)
        if value is not None and not (math.isfinite(value) and value > 0):
            sys.exit(f"scipy_reference: --{name} {value}: allowed: a number > 0")
    rtol = args.rtol if args.rtol is not None else model.rtol
    atol = args.atol if args.atol is not None else model.atol
    os.makedirs(args.out, exist_ok=True)
    solver = ScipySolver(model, args.method, rtol, atol, args.chunk)
    wall = time.perf_counter()
    status, reason = "ok", ""
    try:
        solver.run()
    except RunStopped as error:
        status, reason = "failed", str(error)
    wall = time.perf_counter() - wall
    if status == "ok":
        try:
            solver.recorder.write_csv(os.path.join(args.out, "series.csv"))
            write_events_csv(os.path.join(args.out, "events.csv"), solver.events)
        except (OSError, RuntimeError) as error:
            sys.exit(f"scipy_reference: {error}")
    summary = {
        "status": status, "reason": reason, "model": os.path.abspath(args.model), "scenario": model.scenario,
        "law": model.law.name, "method": args.method, "rtol": rtol, "atol_m_sqrt_kg": atol, "chunk_s": args.chunk,
        "duration_s": model.duration, "modes": model.modes,
        "integration_time_s": solver.integration_time, "integration_cpu_time_s": solver.integration_cpu_time,
        "output_time_s": solver.output_time, "wall_time_s": wall,
        "rhs_evaluations": solver.rhs_evaluations, "solve_ivp_calls": solver.solve_calls,
        "contact_episodes": len(solver.events), "versions": versions()}
    with open(os.path.join(args.out, "scipy_run.json"), "w", encoding="utf-8") as out:
        json.dump(summary, out, indent=2)
        out.write("\n")
    if status != "ok":
        sys.exit(f"scipy_reference: {reason}")
    print(f"scipy_reference: {model.scenario} {model.law.name} {args.method}: integration {solver.integration_time:.3f} s, "
          f"output {solver.output_time:.3f} s, {solver.rhs_evaluations} right-hand side evaluations, "
          f"{len(solver.events)} contact episodes; files in {args.out}")


if __name__ == "__main__":
    main()
