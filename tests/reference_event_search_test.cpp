// The reference's free-flight event search steps over stretches where no contact can start (coarse steps on
// the fast modes' displacement bound, longer ones on the slow modes' speed bound) and scans the fine grid
// elsewhere. It must find exactly the contacts the fine grid alone finds (slow_modes_per_frame = 0): the same
// onsets, to rounding, on grazing approaches and on the stiff and extreme scenarios. The bounds it rests on
// hold along a closed-form free flight, and the long steps' energy forms (doubled) equal the quadrature's.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "reference/free_flight.h"
#include "reference_fixtures.h"

namespace ib {
namespace reference_event_search_test {

const std::string kScenarios = std::string(IMPACTBENCH_SOURCE_DIR) + "/scenarios/";

// Onsets agree when the tips close less than this distance, at their approach speed, between the two [m]: 1e-7
// of the gap. The searches advance the same closed form by different steps (and the time by different sums of
// them), so the onsets they locate differ a little (up to 2e-11 m of closing seen here); a missed contact would
// be off by a whole flight.
constexpr double kOnsetTolerance_m = 1e-10;

ReferenceSettings fine_grid_only() {
  ReferenceSettings settings;
  settings.slow_modes_per_frame = 0;
  return settings;
}

// The whole run with one output sample at its end: the events are what is compared.
ReferenceSolution solve(const ModalModel& model, const ModalState& x0, double duration_s,
                        const ReferenceSettings& settings) {
  return solve_reference(model, x0, duration_s, {duration_s, duration_s, 1}, settings);
}

// The same onsets: as many, each within the tolerance.
void expect_same_onsets(const std::vector<ContactEvent>& a, const std::vector<ContactEvent>& b,
                        const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what << ": contact episodes, bounded steps against the fine grid";
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double closing_m =
        std::abs(a[i].onset_time_s - b[i].onset_time_s) * std::max(b[i].approach_velocity_m_s, 1e-3);
    EXPECT_LE(closing_m, kOnsetTolerance_m)
        << what << ": onset " << i << " at " << b[i].onset_time_s << " s against " << a[i].onset_time_s << " s";
  }
}

// The gap at which the contact-free motion of [0, duration] just touches (the largest b.q it reaches): until
// its first contact a run does not depend on the gap, so "a contact within the run" is monotone in the gap.
// Bisected with the fine grid alone.
double grazing_gap_m(ModalModel model, const ModalState& x0, double duration_s) {
  double touching = 0, missing = 0.05;  // [m]: the tips touch at 0; 5 cm is beyond the rig's reach
  for (int i = 0; i < 60 && missing - touching > 1e-15; ++i) {
    model.gap_m = 0.5 * (touching + missing);
    (solve(model, x0, duration_s, fine_grid_only()).trajectory.events.empty() ? missing : touching) = model.gap_m;
  }
  return touching;
}

// Grazing approaches: the gap a picometre inside and outside the largest approach of the contact-free motion,
// on the free vibration (released at rest) and the forced resonance (the motor and the bounded steps long
// before the approach). Both searches find the same contact, or the same absence of one.
TEST(ReferenceEventSearch, GrazingApproachesAreFoundAsTheFineGridFindsThem) {
  for (const char* name : {"free_vibration", "resonance"}) {
    Scenario s = testing::paper_scenario(name);
    const double duration_s = std::string(name) == "free_vibration" ? 0.3 : 3.0;
    ModalModel model = build_modal_model(s, ContactLaw::hertz, ModeSelection{});
    const ModalState x0 = initial_state(s, model);
    const double grazing = grazing_gap_m(model, x0, duration_s);
    ASSERT_GT(grazing, 0.0) << name;
    for (double overlap_m : {1e-12, -1e-12, 1e-9}) {
      model.gap_m = grazing - overlap_m;
      const ReferenceSolution bounded = solve(model, x0, duration_s, {});
      const ReferenceSolution fine = solve(model, x0, duration_s, fine_grid_only());
      const std::string what = std::string(name) + ", overlap " + std::to_string(overlap_m * 1e12) + " pm";
      ASSERT_EQ(bounded.status, RunStatus::ok) << what << ": " << bounded.reason;
      expect_same_onsets(bounded.trajectory.events, fine.trajectory.events, what);
      EXPECT_EQ(fine.trajectory.events.empty(), overlap_m < 0) << what;
      EXPECT_GT(bounded.coarse_intervals, 0) << what << ": the bounded steps were taken";
    }
  }
}

// Every law of every stiff and extreme scenario (the 1000 s one aside: its own test). Several are sensitive
// (Newton chatter, zero gap, a light tip): a rounding-level difference changes their later impacts, whichever
// search runs, so each free flight of a run is searched again by both from the state it started from, to its
// next onset: both must find that onset, or both none before the run's end.
TEST(ReferenceEventSearch, StiffAndExtremeScenariosHaveTheFineGridsOnsets) {
  int cases = 0;
  long long flights = 0;
  for (const char* folder : {"stiff", "extreme"}) {
    for (const std::string& path : find_scenario_files(kScenarios + folder)) {
      const Scenario s = load_scenario(path);
      if (s.duration_s > 100) continue;
      for (ContactLaw law : {ContactLaw::hertz, ContactLaw::viscoelastic, ContactLaw::newton}) {
        if (!s.contact.has(law)) continue;
        const ModalModel model = build_modal_model(s, law, ModeSelection{});
        const ModalState x0 = initial_state(s, model);
        ReferenceSettings keeping;
        keeping.keep_flight_starts_from_s = 0;
        const ReferenceSolution run = solve(model, x0, s.duration_s, keeping);
        ASSERT_EQ(run.status, RunStatus::ok) << path;
        const std::string what = path + " " + to_string(law);
        // from the start: the first onset
        const double first_end_s = run.trajectory.events.empty()
                                       ? s.duration_s
                                       : std::min(s.duration_s, run.trajectory.events[0].onset_time_s + 1e-3);
        auto first_onsets = [&](const ReferenceSolution& r, double after_s) {
          std::vector<ContactEvent> onsets;
          for (const ContactEvent& e : r.trajectory.events)
            if (e.onset_time_s > after_s && onsets.empty()) onsets.push_back(e);
          return onsets;
        };
        expect_same_onsets(first_onsets(solve(model, x0, first_end_s, {}), -1),
                           first_onsets(solve(model, x0, first_end_s, fine_grid_only()), -1),
                           what + ", from the start");
        // from every free flight's start: its onset (the next one the run found, or none)
        for (const FlightStart& start : run.flight_starts) {
          double next_s = s.duration_s;
          for (const ContactEvent& e : run.trajectory.events)
            if (e.onset_time_s > start.t_s) {
              next_s = std::min(s.duration_s, e.onset_time_s + 1e-3);
              break;
            }
          const ReferenceSolution bounded =
              solve_reference_after_contact(model, start, next_s, {next_s, next_s, 1}, {});
          const ReferenceSolution fine =
              solve_reference_after_contact(model, start, next_s, {next_s, next_s, 1}, fine_grid_only());
          expect_same_onsets(first_onsets(bounded, start.t_s), first_onsets(fine, start.t_s),
                             what + ", from the flight at " + std::to_string(start.t_s) + " s");
          ++flights;
        }
        ++cases;
      }
    }
  }
  EXPECT_GE(cases, 17);
  EXPECT_GT(flights, 1000);
}

// The speed bound holds along a free flight: |b.v(t)| of the slow modes never exceeds it, from states taken
// on the forced rig after impacts (every mode excited).
TEST(ReferenceEventSearch, SpeedBoundHoldsAlongAFreeFlight) {
  const Scenario s = testing::paper_scenario("resonance");
  const ModalModel model = build_modal_model(s, ContactLaw::hertz, ModeSelection{});
  const FreeFlight flight(model);
  ModalState x = initial_state(s, model);
  for (int m = 0; m < model.mode_count(); ++m) x.v[m] += 0.01 * std::sin(1.0 + m);  // every mode moving
  const double t0 = 0.37;
  const double bound = flight.speed_bound(x, flight.motor_phase(t0), model.contact_lever);
  ModalState xt;
  double largest = 0;
  for (int k = 1; k <= 20000; ++k) {
    flight.advance(x, t0, k * 5e-5, xt);
    largest = std::max(largest, std::abs(model.contact_lever.dot(xt.v)));
  }
  EXPECT_LE(largest, bound);
}

// The energy forms over 2 tau composed from those over tau equal the quadrature over 2 tau.
TEST(ReferenceEventSearch, DoubledEnergyFormsEqualTheQuadrature) {
  const Scenario s = testing::paper_scenario("resonance");
  const ModalModel model = build_modal_model(s, ContactLaw::hertz, ModeSelection{});
  const FreeFlight flight(model);
  const double tau_s = 5.3e-4;
  const FreeFlight::EnergyForms doubled = flight.doubled(flight.energy_forms(tau_s), flight.transition(tau_s));
  const FreeFlight::EnergyForms direct = flight.energy_forms(2 * tau_s);
  EXPECT_EQ(doubled.tau_s, direct.tau_s);
  auto expect_close = [](const Eigen::ArrayXd& a, const Eigen::ArrayXd& b, const char* what) {
    const double scale = b.abs().maxCoeff();
    EXPECT_LE((a - b).abs().maxCoeff(), 1e-11 * scale) << what;
  };
  expect_close(doubled.vv_qq, direct.vv_qq, "vv_qq");
  expect_close(doubled.vv_qv, direct.vv_qv, "vv_qv");
  expect_close(doubled.vv_vv, direct.vv_vv, "vv_vv");
  expect_close(doubled.cos_q, direct.cos_q, "cos_q");
  expect_close(doubled.cos_v, direct.cos_v, "cos_v");
  expect_close(doubled.sin_q, direct.sin_q, "sin_q");
  expect_close(doubled.sin_v, direct.sin_v, "sin_v");
  EXPECT_NEAR(doubled.cos_cos, direct.cos_cos, 1e-15);
  EXPECT_NEAR(doubled.cos_sin, direct.cos_sin, 1e-15);
  EXPECT_NEAR(doubled.sin_sin, direct.sin_sin, 1e-15);
}

}  // namespace reference_event_search_test
}  // namespace ib
