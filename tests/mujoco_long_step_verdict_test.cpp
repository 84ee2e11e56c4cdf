// A time step too long for the contact (or for the chain's fastest hinge mode) ends in a verdict that
// says so, unstable or inaccurate with a reason, never in a crash: the free-vibration impact judged
// by the harness (run_job) against the reference on the same chain. A small step passes the same
// judgement, so the verdict tells the steps apart. (The default 1e-4 s is not the control: the energy
// check sees the contact potential k delta^2 / 2 of the first step's penetration before MuJoCo's force
// has acted, up to k (v h)^2 / 2, 1 % of this rig's energy; see adapters/mujoco/README.md.)
#include <gtest/gtest.h>

#include <ostream>
#include <string>
#include <vector>

#include "adapters/common/rig.h"
#include "harness/jobs/run_job.h"
#include "reference/reference_simulator.h"
#include "reference_fixtures.h"
#include "simulators/catalog.h"

namespace ib {
namespace mujoco_long_step_verdict_test {

struct Case {
  ContactLaw law;
  double time_step_s;
  std::vector<Verdict> allowed;
  std::string why;
};

void PrintTo(const Case& c, std::ostream* out) { *out << to_string(c.law) << ", h = " << c.time_step_s << " s"; }

class MujocoLongStep : public ::testing::TestWithParam<Case> {};

TEST_P(MujocoLongStep, VerdictSaysSo) {
  const Case& c = GetParam();
  Scenario s = testing::paper_scenario("free_vibration");
  s.duration_s = 0.3;  // the first impact and the rebound after it
  s.scoring_window_s = s.duration_s;
  const Measurement measurement;
  RunSettings settings;
  settings.law = c.law;
  JobSpec reference_job;
  reference_job.engine = "reference";
  reference_job.settings = settings;
  reference_job.settings.options = chain_reference_options(default_links(s));
  ReferenceData chain_reference;
  run_job(s, reference_job, measurement, nullptr, nullptr, "", &chain_reference, make_simulator);

  JobSpec job;
  job.engine = "mujoco";
  job.settings = settings;
  job.settings.time_step_s = c.time_step_s;
  const RunRecord record = run_job(s, job, measurement, nullptr, &chain_reference, "", nullptr, make_simulator);
  std::printf("%s, h = %g s: %s (%s)\n", to_string(c.law), c.time_step_s, to_string(record.verdict),
              record.reason.c_str());
  bool allowed = false;
  for (Verdict v : c.allowed) allowed = allowed || record.verdict == v;
  EXPECT_TRUE(allowed) << c.why << "; got " << to_string(record.verdict) << ": " << record.reason;
  if (record.verdict != Verdict::ok) {
    EXPECT_FALSE(record.reason.empty());
  }
}

INSTANTIATE_TEST_SUITE_P(
    Steps, MujocoLongStep,
    ::testing::Values(
        // 60 steps per spring-dashpot contact: resolved (the control)
        Case{ContactLaw::viscoelastic, 1e-5, {Verdict::ok}, "a small step resolves the spring-dashpot contact"},
        // 2 steps per contact: the sensor peak is off by about 15 %
        Case{ContactLaw::viscoelastic, 3e-4, {Verdict::inaccurate, Verdict::unstable}, "2 steps per contact"},
        // beyond 2 / omega of the chain's fastest modes (12 400 rad/s, explicit hinge springs)
        Case{ContactLaw::viscoelastic, 1e-3, {Verdict::unstable}, "the hinge springs diverge"},
        // the Hertz contact lasts 0.23 ms: 2 steps of the default 1e-4 s, and the rebound gains energy
        Case{ContactLaw::hertz, 1e-4, {Verdict::inaccurate, Verdict::unstable}, "2 steps per Hertz contact"}),
    [](const auto& info) {
      std::string name =
          std::string(to_string(info.param.law)) + "_h" + std::to_string(int(info.param.time_step_s * 1e6)) + "us";
      return name;
    });

}  // namespace mujoco_long_step_verdict_test
}  // namespace ib
