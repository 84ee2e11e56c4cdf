// The reference's event-driven solver, internal to the reference (reference_solver.h is its interface): the
// state of one solution in one class whose phases live in their own files:
//   reference_solver.cpp   the phase machine (free flight -> contact or impact -> free flight), the chatter guard
//   free_flight_phase.cpp  closed-form free flight, scanned for the next contact onset
//   contact_phase.cpp      compliant contact and sticking, integrated with Dormand-Prince
//   newton_impact.cpp      an instantaneous impact with restitution
// The kinematics, energy and sampling every phase calls in its inner loops stay inline here, so that the
// split costs no speed (bench/reference_benchmark, before and after: docs/layout.md).
#pragma once

#include <algorithm>
#include <array>
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "reference/free_flight.h"
#include "reference/reference_solver.h"
#include "reference/root_finding.h"
#include "reference/series_sampler.h"

namespace ib::reference_internal {

namespace odeint = boost::numeric::odeint;
using OdeState =
    std::vector<double>;  // [q (M), v (M), motor work, structural dissipation, contact dissipation, impulse]
using Dopri = odeint::runge_kutta_dopri5<OdeState>;

constexpr double kTwoPi = 6.28318530717958647692;

// What force acts between the tips in the current phase.
enum class Phase { free, compliant, sticking };

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
    prepare_scan_jerk();
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
        coarse_sub_ = sub_grid(coarse_step_);
        if (settings.track_energy) coarse_energy_ = flight_.energy_forms(coarse_step_);
        // the long steps' transitions in closed form, their energy forms by doubling the coarse step's
        for (int k = 1; k <= settings.long_step_doublings; ++k) {
          const LongStep& shorter = k == 1 ? LongStep{coarse_transition_, coarse_energy_, {}} : long_steps_.back();
          LongStep longer{flight_.transition(std::ldexp(coarse_step_, k)), {}, sub_grid(std::ldexp(coarse_step_, k))};
          if (settings.track_energy) longer.energy = flight_.doubled(shorter.energy, shorter.transition);
          long_steps_.push_back(std::move(longer));
        }
      } else {
        coarse_step_ = 0;  // nothing to gain
      }
    }
  }

  void run(const ModalState& initial, double duration);
  void run_after_contact(const FlightStart& start, double duration);

 private:
  void fail(RunStatus status, const std::string& reason) {
    solution_.status = status;
    solution_.reason = reason;
  }

  // The phase machine from t and x in the given phase, to the end of the run.
  void run_phases(double t, ModalState x, Phase phase, bool after_contact);

  // Keeps a free flight's start as ReferenceSettings::keep_flight_starts_from_s asks.
  void keep_flight_start(double t, const ModalState& x);

  // Stops a run whose contact episodes pile up without time advancing (a guard; physics never needs it).
  bool chatter_guard(double t);

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
    if (phase == Phase::compliant)
      s.force = contact_force_continued(model_.contact, delta, rate);
    else if (phase == Phase::sticking)
      s.force = lever_driven / lever_norm2_;
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

  // What the contact phase's equations need of tip_state: the indentation, its rate and the force, computed as
  // tip_state computes them (the same bits) without the tips' kinematics and energy; motor: the force at t.
  struct ContactState {
    double indentation = 0, indentation_rate = 0, force = 0;
  };
  ContactState contact_state(const double* q, const double* v, double motor, Phase phase) const {
    const double* b = model_.contact_lever.data();
    const double* p = model_.motor_lever.data();
    const double* w2 = omega2_.data();
    const double* c = two_zeta_omega_.data();
    double delta = -model_.gap_m, rate = 0, lever_driven = 0;
    for (int m = 0; m < m_; ++m) {
      delta += b[m] * q[m];
      rate += b[m] * v[m];
      lever_driven += b[m] * (p[m] * motor - c[m] * v[m] - w2[m] * q[m]);
    }
    ContactState s{delta, rate, 0};
    if (phase == Phase::compliant)
      s.force = contact_force_continued(model_.contact, delta, rate);
    else if (phase == Phase::sticking)
      s.force = lever_driven / lever_norm2_;
    return s;
  }

  double mechanical_energy(const double* qp, const double* vp, double indentation) const {
    const Eigen::Map<const Eigen::ArrayXd> q(qp, m_), v(vp, m_);
    return 0.5 * (v.square() + omega2_ * q.square()).sum() + elastic_contact_energy(model_.contact, indentation);
  }

  // Power of the structural damping [W].
  double structural_power(const double* vp) const {
    const Eigen::Map<const Eigen::ArrayXd> v(vp, m_);
    return (two_zeta_omega_ * v.square()).sum();
  }

  // ---- series and peaks ---------------------------------------------------------------------
  // Feeds the recorder everything of [a, b] in time order: interior extrema of both tip
  // accelerations and of the force, the samples that fall in (a, b], and the value at b.
  // eval(t) gives the state at any t in [a, b] (a contact phase's dense output).
  template <class Eval>
  void record_interval(const TipState& sa, const TipState& sb, Eval&& eval);  // contact_phase.cpp

  // The tip accelerations of free flight about (x, t) as Taylor polynomials in the time from t: the modal
  // equations give every derivative of q from q, v and the motor's force (a sinusoid), so an extremum
  // between grid points is located on the polynomial instead of a transition (exp, sin and cos of every
  // mode) per trial. Over a grid step (omega h <= 2 pi / grid_points_per_period <= pi / 2 for the fastest
  // mode) the terms past kTaylorDegree are below 1e-16 of that mode's acceleration at 8 points per period,
  // 1e-13 at the coarsest grid allowed (4).
  static constexpr int kTaylorDegree = 18;
  using AccelerationSeries = std::array<std::array<double, kTaylorDegree + 1>, 2>;  // a_f(t + s) = sum c[f][k] s^k
  // Only the frames asked for (the other's coefficients are left zero).
  AccelerationSeries acceleration_series(const ModalState& x, double t, std::array<bool, 2> frames) const;
  static double series_value(const std::array<double, kTaylorDegree + 1>& c, double s);
  static double series_slope(const std::array<double, kTaylorDegree + 1>& c, double s);

  // record_interval for a free-flight interval that starts at (x, sa.t): its acceleration extrema located on
  // the Taylor polynomials about its start (free flight has no contact force, so no force extremum).
  template <class SampleAt>
  void record_free_interval(const TipState& sa, const TipState& sb, const ModalState& x, SampleAt&& sample_at,
                            bool extrema);

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
  bool free_flight(double& t, ModalState& x, bool after_contact);

  // Takes one coarse step if no contact can start within it: the slow modes' indentation (resolved by
  // the coarse step, its interior maximum located) plus `fast`, the bound on the fast modes, stays negative.
  bool coarse_step_without_contact(double& t, ModalState& x, FreeFlight::MotorPhase& phase_a, double fast, double* work,
                                   double* dissipation);
  // Takes the longest of the long steps within which no contact can start: the slow modes' indentation at t
  // plus their speed bound times the step, plus `fast`, stays negative.
  bool long_step_without_contact(double& t, ModalState& x, FreeFlight::MotorPhase& phase_a, double fast, double* work,
                                 double* dissipation);
  // Whether a bounded step may end at t (inside the output window too: it samples along).
  bool bounded_step_may_end_at(double t) const { return t < end_time_; }
  // A bounded step's sub-grid for the peaks between samples: `count` equal intervals, none longer than the
  // fine grid's, so that each tip's jerk changes sign at most once in each.
  struct SubGrid {
    int count = 0;
    FreeFlight::Transition transition;
    FreeFlight::MotorPhase turn;  // the motor's turn over one interval: its phase advances by rotation
  };
  SubGrid sub_grid(double step_s) const {
    const int count = static_cast<int>(std::ceil(step_s / grid_step_ * (1 - 1e-12)));
    return {count, flight_.transition(step_s / count), flight_.motor_phase(step_s / count)};
  }
  // The scan's motor phase is turned by the sub-interval's rotation and computed afresh this often (and at a
  // step's end), so that rounding cannot drift.
  static constexpr int kTurnsPerAnchor = 64;
  // Both tips' jerk from the free part (q~, v~) of a free-flight state and the motor's phase: linear in each, the
  // free part's with coefficients per mode (scan_jerk_q_, scan_jerk_v_), the steady state's a sinusoid per tip.
  std::array<double, 2> scan_jerk(const Eigen::ArrayXd& q_free, const Eigen::ArrayXd& v_free,
                                  const FreeFlight::MotorPhase& phase) const {
    std::array<double, 2> jerk{};
    for (int f = 0; f < 2; ++f) {
      const int first = f == 0 ? 0 : n1_, count = f == 0 ? n1_ : m_ - n1_;
      jerk[f] = (scan_jerk_q_.segment(first, count) * q_free.segment(first, count)).sum() +
                (scan_jerk_v_.segment(first, count) * v_free.segment(first, count)).sum() +
                steady_jerk_cos_[f] * phase.cos + steady_jerk_sin_[f] * phase.sin;
    }
    return jerk;
  }
  // The output of a bounded step from (t0, x0) to (tb, xb): its samples, the value at its end and, when the
  // peaks are asked for, the tip accelerations' extrema found on its sub-grid.
  void record_bounded_step(double t0, const ModalState& x0, const ModalState& xb, double tb, const SubGrid& sub);
  // Both tips' jerk in free flight.
  std::array<double, 2> free_jerk(const ModalState& x, const FreeFlight::MotorPhase& phase) const;
  // scan_jerk's coefficients, from free_jerk's own sums: the free part's in closed form, the steady state's at
  // the phases 0 and pi/2; and jerk_curvature_lever_.
  void prepare_scan_jerk();
  // A bound on |d^2 jerk / dt^2| of each tip for all later times of free flight from (x, t): every mode's
  // motion is at most its envelope times its rate |lambda| to the power of the derivative (q's fifth).
  std::array<double, 2> jerk_curvature_bound(const ModalState& x, const FreeFlight::MotorPhase& phase) const;
  // Appends to extrema_ the extrema of tip f's acceleration on [ta, ta + length] from its Taylor polynomial c about
  // ta, given the jerk at both ends: where it changes sign, the root; where it does not but could, with the
  // curvature bound, cross zero twice in between (a fast mode's wiggle at the top of a slow peak), the halves
  // searched in turn.
  void extrema_between(const std::array<double, kTaylorDegree + 1>& c, int f, double ta, double s0, double s1,
                       double jerk0, double jerk1, double curvature_bound, int depth);
  // Whether tip f's jerk may vanish inside an interval of this length though it has one sign at both ends.
  static bool may_turn_inside(double jerk0, double jerk1, double length, double curvature_bound) {
    return jerk0 * jerk1 >= 0 && std::min(std::abs(jerk0), std::abs(jerk1)) <= curvature_bound * length * length / 8;
  }
  static constexpr int kExtremumSearchDepth = 8;  // halvings of a sub-interval at most
  // Which tips' accelerations may have an extremum on an interval of this length, from the jerk at its ends.
  static std::array<bool, 2> extremum_search(const std::array<double, 2>& jerk_a, const std::array<double, 2>& jerk_b,
                                             double length, const std::array<double, 2>& curvature_bound);
  // Appends to extrema_, in time order, the extrema of the tips asked for on [ta, ta + length], from the free-flight
  // state x at ta through the Taylor polynomials about it.
  void append_extrema(const ModalState& x, double ta, double length, std::array<bool, 2> search,
                      const std::array<double, 2>& curvature_bound);
  // The free-flight state's kinematics at a sample time ts: from the previous sample by the sample interval's
  // transition when ts follows it (anchored afresh at (x_from, t_from) every kSamplesPerAnchor samples, so
  // that rounding cannot drift), else from (x_from, t_from) in closed form.
  TipState sample_free(double ts, const ModalState& x_from, double t_from);
  static constexpr int kSamplesPerAnchor = 256;

  // The contact onset in (a, b], or infinity. The grid is fine enough that delta' changes sign at
  // most once per interval, so a crossing is either seen at b or hides behind one interior maximum.
  template <class GapAt>
  double find_onset(const Gap& a, const Gap& b, GapAt&& gap_at, bool starts_at_contact);  // free_flight_phase.cpp

  // ---- Newton impacts ---------------------------------------------------------------------------
  // Applies the impulse at an onset; returns true when the impacts accumulate and the tips stick.
  bool newton_impact(double t, ModalState& x);

  Eigen::VectorXd acceleration_without_contact(const ModalState& x, double t) const {
    const double motor = model_.motor ? model_.motor->at(t) : 0;
    return (model_.motor_lever.array() * motor - two_zeta_omega_ * x.v.array() - omega2_ * x.q.array()).matrix();
  }

  // ---- compliant contact and sticking -----------------------------------------------------------
  // Integrates a contact phase with Dormand-Prince until it ends (separation, or release from
  // sticking) or the run ends. Returns false when the run cannot go on (status set).
  bool integrate_contact(double& t, ModalState& x, Phase phase);
  void contact_rates(const OdeState& s, OdeState& ds, double t, Phase phase) const;  // contact_phase.cpp
  template <class Eval>
  void track_force_end(const TipState& sa, const TipState& sb, double ta, Eval&& eval);  // contact_phase.cpp
  // A contact phase ended at t (the state y_stop, the tips tips_stop): the modal state into x, the phase's
  // energy and impulse added up and its episode recorded (a sticking phase continues the impact before it).
  void close_contact_phase(double t, const OdeState& y_stop, const TipState& tips_stop, ContactEvent& event,
                           Phase phase, ModalState& x);

  // Keeps the sticking tips exactly on delta = 0, delta' = 0 (removes integration drift) with the
  // smallest mass-weighted correction.
  void project_onto_contact(ModalState& x) const {
    const Eigen::VectorXd& b = model_.contact_lever;
    x.q -= b * ((b.dot(x.q) - model_.gap_m) / lever_norm2_);
    x.v -= b * (b.dot(x.v) / lever_norm2_);
  }

  // Peak force and maximum indentation of a contact episode, exact between steps.
  template <class Eval>
  void track_event(ContactEvent& event, const TipState& sa, const TipState& sb,
                   Eval&& eval) const;  // contact_phase.cpp

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
  double coarse_step_ = 0;  // 0: no coarse steps
  struct LongStep {
    FreeFlight::Transition transition;
    FreeFlight::EnergyForms energy;
    SubGrid sub;
  };
  SubGrid coarse_sub_;
  ModalState scan_a_;  // a bounded step's sub-grid scan: the state where a peak lies ahead
  Eigen::ArrayXd scan_q_a_, scan_v_a_, scan_q_b_, scan_v_b_;  // and the free parts it steps
  Eigen::ArrayXd scan_jerk_q_, scan_jerk_v_;  // a tip's jerk per unit free displacement and velocity of each mode
  std::array<double, 2> steady_jerk_cos_{}, steady_jerk_sin_{};  // the steady state's tip jerk: cos, sin parts
  Eigen::VectorXd jerk_curvature_lever_;  // |tip_m| max(|lambda_m|, Omega)^5: each mode's share of the bound
  std::vector<TipState> extrema_;
  std::vector<LongStep> long_steps_;  // 2, 4, 8, ... coarse steps
  double last_sample_t_ = -kInf;      // the free-flight sample chain (sample_free)
  FreeFlight::MotorPhase last_sample_phase_;
  int chained_samples_ = 0;
  Eigen::VectorXd slow_lever_, fast_lever_;  // the contact lever split into slow and fast modes
  ModalState xb_, xs_, x_onset_, x_sample_;  // free-flight scratch states, kept to avoid allocation
  double stick_impulse_ = 0;
  std::optional<std::pair<double, double>> force_end_;  // (time, opening speed) where a clipped force ended
  long long guard_impacts_ = 0;
  double guard_time_ = 0;
};

}  // namespace ib::reference_internal
