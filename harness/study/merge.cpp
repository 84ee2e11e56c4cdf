#include "harness/study/merge.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <stdexcept>

#include "harness/records/folder_lock.h"
#include "harness/records/recorded_run.h"
#include "harness/records/reporters.h"
#include "harness/records/run_files.h"
#include "harness/records/run_record.h"
#include "harness/suite/step_search.h"
#include "harness/sweep/sweep.h"

namespace ib {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

// What differs between two runs of the same job on two machines, or at two moments: the measured cost.
std::set<std::string> run_timing_fields() {
  const std::vector<std::string>& names = timing_field_names();
  return {names.begin(), names.end()};
}
const std::set<std::string> kStepTimingFields = {"probes_wall_time_s"};

// A record kept for OUT, with the folder it came from.
struct Kept {
  std::string line;
  Json record;
  std::string folder;
  int folders = 1;  // how many folders recorded it
};

std::string read_whole_file(const std::string& path) {
  errno = 0;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot read: " + std::strerror(errno ? errno : ENOENT));
  std::stringstream text;
  text << in.rdbuf();
  if (in.bad()) throw std::runtime_error(path + ": read error");
  return text.str();
}

std::vector<std::string> columns_of(const std::string& header_line) {
  std::vector<std::string> names;
  std::stringstream in(header_line);
  for (std::string name; std::getline(in, name, ',');) names.push_back(name);
  return names;
}

// A results file's header must be the one this build writes: merge rebuilds runs.csv and steps.csv in
// this build's layout from the records, and the report reads them by these names.
void check_header(const std::string& path, std::string expected) {
  std::ifstream in(path);
  std::string found;
  if (!in || !std::getline(in, found)) return;  // none yet: the records (.jsonl) are what counts
  if (!expected.empty() && expected.back() == '\n') expected.pop_back();
  if (found == expected) return;
  const auto a = columns_of(found), b = columns_of(expected);
  std::string what;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()) && what.empty(); ++i)
    if (a[i] != b[i]) what = "column " + std::to_string(i + 1) + " is '" + a[i] + "', expected '" + b[i] + "'";
  if (what.empty())
    what = std::to_string(a.size()) + " columns, expected " + std::to_string(b.size()) + " (" +
           (a.size() > b.size() ? "extra: '" + a[b.size()] + "'" : "missing: '" + b[a.size()] + "'") + ")";
  throw std::runtime_error(path + ": header differs from this build's: " + what +
                           "; merge shards made by the same version of impactbench");
}

// The first field in which two records differ, `ignored` aside, as a dotted path into nested objects
// (diagnostics.x); "" when they agree.
std::string first_difference(const Json& a, const Json& b, const std::set<std::string>& ignored,
                             const std::string& prefix = "") {
  for (const auto& [name, value] : a.items()) {
    if (ignored.count(name)) continue;
    if (!b.contains(name)) return prefix + name;
    if (value.is_object() && b[name].is_object()) {
      const std::string inner = first_difference(value, b[name], {}, prefix + name + ".");
      if (!inner.empty()) return inner;
    } else if (value != b[name]) {
      return prefix + name;
    }
  }
  for (const auto& [name, value] : b.items())
    if (!ignored.count(name) && !a.contains(name)) return prefix + name;
  return "";
}

// The value at a dotted path, as JSON text ("absent" when missing).
std::string value_text(const Json& record, const std::string& path) {
  const Json* at = &record;
  std::stringstream parts(path);
  for (std::string part; std::getline(parts, part, '.');) {
    if (!at->is_object() || !at->contains(part)) return "absent";
    at = &(*at)[part];
  }
  return at->dump();
}

// Adds a folder's records to `kept`, keyed by `key`; the same key from two folders must agree.
void join(std::map<std::string, Kept>& kept, const std::string& key, const std::string& line, const std::string& folder,
          const std::string& file, const std::string& what, const std::set<std::string>& timing) {
  Json record = Json::parse(line);
  const auto found = kept.find(key);
  if (found == kept.end()) {
    kept.emplace(key, Kept{line, std::move(record), folder, 1});
    return;
  }
  const std::string field = first_difference(found->second.record, record, timing);
  if (!field.empty())
    throw std::runtime_error(
        found->second.folder + " and " + folder + " disagree on " + what + ": field " + field + " is " +
        value_text(found->second.record, field) + " in " + found->second.folder + "/" + file + " and " +
        value_text(record, field) + " in " + folder + "/" + file +
        "; every shard must give a job the same result (made by other builds, options or machines?)");
  ++found->second.folders;
}

// runs/<job id>/: the run's own files (the folder also holds the folders of other jobs whose ids extend
// this one, which are joined on their own). Hard links cost no space; a file system that refuses them
// (another device, no permission to link another's file) gets a copy through the checked writer.
void join_run_folder(const std::string& from, const std::string& to) {
  std::error_code error;
  if (!fs::is_directory(from, error)) return;  // a job that could not run has no folder
  fs::create_directories(to, error);
  if (error) throw OutputError(output_error_text(to, "create the run folder", error.value()));
  for (const fs::directory_entry& entry : fs::directory_iterator(from)) {
    if (!entry.is_regular_file()) continue;
    const fs::path target = fs::path(to) / entry.path().filename();
    fs::create_hard_link(entry.path(), target, error);
    if (error) write_text_file(target.string(), read_whole_file(entry.path().string()));
  }
}

void check_inputs(const MergeSettings& settings) {
  if (settings.inputs.empty())
    throw std::runtime_error("merge: no shard folder given; expected: merge OUT SHARD_FOLDER ...");
  std::map<std::string, std::string> seen;  // canonical path -> as given
  for (const std::string& folder : settings.inputs) {
    std::error_code error;
    if (!fs::is_directory(folder, error))
      throw std::runtime_error(folder + ": " + (fs::exists(folder, error) ? "not a folder" : "no such folder") +
                               "; expected a shard's folder (suite --shard K/N --out FOLDER)");
    if (!fs::exists(folder + "/runs.jsonl") && !fs::exists(folder + "/shard.jsonl") &&
        !fs::exists(folder + "/sweep.json"))
      throw std::runtime_error(folder +
                               ": holds no suite's results (no runs.jsonl); expected a shard's folder "
                               "(suite --shard K/N --out FOLDER)");
    const std::string canonical = fs::canonical(folder).string();
    if (seen.count(canonical)) throw std::runtime_error(folder + ": given twice (also as " + seen[canonical] + ")");
    seen[canonical] = folder;
  }
  std::error_code error;
  if (fs::exists(settings.out, error)) {
    if (!fs::is_directory(settings.out, error))
      throw std::runtime_error(settings.out +
                               ": exists and is not a folder; merge writes a new suite folder: choose another OUT");
    if (!fs::is_empty(settings.out, error))
      throw std::runtime_error(
          settings.out + ": not empty (" +
          (fs::exists(settings.out + "/runs.jsonl") ? "it holds a suite's results" : "it holds files") +
          "); merge writes a new suite folder: choose another OUT, or empty this one first");
  }
}

// What one folder recorded: its job ids and the keys of its step searches' rows.
struct Recorded {
  std::set<std::string> jobs, step_searches;
};

// Shards of one suite (or study) hold the same suites: each folder's plans name suites (a digest of the
// whole plan and its settings, divided into N shards). Two folders with no suite in common are shards of
// different suites, whose merge would be neither: refused, naming both. (Folders that share some suites
// but not all are one study's shards, one stopped before its later parts: check_completeness says which.)
void check_same_suites(const MergeSettings& settings) {
  std::string first_folder;
  std::map<std::pair<std::string, int>, std::string> first;  // (digest, N) -> the command that made it
  for (const std::string& folder : settings.inputs) {
    std::map<std::pair<std::string, int>, std::string> suites;
    for (const ShardPlan& plan : read_shard_plans(folder))
      suites.emplace(std::pair{plan.suite, plan.shard.count}, plan.resume_command);
    if (suites.empty()) continue;  // a whole suite's folder: its records are joined as they are
    if (first_folder.empty()) {
      first_folder = folder;
      first = suites;
      continue;
    }
    bool shared = false;
    for (const auto& [suite, command] : suites) shared = shared || first.count(suite) > 0;
    if (!shared)
      throw std::runtime_error(first_folder + " and " + folder + " are shards of different suites (" +
                               first.begin()->second + "; " + suites.begin()->second +
                               "): merge the shards of one suite, made by the same command with the same settings "
                               "and the same shard count N");
  }
}

// Which shards lack planned results in their own folder (what their resume command would run), and
// which shards of a suite none of the folders holds.
void check_completeness(const MergeSettings& settings, const std::map<std::string, Recorded>& recorded,
                        MergeOutcome& outcome) {
  std::map<std::pair<std::string, int>, std::set<int>> shards_of_suite;  // (digest, N) -> the K present
  std::map<std::pair<std::string, int>, std::string> command_of_suite;
  for (const std::string& folder : settings.inputs) {
    const std::vector<ShardPlan> plans = read_shard_plans(folder);
    if (plans.empty()) outcome.without_plan.push_back(folder);
    for (const ShardPlan& plan : plans) {
      IncompleteShard gap{folder,
                          plan.shard,
                          static_cast<int>(plan.jobs.size()),
                          0,
                          static_cast<int>(plan.step_searches.size()),
                          0,
                          plan.resume_command};
      const Recorded& in_folder = recorded.at(folder);
      for (const std::string& id : plan.jobs) gap.jobs_missing += in_folder.jobs.count(id) ? 0 : 1;
      for (const std::string& key : plan.step_searches)
        gap.step_searches_missing += in_folder.step_searches.count(key) ? 0 : 1;
      if (gap.jobs_missing > 0 || gap.step_searches_missing > 0) outcome.incomplete.push_back(gap);
      shards_of_suite[{plan.suite, plan.shard.count}].insert(plan.shard.index);
      command_of_suite.emplace(std::pair{plan.suite, plan.shard.count}, plan.resume_command);
    }
  }
  for (const auto& [suite, present] : shards_of_suite) {
    int next = 1;  // the first shard not yet accounted for
    for (int k : present) {
      if (k > next) outcome.absent.push_back(AbsentShards{next, k - 1, suite.second, command_of_suite[suite]});
      next = k + 1;
    }
    if (next <= suite.second)
      outcome.absent.push_back(AbsentShards{next, suite.second, suite.second, command_of_suite[suite]});
  }
}

}  // namespace

// A sweep's shards (sweep --shard K/N): every folder must hold the same sweep (sweep.json, sweep_plan.txt);
// the row folders are joined, a row in several folders kept once if its row.json agrees but for timing,
// and the tables made from the plan's order, as the sweep itself makes them.
static MergeOutcome merge_sweep_shards(const MergeSettings& settings) {
  const std::string settings_text = read_whole_file(settings.inputs.front() + "/sweep.json");
  const std::string plan_text = read_whole_file(settings.inputs.front() + "/sweep_plan.txt");
  std::vector<std::string> plan;
  std::istringstream plan_lines(plan_text);
  for (std::string id; std::getline(plan_lines, id);)
    if (!id.empty()) plan.push_back(id);
  const std::set<std::string> timing = {"cpu_time_s", "wall_time_s", "load_average"};
  std::map<std::string, Kept> rows;
  std::map<std::string, Recorded> recorded;
  for (const std::string& folder : settings.inputs) {
    if (!fs::exists(folder + "/sweep.json"))
      throw std::runtime_error(folder + ": holds no sweep (no sweep.json), unlike " + settings.inputs.front() +
                               "; merge joins shards of one sweep or of one suite");
    if (read_whole_file(folder + "/sweep.json") != settings_text ||
        read_whole_file(folder + "/sweep_plan.txt") != plan_text)
      throw std::runtime_error(folder + ": holds another sweep than " + settings.inputs.front() +
                               " (their sweep.json or sweep_plan.txt differ); merge joins the shards of one sweep");
    Recorded& in_folder = recorded[folder];
    for (const std::string& id : plan) {
      const std::string row_path = folder + "/runs/" + id + "/row.json";
      if (!fs::exists(row_path)) continue;
      const std::string row = read_whole_file(row_path);
      std::string line = row;
      while (!line.empty() && line.back() == '\n') line.pop_back();
      join(rows, id, line, folder, "runs/" + id + "/row.json", "sweep row " + id, timing);
      in_folder.jobs.insert(id);
    }
  }
  MergeOutcome outcome;
  check_completeness(settings, recorded, outcome);
  std::error_code error;
  fs::create_directories(settings.out, error);
  if (error) throw OutputError(output_error_text(settings.out, "create the output folder", error.value()));
  const FolderLock lock(settings.out, "merge");
  for (const auto& [id, kept] : rows) {
    join_run_folder(kept.folder + "/runs/" + id, settings.out + "/runs/" + id);
    outcome.runs_in_several += kept.folders > 1 ? 1 : 0;
  }
  write_text_file(settings.out + "/sweep.json", settings_text);
  write_text_file(settings.out + "/sweep_plan.txt", plan_text);
  outcome.runs = write_sweep_tables(settings.out, plan);
  return outcome;
}

MergeOutcome merge_suites(const MergeSettings& settings) {
  check_inputs(settings);
  check_same_suites(settings);
  if (fs::exists(settings.inputs.front() + "/sweep.json")) return merge_sweep_shards(settings);
  // Read and check everything before writing anything.
  MergeOutcome outcome;
  std::map<std::string, Kept> runs, steps;   // by job id; by step_row_key
  std::map<std::string, Recorded> recorded;  // by folder
  bool any_steps = false;
  const std::set<std::string> run_timing = run_timing_fields();
  for (const std::string& folder : settings.inputs) {
    Recorded& in_folder = recorded[folder];
    check_header(folder + "/runs.csv", csv_header(RunRecord{}));
    if (const std::vector<std::string> problems = runs_table_problems(folder); !problems.empty()) {
      std::string text;
      for (std::size_t i = 0; i < problems.size() && i < 5; ++i) text += (i ? "; " : "") + problems[i];
      if (problems.size() > 5) text += "; and " + std::to_string(problems.size() - 5) + " more";
      throw std::runtime_error(folder + ": its results are damaged (" + text +
                               "); continue that shard with --resume, "
                               "which repairs its records and runs again what they lack, then merge");
    }
    check_header(folder + "/steps.csv", steps_csv_header());
    for (const auto& [id, line] : recorded_run_lines(folder)) {
      join(runs, id, line, folder, "runs.jsonl", "job " + id, run_timing);
      in_folder.jobs.insert(id);
    }
    std::ifstream step_lines(folder + "/steps.jsonl");
    any_steps = any_steps || step_lines.is_open();
    for (std::string line; std::getline(step_lines, line);) {
      const RecordedStepRow row = read_step_row(line);
      if (!row.readable) continue;  // cut short by a kill
      in_folder.step_searches.insert(row.key);
      join(steps, row.key, line, folder, "steps.jsonl", "step search " + row.group_id, kStepTimingFields);
    }
  }
  check_completeness(settings, recorded, outcome);

  std::error_code error;
  fs::create_directories(settings.out, error);
  if (error) throw OutputError(output_error_text(settings.out, "create the output folder", error.value()));
  const FolderLock lock(settings.out, "merge");
  // The run folders first, the records last: an OUT with a runs.jsonl has everything it lists.
  for (const auto& [id, kept] : runs) join_run_folder(kept.folder + "/runs/" + id, settings.out + "/runs/" + id);
  std::string jsonl;
  for (const auto& [id, kept] : runs) {
    jsonl += kept.line + "\n";
    outcome.runs_in_several += kept.folders > 1 ? 1 : 0;
  }
  write_text_file(settings.out + "/runs.jsonl", jsonl);
  outcome.runs =
      static_cast<int>(repair_and_list_runs(settings.out).size());  // runs.csv from runs.jsonl, as --resume makes it
  if (any_steps) {
    std::string step_jsonl;
    for (const auto& [key, kept] : steps) step_jsonl += kept.line + "\n";
    write_text_file(settings.out + "/steps.jsonl", step_jsonl);
    outcome.step_rows = static_cast<int>(repair_and_list_step_rows(settings.out).size());
  }
  // A study's sweeps (a study file's [[sweep]] parts: DIR/sweeps/<name>/), each joined as a sweep.
  std::set<std::string> sweeps;
  for (const std::string& folder : settings.inputs)
    if (fs::is_directory(folder + "/sweeps", error))
      for (const fs::directory_entry& entry : fs::directory_iterator(folder + "/sweeps"))
        if (fs::exists(entry.path() / "sweep.json")) sweeps.insert(entry.path().filename().string());
  for (const std::string& name : sweeps) {
    MergeSettings part{{}, settings.out + "/sweeps/" + name};
    for (const std::string& folder : settings.inputs)
      if (fs::exists(folder + "/sweeps/" + name + "/sweep.json")) part.inputs.push_back(folder + "/sweeps/" + name);
    const MergeOutcome joined = merge_sweep_shards(part);
    outcome.incomplete.insert(outcome.incomplete.end(), joined.incomplete.begin(), joined.incomplete.end());
    outcome.absent.insert(outcome.absent.end(), joined.absent.begin(), joined.absent.end());
    outcome.without_plan.insert(outcome.without_plan.end(), joined.without_plan.begin(), joined.without_plan.end());
  }
  return outcome;
}

std::vector<std::string> merge_messages(const MergeOutcome& outcome) {
  std::vector<std::string> lines;
  for (const IncompleteShard& gap : outcome.incomplete) {
    std::string what;
    if (gap.jobs_missing > 0)
      what = std::to_string(gap.jobs_missing) + " of its " + std::to_string(gap.jobs_planned) + " jobs";
    if (gap.step_searches_missing > 0)
      what += (what.empty() ? "" : " and ") + std::to_string(gap.step_searches_missing) + " of its " +
              std::to_string(gap.step_searches_planned) + " step searches";
    lines.push_back(
        "shard " + to_string(gap.shard) + " in " + gap.folder + " is missing " + what +
        " (its task failed or was stopped); finish it, then merge again into an empty folder: " + gap.resume_command);
  }
  for (const AbsentShards& absent : outcome.absent) {
    const std::string n = std::to_string(absent.count), first = std::to_string(absent.first);
    const std::string which = absent.first == absent.last
                                  ? "shard " + first + "/" + n + " is"
                                  : "shards " + first + " to " + std::to_string(absent.last) + " of " + n + " are";
    const std::string shard = absent.first == absent.last ? first + "/" + n : "K/" + n;
    lines.push_back(which + " in none of the folders given (a task failed before it began?); run " +
                    (absent.first == absent.last ? "it" : "each") + " as the other shards ran, with --shard " + shard +
                    " and its own --out, then merge again into an empty folder; " +
                    "another shard ran as: " + absent.sibling_command);
  }
  for (const std::string& folder : outcome.without_plan)
    lines.push_back("note: " + folder +
                    " was not made with --shard (no shard.jsonl): joined as it is, its completeness not checked");
  return lines;
}

}  // namespace ib
