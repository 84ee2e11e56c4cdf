// Which Boost.Odeint stepper suits the reference's contact phases (issue 30): real contact onsets of a
// reference run (bench/contact_onsets.h), each integrated to its separation (bench/contact_phase_steppers.h)
// by every stepper over a ladder of tolerances, each contact's duration, rebound velocity, impulse and peak force
// compared with a very tight answer (dopri5 at rtol 1e-13; bulirsch_stoer at 1e-14 beside it says how tight).
//
//   build/bench/contact_integrators [--case NAME]... [--contacts 40] [--stepper NAME]... [--rtol R]... [--repeat 3]
//   bench/contact_integrators_callgrind.sh [same options]   instructions per contact, from callgrind
//   build/bench/contact_integrators --check                 the cheap correctness check ctest runs
//
// atol is rtol / 1000 throughout, the reference's own ratio (1e-9, 1e-12). CPU time per contact is the
// least of --repeat passes; under valgrind each (case, stepper, rtol) block is one callgrind dump instead,
// named "case/stepper/rtol/contacts=N", and no time is taken. Speed is never asserted here.
#include <valgrind/callgrind.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <string>
#include <vector>

#include "bench/contact_onsets.h"

namespace {

using namespace ib::bench;

struct Case {
  std::string name, scenario;
  ib::ContactLaw law;
};

const std::vector<Case> kCases = {
    {"resonance_hertz", "paper/resonance.toml", ib::ContactLaw::hertz},
    {"resonance_spring_dashpot", "paper/resonance.toml", ib::ContactLaw::viscoelastic},
    {"spring_dashpot_k1e08", "stiff/spring_dashpot_k1e08.toml", ib::ContactLaw::viscoelastic},
    {"spring_dashpot_k1e10", "stiff/spring_dashpot_k1e10.toml", ib::ContactLaw::viscoelastic},
    {"hertz_exponent_1", "stiff/hertz_exponent_1.toml", ib::ContactLaw::hertz},
};

// "Equal accuracy": duration and impulse of every contact within this of the tight answer, relative.
constexpr double kEqualAccuracy = 1e-9;

double cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// The largest relative deviations over a case's contacts from the tight answers. The rebound is taken
// relative to the approach speed: a re-contact's rebound can be near zero.
struct Deviation {
  double duration = 0, impulse = 0, rebound = 0, peak_force = 0;
  void add(const ContactOutcome& got, const ContactOutcome& tight, double approach_m_s) {
    duration = std::max(duration, std::abs(got.duration_s - tight.duration_s) / tight.duration_s);
    impulse = std::max(impulse, std::abs(got.impulse_n_s - tight.impulse_n_s) / std::abs(tight.impulse_n_s));
    rebound = std::max(rebound, std::abs(got.rebound_velocity_m_s - tight.rebound_velocity_m_s) / approach_m_s);
    peak_force = std::max(peak_force, std::abs(got.peak_force_n - tight.peak_force_n) / tight.peak_force_n);
  }
  bool equal_accuracy() const { return duration <= kEqualAccuracy && impulse <= kEqualAccuracy; }
};

struct Block {
  ContactStepper stepper;
  double rtol;
  Deviation deviation;
  double steps = 0, rhs = 0, jacobians = 0, cpu_us = 0;  // per contact
};

StepperTolerance tolerance_at(double rtol) { return {rtol, rtol * 1e-3}; }

std::vector<ContactOutcome> integrate_all(const ContactPhaseSystem& system, const CaseContacts& contacts,
                                          ContactStepper stepper, double rtol) {
  std::vector<ContactOutcome> out;
  out.reserve(contacts.onsets.size());
  for (const ContactOnset& onset : contacts.onsets)
    out.push_back(integrate_contact_phase(system, stepper, tolerance_at(rtol), contacts.max_step_s, onset));
  return out;
}

void print_block(const Block& b) {
  std::printf("  %-15s %8.0e  %9.2e %9.2e %9.2e %9.2e  %7.1f %8.1f %6.1f %9.1f%s\n", to_string(b.stepper), b.rtol,
              b.deviation.duration, b.deviation.impulse, b.deviation.rebound, b.deviation.peak_force, b.steps, b.rhs,
              b.jacobians, b.cpu_us, b.deviation.equal_accuracy() ? "" : "  *");
}

void run_case(const Case& c, int max_contacts, const std::vector<ContactStepper>& steppers,
              const std::vector<double>& rtols, int repeat) {
  const CaseContacts contacts =
      contacts_of(std::string(IMPACTBENCH_SOURCE_DIR) + "/scenarios/" + c.scenario, c.law, max_contacts);
  const ContactPhaseSystem system(contacts.model);
  const int n = static_cast<int>(contacts.onsets.size());
  std::printf(
      "\n%s (%s, %s): %d of the run's %d contacts, max step %.3g s; rebuilt onsets: |delta| <= %.2g m, "
      "<= %.2g s from the reference's\n",
      c.name.c_str(), c.scenario.c_str(), ib::to_string(c.law), n, contacts.contacts_in_run, contacts.max_step_s,
      contacts.worst_onset_indentation_m, contacts.largest_onset_shift_s);
  const std::vector<ContactOutcome> tight = integrate_all(system, contacts, ContactStepper::dopri5, 1e-13);
  double mean_duration = 0;
  for (const ContactOutcome& t : tight) mean_duration += t.duration_s / n;
  std::printf("tight answer: dopri5 at 1e-13; mean contact %.3g us; other tight answers differ from it by:\n",
              1e6 * mean_duration);
  for (auto [stepper, rtol] :
       {std::pair{ContactStepper::fehlberg78, 1e-13}, std::pair{ContactStepper::bulirsch_stoer, 1e-14}}) {
    const std::vector<ContactOutcome> other = integrate_all(system, contacts, stepper, rtol);
    Deviation d;
    for (int i = 0; i < n; ++i) d.add(other[i], tight[i], contacts.reference_events[i].approach_velocity_m_s);
    std::printf("  %s %.0e: duration %.1e impulse %.1e rebound %.1e peak %.1e\n", to_string(stepper), rtol, d.duration,
                d.impulse, d.rebound, d.peak_force);
  }
  // The reference's own record of the same contacts (its Dormand-Prince at 1e-9, its root searches in run time).
  Deviation recorded;
  for (int i = 0; i < n; ++i) {
    const ib::ContactEvent& e = contacts.reference_events[i];
    ContactOutcome as_recorded;
    as_recorded.duration_s = e.end_time_s - e.onset_time_s;
    as_recorded.impulse_n_s = e.impulse_n_s;
    as_recorded.rebound_velocity_m_s = e.rebound_velocity_m_s;
    as_recorded.peak_force_n = e.peak_force_n;
    recorded.add(as_recorded, tight[i], e.approach_velocity_m_s);
  }
  std::printf("the reference's own events differ from it by duration %.1e impulse %.1e rebound %.1e peak %.1e\n",
              recorded.duration, recorded.impulse, recorded.rebound, recorded.peak_force);
  std::printf("  %-15s %8s  %9s %9s %9s %9s  %7s %8s %6s %9s\n", "stepper", "rtol", "duration", "impulse", "rebound",
              "peak F", "steps", "rhs", "jac", "CPU us");
  std::printf("  %-15s %8s  %39s  %24s %9s\n", "", "", "(max relative deviation from the tight answer)",
              "(per contact)", "");

  const bool under_valgrind = RUNNING_ON_VALGRIND;
  if (under_valgrind) CALLGRIND_START_INSTRUMENTATION;
  std::vector<Block> blocks;
  for (ContactStepper stepper : steppers) {
    for (double rtol : rtols) {
      Block b{stepper, rtol, {}};
      const long long rhs0 = system.rhs_calls, jac0 = system.jacobian_calls;
      std::vector<ContactOutcome> got;
      double best = 1e300;
      for (int r = 0; r < (under_valgrind ? 1 : repeat); ++r) {
        CALLGRIND_ZERO_STATS;
        CALLGRIND_TOGGLE_COLLECT;
        const double start = cpu_seconds();
        got = integrate_all(system, contacts, stepper, rtol);
        best = std::min(best, cpu_seconds() - start);
        CALLGRIND_TOGGLE_COLLECT;
      }
      if (under_valgrind) {
        char name[160];
        std::snprintf(name, sizeof name, "%s/%s/%.0e/contacts=%d", c.name.c_str(), to_string(stepper), rtol, n);
        CALLGRIND_DUMP_STATS_AT(name);
      }
      const int passes = under_valgrind ? 1 : repeat;
      for (int i = 0; i < n; ++i) {
        b.deviation.add(got[i], tight[i], contacts.reference_events[i].approach_velocity_m_s);
        b.steps += static_cast<double>(got[i].steps) / n;
      }
      b.rhs = static_cast<double>(system.rhs_calls - rhs0) / passes / n;
      b.jacobians = static_cast<double>(system.jacobian_calls - jac0) / passes / n;
      b.cpu_us = under_valgrind ? 0 : 1e6 * best / n;
      print_block(b);
      blocks.push_back(b);
    }
  }
  if (under_valgrind) CALLGRIND_STOP_INSTRUMENTATION;
  std::printf(
      "equal accuracy (duration and impulse within %.0e of the tight answer), at each stepper's loosest such rtol:\n",
      kEqualAccuracy);
  for (ContactStepper stepper : steppers) {
    const Block* loosest = nullptr;
    for (const Block& b : blocks)
      if (b.stepper == stepper && b.deviation.equal_accuracy() && (!loosest || b.rtol > loosest->rtol)) loosest = &b;
    if (loosest)
      print_block(*loosest);
    else
      std::printf("  %-15s never, on this ladder\n", to_string(stepper));
  }
}

// The cheap correctness check (ctest): on the stiffest Hertz case, the bench's dopri5 at the reference's
// tolerance gives the reference's own events back, and every stepper at rtol 1e-12 agrees with the tight answer.
int check(int max_contacts) {
  const Case& c = kCases.back();
  const CaseContacts contacts =
      contacts_of(std::string(IMPACTBENCH_SOURCE_DIR) + "/scenarios/" + c.scenario, c.law, max_contacts);
  const ContactPhaseSystem system(contacts.model);
  const int n = static_cast<int>(contacts.onsets.size());
  int failures = 0;
  auto expect = [&](bool ok, const std::string& what, double value, double limit) {
    std::printf("%s %s: %.2e (limit %.0e)\n", ok ? "ok  " : "FAIL", what.c_str(), value, limit);
    failures += ok ? 0 : 1;
  };
  expect(contacts.worst_onset_indentation_m < 1e-15, "rebuilt onsets on delta = 0 [m]",
         contacts.worst_onset_indentation_m, 1e-15);
  const std::vector<ContactOutcome> as_reference = integrate_all(system, contacts, ContactStepper::dopri5, 1e-9);
  double duration = 0, impulse = 0;
  for (int i = 0; i < n; ++i) {
    const ib::ContactEvent& e = contacts.reference_events[i];
    duration = std::max(duration, std::abs(as_reference[i].duration_s - (e.end_time_s - e.onset_time_s)) /
                                      (e.end_time_s - e.onset_time_s));
    impulse = std::max(impulse, std::abs(as_reference[i].impulse_n_s - e.impulse_n_s) / e.impulse_n_s);
  }
  // The reference locates its onsets and separations on the run's clock (50 bits of ~3 s: 5e-15 s, 5e-10 of a
  // 10.5 us contact) and from states its grid steps rounded: its durations agree to some 1e-9, not to the last bit.
  expect(duration < 1e-8, "dopri5 1e-9 vs the reference's contact durations", duration, 1e-8);
  expect(impulse < 1e-9, "dopri5 1e-9 vs the reference's impulses", impulse, 1e-9);
  const std::vector<ContactOutcome> tight = integrate_all(system, contacts, ContactStepper::dopri5, 1e-13);
  for (ContactStepper s : {ContactStepper::dopri5, ContactStepper::cash_karp54, ContactStepper::fehlberg78,
                           ContactStepper::bulirsch_stoer, ContactStepper::rosenbrock4}) {
    const std::vector<ContactOutcome> got = integrate_all(system, contacts, s, 1e-12);
    Deviation d;
    for (int i = 0; i < n; ++i) d.add(got[i], tight[i], contacts.reference_events[i].approach_velocity_m_s);
    const double worst = std::max({d.duration, d.impulse, d.rebound, d.peak_force});
    expect(worst < 1e-8, std::string(to_string(s)) + " 1e-12 vs the tight answer (worst of four figures)", worst, 1e-8);
  }
  return failures == 0 ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Boost.Odeint steppers on the reference's contact phases, at equal accuracy"};
  std::vector<std::string> case_names, stepper_names;
  std::vector<double> rtols = {1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12};
  int max_contacts = 40, repeat = 3;
  bool run_check = false;
  std::string all_cases;
  for (const Case& c : kCases) all_cases += (all_cases.empty() ? "" : ", ") + c.name;
  app.add_option("--case", case_names, "cases (default all): " + all_cases);
  app.add_option("--stepper", stepper_names,
                 "steppers (default all): dopri5, cash_karp54, fehlberg78, bulirsch_stoer, rosenbrock4");
  app.add_option("--rtol", rtols, "the tolerance ladder (atol = rtol / 1000)");
  app.add_option("--contacts", max_contacts, "at most this many contacts per case, spread over the run")
      ->check(CLI::PositiveNumber);
  app.add_option("--repeat", repeat, "CPU time: the least of this many passes")->check(CLI::PositiveNumber);
  app.add_flag("--check", run_check, "the correctness check only (ctest): exit 1 on failure");
  CLI11_PARSE(app, argc, argv);
  try {
    if (run_check) return check(std::min(max_contacts, 8));
    std::vector<ContactStepper> steppers;
    for (const std::string& s : stepper_names) steppers.push_back(contact_stepper_from_string(s));
    if (steppers.empty())
      steppers = {ContactStepper::dopri5, ContactStepper::cash_karp54, ContactStepper::fehlberg78,
                  ContactStepper::bulirsch_stoer, ContactStepper::rosenbrock4};
    for (const Case& c : kCases)
      if (case_names.empty() || std::find(case_names.begin(), case_names.end(), c.name) != case_names.end())
        run_case(c, max_contacts, steppers, rtols, repeat);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "contact_integrators: %s\n", error.what());
    return 1;
  }
  return 0;
}
