// Agreement of every engine with the reference (issue 8): per engine, published case and contact law,
// on the matched contact path (the engine's own mapping of the scenario's law), three window
// statistics against the reference:
//   (1) impacts per motor cycle              |run - ref|            [impacts per cycle]
//   (2) frame 1's sensor peak acceleration   |run / ref - 1|        [-] (the 2048 Hz accelerometer of rig.md 5)
//   (3) the mean contact duration            |run / ref - 1|        [-]
// each against two references, both run through the harness's own run_job (metrics, comparisons):
//   chain: the reference on the engine's own K-link chain (chain_reference_options(K), K from
//          Simulator::chain_links): the same physics, so the error is the engine's contact handling and
//          time stepping alone. The engines' contacts cannot pull, so for the spring-dashpot the chain
//          reference runs the law clipped at zero force (clip_tension = true), which is what all three
//          matched paths realise (adapters/*/README.md); the published law's tensile tail would
//          otherwise make every engine's contacts 4 % (c/k = 24 us) short by construction.
//   beam:  the continuous-beam reference of the published scenario (default options): the whole error
//          a user sees, chain discretisation included. The K = 8 chain itself is a few percent off the
//          beam (first frequency 0.22 %, but the tip's effective mass and the higher modes more: frame 1's
//          sensor peak on the chain is 3 % (pre-resonance) to 10 % (resonance) below the beam's), so these
//          tolerances are the chain's plus that model gap, stated separately and looser.
// The tolerances and time steps stand in ONE table, kAgreement below, each row with why. A metric that
// does not exist for a row (no excitation: no impacts per cycle; Newton: instantaneous impacts, no
// contact duration; no impacts in the reference: no contact duration) is skipped by name with the reason.
//
// ctest runs one entry per engine x case x law (tests/CMakeLists.txt, label "agreement"), each running
// this binary's three metric tests of that row in one process, so the engine runs once per entry.
// Every comparison prints one line "agreement: ..." with the measured errors (the README table is
// made from them).
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "reference_fixtures.h"
#include "simulators/catalog.h"
#include "reference/reference_simulator.h"
#include "harness/run_job.h"
#include "model/simulator.h"

namespace ib {
namespace {

constexpr double kNotApplicable = std::numeric_limits<double>::quiet_NaN();

// How long each case runs in the test, and the scoring window (its last window_s). The reference's
// window statistics were measured at these lengths against the published 100 s / 14 s (K = 8 chain
// and beam, every law; tests print them again): see each row.
struct RunLength {
  const char* scenario;
  double duration_s;  // simulated time [s]
  double window_s;    // scoring window: the last window_s of the run [s]
  const char* why;
};
constexpr RunLength kRunLengths[] = {
    {"resonance", 20, 10,
     "settles within 10 s into one impact every second motor cycle; chain reference, [10, 20] s against [86, 100] s "
     "of 100 s: 0.4892 / 0.4933 impacts per cycle, frame 1 sensor peak -0.0 % (spring-dashpot), +0.1 % (Hertz), "
     "0.0 % (Newton), mean contact duration 0.0 %"},
    {"pre_resonance", 20, 10,
     "steady by 10 s: 0.3332 / 0.3354 impacts per cycle, frame 1 sensor peak within 0.2 %, contact duration within "
     "1e-6 of the 100 s run's (chain reference, every law)"},
    {"post_resonance", 50, 14,
     "no impacts; frame 1's peak is the forced response plus the start-up transient, which decays with "
     "zeta omega_1 = 0.13 1/s: at 50 s the peak is 0.6 % above the 100 s run's (0.1252 g vs 0.1245 g), at 30 s 8 %"},
    {"free_vibration", 4, 4,
     "the whole run is the window; every reference impact comes before 2.6 s (beam and chain, every law), so 4 s "
     "holds all of them and the metrics are those of the published 14 s"},
};

struct Tolerances {
  double impacts_per_cycle;   // largest |run - reference| [impacts per motor cycle]; kNotApplicable: no such metric
  double sensor_peak;         // largest |run / reference - 1| of frame 1's sensor peak [-]
  double contact_duration;    // largest |run / reference - 1| of the mean contact duration [-]; kNotApplicable: none
};

struct AgreementRow {
  const char* engine;         // simulator name, as the registry knows it
  const char* scenario;       // scenarios/paper/<scenario>.toml
  ContactLaw law;
  double time_step_s;         // the engine's fixed step [s]
  const char* contact_path;   // option contact=
  Tolerances chain;           // against the reference on the engine's own K-link chain
  Tolerances beam;            // against the continuous-beam reference (chain tolerance + the chain's model gap)
  const char* why;            // why these tolerances at this step
};

constexpr ContactLaw kHertz = ContactLaw::hertz, kSpringDashpot = ContactLaw::viscoelastic, kNewton = ContactLaw::newton;
constexpr double na = kNotApplicable;

// Tolerances from the physics, then checked against the measured errors (README "Agreement with the
// reference" has both side by side):
// - impacts per cycle, forced cases: 0.03 per cycle = 2 impacts in the 10 s window (66 to 70 motor
//   cycles): the regime (one impact every second cycle at resonance, one in three before it) must be the
//   reference's; a window edge can cut the pattern one impact differently on either side. The K = 8 chain
//   and the beam differ by one impact at resonance with Hertz, so the beam gets the same 0.03.
//   Post-resonance: 0 (no impacts in the reference; any impact is a different regime).
// - frame 1's sensor peak: 5 % where the step resolves the contact: the peak is the largest velocity change
//   over a 0.49 ms sensor window, about (1 + e) times the approach speed, so a restitution error of up to
//   7 % (backward-Euler contacts at 1e-5 s) moves it by up to 4 %; the maximum over 20 to 35 impacts
//   averages the sensor-window phase. Beam: plus the chain's own gap to the beam at these windows
//   (resonance 7 to 9 %, pre-resonance 2 to 4 %, free vibration 1 to 2 %, post-resonance 1.3 %).
// - mean contact duration: 5 %: an engine's episode is a whole number of steps (+-h/2 per impact, averaged
//   over >= 8 impacts: <= 2 % at tau/h = 6, less at finer steps) plus the contact integration error (about
//   1 % where the contact spans >= 12 steps). Beam: Hertz plus 2 % (the chain's tip effective mass moves the
//   contact time by 1 to 1.5 %); spring-dashpot plus 5 %, because the beam reference runs the published law,
//   whose tensile tail makes its contacts 4 % (c/k = 24 us) longer than any engine's compressive contact.
constexpr const char* kHertzStep =
    "Hertz is a force from the tip states (no engine has a nonlinear contact), explicit: its 0.25 ms contact "
    "stiffens to 18000 rad/s and gains energy at 1e-4 s (e > 1), so 1e-5 s (25 steps per contact)";
constexpr const char* kOdeHertzStep =
    "Hertz as a force from the tip states; ODE's implicit hinge springs keep 2e-5 s (12 steps per contact) within "
    "1.3 % of the chain reference, so the smaller 1e-5 s is not needed in the forced cases";
constexpr const char* kMujocoSpringDashpot =
    "MuJoCo's own contact from solref/solimp at the default 1e-4 s (6 steps per 0.6 ms contact): restitution "
    "within 1 % of the clipped law, so the default step meets 5 %";
constexpr const char* kImplicitSpringDashpot =
    "the soft contact is a backward-Euler spring-dashpot, losing about pi omega h / 2 of the restitution "
    "(omega = 5200 rad/s): at the default step (ODE 1e-4 s: -40 %, Bullet 5e-5 s: -30 %) the peak is 9 % low "
    "before resonance and ODE changes regime, so 1e-5 s (-7 %; ODE 2e-5 s gives -4.6 %, Bullet 5e-5 s -9.0 % "
    "pre-resonance), where 5 % holds";
constexpr const char* kMujocoNewton =
    "MuJoCo has no restitution: a no-tension spring-dashpot lasting 4 steps (0.4 ms at the default 1e-4 s) "
    "that rebounds with e; an impulse spread over most of a 0.49 ms sensor window reads 2 to 4 % low, inside 5 %";
constexpr const char* kOdeNewton =
    "dContactBounce is exact per impact but found at the start of the step that begins overlapping, up to one "
    "step late: at the default 1e-4 s the peak is 3.7 % / 7.2 % low (resonance / pre-resonance), at 2e-5 s "
    "within 2 %, so 2e-5 s";
constexpr const char* kBulletNewton =
    "restitution with threshold 0 and no push-out: e within 0.2 % at the default 5e-5 s, exact impulse";
constexpr const char* kPostResonance =
    "no impacts in the reference (tip amplitude 0.46 mm below the 1 mm gap): the forced response of the chain "
    "alone at the engine's default step; peak within 2 % (the chain's frequencies are exact to 1e-5; ODE's implicit "
    "hinge springs add omega h / 2 to zeta, which shortens the start-up transient: measured -0.6 %)";
constexpr const char* kFreeVibration =
    "free vibration at 1e-5 s for every law (4 s runs are cheap); the largest sensor reading is the first "
    "impact's (t = 0.048 s, before any drift; chain reference: Hertz 11.69 g, Newton 10.64 g both from it), so 5 %";
constexpr const char* kFreeVibrationSpringDashpot =
    "finding: frame 1's sensor peak in free vibration is a phase-sampled statistic of a few impacts. With the "
    "0.6 ms spring-dashpot contact (longer than the 0.49 ms sensor window) the peak comes from a later impact "
    "(chain reference: the first impact alone reads 7.33 g, the whole run 8.11 g), and where it falls on the 2048 Hz grid decides it: a 0.4 % change of the sensor rate moves the reference's "
    "own value by -30 % to +19 %. Engines whose later impacts drift by tens of us land anywhere in that range, "
    "and a smaller step does not help (ODE -6.6 % at 1e-5 s, -10.3 % at 2e-6 s; Bullet +4.0 % at 1e-5 s, -9.3 % "
    "at 5e-6 s): the bound 12 % is the measured spread plus margin, not a convergence check";

// THE table: engine, case, law, step [s], contact path, tolerances {impacts per cycle, sensor peak, contact
// duration} against the chain reference, then against the beam reference, and why.
constexpr AgreementRow kAgreement[] = {
    // ---------------------------------------------------------------- MuJoCo 2.2.2, semi-implicit Euler
    {"mujoco", "resonance", kHertz, 1e-5, "matched", {0.03, 0.05, 0.05}, {0.03, 0.15, 0.07}, kHertzStep},
    {"mujoco", "resonance", kSpringDashpot, 1e-4, "matched", {0.03, 0.05, 0.05}, {0.03, 0.15, 0.10}, kMujocoSpringDashpot},
    {"mujoco", "resonance", kNewton, 1e-4, "matched", {0.03, 0.05, na}, {0.03, 0.15, na}, kMujocoNewton},
    {"mujoco", "pre_resonance", kHertz, 1e-5, "matched", {0.03, 0.05, 0.05}, {0.03, 0.10, 0.07}, kHertzStep},
    {"mujoco", "pre_resonance", kSpringDashpot, 1e-4, "matched", {0.03, 0.05, 0.05}, {0.03, 0.10, 0.10}, kMujocoSpringDashpot},
    {"mujoco", "pre_resonance", kNewton, 1e-4, "matched", {0.03, 0.05, na}, {0.03, 0.10, na}, kMujocoNewton},
    {"mujoco", "post_resonance", kHertz, 1e-4, "matched", {0, 0.02, na}, {0, 0.04, na}, kPostResonance},
    {"mujoco", "post_resonance", kSpringDashpot, 1e-4, "matched", {0, 0.02, na}, {0, 0.04, na}, kPostResonance},
    {"mujoco", "post_resonance", kNewton, 1e-4, "matched", {0, 0.02, na}, {0, 0.04, na}, kPostResonance},
    {"mujoco", "free_vibration", kHertz, 1e-5, "matched", {na, 0.05, 0.05}, {na, 0.10, 0.07}, kFreeVibration},
    {"mujoco", "free_vibration", kSpringDashpot, 1e-5, "matched", {na, 0.12, 0.05}, {na, 0.15, 0.10}, kFreeVibrationSpringDashpot},
    {"mujoco", "free_vibration", kNewton, 1e-5, "matched", {na, 0.05, na}, {na, 0.10, na}, kFreeVibration},
    // ---------------------------------------------------------------- ODE 0.16.2, dWorldStep, implicit hinge springs
    {"ode", "resonance", kHertz, 2e-5, "matched", {0.03, 0.05, 0.05}, {0.03, 0.15, 0.07}, kOdeHertzStep},
    {"ode", "resonance", kSpringDashpot, 1e-5, "matched", {0.03, 0.05, 0.05}, {0.03, 0.15, 0.10}, kImplicitSpringDashpot},
    {"ode", "resonance", kNewton, 2e-5, "matched", {0.03, 0.05, na}, {0.03, 0.15, na}, kOdeNewton},
    {"ode", "pre_resonance", kHertz, 2e-5, "matched", {0.03, 0.05, 0.05}, {0.03, 0.10, 0.07}, kOdeHertzStep},
    {"ode", "pre_resonance", kSpringDashpot, 1e-5, "matched", {0.03, 0.05, 0.05}, {0.03, 0.10, 0.10}, kImplicitSpringDashpot},
    {"ode", "pre_resonance", kNewton, 2e-5, "matched", {0.03, 0.05, na}, {0.03, 0.10, na}, kOdeNewton},
    {"ode", "post_resonance", kHertz, 1e-4, "matched", {0, 0.02, na}, {0, 0.04, na}, kPostResonance},
    {"ode", "post_resonance", kSpringDashpot, 1e-4, "matched", {0, 0.02, na}, {0, 0.04, na}, kPostResonance},
    {"ode", "post_resonance", kNewton, 1e-4, "matched", {0, 0.02, na}, {0, 0.04, na}, kPostResonance},
    {"ode", "free_vibration", kHertz, 1e-5, "matched", {na, 0.05, 0.05}, {na, 0.10, 0.07}, kFreeVibration},
    {"ode", "free_vibration", kSpringDashpot, 1e-5, "matched", {na, 0.12, 0.05}, {na, 0.15, 0.10}, kFreeVibrationSpringDashpot},
    {"ode", "free_vibration", kNewton, 1e-5, "matched", {na, 0.05, na}, {na, 0.10, na}, kFreeVibration},
    // ---------------------------------------------------------------- Bullet 3.24 (double), btMultiBody
    {"bullet", "resonance", kHertz, 1e-5, "matched", {0.03, 0.05, 0.05}, {0.03, 0.15, 0.07}, kHertzStep},
    {"bullet", "resonance", kSpringDashpot, 1e-5, "matched", {0.03, 0.05, 0.05}, {0.03, 0.15, 0.10}, kImplicitSpringDashpot},
    {"bullet", "resonance", kNewton, 5e-5, "matched", {0.03, 0.05, na}, {0.03, 0.15, na}, kBulletNewton},
    {"bullet", "pre_resonance", kHertz, 1e-5, "matched", {0.03, 0.05, 0.05}, {0.03, 0.10, 0.07}, kHertzStep},
    {"bullet", "pre_resonance", kSpringDashpot, 1e-5, "matched", {0.03, 0.05, 0.05}, {0.03, 0.10, 0.10}, kImplicitSpringDashpot},
    {"bullet", "pre_resonance", kNewton, 5e-5, "matched", {0.03, 0.05, na}, {0.03, 0.10, na}, kBulletNewton},
    {"bullet", "post_resonance", kHertz, 5e-5, "matched", {0, 0.02, na}, {0, 0.04, na}, kPostResonance},
    {"bullet", "post_resonance", kSpringDashpot, 5e-5, "matched", {0, 0.02, na}, {0, 0.04, na}, kPostResonance},
    {"bullet", "post_resonance", kNewton, 5e-5, "matched", {0, 0.02, na}, {0, 0.04, na}, kPostResonance},
    {"bullet", "free_vibration", kHertz, 1e-5, "matched", {na, 0.05, 0.05}, {na, 0.10, 0.07}, kFreeVibration},
    {"bullet", "free_vibration", kSpringDashpot, 1e-5, "matched", {na, 0.12, 0.05}, {na, 0.15, 0.10}, kFreeVibrationSpringDashpot},
    {"bullet", "free_vibration", kNewton, 1e-5, "matched", {na, 0.05, na}, {na, 0.10, na}, kFreeVibration},
};

constexpr const char* kCases[] = {"resonance", "pre_resonance", "post_resonance", "free_vibration"};
constexpr ContactLaw kLaws[] = {kHertz, kSpringDashpot, kNewton};

const RunLength& run_length(const std::string& scenario) {
  for (const RunLength& r : kRunLengths)
    if (scenario == r.scenario) return r;
  throw std::invalid_argument("no run length for scenario '" + scenario + "'");
}

// "pre_resonance" -> "PreResonance"
std::string camel(const std::string& snake) {
  std::string out;
  bool upper = true;
  for (char c : snake) {
    if (c == '_') { upper = true; continue; }
    out += upper ? static_cast<char>(std::toupper(static_cast<unsigned char>(c))) : c;
    upper = false;
  }
  return out;
}

std::string row_name(const AgreementRow& row) {
  return camel(row.engine) + "_" + camel(row.scenario) + "_" + camel(to_string(row.law));
}

bool in_build(const std::string& engine) {
  const std::vector<std::string> names = simulator_names();
  return std::find(names.begin(), names.end(), engine) != names.end();
}

std::vector<AgreementRow> rows_in_this_build() {
  std::vector<AgreementRow> rows;
  for (const AgreementRow& row : kAgreement)
    if (in_build(row.engine)) rows.push_back(row);
  return rows;
}

// The scenario as the test runs it: the published file, shortened (kRunLengths).
Scenario test_scenario(const std::string& name) {
  Scenario s = testing::paper_scenario(name);
  const RunLength& length = run_length(name);
  s.duration_s = length.duration_s;
  s.scoring_window_s = length.window_s;
  return s;
}

// ---------------------------------------------------------------------------------------------- runs

// A reference run, computed once per (case, law, mode set) in this process.
const ReferenceData& reference_run(const std::string& scenario_name, ContactLaw law, std::optional<int> chain_links) {
  static std::map<std::string, std::unique_ptr<ReferenceData>> cache;
  const std::string key = scenario_name + "/" + to_string(law) + "/" +
                          (chain_links ? "chain K=" + std::to_string(*chain_links) : std::string("beam"));
  auto& slot = cache[key];
  if (!slot) {
    Scenario s = test_scenario(scenario_name);
    JobSpec job;
    job.scenario_path = s.source_path;
    job.engine = "reference";
    job.settings.law = law;
    if (chain_links) {
      job.settings.options = chain_reference_options(*chain_links);
      // the engines' contacts only push: on the chain, the reference runs the law they realise
      if (s.contact.viscoelastic) s.contact.viscoelastic->clip_tension = true;
    }
    slot = std::make_unique<ReferenceData>();
    const RunRecord record = run_job(s, job, Measurement{}, nullptr, nullptr, "", slot.get(), make_simulator);
    if (record.verdict == Verdict::unstable || record.verdict == Verdict::failed)
      throw std::runtime_error("reference " + key + ": " + to_string(record.verdict) + ": " + record.reason);
  }
  return *slot;
}

struct Comparison {
  RunRecord engine;                // the engine's run, with errors against both references
  Metrics chain_reference, beam_reference;
  int chain_links = 0;
};

// The engine's run of a row against both references, computed once per row in this process.
const Comparison& compare(const AgreementRow& row) {
  static std::map<std::string, std::unique_ptr<Comparison>> cache;
  auto& slot = cache[row_name(row)];
  if (!slot) {
    const Scenario s = test_scenario(row.scenario);
    JobSpec job;
    job.scenario_path = s.source_path;
    job.engine = row.engine;
    job.settings.law = row.law;
    job.settings.time_step_s = row.time_step_s;
    job.settings.options = {{"contact", row.contact_path}};
    const auto simulator = make_simulator(row.engine);
    if (!simulator) throw std::runtime_error(std::string("engine '") + row.engine + "' is not in this build");
    const std::optional<int> links = simulator->chain_links(s, job.settings);
    if (!links) throw std::runtime_error(std::string(row.engine) + " reports no chain");
    const ReferenceData& chain = reference_run(row.scenario, row.law, *links);
    const ReferenceData& beam = reference_run(row.scenario, row.law, std::nullopt);
    slot = std::make_unique<Comparison>();
    slot->engine = run_job(s, job, Measurement{}, &beam, &chain, "", nullptr, make_simulator);
    slot->chain_reference = chain.metrics;
    slot->beam_reference = beam.metrics;
    slot->chain_links = *links;
  }
  return *slot;
}

// ----------------------------------------------------------------------------------------- checking

enum class Metric { impacts_per_cycle, sensor_peak, contact_duration };

const char* metric_name(Metric m) {
  switch (m) {
    case Metric::impacts_per_cycle: return "impacts_per_cycle";
    case Metric::sensor_peak: return "frame1_sensor_peak";
    case Metric::contact_duration: return "contact_duration_mean";
  }
  return "";
}

double tolerance(const Tolerances& t, Metric m) {
  switch (m) {
    case Metric::impacts_per_cycle: return t.impacts_per_cycle;
    case Metric::sensor_peak: return t.sensor_peak;
    case Metric::contact_duration: return t.contact_duration;
  }
  return kNotApplicable;
}

// The harness's error of a metric (compare_metrics): a difference for impacts per cycle, relative otherwise.
double error(const MetricErrors& e, Metric m) {
  switch (m) {
    case Metric::impacts_per_cycle: return e.impacts_per_cycle_difference;
    case Metric::sensor_peak: return e.sensor_peak_relative_error[0];
    case Metric::contact_duration: return e.contact_duration_relative_error;
  }
  return kNotApplicable;
}

double value(const Metrics& m, Metric metric) {
  switch (metric) {
    case Metric::impacts_per_cycle: return m.impacts_per_cycle;
    case Metric::sensor_peak: return m.frames[0].sensor_peak_acceleration_g;
    case Metric::contact_duration: return m.contact_duration_mean_s;
  }
  return kNotApplicable;
}

// Why a metric does not exist for a row, from the physics of the case and law alone; empty when it does.
std::string why_not_applicable(const AgreementRow& row, Metric m) {
  const Scenario s = testing::paper_scenario(row.scenario);
  if (m == Metric::impacts_per_cycle && !s.motor)
    return std::string(row.scenario) + " has no motor: no excitation cycles, so no impacts per cycle";
  if (m == Metric::contact_duration && row.law == ContactLaw::newton)
    return "Newton's law has instantaneous impacts: the reference has no contact duration to compare with";
  return {};
}

class EngineAgreement : public ::testing::TestWithParam<AgreementRow> {
 protected:
  void check(Metric m) {
    const AgreementRow& row = GetParam();
    const std::string skip = why_not_applicable(row, m);
    if (!skip.empty()) {
      ASSERT_TRUE(std::isnan(tolerance(row.chain, m)) && std::isnan(tolerance(row.beam, m)))
          << "kAgreement gives a tolerance for a metric that does not exist: " << skip;
      GTEST_SKIP() << metric_name(m) << ": " << skip;
    }
    const Comparison& c = compare(row);
    const RunRecord& run = c.engine;
    ASSERT_TRUE(run.verdict == Verdict::ok || run.verdict == Verdict::inaccurate)
        << row.engine << " at h = " << row.time_step_s << " s: " << to_string(run.verdict) << ": " << run.reason;
    ASSERT_TRUE(run.metrics && run.errors_vs_chain_reference && run.errors_vs_reference);
    if (m == Metric::contact_duration && c.chain_reference.impacts == 0) {
      ASSERT_TRUE(std::isnan(tolerance(row.chain, m)))
          << "kAgreement gives a contact duration tolerance, but the reference has no impacts in the window";
      GTEST_SKIP() << metric_name(m) << ": the reference on the chain has no impacts in the window (" << row.scenario
                   << ": the tips never close the gap), so there is no contact duration to compare with; "
                   << "the engine's " << run.metrics->impacts << " impacts are checked by impacts_per_cycle";
    }
    const double chain_tolerance = tolerance(row.chain, m), beam_tolerance = tolerance(row.beam, m);
    ASSERT_FALSE(std::isnan(chain_tolerance) || std::isnan(beam_tolerance))
        << "kAgreement has no tolerance for " << metric_name(m) << ", which exists for this row";
    const double chain_error = error(*run.errors_vs_chain_reference, m), beam_error = error(*run.errors_vs_reference, m);
    // one line per comparison, the source of the README's table
    std::printf(
        "agreement: engine=%s case=%s law=%s step_s=%g path=%s K=%d metric=%s engine_value=%.6g "
        "chain_reference=%.6g chain_error=%+.4f chain_tolerance=%.4f beam_reference=%.6g beam_error=%+.4f "
        "beam_tolerance=%.4f impacts=%d/%d/%d verdict=%s\n",
        row.engine, row.scenario, to_string(row.law), row.time_step_s, row.contact_path, c.chain_links,
        metric_name(m), value(*run.metrics, m), value(c.chain_reference, m), chain_error, chain_tolerance,
        value(c.beam_reference, m), beam_error, beam_tolerance, run.metrics->impacts, c.chain_reference.impacts,
        c.beam_reference.impacts, to_string(run.verdict));
    RecordProperty(std::string(metric_name(m)) + "_chain_error", std::to_string(chain_error));
    RecordProperty(std::string(metric_name(m)) + "_beam_error", std::to_string(beam_error));
    // NaN (a metric one side lacks, e.g. impacts in the engine but none in the reference) fails too
    EXPECT_TRUE(std::abs(chain_error) <= chain_tolerance)
        << metric_name(m) << " against the reference on the K = " << c.chain_links << " chain: error " << chain_error
        << ", tolerance " << chain_tolerance << " (" << row.why << ")";
    EXPECT_TRUE(std::abs(beam_error) <= beam_tolerance)
        << metric_name(m) << " against the beam reference: error " << beam_error << ", tolerance " << beam_tolerance
        << " (" << row.why << ")";
  }
};

TEST_P(EngineAgreement, ImpactsPerCycle) { check(Metric::impacts_per_cycle); }
TEST_P(EngineAgreement, SensorPeak) { check(Metric::sensor_peak); }
TEST_P(EngineAgreement, ContactDuration) { check(Metric::contact_duration); }

INSTANTIATE_TEST_SUITE_P(Agreement, EngineAgreement, ::testing::ValuesIn(rows_in_this_build()),
                         [](const ::testing::TestParamInfo<AgreementRow>& info) { return row_name(info.param); });

// The table holds exactly one row per engine of this build, case and law, each runnable.
TEST(AgreementTable, OneRowPerEngineCaseAndLaw) {
  for (const std::string& engine : simulator_names()) {
    if (engine == "reference") continue;
    for (const char* scenario : kCases)
      for (ContactLaw law : kLaws) {
        const auto n = std::count_if(std::begin(kAgreement), std::end(kAgreement), [&](const AgreementRow& r) {
          return engine == r.engine && std::string(scenario) == r.scenario && law == r.law;
        });
        EXPECT_EQ(n, 1) << engine << " " << scenario << " " << to_string(law);
      }
  }
  for (const AgreementRow& row : kAgreement) {
    EXPECT_GT(row.time_step_s, 0) << row_name(row);
    EXPECT_NO_THROW(run_length(row.scenario)) << row_name(row);
    EXPECT_STRNE(row.why, "") << row_name(row);
  }
}

}  // namespace
}  // namespace ib
