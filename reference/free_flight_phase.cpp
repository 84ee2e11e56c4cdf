// Free flight (event_solver.h): the closed-form motion between contacts. Where bounds prove that no contact
// can start, it takes long or coarse steps; elsewhere it scans the fine grid for the next onset, which is then
// located to full precision. Inside the output window it samples along, and finds the tip accelerations'
// extrema between samples (the series' peaks) on Taylor polynomials of the motion.
#include "reference/event_solver.h"

namespace ib::reference_internal {

// Horner's scheme for the series and its derivative.
double Solver::series_value(const std::array<double, kTaylorDegree + 1>& c, double s) {
  double value = 0;
  for (int k = kTaylorDegree; k >= 0; --k) value = value * s + c[k];
  return value;
}
double Solver::series_slope(const std::array<double, kTaylorDegree + 1>& c, double s) {
  double slope = 0;
  for (int k = kTaylorDegree; k >= 1; --k) slope = slope * s + k * c[k];
  return slope;
}

template <class GapAt>
double Solver::find_onset(const Gap& a, const Gap& b, GapAt&& gap_at, bool starts_at_contact) {
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

template <class SampleAt>
void Solver::record_free_interval(const TipState& sa, const TipState& sb, const ModalState& x, SampleAt&& sample_at,
                                  bool extrema) {
  if (!recorder_.wants(sb.t)) return;
  extrema_.clear();
  if (extrema) {
    const double h = sb.t - sa.t;
    const std::array<double, 2> bound = jerk_curvature_bound(x, flight_.motor_phase(sa.t));
    const std::array<bool, 2> search = extremum_search(sa.jerk, sb.jerk, h, bound);
    if (search[0] || search[1]) append_extrema(x, sa.t, h, search, bound);
  }
  std::size_t next = 0;
  for (double ts = recorder_.next_sample_time(); ts <= sb.t; ts = recorder_.next_sample_time()) {
    while (next < extrema_.size() && extrema_[next].t <= ts) recorder_.feed(extrema_[next++]);
    recorder_.sample(ts == sb.t ? sb : sample_at(ts));
  }
  while (next < extrema_.size()) recorder_.feed(extrema_[next++]);
  recorder_.feed(sb);
}

std::array<bool, 2> Solver::extremum_search(const std::array<double, 2>& jerk_a, const std::array<double, 2>& jerk_b,
                                            double length, const std::array<double, 2>& curvature_bound) {
  std::array<bool, 2> search{};
  for (int f = 0; f < 2; ++f)
    search[f] = jerk_a[f] * jerk_b[f] < 0 || may_turn_inside(jerk_a[f], jerk_b[f], length, curvature_bound[f]);
  return search;
}

void Solver::append_extrema(const ModalState& x, double ta, double length, std::array<bool, 2> search,
                            const std::array<double, 2>& curvature_bound) {
  const AccelerationSeries series = acceleration_series(x, ta, search);
  const std::size_t first = extrema_.size();
  for (int f = 0; f < 2; ++f)
    if (search[f])
      extrema_between(series[f], f, ta, 0.0, length, series_slope(series[f], 0.0), series_slope(series[f], length),
                      curvature_bound[f], kExtremumSearchDepth);
  std::sort(extrema_.begin() + static_cast<std::ptrdiff_t>(first), extrema_.end(),
            [](const TipState& p, const TipState& q) { return p.t < q.t; });
}

void Solver::extrema_between(const std::array<double, kTaylorDegree + 1>& c, int f, double ta, double s0, double s1,
                             double jerk0, double jerk1, double curvature_bound, int depth) {
  if (jerk0 * jerk1 < 0) {
    const double s = find_root([&](double u) { return series_slope(c, u); }, s0, s1, jerk0, jerk1, kExtremumBits);
    TipState point;
    point.t = ta + s;
    point.acceleration[f] = series_value(c, s);  // the other tip's peaks are its own extrema
    extrema_.push_back(point);
    return;
  }
  if (depth == 0 || !may_turn_inside(jerk0, jerk1, s1 - s0, curvature_bound)) return;
  const double mid = 0.5 * (s0 + s1), jerk_mid = series_slope(c, mid);
  extrema_between(c, f, ta, s0, mid, jerk0, jerk_mid, curvature_bound, depth - 1);
  extrema_between(c, f, ta, mid, s1, jerk_mid, jerk1, curvature_bound, depth - 1);
}

std::array<double, 2> Solver::jerk_curvature_bound(const ModalState& x, const FreeFlight::MotorPhase& phase) const {
  return {flight_.displacement_bound(x, phase, jerk_curvature_lever_, 0, n1_),
          flight_.displacement_bound(x, phase, jerk_curvature_lever_, n1_, m_)};
}

// Advances in closed form until a contact onset (returns true, t and x at the onset) or the end
// of the run (returns false). after_contact: t is where a contact ended, so delta(t) is zero and
// a re-contact counts only after the tips have really moved apart.
bool Solver::free_flight(double& t, ModalState& x, bool after_contact) {
  Gap ga = gap_of(x, t);
  FreeFlight::MotorPhase phase_a = flight_.motor_phase(t);
  bool first = true;
  double* work = settings_.track_energy ? &solution_.energy.motor_work_j : nullptr;
  double* dissipation = settings_.track_energy ? &solution_.energy.structural_dissipation_j : nullptr;
  double fine_until = after_contact ? t + coarse_step_ : t;  // no coarse step right after a contact
  TipState tips_a;
  bool tips_a_valid = false;
  last_sample_t_ = -kInf;  // a new flight: its samples chain anew
  auto sample_at = [&](double ts, const ModalState& x_grid, double t_grid) { return sample_free(ts, x_grid, t_grid); };
  while (t < end_time_) {
    if (coarse_step_ > 0 && t >= fine_until && bounded_step_may_end_at(t + coarse_step_)) {
      const double fast = flight_.displacement_bound(x, phase_a, fast_lever_, 0, m_);
      if (long_step_without_contact(t, x, phase_a, fast, work, dissipation) ||
          coarse_step_without_contact(t, x, phase_a, fast, work, dissipation)) {
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
      // the start's kinematics carry over from the previous step when it was recorded too
      if (!(tips_a_valid && tips_a.t == t0)) tips_a = tip_state(x.q.data(), x.v.data(), t0, Phase::free);
      const TipState tips_b = tip_state(x_end.q.data(), x_end.v.data(), t_end, Phase::free);
      record_free_interval(
          tips_a, tips_b, x, [&](double ts) { return sample_at(ts, x, t0); }, settings_.peaks_between_samples);
      tips_a = tips_b;
      tips_a_valid = true;
    }
    if (work) {
      if (standard && onset == kInf) {
        *work += step_work;
        *dissipation += step_dissipation;
      } else {  // a cut step: its own integrals (the scratch state receives a discarded copy)
        const FreeFlight::EnergyForms forms = flight_.energy_forms(t_end - t0, 1);
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
bool Solver::coarse_step_without_contact(double& t, ModalState& x, FreeFlight::MotorPhase& phase_a, double fast,
                                         double* work, double* dissipation) {
  const double t0 = t, tb = t + coarse_step_;
  const FreeFlight::MotorPhase phase_b = flight_.motor_phase(tb);
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
    const double c = find_root_after(rate_at, t0, tb, rate_a, rate_b, kExtremumBits);
    flight_.advance(x, t0, c - t0, xs_);
    highest = std::max(highest, slow_delta(xs_));
  }
  if (highest + fast >= 0) return false;
  ++solution_.coarse_intervals;
  if (work) *work += step_work, *dissipation += step_dissipation;
  record_bounded_step(t0, x, xb_, tb, coarse_sub_);
  t = tb;
  std::swap(x, xb_);
  phase_a = phase_b;
  return true;
}

// The slow modes close the gap at most at speed_bound: from an indentation delta_slow(t0) + fast < 0 no contact
// can start before (-(delta_slow + fast)) / speed has passed.
bool Solver::long_step_without_contact(double& t, ModalState& x, FreeFlight::MotorPhase& phase_a, double fast,
                                       double* work, double* dissipation) {
  if (long_steps_.empty()) return false;
  const double distance = model_.gap_m - slow_lever_.dot(x.q) - fast;
  if (!(distance > 0)) return false;
  const double speed = flight_.speed_bound(x, phase_a, slow_lever_);
  const double reach_s = speed > 0 ? distance / speed : kInf;
  const LongStep* step = nullptr;
  for (const LongStep& longer : long_steps_) {
    if (!(longer.transition.tau_s < reach_s) || !bounded_step_may_end_at(t + longer.transition.tau_s)) break;
    step = &longer;
  }
  if (!step) return false;
  const double t0 = t, tb = t + step->transition.tau_s;
  const FreeFlight::MotorPhase phase_b = flight_.motor_phase(tb);
  flight_.advance(step->transition, phase_a, phase_b, x, xb_, work ? &step->energy : nullptr, work, dissipation);
  ++solution_.coarse_intervals;
  record_bounded_step(t0, x, xb_, tb, step->sub);
  t = tb;
  std::swap(x, xb_);
  phase_a = phase_b;
  return true;
}

Solver::AccelerationSeries Solver::acceleration_series(const ModalState& x, double t,
                                                       std::array<bool, 2> frames) const {
  // the motor force's derivatives: F cos(Omega t + k pi / 2) Omega^k
  std::array<double, kTaylorDegree + 1> motor{};
  if (model_.motor) {
    const double w = model_.motor->omega_rad_s, c = std::cos(w * t), s = std::sin(w * t);
    const std::array<double, 4> turn = {c, -s, -c, s};
    double scale = model_.motor->amplitude_n;
    for (int k = 0; k <= kTaylorDegree; ++k, scale *= w) motor[k] = scale * turn[k % 4];
  }
  AccelerationSeries series{};
  std::array<double, kTaylorDegree + 1> inverse_factorial{};
  inverse_factorial[0] = 1;
  for (int k = 1; k <= kTaylorDegree; ++k) inverse_factorial[k] = inverse_factorial[k - 1] / k;
  const double* p = model_.motor_lever.data();
  const double* c = two_zeta_omega_.data();
  const double* w2 = omega2_.data();
  for (int m = 0; m < m_; ++m) {
    const int f = m < n1_ ? 0 : 1;
    const double tip = model_.frames[f].tip[f == 0 ? m : m - n1_];
    if (tip == 0 || !frames[f]) continue;
    // q^(k+2) = p F^(k) - 2 zeta omega q^(k+1) - omega^2 q^(k)
    double d0 = x.q[m], d1 = x.v[m];
    for (int k = 0; k <= kTaylorDegree; ++k) {
      const double d2 = p[m] * motor[k] - c[m] * d1 - w2[m] * d0;
      series[f][k] += tip * d2 * inverse_factorial[k];
      d0 = d1;
      d1 = d2;
    }
  }
  return series;
}

void Solver::record_bounded_step(double t0, const ModalState& x0, const ModalState& xb, double tb, const SubGrid& sub) {
  if (!recorder_.wants(tb)) return;
  extrema_.clear();
  if (settings_.peaks_between_samples) {
    // The scan steps the free part alone (a 2x2 transition per mode) and turns the motor's phase; the full state
    // is formed only where a tip's jerk changes sign, for the Taylor polynomials about that sub-interval's start.
    const double h = (tb - t0) / sub.count;
    FreeFlight::MotorPhase phase_a = flight_.motor_phase(t0);
    flight_.free_part(x0, phase_a, scan_q_a_, scan_v_a_);
    std::array<double, 2> jerk_a = scan_jerk(scan_q_a_, scan_v_a_, phase_a);
    const std::array<double, 2> bound = jerk_curvature_bound(x0, phase_a);  // holds over the whole step
    const FreeFlight::Transition& tr = sub.transition;
    for (int j = 1; j <= sub.count; ++j) {
      const double ta = phase_a.t_s;
      FreeFlight::MotorPhase phase_b;
      if (j == sub.count) {
        phase_b = flight_.motor_phase(tb);
      } else if (j % kTurnsPerAnchor == 0) {
        phase_b = flight_.motor_phase(t0 + j * h);
      } else {
        phase_b = {t0 + j * h, phase_a.cos * sub.turn.cos - phase_a.sin * sub.turn.sin,
                   phase_a.sin * sub.turn.cos + phase_a.cos * sub.turn.sin};
      }
      scan_q_b_ = tr.qq * scan_q_a_ + tr.qv * scan_v_a_;
      scan_v_b_ = tr.vq * scan_q_a_ + tr.vv * scan_v_a_;
      const std::array<double, 2> jerk_b = scan_jerk(scan_q_b_, scan_v_b_, phase_b);
      const double length = phase_b.t_s - ta;
      const std::array<bool, 2> search = extremum_search(jerk_a, jerk_b, length, bound);
      if (search[0] || search[1]) {
        flight_.with_steady_state(scan_q_a_, scan_v_a_, phase_a, scan_a_);
        append_extrema(scan_a_, ta, length, search, bound);
      }
      std::swap(scan_q_a_, scan_q_b_);
      std::swap(scan_v_a_, scan_v_b_);
      phase_a = phase_b;
      jerk_a = jerk_b;
    }
  }
  const TipState sb = tip_state(xb.q.data(), xb.v.data(), tb, Phase::free);
  std::size_t next = 0;
  for (double ts = recorder_.next_sample_time(); ts <= tb; ts = recorder_.next_sample_time()) {
    while (next < extrema_.size() && extrema_[next].t <= ts) recorder_.feed(extrema_[next++]);
    recorder_.sample(ts == tb ? sb : sample_free(ts, x0, t0));
  }
  while (next < extrema_.size()) recorder_.feed(extrema_[next++]);
  recorder_.feed(sb);
}

std::array<double, 2> Solver::free_jerk(const ModalState& x, const FreeFlight::MotorPhase& phase) const {
  const double motor = model_.motor ? model_.motor->amplitude_n * phase.cos : 0;
  const double motor_rate = model_.motor ? -model_.motor->amplitude_n * model_.motor->omega_rad_s * phase.sin : 0;
  const double* p = model_.motor_lever.data();
  const double* c = two_zeta_omega_.data();
  const double* w2 = omega2_.data();
  std::array<double, 2> jerk{};
  for (int f = 0; f < 2; ++f) {
    const int first = f == 0 ? 0 : n1_, last = f == 0 ? n1_ : m_;
    const double* tip = model_.frames[f].tip.data();
    double sum = 0;
    for (int m = first; m < last; ++m) {
      const double acc = p[m] * motor - c[m] * x.v[m] - w2[m] * x.q[m];
      sum += tip[m - first] * (p[m] * motor_rate - c[m] * acc - w2[m] * x.v[m]);
    }
    jerk[f] = sum;
  }
  return jerk;
}

void Solver::prepare_scan_jerk() {
  // the free part's jerk: a~ = -c v~ - w^2 q~, j~ = -c a~ - w^2 v~ = c w^2 q~ + (c^2 - w^2) v~
  scan_jerk_q_.setZero(m_);
  scan_jerk_v_.setZero(m_);
  jerk_curvature_lever_.setZero(m_);
  const double motor_rate = model_.motor ? model_.motor->omega_rad_s : 0;
  for (int m = 0; m < m_; ++m) {
    const int f = m < n1_ ? 0 : 1;
    const double tip = model_.frames[f].tip[f == 0 ? m : m - n1_];
    scan_jerk_q_[m] = tip * two_zeta_omega_[m] * omega2_[m];
    scan_jerk_v_[m] = tip * (two_zeta_omega_[m] * two_zeta_omega_[m] - omega2_[m]);
    // the curvature bound's lever: the mode's rate |lambda| (omega underdamped, the fast root overdamped) or the
    // motor's, whichever is faster, to the fifth power (the jerk's second derivative is q's fifth)
    const double omega = model_.omega_rad_s[m], zeta = model_.zeta[m];
    const double rate = std::max(omega * (zeta > 1 ? zeta + std::sqrt(zeta * zeta - 1) : 1.0), motor_rate);
    jerk_curvature_lever_[m] = std::abs(tip) * std::pow(rate, 5);
  }
  // the steady state's: free_jerk is linear in the state and the motor's cos and sin
  const Eigen::ArrayXd zero = Eigen::ArrayXd::Zero(m_);
  ModalState steady;
  for (const bool sine : {false, true}) {
    const FreeFlight::MotorPhase phase{0, sine ? 0.0 : 1.0, sine ? 1.0 : 0.0};
    flight_.with_steady_state(zero, zero, phase, steady);
    const std::array<double, 2> jerk = free_jerk(steady, phase);
    (sine ? steady_jerk_sin_ : steady_jerk_cos_) = jerk;
  }
}

TipState Solver::sample_free(double ts, const ModalState& x_from, double t_from) {
  const FreeFlight::MotorPhase phase = flight_.motor_phase(ts);
  // Sample times are one interval apart up to rounding (~1e-16 s).
  const bool follows = std::abs(ts - last_sample_t_ - sample_transition_.tau_s) <= 1e-9 * sample_transition_.tau_s;
  if (follows && chained_samples_ < kSamplesPerAnchor) {
    flight_.advance(sample_transition_, last_sample_phase_, phase, x_sample_, xs_);
    std::swap(x_sample_, xs_);
    ++chained_samples_;
  } else {
    flight_.advance(x_from, t_from, ts - t_from, x_sample_);
    chained_samples_ = 0;
  }
  last_sample_t_ = ts;
  last_sample_phase_ = phase;
  return tip_state(x_sample_.q.data(), x_sample_.v.data(), ts, Phase::free);
}

}  // namespace ib::reference_internal
