// A suite's plan is plain data (plan_suites), made without running anything or writing a file: its job matrix,
// the references each run waits for, the native run that answers for every law, a step search that shares a
// suite's reference, and what cannot run.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "harness/suite/suite.h"
#include "mirror_simulator.h"
#include "simulators/catalog.h"
#include "suite_test_support.h"

namespace ib {
namespace suite_plan_test {

namespace fs = std::filesystem;

std::unique_ptr<Simulator> test_factory(const std::string& name) {
  if (name == "mirror") return std::make_unique<test::Mirror>();
  return make_simulator(name);
}

class SuitePlan : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = test::fresh_test_folder("impactbench_plan_");
    test::write_short_free_vibration(root_ / "scenarios");
    settings_.inputs = {(root_ / "scenarios").string()};
    settings_.engines = {"reference", "mirror"};
    settings_.laws = {ContactLaw::hertz, ContactLaw::newton};
    settings_.time_steps_s = {1e-4, 5e-5};
    settings_.contact_paths = {"matched", "native"};
    settings_.out = (root_ / "out").string();
    settings_.simulators = simulator_catalog();
    settings_.simulators.make = test_factory;
  }
  void TearDown() override { fs::remove_all(root_); }

  static std::map<std::string, PlannedUnit> by_id(const std::vector<PlannedUnit>& units) {
    std::map<std::string, PlannedUnit> map;
    for (const PlannedUnit& u : units) EXPECT_TRUE(map.emplace(u.id, u).second) << "planned twice: " << u.id;
    return map;
  }
  static int count(const std::vector<PlannedUnit>& units, PlannedUnit::Kind kind) {
    return static_cast<int>(
        std::count_if(units.begin(), units.end(), [kind](const PlannedUnit& u) { return u.kind == kind; }));
  }

  fs::path root_;
  SuiteSettings settings_;
};

TEST_F(SuitePlan, TheMatrixAndWhatEachRunWaitsFor) {
  const std::vector<PlannedUnit> units = plan_suites({settings_});
  EXPECT_FALSE(fs::exists(settings_.out)) << "planning writes nothing";
  // laws x steps x paths engine runs, a beam reference per law, a chain reference (the engine's 4 links) per law
  EXPECT_EQ(count(units, PlannedUnit::Kind::engine), 2 * 2 * 2);
  EXPECT_EQ(count(units, PlannedUnit::Kind::beam_reference), 2);
  EXPECT_EQ(count(units, PlannedUnit::Kind::chain_reference), 2);
  const auto plan = by_id(units);
  for (const PlannedUnit& u : units) {
    for (const std::string& before : u.after) {
      ASSERT_TRUE(plan.count(before)) << u.id << " waits for " << before << ", which is not planned";
      EXPECT_NE(plan.at(before).kind, PlannedUnit::Kind::engine) << u.id << " waits for a reference only";
    }
    if (u.kind == PlannedUnit::Kind::engine) {
      ASSERT_EQ(u.after.size(), 2u) << u.id << ": its beam and its chain reference";
      EXPECT_EQ(plan.at(u.after[0]).kind, PlannedUnit::Kind::beam_reference);
      EXPECT_EQ(plan.at(u.after[1]).kind, PlannedUnit::Kind::chain_reference);
      // each run is compared with the references of its own law
      const std::string law = u.id.find("/hertz/") != std::string::npos ? "/hertz" : "/newton";
      for (const std::string& before : u.after)
        EXPECT_NE(before.find(law), std::string::npos) << u.id << " -> " << before;
    }
    if (u.kind == PlannedUnit::Kind::chain_reference) {
      ASSERT_EQ(u.after.size(), 1u) << u.id << " is compared with the beam";
      EXPECT_EQ(plan.at(u.after[0]).kind, PlannedUnit::Kind::beam_reference);
    }
  }
}

TEST_F(SuitePlan, OneNativeRunAnswersForEveryLaw) {
  const auto plan = by_id(plan_suites({settings_}));
  int scored = 0;
  for (const auto& [id, u] : plan) {
    if (u.same_run_as.empty()) continue;
    ++scored;
    EXPECT_NE(id.find("contact=native"), std::string::npos) << id;
    EXPECT_NE(id.find("/newton/"), std::string::npos) << id << " is the second law's";
    ASSERT_TRUE(plan.count(u.same_run_as)) << u.same_run_as;
    EXPECT_NE(u.same_run_as.find("/hertz/"), std::string::npos) << "the first law's native run: " << u.same_run_as;
  }
  EXPECT_EQ(scored, 2) << "the second law's native runs at both steps";
}

TEST_F(SuitePlan, AStepSearchSharesTheSuitesReferenceAndWaitsForIt) {
  SuiteSettings search = settings_;
  search.laws = {ContactLaw::hertz};
  search.contact_paths = {"matched"};
  search.time_steps_s.clear();
  search.step_search = StepSearchSettings{};
  search.step_search->min_step_s = 1e-4;
  const std::vector<PlannedUnit> units = plan_suites({settings_, search});
  const auto plan = by_id(units);  // a shared reference is planned once
  ASSERT_EQ(count(units, PlannedUnit::Kind::step_search), 1);
  EXPECT_EQ(count(units, PlannedUnit::Kind::beam_reference), 2);
  for (const PlannedUnit& u : units)
    if (u.kind == PlannedUnit::Kind::step_search) {
      ASSERT_FALSE(u.after.empty());
      for (const std::string& before : u.after) EXPECT_TRUE(plan.count(before)) << before;
    }
}

TEST_F(SuitePlan, WhatCannotRunIsPlannedAsSuch) {
  std::ofstream(root_ / "scenarios" / "broken.toml") << "[scenario\nname = \n";
  settings_.laws = {ContactLaw::hertz};
  const std::vector<PlannedUnit> units = plan_suites({settings_});
  ASSERT_EQ(count(units, PlannedUnit::Kind::unrunnable), 1);
  EXPECT_EQ(units.front().id, "broken/unreadable");
  EXPECT_TRUE(units.front().after.empty());
}

// --shard K/N is a function from the whole plan to a share of it: the shards' engine runs partition the whole
// plan's, each shard keeps the references its runs wait for, and planning a shard writes nothing.
TEST_F(SuitePlan, ShardsPartitionTheEngineRunsAndKeepTheirReferences) {
  const auto whole = by_id(plan_suites({settings_}));
  std::map<std::string, int> shards_of_run;
  for (int k = 1; k <= 3; ++k) {
    settings_.shard = Shard{k, 3};
    const std::vector<PlannedUnit> units = plan_suites({settings_});
    EXPECT_FALSE(fs::exists(settings_.out)) << "planning a shard writes nothing";
    const auto shard = by_id(units);
    for (const PlannedUnit& u : units) {
      ASSERT_TRUE(whole.count(u.id)) << u.id << " is not in the whole plan";
      if (u.kind == PlannedUnit::Kind::engine) ++shards_of_run[u.id];
      for (const std::string& before : u.after)
        EXPECT_TRUE(shard.count(before)) << "shard " << k << ": " << u.id << " waits for " << before << ", not kept";
    }
    EXPECT_GE(count(units, PlannedUnit::Kind::engine), 1) << "shard " << k << " of 8 runs";
  }
  const auto engine_runs = std::count_if(
      whole.begin(), whole.end(), [](const auto& unit) { return unit.second.kind == PlannedUnit::Kind::engine; });
  EXPECT_EQ(static_cast<long>(shards_of_run.size()), engine_runs) << "every engine run is in a shard";
  for (const auto& [id, shards] : shards_of_run) EXPECT_EQ(shards, 1) << id << " in " << shards << " shards";
}

// An ensemble plans each start as a run of its own: start 0 is the single run (its id unchanged), start K
// adds /start=K, and every engine start waits for the references of the same start; the references may run
// more starts than the engines (their spread decides whether a case needs an ensemble).
TEST_F(SuitePlan, AnEnsemblePlansEveryStartAgainstTheReferencesOfTheSameStart) {
  const std::vector<PlannedUnit> single = plan_suites({settings_});
  settings_.ensemble.engine_starts = 2;
  settings_.ensemble.reference_starts = 3;
  const std::vector<PlannedUnit> units = plan_suites({settings_});
  EXPECT_EQ(count(units, PlannedUnit::Kind::engine), 2 * count(single, PlannedUnit::Kind::engine));
  EXPECT_EQ(count(units, PlannedUnit::Kind::beam_reference), 3 * count(single, PlannedUnit::Kind::beam_reference));
  EXPECT_EQ(count(units, PlannedUnit::Kind::chain_reference), 2 * count(single, PlannedUnit::Kind::chain_reference));
  const auto plan = by_id(units);
  for (const PlannedUnit& u : single) EXPECT_TRUE(plan.count(u.id)) << "start 0 is the single run: " << u.id;
  const auto start_of = [](const std::string& id) {
    const std::size_t at = id.rfind("/start=");
    return at == std::string::npos ? 0 : std::stoi(id.substr(at + 7));
  };
  int third_reference_starts = 0;
  for (const PlannedUnit& u : units) {
    if (u.kind == PlannedUnit::Kind::engine) {
      EXPECT_LT(start_of(u.id), 2) << u.id;
    }
    if (start_of(u.id) == 2) ++third_reference_starts;
    for (const std::string& before : u.after)
      EXPECT_EQ(start_of(before), start_of(u.id)) << u.id << " waits for " << before;
    if (!u.same_run_as.empty()) {  // braces: GoogleTest's macros hold an if of their own
      EXPECT_EQ(start_of(u.same_run_as), start_of(u.id)) << u.id << " <- " << u.same_run_as;
    }
  }
  EXPECT_EQ(third_reference_starts, 2) << "the third start: the beam reference of each law alone";
}

// An engine's chain damping (option chain_damping) is its chain reference's too: an engine run with the
// hinge dampers is compared with the reference on a chain damped alike, not with the modal one.
TEST_F(SuitePlan, AnEnginesChainDampingIsItsChainReferences) {
  settings_.engine_options["mirror"] = {{"chain_damping", "hinge"}};
  const auto plan = by_id(plan_suites({settings_}));
  int engines = 0;
  for (const auto& [id, u] : plan) {
    if (u.kind != PlannedUnit::Kind::engine) continue;
    ++engines;
    ASSERT_EQ(u.after.size(), 2u) << id;
    EXPECT_NE(u.after[1].find("chain_damping=hinge"), std::string::npos) << id << " -> " << u.after[1];
  }
  EXPECT_GT(engines, 0);
}

// The reference alone on K-link chains (--reference-chains): one chain reference per K, law and reference start,
// each compared with the beam reference of its start; the chain an engine of the same K builds is the same job.
TEST_F(SuitePlan, ReferenceChainsPlanTheReferenceOnEachChainForEveryStart) {
  settings_.engines = {"reference"};
  settings_.reference_chain_links = {4, 16};
  settings_.ensemble.reference_starts = 3;
  const std::vector<PlannedUnit> units = plan_suites({settings_});
  const auto plan = by_id(units);
  EXPECT_EQ(count(units, PlannedUnit::Kind::engine), 0);
  EXPECT_EQ(count(units, PlannedUnit::Kind::beam_reference), 2 * 3);
  EXPECT_EQ(count(units, PlannedUnit::Kind::chain_reference), 2 * 2 * 3) << "laws x K x starts";
  for (const PlannedUnit& u : units) {
    if (u.kind != PlannedUnit::Kind::chain_reference) continue;
    EXPECT_TRUE(u.id.find("/links=4;modes=chain") != std::string::npos ||
                u.id.find("/links=16;modes=chain") != std::string::npos)
        << u.id;
    ASSERT_EQ(u.after.size(), 1u) << u.id << " is compared with the beam";
    EXPECT_EQ(plan.at(u.after[0]).kind, PlannedUnit::Kind::beam_reference) << u.id;
    const std::size_t at = u.id.rfind("/start=");
    const std::string start = at == std::string::npos ? "" : u.id.substr(at);
    EXPECT_EQ(u.after[0].size() >= start.size() &&
                  u.after[0].compare(u.after[0].size() - start.size(), start.size(), start) == 0,
              true)
        << u.id << " waits for " << u.after[0] << ", of another start";
  }
  // the mirror engine builds a 4-link chain: planned beside the chains, its chain reference is one of them
  settings_.engines = {"reference", "mirror"};
  const std::vector<PlannedUnit> with_engine = plan_suites({settings_});
  EXPECT_EQ(count(with_engine, PlannedUnit::Kind::chain_reference), 2 * 2 * 3);
}

TEST_F(SuitePlan, RecommendedRunsEachEnginesOwnConfigurationForEachLaw) {
  // the mirror's authors name a configuration for Hertz only: its options over the part's, at its own step
  SimulatorDescriptor mirror;
  mirror.name = "mirror";
  mirror.recommended = {{"hertz", {{"contact", "native"}, {"chain_damping", "hinge"}}, 2e-5}};
  settings_.simulators.descriptors.push_back(mirror);
  settings_.recommended = true;
  settings_.time_steps_s.clear();
  settings_.contact_paths.clear();
  settings_.engine_options["mirror"] = {{"chain_damping", "modal"}, {"links", "4"}};
  std::vector<std::string> engine_runs;
  for (const auto& [id, u] : by_id(plan_suites({settings_})))
    if (u.kind == PlannedUnit::Kind::engine) engine_runs.push_back(id);
  ASSERT_EQ(engine_runs.size(), 1u) << "one run, Hertz's: the Newton law has no recommended configuration";
  const std::string& id = engine_runs[0];
  EXPECT_NE(id.find("/hertz/"), std::string::npos) << id;
  EXPECT_NE(id.find("dt=2e-05"), std::string::npos) << id;
  EXPECT_NE(id.find("contact=native"), std::string::npos) << id;
  EXPECT_NE(id.find("chain_damping=hinge"), std::string::npos) << id << ": the authors' setting wins";
  EXPECT_NE(id.find("links=4"), std::string::npos) << id << ": the part's own option stays beneath";
}

}  // namespace suite_plan_test
}  // namespace ib
