// The stiff and extreme scenarios (scenarios/stiff, scenarios/extreme): every file loads and says what
// it probes, every law it defines runs on the reference, and the reference obeys the closed forms and
// conservation laws that apply to them: the contact duration of a linear spring, pi / omega_d, across
// the stiffness sweep and for Hertz with exponent 1; sticking at restitution 0; no contact loss at
// restitution 1; the energy an initial overlap stores (total energy over 1000 s without damping:
// zero_damping_energy_test.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "reference_fixtures.h"

namespace ib {
namespace stiff_extreme_scenarios_test {

const std::string kScenarios = std::string(IMPACTBENCH_SOURCE_DIR) + "/scenarios/";

Scenario scenario(const std::string& relative_path) { return load_scenario(kScenarios + relative_path); }

struct ReferenceRun {
  ModalModel model;
  ReferenceSolution solution;
};

// The reference on the continuous beam (default settings) over the whole scenario; one output sample at
// the end (events and the energy ledger cover the whole run whatever the output window).
ReferenceRun run_reference(const Scenario& s, ContactLaw law, ReferenceSettings settings = {}) {
  ReferenceRun r{build_modal_model(s, law, settings.modes), {}};
  r.solution =
      solve_reference(r.model, initial_state(s, r.model), s.duration_s, {s.duration_s, s.duration_s, 1}, settings);
  return r;
}

// Two tips of effective mass m_eff on a spring-dashpot k, c: the contact lasts pi / omega_d and the
// tips part at e times the approach speed (rig.md section 3.2, unclipped law).
struct SpringDashpotContact {
  double omega_rad_s, zeta;
  SpringDashpotContact(double k, double c, double m_eff)
      : omega_rad_s(std::sqrt(k / m_eff)), zeta(c / (2 * std::sqrt(k * m_eff))) {}
  double duration_s() const { return M_PI / (omega_rad_s * std::sqrt(1 - zeta * zeta)); }
  double restitution() const { return std::exp(-zeta * M_PI / std::sqrt(1 - zeta * zeta)); }
  // Released at rest from indentation x0: the speed at which the indentation returns to zero.
  double separation_speed_from_rest_m_s(double x0_m) const {
    return x0_m * omega_rad_s * std::exp(-zeta * (M_PI - std::acos(zeta)) / std::sqrt(1 - zeta * zeta));
  }
};

// ------------------------------------------------------------------------------------------------
// The files.

TEST(StiffExtremeScenarios, EveryFileLoadsAndSaysWhatItProbes) {
  std::set<std::string> names;
  int files = 0;
  for (const char* folder : {"stiff", "extreme"}) {
    for (const std::string& path : find_scenario_files(kScenarios + folder)) {
      ++files;
      const Scenario s = load_scenario(path);
      EXPECT_GE(s.description.size(), 40u) << path << ": the description says what the scenario probes";
      EXPECT_TRUE(names.insert(s.name).second) << path << ": scenario name " << s.name << " is used twice";
      EXPECT_EQ(s.name.rfind(std::string(folder) + "_", 0), 0u) << path << ": names start with the folder";
      EXPECT_TRUE(s.contact.hertz || s.contact.viscoelastic || s.contact.newton) << path;
    }
  }
  EXPECT_GE(files, 17);
  // the cases issue 8 asks for
  for (const char* file :
       {"stiff/spring_dashpot_k1e05.toml", "stiff/spring_dashpot_k1e06.toml", "stiff/spring_dashpot_k1e07.toml",
        "stiff/spring_dashpot_k1e08.toml", "stiff/spring_dashpot_k1e09.toml", "stiff/spring_dashpot_k1e10.toml",
        "stiff/hertz_exponent_1.toml", "extreme/restitution_0.toml", "extreme/restitution_0_3.toml",
        "extreme/restitution_1.toml", "extreme/zero_gap.toml", "extreme/initial_penetration.toml",
        "extreme/tip_mass_ratio_0_1.toml", "extreme/tip_mass_ratio_10.toml", "extreme/zero_damping_1000s.toml",
        "extreme/unbalance_x10.toml", "extreme/second_mode.toml"}) {
    EXPECT_NO_THROW(scenario(file)) << file;
  }
}

// The parameters each case is defined by, as its header says.
TEST(StiffExtremeScenarios, EachCaseHasTheParametersItIsDefinedBy) {
  const Scenario hertz1 = scenario("stiff/hertz_exponent_1.toml");
  EXPECT_EQ(hertz1.contact.hertz->exponent, 1.0);
  EXPECT_EQ(hertz1.contact.hertz->stiffness, 2.31e10);
  for (const char* file : {"extreme/tip_mass_ratio_0_1.toml", "extreme/tip_mass_ratio_10.toml"}) {
    const Scenario s = scenario(file);
    const double ratio = std::string(file).find("0_1") != std::string::npos ? 0.1 : 10.0;
    for (const FrameSpec& f : s.frames) EXPECT_NEAR(f.tip_mass_kg / f.beam_mass_kg(), ratio, 1e-5 * ratio) << file;
  }
  const Scenario paper = testing::paper_scenario("resonance");
  const Scenario x10 = scenario("extreme/unbalance_x10.toml");
  EXPECT_NEAR(x10.motor->unbalance_mass_kg * x10.motor->unbalance_radius_m,
              10 * paper.motor->unbalance_mass_kg * paper.motor->unbalance_radius_m, 1e-12);
  // at frame 1's second natural frequency, to within 0.01 Hz (half-power bandwidth 2 zeta f_2 = 0.44 Hz)
  const Scenario second = scenario("extreme/second_mode.toml");
  const ModalBasis modes = frame_modes(second.frames[0], ModeSelection{});
  EXPECT_NEAR(*second.motor->frequency_hz, modes.omega_rad_s[1] / (2 * M_PI), 0.01);
  const Scenario zero_gap = scenario("extreme/zero_gap.toml");
  EXPECT_EQ(zero_gap.gap_m, 0.0);
  EXPECT_TRUE(zero_gap.motor.has_value());
}

// Every law of every file runs on the reference without a failure, and the energy ledger balances.
// (The 1000 s case has its own test below.)
TEST(StiffExtremeScenarios, EveryLawOfEveryFileRunsOnTheReferenceAndBalancesEnergy) {
  for (const char* folder : {"stiff", "extreme"}) {
    for (const std::string& path : find_scenario_files(kScenarios + folder)) {
      const Scenario s = load_scenario(path);
      if (s.duration_s > 100) continue;
      for (ContactLaw law : {ContactLaw::hertz, ContactLaw::viscoelastic, ContactLaw::newton}) {
        if (!s.contact.has(law)) continue;
        const ReferenceRun r = run_reference(s, law);
        EXPECT_EQ(r.solution.status, RunStatus::ok) << path << " " << to_string(law) << ": " << r.solution.reason;
        EXPECT_GT(r.solution.impacts, 0) << path << " " << to_string(law);
        EXPECT_LT(r.solution.energy.relative_residual(), 1e-6) << path << " " << to_string(law);
      }
    }
  }
}

// ------------------------------------------------------------------------------------------------
// Stiff: the contact duration of a linear spring.

// Each decade's damping keeps zeta_v = c / (2 sqrt(k m_ef)) = 0.05 with the published m_ef = 0.4138 kg.
TEST(StiffnessSweep, DampingKeepsThePublishedDampingRatio) {
  for (int decade = 5; decade <= 10; ++decade) {
    char file[64];
    std::snprintf(file, sizeof file, "stiff/spring_dashpot_k1e%02d.toml", decade);
    const Scenario s = scenario(file);
    const ViscoelasticSpec& v = *s.contact.viscoelastic;
    EXPECT_EQ(v.stiffness_n_per_m, std::pow(10.0, decade)) << file;
    EXPECT_NEAR(v.damping_n_s_per_m / (2 * std::sqrt(v.stiffness_n_per_m * 0.4138)), 0.05, 1e-6) << file;
    EXPECT_FALSE(v.clip_tension) << file;
  }
}

// Contacts much shorter than the beam's modes see two tips of effective mass m_eff = 1 / sum b_m^2 on the
// spring-dashpot, so they last pi / omega_d, which scales as k^-1/2. The beam's fastest modes (up to
// 3.8 kHz with 10 modes per frame) still join in a contact of 1e8 N/m (6 kHz): each impact within 2 %
// there, within 0.5 % at 1e9 and 1e10 N/m. Not checked: impacts that start below 5 mm/s, where the
// frames' own relative acceleration over the contact (tens of m/s^2 x t_c) is not small against the
// approach speed (the reference has a 0.9 mm/s re-contact at 1e10 N/m that lasts 5 % less), and the
// soft decades 1e5 to 1e7 N/m, where the contact is slow enough for the beam's modes to join in (mean
// duration +6.6 %, +4.3 %, +2.5 %): that is what a soft contact on a beam does, and it is only printed.
TEST(StiffnessSweep, ContactDurationIsTheSpringClosedFormAndScalesAsOneOverSqrtK) {
  double previous_mean = 0;
  for (int decade = 5; decade <= 10; ++decade) {
    char file[64];
    std::snprintf(file, sizeof file, "stiff/spring_dashpot_k1e%02d.toml", decade);
    const Scenario s = scenario(file);
    const ReferenceRun r = run_reference(s, ContactLaw::viscoelastic);
    ASSERT_EQ(r.solution.status, RunStatus::ok) << file << ": " << r.solution.reason;
    const ViscoelasticSpec& v = *s.contact.viscoelastic;
    const SpringDashpotContact closed(v.stiffness_n_per_m, v.damping_n_s_per_m, r.model.contact_effective_mass_kg());
    const double tolerance = decade == 8 ? 0.02 : 0.005;
    double sum = 0;
    int counted = 0;
    for (const ContactEvent& e : r.solution.trajectory.events) {
      if (e.approach_velocity_m_s < 5e-3) continue;
      const double duration = e.end_time_s - e.onset_time_s;
      sum += duration;
      ++counted;
      if (decade >= 8) {
        EXPECT_NEAR(duration / closed.duration_s(), 1.0, tolerance) << file << " impact at " << e.onset_time_s << " s";
      }
    }
    ASSERT_GE(counted, 5) << file;
    const double mean = sum / counted;
    std::printf("k = 1e%d N/m: %d impacts, mean contact %.6g s, closed form %.6g s (%+.2f %%)\n", decade, counted, mean,
                closed.duration_s(), 100 * (mean / closed.duration_s() - 1));
    // a decade stiffer: sqrt(10) times shorter
    if (decade >= 9) {
      EXPECT_NEAR(previous_mean / mean, std::sqrt(10.0), 0.01 * std::sqrt(10.0)) << file;
    }
    previous_mean = mean;
  }
}

// Hertz with exponent 1 is a linear spring k_h = 2.31e10 N/m: contacts of pi sqrt(m_eff / k_h) = 10.5 us.
// Its Hunt-Crossley damping k_h delta (c_h/k_h) delta' shifts the duration by a fraction of order
// (alpha v)^2 (alpha = c_h/k_h = 4.15 s/m, approach speeds about 0.035 m/s): well under 1 %.
TEST(HertzExponentOne, ContactDurationIsTheLinearSpringClosedForm) {
  const Scenario s = scenario("stiff/hertz_exponent_1.toml");
  ASSERT_EQ(s.contact.hertz->exponent, 1.0);
  const ReferenceRun r = run_reference(s, ContactLaw::hertz);
  ASSERT_EQ(r.solution.status, RunStatus::ok) << r.solution.reason;
  const auto& events = r.solution.trajectory.events;
  ASSERT_GE(events.size(), 5u);
  const double closed = M_PI * std::sqrt(r.model.contact_effective_mass_kg() / s.contact.hertz->stiffness);
  EXPECT_NEAR(closed, 10.5e-6, 0.1e-6);  // rig.md section 6.5: "contacts of about 10 microseconds"
  for (const ContactEvent& e : events)
    EXPECT_NEAR((e.end_time_s - e.onset_time_s) / closed, 1.0, 0.01) << "impact at " << e.onset_time_s << " s";
}

// ------------------------------------------------------------------------------------------------
// Extreme: restitution 0 and 1.

// Newton e = 0: no impact rebounds; the tips stick and the constraint force holds them until the
// frames pull apart, every sticking phase released.
TEST(RestitutionZero, NewtonImpactsStickWithZeroRelativeVelocity) {
  const Scenario s = scenario("extreme/restitution_0.toml");
  ASSERT_EQ(s.contact.newton->restitution, 0.0);
  EXPECT_FALSE(s.contact.viscoelastic.has_value());  // no finite damping gives e = 0
  const ReferenceRun r = run_reference(s, ContactLaw::newton);
  ASSERT_EQ(r.solution.status, RunStatus::ok) << r.solution.reason;
  ASSERT_GE(r.solution.trajectory.events.size(), 5u);
  EXPECT_GE(r.solution.sticking_phases, 5);
  for (const ContactEvent& e : r.solution.trajectory.events) {
    EXPECT_NEAR(e.rebound_velocity_m_s, 0.0, 1e-12) << "impact at " << e.onset_time_s << " s";
    // the episode's restitution is its rebound over its own approach: zero, not a ratio of roundings
    EXPECT_NEAR(e.restitution, 0.0, 1e-9) << "impact at " << e.onset_time_s << " s";
    EXPECT_GE(e.end_time_s, e.onset_time_s);
  }
  // every sticking phase ends before the run does: the tips are apart at the end
  EXPECT_LT(r.solution.trajectory.events.back().end_time_s, s.duration_s);
  // the plastic impacts and the sticking dissipate
  EXPECT_GT(r.solution.energy.contact_dissipation_j, 0.1 * r.solution.energy.motor_work_j);
}

// Restitution 1 in every law (Newton e = 1, Hertz c_h = 0, spring-dashpot c_v = 0): contacts lose
// nothing, so the motor's work goes to the structure and its energy alone, and Newton's rebound is the
// approach speed.
TEST(RestitutionOne, ContactsLoseNoEnergy) {
  const Scenario s = scenario("extreme/restitution_1.toml");
  EXPECT_EQ(s.contact.hertz->damping_coefficient(), 0.0);
  EXPECT_EQ(s.contact.viscoelastic->damping_n_s_per_m, 0.0);
  for (ContactLaw law : {ContactLaw::hertz, ContactLaw::viscoelastic, ContactLaw::newton}) {
    const ReferenceRun r = run_reference(s, law);
    ASSERT_EQ(r.solution.status, RunStatus::ok) << to_string(law) << ": " << r.solution.reason;
    EXPECT_GE(r.solution.impacts, 5) << to_string(law);
    const EnergyLedger& e = r.solution.energy;
    EXPECT_NEAR(e.contact_dissipation_j, 0.0, 1e-9 * e.motor_work_j) << to_string(law);
    EXPECT_LT(e.relative_residual(), 1e-6) << to_string(law);
    if (law == ContactLaw::newton) {
      for (const ContactEvent& ev : r.solution.trajectory.events)
        EXPECT_NEAR(ev.rebound_velocity_m_s, ev.approach_velocity_m_s, 1e-12)
            << "impact at " << ev.onset_time_s << " s";
    }
  }
}

// ------------------------------------------------------------------------------------------------
// Extreme: an initial overlap.

// Released at rest 10 um into frame 2 (gap 0): the first contact starts at t = 0 with that indentation
// and no motion, and the overlap's stored energy parts the tips. Closed forms for two tips of effective
// mass m_eff on the law:
//   spring-dashpot: the separation speed of a damped oscillator released from rest at x0,
//     x0 omega exp(-zeta (pi - acos zeta) / sqrt(1 - zeta^2));
//   Hertz without damping: (1/2) m_eff v^2 = k_h x0^(n+1) / (n+1).
// With one mode per frame (7 and 8 Hz against a contact of about 1 kHz) the tips are that pair of masses
// on the frames' soft springs, which shift the result by about (omega_1 / omega_contact)^2 = 1e-4: the
// closed forms hold to 3e-4 (measured 2e-5). On the 10-mode beam the higher modes (up to 3.8 kHz) join the
// contact and keep part of the energy as vibration: the tips part 3.9 % slower (spring-dashpot) and with
// 2.3 % less energy (Hertz); checked within 6 %.
TEST(InitialPenetration, TipsPartWithTheEnergyTheOverlapStored) {
  const Scenario s = scenario("extreme/initial_penetration.toml");
  ASSERT_EQ(s.gap_m, 0.0);
  EXPECT_FALSE(s.motor.has_value());
  EXPECT_FALSE(s.contact.newton.has_value());  // an instantaneous law has no meaning for an overlap
  const double x0 = s.initial.frame1_tip_displacement_m;
  ASSERT_GT(x0, 0.0);
  Scenario undamped_hertz = s;
  undamped_hertz.contact.hertz->damping = 0.0;

  for (int modes : {1, 10}) {
    ReferenceSettings settings;
    settings.modes.modes_per_frame = modes;
    const double tolerance = modes == 1 ? 3e-4 : 0.06;
    {  // spring-dashpot, as in the file
      const ReferenceRun r = run_reference(s, ContactLaw::viscoelastic, settings);
      ASSERT_EQ(r.solution.status, RunStatus::ok) << r.solution.reason;
      const ContactEvent& first = r.solution.trajectory.events.at(0);
      EXPECT_EQ(first.onset_time_s, 0.0);
      EXPECT_NEAR(first.approach_velocity_m_s, 0.0, 1e-12);
      EXPECT_NEAR(first.max_indentation_m / x0, 1.0, 1e-9);
      const ViscoelasticSpec& v = *s.contact.viscoelastic;
      const SpringDashpotContact closed(v.stiffness_n_per_m, v.damping_n_s_per_m, r.model.contact_effective_mass_kg());
      std::printf("%d modes, spring-dashpot: separation speed %.6g m/s, closed form %.6g m/s\n", modes,
                  first.rebound_velocity_m_s, closed.separation_speed_from_rest_m_s(x0));
      EXPECT_NEAR(first.rebound_velocity_m_s / closed.separation_speed_from_rest_m_s(x0), 1.0, tolerance)
          << modes << " modes";
      // the ledger starts with the overlap's elastic energy (plus frame 1's strain energy, below 1e-3 of it)
      EXPECT_NEAR(r.solution.energy.initial_energy_j / (0.5 * v.stiffness_n_per_m * x0 * x0), 1.0, 1e-3);
    }
    {  // Hertz with its damping off: the stored energy comes back as motion
      const ReferenceRun r = run_reference(undamped_hertz, ContactLaw::hertz, settings);
      ASSERT_EQ(r.solution.status, RunStatus::ok) << r.solution.reason;
      const ContactEvent& first = r.solution.trajectory.events.at(0);
      EXPECT_EQ(first.onset_time_s, 0.0);
      const HertzSpec& h = *s.contact.hertz;
      const double stored = h.stiffness * std::pow(x0, h.exponent + 1) / (h.exponent + 1);
      const double speed = first.rebound_velocity_m_s;
      const double kinetic = 0.5 * r.model.contact_effective_mass_kg() * speed * speed;
      std::printf("%d modes, Hertz undamped: kinetic energy at separation %.6g J, stored %.6g J\n", modes, kinetic,
                  stored);
      EXPECT_NEAR(kinetic / stored, 1.0, tolerance) << modes << " modes";
      EXPECT_NEAR(r.solution.energy.initial_energy_j / stored, 1.0, 1e-3);
    }
  }
}

}  // namespace stiff_extreme_scenarios_test
}  // namespace ib
