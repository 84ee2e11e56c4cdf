// `study --plan`'s counts and CPU estimate (study.h, describe_study_work; the estimate: study_cost.h).
#include <cstdio>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "harness/study/study.h"
#include "harness/study/study_cost.h"
#include "model/scenario_toml.h"

namespace ib {

namespace {

// A part's estimated CPU time and the simulators it could not estimate (no measured cost).
struct Estimate {
  double cpu_s = 0;
  std::set<std::string> unmeasured;
  void add(const SimulatorCatalog& catalog, const std::string& engine,
           const std::map<std::string, std::string>& options, double time_step_s, double simulated_s) {
    if (const auto cpu = estimated_cpu_s(catalog, engine, options, time_step_s, simulated_s))
      cpu_s += *cpu;
    else
      unmeasured.insert(engine);
  }
  void add(const Estimate& other) {
    cpu_s += other.cpu_s;
    unmeasured.insert(other.unmeasured.begin(), other.unmeasured.end());
  }
};

// Seconds as a person reads an estimate: two significant figures below 10 s, whole seconds to 10 minutes, then
// minutes.
std::string seconds_text(double seconds) {
  char text[48];
  if (seconds >= 600)
    std::snprintf(text, sizeof text, "%.0f min", seconds / 60);
  else if (seconds >= 10)
    std::snprintf(text, sizeof text, "%.0f s", seconds);
  else
    std::snprintf(text, sizeof text, "%.2g s", seconds);
  return text;
}

std::string runs_text(int runs) { return std::to_string(runs) + (runs == 1 ? " run" : " runs"); }

std::string cpu_text(const Estimate& estimate) {
  std::string text = "about " + seconds_text(estimate.cpu_s) + " of CPU";
  if (!estimate.unmeasured.empty()) {
    std::string names;
    for (const std::string& name : estimate.unmeasured) names += (names.empty() ? "" : ",") + name;
    text += " (without " + names + ": no measured cost in its descriptor)";
  }
  return text;
}

// A sweep's rows and their estimate: each row from rest runs the rest duration (or the scenario's), each continued
// row the continuation's.
std::pair<int, Estimate> sweep_work(const SweepSettings& s) {
  Estimate estimate;
  double scenario_s = 0;
  std::string name;
  try {
    const Scenario scenario = load_scenario(s.scenario_path);
    scenario_s = scenario.duration_s;
    name = scenario.name;
  } catch (const std::exception&) {  // the sweep refuses it before anything runs; the plan counts its rows anyway
  }
  int rows = 0;
  for (const SweepChain& chain : plan_sweep(s, name))
    for (const SweepRow& row : chain.rows) {
      ++rows;
      const double simulated_s =
          row.first_of_chain ? s.rest_duration_s.value_or(scenario_s) : s.continuation_duration_s;
      estimate.add(s.simulators, row.job.engine, row.job.settings.options, row.job.settings.time_step_s, simulated_s);
    }
  return {rows, estimate};
}

std::string suite_work_line(const StudyPart& part, const PartRuns& counted, Estimate& estimate) {
  const SuiteSettings& s = std::get<SuiteSettings>(part.settings);
  for (const PlannedRunWork& run : counted.to_run)
    estimate.add(s.simulators, run.engine, run.options, run.time_step_s, run.simulated_s);
  std::vector<std::string> notes;
  if (counted.shared > 0)
    notes.push_back(std::to_string(counted.shared) + " more planned by an earlier part: run and counted there");
  if (counted.scored_only > 0)
    notes.push_back(std::to_string(counted.scored_only) + " of them scored from another law's native run");
  if (counted.step_searches > 0)
    notes.push_back("and " + std::to_string(counted.step_searches) +
                    " step searches, whose probes are planned as each goes: not counted");
  std::string text;
  for (const std::string& note : notes) text += (text.empty() ? " (" : "; ") + note;
  if (!text.empty()) text += ")";
  return "  " + std::string(to_string(part.kind)) + " \"" + part.name + "\": " + runs_text(counted.runs) + text + ", " +
         cpu_text(estimate);
}

}  // namespace

std::vector<std::string> describe_study_work(const std::vector<StudyPart>& parts, const StudySettings& settings) {
  const std::vector<StudyPart> placed = place_study_parts(parts, settings);
  std::vector<SuiteSettings> suites;
  for (const StudyPart& part : placed)
    if (const auto* suite = std::get_if<SuiteSettings>(&part.settings)) suites.push_back(*suite);
  const std::vector<PartRuns> counted = suites.empty() ? std::vector<PartRuns>{} : count_part_runs(suites);
  std::vector<std::string> lines;
  Estimate total;
  int runs = 0, not_counted = 0;
  std::size_t index = 0;
  for (const StudyPart& part : placed)
    if (std::holds_alternative<SuiteSettings>(part.settings)) {
      Estimate estimate;
      lines.push_back(suite_work_line(part, counted[index], estimate));
      runs += counted[index].runs;
      not_counted += counted[index++].step_searches > 0;
      total.add(estimate);
    }
  for (const StudyPart& part : placed)
    if (const auto* sweep = std::get_if<SweepSettings>(&part.settings)) {
      const auto [rows, estimate] = sweep_work(*sweep);
      lines.push_back("  sweep \"" + part.name + "\": " + std::to_string(rows) + (rows == 1 ? " row, " : " rows, ") +
                      cpu_text(estimate));
      runs += rows;
      total.add(estimate);
    }
  for (const StudyPart& part : placed)
    if (const auto* own = std::get_if<std::shared_ptr<const PartOfItsOwnKind>>(&part.settings)) {
      const std::string head = "  " + (*own)->kind() + " \"" + part.name + "\": ";
      if (const auto work = (*own)->planned_work()) {
        Estimate estimate;
        estimate.cpu_s = work->cpu_s;
        lines.push_back(head + runs_text(work->runs) + ", " + cpu_text(estimate));
        runs += work->runs;
        total.add(estimate);
        continue;
      }
      lines.push_back(head + "not counted (a part of a kind of its own)");
      ++not_counted;
    }
  lines.push_back("total: " + runs_text(runs) +
                  (not_counted == 1 ? " (a part not counted in full: above)"
                   : not_counted    ? " (" + std::to_string(not_counted) + " parts not counted in full: above)"
                                    : "") +
                  ", " + cpu_text(total) + ", about " + seconds_text(total.cpu_s / settings.jobs) + " of wall on " +
                  std::to_string(settings.jobs) + (settings.jobs == 1 ? " worker" : " workers") +
                  " without the report; an estimate, within a factor of 2 where engines' runs dominate "
                  "(docs/performance.md, \"The plan's CPU estimate\")");
  return lines;
}

}  // namespace ib
