#include "harness/jobs/shard_plan.h"

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "harness/records/run_files.h"

namespace ib {
namespace {

using Json = nlohmann::ordered_json;

const char* const kPlanFile = "/shard.jsonl";

// A whole number of at most 9 digits (no sign, no spaces), or -1.
int whole_number(const std::string& text) {
  if (text.empty() || text.size() > 9 || text.find_first_not_of("0123456789") != std::string::npos) return -1;
  return std::stoi(text);
}

std::vector<std::string> strings_of(const Json& j, const char* name) {
  std::vector<std::string> out;
  if (!j.contains(name) || !j[name].is_array()) return out;
  for (const Json& item : j[name])
    if (item.is_string()) out.push_back(item.get<std::string>());
  return out;
}

}  // namespace

Shard parse_shard(const std::string& text) {
  const auto slash = text.find('/');
  const int index = slash == std::string::npos ? -1 : whole_number(text.substr(0, slash));
  const int count = slash == std::string::npos ? -1 : whole_number(text.substr(slash + 1));
  if (index < 1 || count < 1 || index > count)
    throw std::invalid_argument("--shard " + text +
                                ": allowed: K/N with whole numbers 1 <= K <= N (shard K of N shards, numbered from 1 "
                                "as Slurm's --array=1-N numbers its tasks), e.g. --shard 2/8");
  return Shard{index, count};
}

std::string to_string(const Shard& shard) { return std::to_string(shard.index) + "/" + std::to_string(shard.count); }

bool in_shard(std::size_t unit, const Shard& shard) {
  return unit % static_cast<std::size_t>(shard.count) == static_cast<std::size_t>(shard.index - 1);
}

std::string file_digest(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return in ? plan_digest({text.str()}) : "unreadable";
}

std::string plan_digest(const std::vector<std::string>& planned) {
  std::uint64_t hash = 14695981039346656037ull;  // FNV-1a offset basis
  for (const std::string& id : planned) {
    for (const char c : id + "\n") {
      hash ^= static_cast<unsigned char>(c);
      hash *= 1099511628211ull;  // FNV-1a prime
    }
  }
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash));
  return text;
}

void record_shard_plan(const std::string& folder, const ShardPlan& plan) {
  for (const ShardPlan& recorded : read_shard_plans(folder))
    if (recorded.suite == plan.suite && recorded.shard == plan.shard) return;
  Json j;
  j["shard"] = plan.shard.index;
  j["shards"] = plan.shard.count;
  j["suite"] = plan.suite;
  j["jobs"] = plan.jobs;
  j["step_searches"] = plan.step_searches;
  j["resume_command"] = plan.resume_command;
  // The whole file replaced through a rename: a kill never leaves half a line, so a line that is not a
  // plan is damage, which read_shard_plans reports.
  std::ifstream existing(folder + kPlanFile, std::ios::binary);
  std::stringstream text;
  if (existing) text << existing.rdbuf();
  replace_text_file(folder + kPlanFile, text.str() + j.dump(-1, ' ', false, Json::error_handler_t::replace) + "\n");
}

std::vector<ShardPlan> read_shard_plans(const std::string& folder) {
  std::vector<ShardPlan> plans;
  std::ifstream in(folder + kPlanFile);
  int line_number = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_number;
    const Json j = Json::parse(line, nullptr, /*allow_exceptions=*/false);
    const bool plan_like = j.is_object() && j.contains("shard") && j["shard"].is_number_integer() &&
                           j.contains("shards") && j["shards"].is_number_integer() && j.contains("suite") &&
                           j["suite"].is_string() && j.contains("jobs") && j["jobs"].is_array() &&
                           j.contains("resume_command");
    if (!plan_like || j["shard"].get<int>() < 1 || j["shard"].get<int>() > j["shards"].get<int>())
      throw std::runtime_error(folder + kPlanFile + " line " + std::to_string(line_number) +
                               ": not a shard's plan (expected shard K <= shards N, suite, jobs, resume_command); the "
                               "folder is damaged: restore the file, or run the shard again into another --out");
    ShardPlan plan;
    plan.shard = Shard{j["shard"].get<int>(), j["shards"].get<int>()};
    plan.suite = j["suite"].get<std::string>();
    plan.jobs = strings_of(j, "jobs");
    plan.step_searches = strings_of(j, "step_searches");
    plan.resume_command = j["resume_command"].is_string() ? j["resume_command"].get<std::string>() : "";
    plans.push_back(std::move(plan));
  }
  return plans;
}

}  // namespace ib
