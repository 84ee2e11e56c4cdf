#include "reference/reference_solver.h"

#include <algorithm>
#include <array>
#include <boost/math/tools/toms748_solve.hpp>
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "reference/free_flight.h"

namespace ib {

double EnergyLedger::relative_residual() const {
  const double change = final_energy_j - initial_energy_j;
  const double residual = motor_work_j - (change + structural_dissipation_j + contact_dissipation_j);
  const double scale = std::max({std::abs(motor_work_j), std::abs(change), std::abs(structural_dissipation_j),
                                 std::abs(contact_dissipation_j), std::abs(initial_energy_j), 1e-300});
  return std::abs(residual) / scale;
}

namespace {

namespace odeint = boost::numeric::odeint;
using OdeState = std::vector<double>;  // [q (M), v (M), motor work, structural dissipation, contact dissipation, impulse]
using Dopri = odeint::runge_kutta_dopri5<OdeState>;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kTwoPi = 6.28318530717958647692;

// What force acts between the tips in the current phase.
enum class Phase { free, compliant, sticking };

// Kinematics of both tips and the contact at one instant; derivatives included so that extrema
// between samples can be located (jerk for acceleration peaks, dF/dt for force peaks).
struct TipState {
  double t = 0;
  std::array<double, 2> displacement{}, velocity{}, acceleration{}, jerk{};
  double indentation = 0, indentation_rate = 0;  // delta [m], delta' [m/s]
  double force = 0, force_rate = 0;              // F_c [N], dF_c/dt [N/s]
  double energy = 0;                             // mechanical energy [J]
};

// First root of f on [a, b] given f(a), f(b) of opposite signs (or one of them zero), to `bits` bits.
// Event times need full precision; the location of an extremum much less, as the value there is
// flat in it (a relative location error e changes the value by order e^2).
constexpr int kEventBits = 50, kExtremumBits = 26;
template <class F>
double find_root(F&& f, double a, double b, double fa, double fb, int bits = kEventBits) {
  if (fa == 0) return a;
  if (fb == 0) return b;
  if ((fa > 0) == (fb > 0)) return std::abs(fa) < std::abs(fb) ? a : b;  // no sign change: nearest end
  std::uintmax_t iterations = 60;
  const auto bracket =
      boost::math::tools::toms748_solve(f, a, b, fa, fb, boost::math::tools::eps_tolerance<double>(bits), iterations);
  return 0.5 * (bracket.first + bracket.second);
}

// Samples the output series and keeps the exact maximum of |acceleration| and of the force over
// each output interval (t_{k-1}, t_k] from every value it is fed in time order.
class SeriesRecorder {
 public:
  SeriesRecorder(const OutputWindow& window, Trajectory& out) : window_(window), out_(out) {
    out_.output_rate_hz = window.rate_hz;
    out_.start_time_s = window.start_s;
    const double count = std::floor((window.end_s - window.start_s) * window.rate_hz + 1e-9) + 1;
    total_ = window.end_s >= window.start_s ? static_cast<long long>(count) : 0;
    out_.reserve(static_cast<std::size_t>(total_));
  }
  double sample_interval_s() const { return 1 / window_.rate_hz; }
  double next_sample_time() const {
    return index_ < total_ ? window_.start_s + static_cast<double>(index_) / window_.rate_hz : kInf;
  }
  // Whether an interval ending at t holds anything to record (samples or peaks).
  bool wants(double t) const { return index_ < total_ && (index_ > 0 || t >= window_.start_s); }
  void feed(const TipState& s) {
    if (index_ == 0) return;  // peaks count from the first sample on
    for (int f = 0; f < 2; ++f) peak_acc_[f] = std::max(peak_acc_[f], std::abs(s.acceleration[f]));
    peak_force_ = std::max(peak_force_, s.force);
  }
  void sample(const TipState& s) {
    out_.time_s.push_back(s.t);
    for (int f = 0; f < 2; ++f) {
      out_.displacement_m[f].push_back(s.displacement[f]);
      out_.velocity_m_s[f].push_back(s.velocity[f]);
      out_.acceleration_m_s2[f].push_back(s.acceleration[f]);
      const double a = std::abs(s.acceleration[f]);
      out_.peak_abs_acceleration_m_s2[f].push_back(index_ == 0 ? a : std::max(peak_acc_[f], a));
      peak_acc_[f] = a;  // the sample opens the next interval
    }
    out_.contact_force_n.push_back(s.force);
    out_.mechanical_energy_j.push_back(s.energy);
    out_.peak_contact_force_n.push_back(index_ == 0 ? s.force : std::max(peak_force_, s.force));
    peak_force_ = s.force;
    ++index_;
  }

 private:
  OutputWindow window_;
  Trajectory& out_;
  long long index_ = 0, total_ = 0;
  std::array<double, 2> peak_acc_{};
  double peak_force_ = 0;
};

class Solver {
 public:
  Solver(const ModalModel& model, const OutputWindow& output, const ReferenceSettings& settings,
         ReferenceSolution& solution)
      : model_(model),
        settings_(settings),
        solution_(solution),
        flight_(model),
        recorder_(output, solution.trajectory),
        m_(model.mode_count()),
        n1_(model.frame_mode_count(0)) {
    omega2_ = model.omega_rad_s.array().square();
    two_zeta_omega_ = 2 * model.zeta.array() * model.omega_rad_s.array();
    lever_norm2_ = model.contact_lever.squaredNorm();
    // Scan grid and the integrator's largest step: a fraction of the fastest period (the motor's too).
    double fastest = model.omega_rad_s.maxCoeff();
    if (model.motor) fastest = std::max(fastest, model.motor->omega_rad_s);
    grid_step_ = std::min(kTwoPi / fastest / settings.grid_points_per_period, settings.max_grid_step_s);
    solution.grid_step_s = grid_step_;
    grid_transition_ = flight_.transition(grid_step_);
    if (output.rate_hz > 0) sample_transition_ = flight_.transition(recorder_.sample_interval_s());
    if (settings.track_energy) grid_energy_ = flight_.energy_forms(grid_step_);
    // The coarse step resolves the slow modes only; the rest is bounded (see free_flight).
    const int n2 = m_ - n1_, slow = settings.slow_modes_per_frame;
    if (slow > 0 && (slow < n1_ || slow < n2)) {
      slow_lever_ = fast_lever_ = model.contact_lever;
      double slow_fastest = model.motor ? model.motor->omega_rad_s : 0;
      for (int m = 0; m < m_; ++m) {
        const bool is_slow = (m < n1_ ? m : m - n1_) < slow;
        (is_slow ? fast_lever_ : slow_lever_)[m] = 0;
        if (is_slow) slow_fastest = std::max(slow_fastest, model.omega_rad_s[m]);
      }
      coarse_step_ = std::min(kTwoPi / slow_fastest / settings.grid_points_per_period, settings.max_grid_step_s);
      if (coarse_step_ > 2 * grid_step_) {
        coarse_transition_ = flight_.transition(coarse_step_);
        if (settings.track_energy) coarse_energy_ = flight_.energy_forms(coarse_step_);
      } else {
        coarse_step_ = 0;  // nothing to gain
      }
    }
  }

  void run(const ModalState& initial, double duration) {
    end_time_ = duration;
    double t = 0;
    ModalState x = initial;
    const TipState s0 = tip_state(x.q.data(), x.v.data(), 0, Phase::free);
    solution_.energy.initial_energy_j = mechanical_energy(x.q.data(), x.v.data(), s0.indentation);
    Phase phase = Phase::free;
    bool after_contact = false;
    if (s0.indentation > 0 || (s0.indentation == 0 && s0.indentation_rate > 0)) {
      if (is_instantaneous(model_.contact)) {
        if (s0.indentation > 0)
          return fail(RunStatus::failed, "the Newton law cannot start with the tips interpenetrating (delta = " +
                                             std::to_string(s0.indentation) + " m at t = 0)");
        phase = Phase::sticking;  // touching and closing: treated as an impact below
      } else {
        phase = Phase::compliant;
      }
    }
    if (phase == Phase::sticking) {  // Newton, touching at t = 0
      if (!newton_impact(t, x)) phase = Phase::free, after_contact = true;
    }
    while (t < end_time_) {
      if (solution_.impacts > settings_.max_contact_episodes)
        return fail(RunStatus::failed, "more than " + std::to_string(settings_.max_contact_episodes) +
                                           " contact episodes by t = " + std::to_string(t) + " s: chatter not resolved");
      if (chatter_guard(t)) return;
      switch (phase) {
        case Phase::free: {
          if (!free_flight(t, x, after_contact)) break;  // reached the end
          if (is_instantaneous(model_.contact)) {
            phase = newton_impact(t, x) ? Phase::sticking : Phase::free;
            after_contact = true;
          } else {
            phase = Phase::compliant;
          }
          break;
        }
        case Phase::compliant:
          if (!integrate_contact(t, x, Phase::compliant)) return;
          phase = Phase::free;
          after_contact = true;
          break;
        case Phase::sticking:
          if (!integrate_contact(t, x, Phase::sticking)) return;
          phase = Phase::free;
          after_contact = true;
          break;
      }
    }
    const TipState s = tip_state(x.q.data(), x.v.data(), t, phase == Phase::free ? Phase::free : phase);
    solution_.energy.final_energy_j = mechanical_energy(x.q.data(), x.v.data(), s.indentation);
  }

 private:
  void fail(RunStatus status, const std::string& reason) {
    solution_.status = status;
    solution_.reason = reason;
  }

  // Stops a run whose contact episodes pile up without time advancing (a guard; physics never needs it).
  bool chatter_guard(double t) {
    if (solution_.impacts - guard_impacts_ < 100000) return false;
    if (t - guard_time_ < 1e-9) {
      std::ostringstream why;
      why << "100000 contact episodes within " << (t - guard_time_) << " s at t = " << t << " s: chatter not resolved";
      fail(RunStatus::failed, why.str());
      return true;
    }
    guard_impacts_ = solution_.impacts;
    guard_time_ = t;
    return false;
  }

  // ---- kinematics -------------------------------------------------------------------------
  TipState tip_state(const double* q, const double* v, double t, Phase phase) const {
    TipState s;
    s.t = t;
    const double motor = model_.motor ? model_.motor->at(t) : 0;
    const double motor_rate = model_.motor ? model_.motor->rate_at(t) : 0;
    const double* b = model_.contact_lever.data();
    const double* p = model_.motor_lever.data();
    const double* w2 = omega2_.data();
    const double* c = two_zeta_omega_.data();
    // Plain loops without temporaries: this runs at every sample and in every root search.
    double delta = -model_.gap_m, rate = 0, lever_driven = 0, twice_energy = 0;
    for (int m = 0; m < m_; ++m) {
      delta += b[m] * q[m];
      rate += b[m] * v[m];
      lever_driven += b[m] * (p[m] * motor - c[m] * v[m] - w2[m] * q[m]);
      twice_energy += v[m] * v[m] + w2[m] * q[m] * q[m];
    }
    s.indentation = delta;
    s.indentation_rate = rate;
    s.energy = 0.5 * twice_energy + (phase == Phase::compliant ? elastic_contact_energy(model_.contact, delta) : 0);
    if (phase == Phase::compliant) s.force = contact_force_continued(model_.contact, delta, rate);
    else if (phase == Phase::sticking) s.force = lever_driven / lever_norm2_;
    // delta'' = b . (driven - b F) and the jerk without the force rate, b . (p F_m' - c a - w^2 v)
    const double indentation_acc = lever_driven - lever_norm2_ * s.force;
    if (phase == Phase::compliant) {
      s.force_rate = contact_force_rate(model_.contact, delta, rate, indentation_acc);
    } else if (phase == Phase::sticking) {  // a pass of its own, needed only while sticking
      double lever_jerk_free = 0;
      for (int m = 0; m < m_; ++m) {
        const double acc = p[m] * motor - c[m] * v[m] - w2[m] * q[m] - b[m] * s.force;
        lever_jerk_free += b[m] * (p[m] * motor_rate - c[m] * acc - w2[m] * v[m]);
      }
      s.force_rate = lever_jerk_free / lever_norm2_;
    }
    for (int f = 0; f < 2; ++f) {
      const int first = f == 0 ? 0 : n1_, last = f == 0 ? n1_ : m_;
      const Eigen::VectorXd& tip_of_mode = model_.frames[f].tip;
      double u = 0, du = 0, acc_sum = 0, jerk_sum = 0;
      for (int m = first; m < last; ++m) {
        const double tip_m = tip_of_mode[m - first];
        const double acc = p[m] * motor - c[m] * v[m] - w2[m] * q[m] - b[m] * s.force;
        const double jerk = p[m] * motor_rate - c[m] * acc - w2[m] * v[m] - b[m] * s.force_rate;
        u += tip_m * q[m];
        du += tip_m * v[m];
        acc_sum += tip_m * acc;
        jerk_sum += tip_m * jerk;
      }
      s.displacement[f] = u;
      s.velocity[f] = du;
      s.acceleration[f] = acc_sum;
      s.jerk[f] = jerk_sum;
    }
    return s;
  }

  double mechanical_energy(const double* qp, const double* vp, double indentation) const {
    const Eigen::Map<const Eigen::ArrayXd> q(qp, m_), v(vp, m_);
    return 0.5 * (v.square() + omega2_ * q.square()).sum() + elastic_contact_energy(model_.contact, indentation);
  }

  // Power of the motor on frame 1's tip and of the structural damping [W].
  double motor_power(const double* vp, double t) const {
    if (!model_.motor) return 0;
    const Eigen::Map<const Eigen::VectorXd> v(vp, m_);
    return model_.motor->at(t) * model_.motor_lever.dot(v);
  }
  double structural_power(const double* vp) const {
    const Eigen::Map<const Eigen::ArrayXd> v(vp, m_);
    return (two_zeta_omega_ * v.square()).sum();
  }

  // ---- series and peaks ---------------------------------------------------------------------
  // Feeds the recorder everything of [a, b] in time order: interior extrema of both tip
  // accelerations and of the force, the samples that fall in (a, b], and the value at b.
  // eval(t) gives the state at any t in [a, b]; sample_at(t) the same at sample times, where the
  // caller may have a cheaper way.
  template <class Eval>
  void record_interval(const TipState& sa, const TipState& sb, Eval&& eval) {
    record_interval(sa, sb, eval, eval);
  }
  template <class Eval, class SampleAt>
  void record_interval(const TipState& sa, const TipState& sb, Eval&& eval, SampleAt&& sample_at) {
    if (!recorder_.wants(sb.t)) return;
    std::array<TipState, 3> points;  // at most one extremum each of a1, a2 and F_c
    int count = 0;
    for (int f = 0; f < 2; ++f) {
      if (sa.jerk[f] * sb.jerk[f] < 0) {
        const double c =
            find_root([&](double t) { return eval(t).jerk[f]; }, sa.t, sb.t, sa.jerk[f], sb.jerk[f], kExtremumBits);
        points[count++] = eval(c);
      }
    }
    if (sa.force_rate * sb.force_rate < 0) {
      const double c = find_root([&](double t) { return eval(t).force_rate; }, sa.t, sb.t, sa.force_rate,
                                 sb.force_rate, kExtremumBits);
      points[count++] = eval(c);
    }
    for (int i = 1; i < count; ++i)  // insertion sort by time: at most three points
      for (int j = i; j > 0 && points[j].t < points[j - 1].t; --j) std::swap(points[j], points[j - 1]);
    int next = 0;
    for (double ts = recorder_.next_sample_time(); ts <= sb.t; ts = recorder_.next_sample_time()) {
      while (next < count && points[next].t <= ts) recorder_.feed(points[next++]);
      recorder_.sample(ts == sb.t ? sb : sample_at(ts));
    }
    while (next < count) recorder_.feed(points[next++]);
    recorder_.feed(sb);
  }

  // ---- free flight ----------------------------------------------------------------------------
  // The indentation and its rate: all that onset detection needs.
  struct Gap {
    double t = 0, delta = 0, rate = 0;
  };
  Gap gap_of(const ModalState& x, double t) const {
    return {t, model_.contact_lever.dot(x.q) - model_.gap_m, model_.contact_lever.dot(x.v)};
  }

  // Advances in closed form until a contact onset (returns true, t and x at the onset) or the end
  // of the run (returns false). after_contact: t is where a contact ended, so delta(t) is zero and
  // a re-contact counts only after the tips have really moved apart.
  bool free_flight(double& t, ModalState& x, bool after_contact) {
    Gap ga = gap_of(x, t);
    FreeFlight::MotorPhase phase_a = flight_.motor_phase(t);
    bool first = true;
    double* work = settings_.track_energy ? &solution_.energy.motor_work_j : nullptr;
    double* dissipation = settings_.track_energy ? &solution_.energy.structural_dissipation_j : nullptr;
    double fine_until = after_contact ? t + coarse_step_ : t;  // no coarse step right after a contact
    TipState tips_a;
    bool tips_a_valid = false;
    // Consecutive samples within one flight follow from the previous one by the precomputed
    // transition over the sample interval, instead of a fresh transition (exp, sin and cos of every
    // mode) from the grid point. Sample times are one interval apart up to rounding (~1e-16 s).
    double last_sample_t = -kInf;
    FreeFlight::MotorPhase last_sample_phase;
    auto sample_at = [&](double ts, const ModalState& x_grid, double t_grid) {
      const FreeFlight::MotorPhase phase = flight_.motor_phase(ts);
      if (std::abs(ts - last_sample_t - sample_transition_.tau_s) <= 1e-9 * sample_transition_.tau_s) {
        flight_.advance(sample_transition_, last_sample_phase, phase, x_sample_, xs_);
        std::swap(x_sample_, xs_);
      } else {
        flight_.advance(x_grid, t_grid, ts - t_grid, x_sample_);
      }
      last_sample_t = ts;
      last_sample_phase = phase;
      return tip_state(x_sample_.q.data(), x_sample_.v.data(), ts, Phase::free);
    };
    while (t < end_time_) {
      if (coarse_step_ > 0 && t >= fine_until && t + coarse_step_ < end_time_ && !recorder_.wants(t + coarse_step_)) {
        if (coarse_step_without_contact(t, x, phase_a, work, dissipation)) {
          ga = gap_of(x, t);
          first = false;
          continue;
        }
        fine_until = t + coarse_step_;  // a contact may start: scan this stretch on the fine grid
      }
      const double t0 = t;
      const bool standard = grid_step_ < end_time_ - t0;
      const double tb = standard ? t0 + grid_step_ : end_time_;
      const FreeFlight::MotorPhase phase_b = flight_.motor_phase(tb);
      double step_work = 0, step_dissipation = 0;  // energy over a full grid step, kept if no onset cuts it
      if (standard) {
        flight_.advance(grid_transition_, phase_a, phase_b, x, xb_, work ? &grid_energy_ : nullptr, &step_work,
                        &step_dissipation);
      } else {
        flight_.advance(x, t0, tb - t0, xb_);
      }
      const Gap gb = gap_of(xb_, tb);
      ++solution_.grid_intervals;
      auto gap_at = [&](double ts) {
        flight_.advance(x, t0, ts - t0, xs_);
        return gap_of(xs_, ts);
      };
      const double onset = find_onset(ga, gb, gap_at, first && after_contact);
      first = false;
      const double t_end = onset < kInf ? onset : tb;
      ModalState& x_end = onset < kInf ? x_onset_ : xb_;
      if (onset < kInf) flight_.advance(x, t0, onset - t0, x_onset_);
      if (recorder_.wants(t_end)) {
        auto eval = [&](double ts) {
          flight_.advance(x, t0, ts - t0, xs_);
          return tip_state(xs_.q.data(), xs_.v.data(), ts, Phase::free);
        };
        // the start's kinematics carry over from the previous step when it was recorded too
        if (!(tips_a_valid && tips_a.t == t0)) tips_a = tip_state(x.q.data(), x.v.data(), t0, Phase::free);
        const TipState tips_b = tip_state(x_end.q.data(), x_end.v.data(), t_end, Phase::free);
        record_interval(tips_a, tips_b, eval, [&](double ts) { return sample_at(ts, x, t0); });
        tips_a = tips_b;
        tips_a_valid = true;
      }
      if (work) {
        if (standard && onset == kInf) {
          *work += step_work;
          *dissipation += step_dissipation;
        } else {  // a cut step: its own integrals (the scratch state receives a discarded copy)
          const FreeFlight::EnergyForms forms = flight_.energy_forms(t_end - t0);
          flight_.advance(flight_.transition(t_end - t0), phase_a, flight_.motor_phase(t_end), x, xs_, &forms, work,
                          dissipation);
        }
      }
      t = t_end;
      std::swap(x, x_end);
      if (onset < kInf) return true;
      ga = gb;
      phase_a = phase_b;
    }
    return false;
  }

  // Takes one coarse step if no contact can start within it: the slow modes' indentation (resolved by
  // the coarse step, its interior maximum located) plus the bound on the fast modes stays negative.
  bool coarse_step_without_contact(double& t, ModalState& x, FreeFlight::MotorPhase& phase_a, double* work,
                                   double* dissipation) {
    const double t0 = t, tb = t + coarse_step_;
    const FreeFlight::MotorPhase phase_b = flight_.motor_phase(tb);
    const double fast = flight_.displacement_bound(x, phase_a, fast_lever_, 0, m_);
    double step_work = 0, step_dissipation = 0;
    flight_.advance(coarse_transition_, phase_a, phase_b, x, xb_, work ? &coarse_energy_ : nullptr, &step_work,
                    &step_dissipation);
    auto slow_delta = [&](const ModalState& s) { return slow_lever_.dot(s.q) - model_.gap_m; };
    double highest = std::max(slow_delta(x), slow_delta(xb_));
    const double rate_a = slow_lever_.dot(x.v), rate_b = slow_lever_.dot(xb_.v);
    if (rate_a > 0 && rate_b < 0) {
      auto rate_at = [&](double ts) {
        flight_.advance(x, t0, ts - t0, xs_);
        return slow_lever_.dot(xs_.v);
      };
      const double c = find_root(rate_at, t0, tb, rate_a, rate_b, kExtremumBits);
      flight_.advance(x, t0, c - t0, xs_);
      highest = std::max(highest, slow_delta(xs_));
    }
    if (highest + fast >= 0) return false;
    ++solution_.coarse_intervals;
    if (work) *work += step_work, *dissipation += step_dissipation;
    t = tb;
    std::swap(x, xb_);
    phase_a = phase_b;
    return true;
  }

  // The contact onset in (a, b], or infinity. The grid is fine enough that delta' changes sign at
  // most once per interval, so a crossing is either seen at b or hides behind one interior maximum.
  template <class GapAt>
  double find_onset(const Gap& a, const Gap& b, GapAt&& gap_at, bool starts_at_contact) {
    auto delta = [&](double t) { return gap_at(t).delta; };
    auto delta_rate = [&](double t) { return gap_at(t).rate; };
    // At a contact end delta(a) is zero up to rounding: treat it as just negative.
    const double delta_a = starts_at_contact ? -std::numeric_limits<double>::min() : a.delta;
    if (b.delta >= 0) {
      double lo = a.t, f_lo = delta_a;
      if (a.rate < 0 && b.rate > 0) {  // a minimum inside: the crossing comes after it
        const double c = find_root(delta_rate, a.t, b.t, a.rate, b.rate);
        const double f_c = delta(c);
        if (f_c < 0) lo = c, f_lo = f_c;
      }
      return find_root(delta, lo, b.t, f_lo, b.delta);
    }
    // Leaving a contact with (numerically) zero relative velocity: no maximum can follow at once.
    if (starts_at_contact && a.rate <= 1e-12) return kInf;
    if (a.rate > 0 && b.rate < 0) {  // a maximum inside: a grazing contact?
      const double c = find_root(delta_rate, a.t, b.t, a.rate, b.rate);
      const double f_c = delta(c);
      if (f_c >= 0) return find_root(delta, a.t, c, delta_a, f_c);
    }
    return kInf;
  }

  // ---- Newton impacts ---------------------------------------------------------------------------
  // Applies the impulse at an onset; returns true when the impacts accumulate and the tips stick.
  bool newton_impact(double t, ModalState& x) {
    const double e = std::get<NewtonLaw>(model_.contact).restitution;
    const Eigen::VectorXd& b = model_.contact_lever;
    const double approach = std::max(0.0, b.dot(x.v));
    const double impulse = (1 + e) * approach / lever_norm2_;
    x.v -= b * impulse;
    const double meff = 1 / lever_norm2_;
    solution_.energy.contact_dissipation_j += 0.5 * meff * (1 - e * e) * approach * approach;
    ContactEvent event;
    event.onset_time_s = event.end_time_s = t;
    event.approach_velocity_m_s = approach;
    event.rebound_velocity_m_s = e * approach;
    event.restitution = approach > 0 ? e : 0;
    event.peak_force_n = std::numeric_limits<double>::quiet_NaN();
    event.impulse_n_s = impulse;
    event.max_indentation_m = 0;
    ++solution_.impacts;
    // Relative acceleration with no contact force: > 0 pushes the tips back together.
    const TipState s = tip_state(x.q.data(), x.v.data(), t, Phase::free);
    const double closing_acc = model_.contact_lever.dot(acceleration_without_contact(x, t));
    const double rebound = -s.indentation_rate;
    bool accumulate = false;
    if (closing_acc > 0) {
      // A bouncing tip under constant closing acceleration stops after sum 2 e^k v / a = 2 v / ((1 - e) a).
      accumulate = e < 1 && 2 * rebound / ((1 - e) * closing_acc) < settings_.accumulation_time_s;
    }
    if (accumulate) {
      const double plastic = b.dot(x.v) / lever_norm2_;  // removes the remaining rebound velocity
      x.v -= b * plastic;
      solution_.energy.contact_dissipation_j += 0.5 * meff * rebound * rebound;
      event.impulse_n_s += plastic;
      event.rebound_velocity_m_s = 0;
      event.restitution = 0;
      stick_impulse_ = event.impulse_n_s;
    }
    solution_.trajectory.events.push_back(event);
    return accumulate;
  }

  Eigen::VectorXd acceleration_without_contact(const ModalState& x, double t) const {
    const double motor = model_.motor ? model_.motor->at(t) : 0;
    return (model_.motor_lever.array() * motor - two_zeta_omega_ * x.v.array() - omega2_ * x.q.array()).matrix();
  }

  // ---- compliant contact and sticking -----------------------------------------------------------
  // Integrates a contact phase with Dormand-Prince until it ends (separation, or release from
  // sticking) or the run ends. Returns false when the run cannot go on (status set).
  bool integrate_contact(double& t, ModalState& x, Phase phase) {
    OdeState y(2 * m_ + 4, 0.0);
    std::copy(x.q.data(), x.q.data() + m_, y.begin());
    std::copy(x.v.data(), x.v.data() + m_, y.begin() + m_);
    auto rhs = [&](const OdeState& s, OdeState& ds, double ts) {
      const TipState k = tip_state(s.data(), s.data() + m_, ts, phase);
      const Eigen::Map<const Eigen::ArrayXd> q(s.data(), m_), v(s.data() + m_, m_);
      Eigen::Map<Eigen::ArrayXd> dq(ds.data(), m_), dv(ds.data() + m_, m_);
      const double motor = model_.motor ? model_.motor->at(ts) : 0;
      dq = v;
      dv = model_.motor_lever.array() * motor - two_zeta_omega_ * v - omega2_ * q - model_.contact_lever.array() * k.force;
      ds[2 * m_] = motor_power(s.data() + m_, ts);
      ds[2 * m_ + 1] = structural_power(s.data() + m_);
      ds[2 * m_ + 2] = (k.force - elastic_contact_force(model_.contact, k.indentation)) * k.indentation_rate;
      ds[2 * m_ + 3] = k.force;
    };
    // The integrator's step never exceeds the scan grid, so extrema stay one per step.
    auto dense = odeint::make_dense_output(settings_.absolute_tolerance, settings_.relative_tolerance, grid_step_, Dopri());
    dense.initialize(y, t, std::min(grid_step_, 1e-6));
    TipState sa = tip_state(y.data(), y.data() + m_, t, phase);
    ContactEvent event;
    event.onset_time_s = t;
    event.approach_velocity_m_s = sa.indentation_rate;
    event.impulse_n_s = phase == Phase::sticking ? stick_impulse_ : 0;
    event.peak_force_n = sa.force;
    event.max_indentation_m = std::max(0.0, sa.indentation);
    OdeState ys(y.size());
    auto eval = [&](double ts) {
      dense.calc_state(ts, ys);
      return tip_state(ys.data(), ys.data() + m_, ts, phase);
    };
    // The quantity whose sign change ends the phase: delta for a compliant contact, F_c for sticking.
    auto ending = [&](const TipState& s) { return phase == Phase::compliant ? s.indentation : s.force; };
    while (true) {
      try {
        dense.do_step(rhs);
      } catch (const std::exception& error) {
        fail(RunStatus::failed, std::string("reference integrator failed at t = ") + std::to_string(t) + " s: " + error.what());
        return false;
      }
      ++solution_.integrator_steps;
      const double ta = dense.previous_time(), tb = dense.current_time();
      const OdeState& yb = dense.current_state();
      if (!std::isfinite(yb[0]) || !std::isfinite(yb[m_])) {
        fail(RunStatus::failed, "reference integrator produced a non-finite state at t = " + std::to_string(tb) + " s");
        return false;
      }
      TipState sb = tip_state(yb.data(), yb.data() + m_, tb, phase);
      double t_stop = tb;
      bool ended = false;
      if (ending(sb) < 0) {
        // Locate the end on the dense output, after the last interior maximum of the ending quantity.
        double lo = ta, f_lo = ending(sa);
        if (f_lo <= 0) {
          const double c = phase == Phase::compliant
                               ? find_root([&](double s) { return eval(s).indentation_rate; }, ta, tb, sa.indentation_rate, sb.indentation_rate)
                               : ta;
          lo = c;
          f_lo = ending(eval(c));
        }
        t_stop = f_lo > 0 ? find_root([&](double s) { return ending(eval(s)); }, lo, tb, f_lo, ending(sb)) : lo;
        ended = true;
      }
      if (t_stop > end_time_) t_stop = end_time_, ended = false;
      OdeState y_stop = yb;
      if (t_stop < tb) {
        // Retake the step exactly to the stop time: the force is smooth on [ta, t_stop].
        Dopri().do_step(rhs, dense.previous_state(), ta, y_stop, t_stop - ta);
        sb = tip_state(y_stop.data(), y_stop.data() + m_, t_stop, phase);
      }
      record_interval(sa, sb, eval);
      track_event(event, sa, sb, eval);
      // A contact episode lasts while the tips exchange a force: a clipped law's force can end before
      // the overlap does (the tips part faster than the spring relaxes), and the episode with it.
      if (phase == Phase::compliant) {
        if (sa.force > 0 && sb.force == 0) {
          auto unclipped = [&](double s) {
            const TipState k = eval(s);
            return contact_force_unclipped(model_.contact, k.indentation, k.indentation_rate);
          };
          const double end = find_root(unclipped, ta, sb.t, unclipped(ta), unclipped(sb.t));
          force_end_ = {end, -eval(end).indentation_rate};
        } else if (sb.force != 0) {
          force_end_.reset();
        }
      }
      if (ended || t_stop >= end_time_) {
        t = t_stop;
        x.q = Eigen::Map<const Eigen::VectorXd>(y_stop.data(), m_);
        x.v = Eigen::Map<const Eigen::VectorXd>(y_stop.data() + m_, m_);
        if (phase == Phase::sticking) project_onto_contact(x);
        solution_.energy.motor_work_j += y_stop[2 * m_];
        solution_.energy.structural_dissipation_j += y_stop[2 * m_ + 1];
        solution_.energy.contact_dissipation_j += y_stop[2 * m_ + 2];
        event.end_time_s = force_end_ ? force_end_->first : t;
        event.impulse_n_s += y_stop[2 * m_ + 3];
        event.rebound_velocity_m_s = force_end_ ? force_end_->second : -sb.indentation_rate;
        force_end_.reset();
        event.restitution = event.approach_velocity_m_s > 0 ? event.rebound_velocity_m_s / event.approach_velocity_m_s : 0;
        if (phase == Phase::sticking) {
          ++solution_.sticking_phases;
          // the sticking phase continues the impact episode that started it. Held at delta' = 0 and
          // released where the holding force would turn tensile, the tips part with zero relative
          // speed: what the state shows there is rounding (about 1e-17 m/s, of either sign).
          ContactEvent& start = solution_.trajectory.events.back();
          start.end_time_s = event.end_time_s;
          start.impulse_n_s = event.impulse_n_s;
          start.peak_force_n = event.peak_force_n;
          start.rebound_velocity_m_s = std::max(0.0, event.rebound_velocity_m_s);
          // rebound over the approach of the impact that started the episode (the sticking phase's own
          // "approach" is the rounding left after the plastic impulse)
          start.restitution =
              start.approach_velocity_m_s > 0 ? start.rebound_velocity_m_s / start.approach_velocity_m_s : 0;
        } else {
          ++solution_.impacts;
          solution_.trajectory.events.push_back(event);
        }
        return true;
      }
      sa = sb;
    }
  }

  // Keeps the sticking tips exactly on delta = 0, delta' = 0 (removes integration drift) with the
  // smallest mass-weighted correction.
  void project_onto_contact(ModalState& x) const {
    const Eigen::VectorXd& b = model_.contact_lever;
    x.q -= b * ((b.dot(x.q) - model_.gap_m) / lever_norm2_);
    x.v -= b * (b.dot(x.v) / lever_norm2_);
  }

  // Peak force and maximum indentation of a contact episode, exact between steps.
  template <class Eval>
  void track_event(ContactEvent& event, const TipState& sa, const TipState& sb, Eval&& eval) const {
    event.peak_force_n = std::max({event.peak_force_n, sa.force, sb.force});
    event.max_indentation_m = std::max({event.max_indentation_m, sa.indentation, sb.indentation});
    if (sa.force_rate > 0 && sb.force_rate < 0) {
      const double c = find_root([&](double t) { return eval(t).force_rate; }, sa.t, sb.t, sa.force_rate,
                                 sb.force_rate, kExtremumBits);
      event.peak_force_n = std::max(event.peak_force_n, eval(c).force);
    }
    if (sa.indentation_rate > 0 && sb.indentation_rate < 0) {
      const double c = find_root([&](double t) { return eval(t).indentation_rate; }, sa.t, sb.t, sa.indentation_rate,
                                 sb.indentation_rate, kExtremumBits);
      event.max_indentation_m = std::max(event.max_indentation_m, eval(c).indentation);
    }
  }

  const ModalModel& model_;
  const ReferenceSettings& settings_;
  ReferenceSolution& solution_;
  FreeFlight flight_;
  SeriesRecorder recorder_;
  int m_, n1_;
  Eigen::ArrayXd omega2_, two_zeta_omega_;
  double lever_norm2_ = 0;
  double grid_step_ = 0;
  double end_time_ = 0;
  FreeFlight::Transition grid_transition_, coarse_transition_, sample_transition_;
  FreeFlight::EnergyForms grid_energy_, coarse_energy_;
  double coarse_step_ = 0;                   // 0: no coarse steps
  Eigen::VectorXd slow_lever_, fast_lever_;  // the contact lever split into slow and fast modes
  ModalState xb_, xs_, x_onset_, x_sample_;  // free-flight scratch states, kept to avoid allocation
  double stick_impulse_ = 0;
  std::optional<std::pair<double, double>> force_end_;  // (time, opening speed) where a clipped force ended
  long long guard_impacts_ = 0;
  double guard_time_ = 0;
};

}  // namespace

ReferenceSolution solve_reference(const ModalModel& model, const ModalState& initial, double duration_s,
                                  const OutputWindow& output, const ReferenceSettings& settings) {
  if (!(settings.relative_tolerance > 0) || !(settings.absolute_tolerance > 0))
    throw std::invalid_argument("reference tolerances must be > 0");
  if (settings.grid_points_per_period < 4)
    throw std::invalid_argument("grid_points_per_period must be >= 4");
  if (!(settings.max_grid_step_s > 0)) throw std::invalid_argument("max_grid_step_s must be > 0");
  ReferenceSolution solution;
  Solver solver(model, output, settings, solution);
  solver.run(initial, duration_s);
  return solution;
}

}  // namespace ib
