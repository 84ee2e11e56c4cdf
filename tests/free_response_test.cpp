// The reference without contact: free decay at the structural damping, forced response at the
// closed-form steady state (rig.md section 2).
#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "reference_fixtures.h"

namespace ib {
namespace free_response_test {

using testing::paper_scenario;

// The free vibration's frame 1 with one mode and no contact (gap 1 m), released from its static shape.
struct OneModeDecay {
  Scenario scenario = no_contact(paper_scenario("free_vibration"));
  ReferenceSettings settings = one_mode();
  ModalModel model = build_modal_model(scenario, ContactLaw::hertz, settings.modes);

  // sampled at rate_hz from t = 0 to duration_s
  ReferenceSolution solve(double duration_s, double rate_hz) const {
    return solve_reference(model, initial_state(scenario, model), duration_s, {0, duration_s, rate_hz}, settings);
  }
  static Scenario no_contact(Scenario s) {
    s.gap_m = 1.0;
    return s;
  }
  static ReferenceSettings one_mode() {
    ReferenceSettings settings;
    settings.modes.modes_per_frame = 1;
    return settings;
  }
};

// One mode released from its static shape: u(k T_d) = u(0) exp(-zeta omega k T_d) exactly, so the
// logarithmic decrement gives zeta back to the closed form's precision.
TEST(FreeResponse, LogarithmicDecrementOfOneModeGivesZeta) {
  const OneModeDecay decay;
  const double omega = decay.model.omega_rad_s[0], zeta = decay.model.zeta[0];
  const double period = 2 * M_PI / (omega * std::sqrt(1 - zeta * zeta));
  const int cycles = 40;
  const ReferenceSolution r = decay.solve(cycles * period, 1 / period);
  const auto& u = r.trajectory.displacement_m[0];
  ASSERT_EQ(u.size(), static_cast<std::size_t>(cycles + 1));
  EXPECT_NEAR(u[0], -2e-3, 1e-15);
  const double decrement = std::log(u[0] / u[cycles]) / cycles;
  const double measured_zeta = decrement / std::sqrt(4 * M_PI * M_PI + decrement * decrement);
  EXPECT_NEAR(measured_zeta / zeta, 1.0, 1e-9);
}

// Every sample of a long series, not only one per period: the samples follow one another by the
// transition over the sample interval, so this checks that chain against the closed form
// q(t) = q0 e^{-zeta omega t} (cos omega_d t + zeta omega / omega_d sin omega_d t) from rest.
TEST(FreeResponse, EverySampleOfOneModeFollowsTheClosedForm) {
  const OneModeDecay decay;
  const double omega = decay.model.omega_rad_s[0], zeta = decay.model.zeta[0];
  const double omega_d = omega * std::sqrt(1 - zeta * zeta), rate_hz = 4096, duration_s = 10;
  const ReferenceSolution r = decay.solve(duration_s, rate_hz);
  const auto& u = r.trajectory.displacement_m[0];
  const auto& time = r.trajectory.time_s;
  ASSERT_EQ(u.size(), static_cast<std::size_t>(duration_s * rate_hz + 1));
  double worst = 0;
  for (std::size_t k = 0; k < u.size(); ++k) {
    const double t = time[k];
    const double closed_form =
        u[0] * std::exp(-zeta * omega * t) * (std::cos(omega_d * t) + zeta * omega / omega_d * std::sin(omega_d * t));
    worst = std::max(worst, std::abs(u[k] - closed_form));
  }
  EXPECT_LT(worst, 1e-10 * std::abs(u[0])) << "largest difference from the closed form [m]";
}

// Ten modes: the tip's successive maxima still decay at zeta (higher modes barely ripple them).
TEST(FreeResponse, LogarithmicDecrementOfTheBeamGivesZeta) {
  Scenario s = paper_scenario("free_vibration");
  s.gap_m = 1.0;
  ReferenceSettings settings;  // default: 10 modes per frame
  const ModalModel model = build_modal_model(s, ContactLaw::hertz, settings.modes);
  const double duration = 3.0;
  const ReferenceSolution r = solve_reference(model, initial_state(s, model), duration, {0, duration, 20000}, settings);
  const auto& u = r.trajectory.displacement_m[0];
  std::vector<double> peaks;
  for (std::size_t k = 1; k + 1 < u.size(); ++k)
    if (u[k] > u[k - 1] && u[k] >= u[k + 1] && u[k] > 1e-4) peaks.push_back(u[k]);
  ASSERT_GE(peaks.size(), 15u);
  const double n = static_cast<double>(peaks.size() - 1);
  const double decrement = std::log(peaks.front() / peaks.back()) / n;
  EXPECT_NEAR(decrement / std::sqrt(4 * M_PI * M_PI + decrement * decrement) / s.frames[0].damping_ratio, 1.0, 0.01);
}

// Motor on, no contact: after the transient (200 s, e^-26 of it left) the tip moves at the modal
// steady-state amplitude |sum phi^2 F / (omega^2 - Omega^2 + 2 i zeta omega Omega)|.
TEST(FreeResponse, ForcedResponseReachesTheSteadyStateAmplitude) {
  Scenario s = paper_scenario("post_resonance");
  s.gap_m = 1.0;
  s.duration_s = 200;
  ReferenceSettings settings;
  const ModalModel model = build_modal_model(s, ContactLaw::hertz, settings.modes);
  const double rate = 16384;
  const ReferenceSolution r = solve_reference(model, initial_state(s, model), s.duration_s, {195, 200, rate}, settings);
  double amplitude = 0;
  for (double u : r.trajectory.displacement_m[0]) amplitude = std::max(amplitude, std::abs(u));
  const double force = model.motor->amplitude_n, w = model.motor->omega_rad_s;
  std::complex<double> receptance = 0;
  for (int n = 0; n < model.frame_mode_count(0); ++n) {
    const double om = model.omega_rad_s[n];
    receptance += model.frames[0].tip[n] * model.frames[0].tip[n] /
                  std::complex<double>(om * om - w * w, 2 * model.zeta[n] * om * w);
  }
  // samples straddle the crest: the largest is within (pi f / rate)^2 / 2 ~ 1e-6 below it
  EXPECT_NEAR(amplitude / (force * std::abs(receptance)), 1.0, 5e-6);
  EXPECT_TRUE(r.trajectory.events.empty());
  EXPECT_EQ(r.status, RunStatus::ok);
}

}  // namespace free_response_test
}  // namespace ib
