// Each engine's contact law, fitted from its own force history: on the first impact of the free vibration
// case at a short step, the contact force each engine reports against the indentation and its rate gives
// back the scenario's stiffness and damping (spring-dashpot: F = k delta + c delta'; Hertz: F / delta^n =
// k_h + c_h delta'). Least squares over the contact's samples, independent of the mapping code: a stiffness
// or damping 5 % off in any engine's mapping fails here. Every engine of the build (the catalog), so that a
// new engine is fitted too; when its force is computed (from the step's start or end state) is read from its
// own samples, not from a list of engines.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <string>

#include <Eigen/Dense>

#include "reference_fixtures.h"
#include "simulators/catalog.h"

namespace ib {
namespace contact_law_fit_test {

struct Case {
  std::string engine, path;
  ContactLaw law;
};

struct Fit {
  double stiffness = NAN, damping = NAN;
  double residual = INFINITY;  // |A x - b| / |b|
  int samples = 0;
};

// F = k delta^n + c delta^m delta' over the contact's samples, least squares in k and c (Hertz: m = n;
// the spring-dashpot: n = 1, m = 0). The force a sample reports is what the step that ended there
// applied: computed from the state at the step's start (an explicit force, `lag` 1: one sample per step)
// or at its end (an implicit one, lag 0).
Fit fit_law(const Trajectory& t, double gap_m, double exponent, double damping_exponent, std::size_t lag) {
  std::vector<std::array<double, 3>> rows;  // delta^n, delta^m delta', F
  for (std::size_t j = lag; j < t.size(); ++j) {
    const std::size_t k = j - lag;  // the state the force was computed from
    const double delta = t.displacement_m[0][k] - t.displacement_m[1][k] - gap_m;
    const double force = t.contact_force_n[j];
    // well inside the contact: the first and last micrometre (and any clipped, zero-force sample) left out
    if (!(delta > 1e-6) || !(force > 0)) continue;
    const double rate = t.velocity_m_s[0][k] - t.velocity_m_s[1][k];
    rows.push_back({std::pow(delta, exponent), std::pow(delta, damping_exponent) * rate, force});
  }
  Fit fit;
  fit.samples = static_cast<int>(rows.size());
  if (fit.samples < 10) return fit;
  Eigen::MatrixXd a(fit.samples, 2);
  Eigen::VectorXd b(fit.samples);
  for (int i = 0; i < fit.samples; ++i) a(i, 0) = rows[i][0], a(i, 1) = rows[i][1], b(i) = rows[i][2];
  const Eigen::Vector2d kc = a.colPivHouseholderQr().solve(b);
  fit.stiffness = kc(0);
  fit.damping = kc(1);
  fit.residual = (a * kc - b).norm() / b.norm();
  return fit;
}

void PrintTo(const Case& c, std::ostream* out) { *out << c.engine << " " << c.path << " " << to_string(c.law); }

class ContactLawFit : public ::testing::TestWithParam<Case> {};

// The case's first impact at step h, one sample per step (fit_law's samples are steps).
RunResult first_impact(Simulator& simulator, const Case& c, const Scenario& s, double step_s) {
  RunSettings settings;
  settings.law = c.law;
  settings.time_step_s = step_s;
  settings.output_rate_hz = 1 / step_s;
  settings.series_start_s = 0.047;
  settings.options["contact"] = c.path;
  return simulator.run(s, settings);
}

TEST_P(ContactLawFit, TheEnginesOwnForcesGiveBackTheScenariosStiffnessAndDamping) {
  const Case c = GetParam();
  auto simulator = make_simulator(c.engine);
  if (!simulator) GTEST_SKIP() << c.engine << " is not in this build";
  Scenario s = testing::paper_scenario("free_vibration");
  s.duration_s = 0.05;  // the first impact: 48 to 49 ms
  s.scoring_window_s = 0.05;
  constexpr double kStep_s = 1e-6;
  const RunResult run = first_impact(*simulator, c, s, kStep_s);
  ASSERT_EQ(run.status, RunStatus::ok) << run.reason;
  const RunResult coarser = first_impact(*simulator, c, s, 2 * kStep_s);
  ASSERT_EQ(coarser.status, RunStatus::ok) << coarser.reason;
  // the law from the scenario's numbers, by hand (rig.md section 3): c_h = 3 k_h (1 - e^2) / (4 v_rel)
  double k = 0, damping = 0, n = 1;
  if (c.law == ContactLaw::hertz) {
    const HertzSpec& h = *s.contact.hertz;
    k = h.stiffness, n = h.exponent;
    damping = 3 * k * (1 - h.restitution * h.restitution) / (4 * h.approach_velocity_m_s);
  } else {
    k = s.contact.viscoelastic->stiffness_n_per_m, damping = s.contact.viscoelastic->damping_n_s_per_m;
  }
  // The force a step applies is computed from the state at its start (a force from the tip states: every
  // injected path, and a matched path that applies the law as a force) or at its end (an engine's implicit
  // springs, such as soft contact by ERP/CFM or force elements evaluated on the state the step ends in).
  // Which one is the engine's, not this test's to list: fitted against the other state, the spring moves
  // about k h into the damping (the indentations one step apart differ by h delta'), an error that grows
  // with the step, so the state whose fitted damping the step leaves alone (h and 2 h) is the one the force
  // came from. Its stiffness and damping must then be the law's: a mapping 5 % off is 5 % off at every step.
  const double m = c.law == ContactLaw::hertz ? n : 0;
  const Fit from_start = fit_law(run.trajectory, s.gap_m, n, m, 1),
            from_end = fit_law(run.trajectory, s.gap_m, n, m, 0);
  const double start_drift = std::abs(fit_law(coarser.trajectory, s.gap_m, n, m, 1).damping / from_start.damping - 1);
  const double end_drift = std::abs(fit_law(coarser.trajectory, s.gap_m, n, m, 0).damping / from_end.damping - 1);
  ASSERT_FALSE(std::isnan(start_drift) && std::isnan(end_drift)) << "too few samples in contact to fit";
  const bool start = !(end_drift < start_drift);
  const Fit& fit = start ? from_start : from_end;
  std::printf(
      "%s %s %s: k = %.6g (law %.6g), c = %.6g (law %.6g) from %d samples (residual %.2g), force from the step's %s "
      "(damping from h to 2 h: %+.2g %%; from the step's %s: %+.2g %%)\n",
      c.engine.c_str(), c.path.c_str(), to_string(c.law), fit.stiffness, k, fit.damping, damping, fit.samples,
      fit.residual, start ? "start" : "end", 100 * (start ? start_drift : end_drift), start ? "end" : "start",
      100 * (start ? end_drift : start_drift));
  ASSERT_GE(fit.samples, 100);
  EXPECT_NEAR(fit.stiffness / k, 1, 0.01) << c.engine << " " << c.path;
  EXPECT_NEAR(fit.damping / damping, 1, 0.01) << c.engine << " " << c.path;
}

std::vector<Case> cases() {
  std::vector<Case> all;
  // every engine of the build (the catalog), so a new engine is fitted too; the reference has no contact path
  for (const std::string& engine : simulator_names()) {
    if (engine == "reference") continue;
    for (const std::string path : {"matched", "injected"})
      for (ContactLaw law : {ContactLaw::hertz, ContactLaw::viscoelastic}) all.push_back({engine, path, law});
  }
  return all;
}

INSTANTIATE_TEST_SUITE_P(Engines, ContactLawFit, ::testing::ValuesIn(cases()),
                         [](const ::testing::TestParamInfo<Case>& info) {
                           return info.param.engine + "_" + info.param.path + "_" + to_string(info.param.law);
                         });

}  // namespace contact_law_fit_test
}  // namespace ib
