#include "harness/jobs/campaign_folder.h"

#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <stdexcept>
#include <system_error>

#include "harness/records/run_files.h"

namespace ib {

namespace fs = std::filesystem;

namespace {

// The file whose presence says the folder holds this kind's results: a suite's runs.jsonl, a sweep's settings
// record (its rows are in their folders).
std::string results_file(CampaignKind kind) { return kind == CampaignKind::suite ? "runs.jsonl" : "sweep.json"; }
// The file of the settings record that --resume is checked against.
std::string settings_file(CampaignKind kind) { return kind == CampaignKind::suite ? "suite.jsonl" : "sweep.json"; }

// The files that say a folder holds a campaign of this kind (its settings record, or results of an older one).
bool holds_kind(const std::string& dir, CampaignKind kind) {
  return fs::exists(dir + "/" + results_file(kind)) || fs::exists(dir + "/" + settings_file(kind));
}

}  // namespace

const char* to_string(CampaignKind kind) { return kind == CampaignKind::suite ? "suite" : "sweep"; }

std::unique_ptr<FolderLock> open_campaign_folder(const std::string& dir, CampaignKind kind) {
  std::error_code error;
  fs::create_directories(dir, error);
  if (error) throw OutputError(output_error_text(dir, "create the output folder", error.value()));
  fs::create_directories(dir + "/runs", error);  // before any run: a runs/ that cannot be made stops it now
  if (error) throw OutputError(output_error_text(dir + "/runs", "create the run folders' folder", error.value()));
  if (access(dir.c_str(), W_OK) != 0) throw OutputError(output_error_text(dir, "write into the output folder", errno));
  auto lock = std::make_unique<FolderLock>(dir, to_string(kind));
  const CampaignKind other = kind == CampaignKind::suite ? CampaignKind::sweep : CampaignKind::suite;
  if (holds_kind(dir, other) && !holds_kind(dir, kind))
    throw std::invalid_argument(dir + " holds a " + to_string(other) + "; choose another --out for a " +
                                to_string(kind));
  return lock;
}

void check_same_shard(const std::string& dir, CampaignKind kind, const std::optional<Shard>& shard,
                      bool holds_results) {
  const std::string what = to_string(kind);
  const std::vector<ShardPlan> plans = read_shard_plans(dir);
  if (!shard) {
    if (!plans.empty())
      throw std::invalid_argument(dir + " holds shard " + to_string(plans.front().shard) + " of a " + what +
                                  " (shard.jsonl): resume it with --shard " + to_string(plans.front().shard));
    return;
  }
  if (plans.empty()) {
    if (holds_results)
      throw std::invalid_argument(dir + " holds a whole " + what +
                                  "'s results, not a shard's: resume it without --shard " + to_string(*shard) +
                                  ", or choose another --out for the shard");
    return;
  }
  for (const ShardPlan& p : plans)
    if (p.shard != *shard)
      throw std::invalid_argument(dir + " holds shard " + to_string(p.shard) + " of a " + what +
                                  " (shard.jsonl), not --shard " + to_string(*shard) + ": resume it with --shard " +
                                  to_string(p.shard) + ", or choose another --out for this shard");
}

void refuse_results_without_resume(const std::string& dir, CampaignKind kind, bool resume) {
  if (resume || !fs::exists(dir + "/" + results_file(kind))) return;
  throw std::invalid_argument(dir + " already holds a " + to_string(kind) + "'s results (" + results_file(kind) +
                              "): pass --resume to continue it, or choose another --out");
}

void refuse_other_settings(const std::string& dir, CampaignKind kind, const std::string& keys,
                           const std::string& recorded_by) {
  const std::string what = to_string(kind);
  const bool can_extend = kind == CampaignKind::suite;  // a suite's --extend adds another suite to its folder
  throw std::invalid_argument(dir + " holds a " + what + " with other settings (" + keys + " differ" +
                              (recorded_by.empty() ? "" : " from: " + recorded_by) + ", see " + dir + "/" +
                              settings_file(kind) + "): --resume continues the same " + what + " only; " +
                              (can_extend ? "add --extend to add this " + what + " to the folder, or " : "") +
                              "choose another --out");
}

CampaignResult result_of(const CampaignEnd& end) {
  if (end.interrupted_by != 0) return {CampaignStatus::stopped, end.interrupted_by};
  if (end.units_stopped > 0) return {CampaignStatus::stopped, end.stopped_by};
  return {end.not_ok_recorded > 0 ? CampaignStatus::not_ok : CampaignStatus::ok, 0};
}

CampaignResult worse(const CampaignResult& a, const CampaignResult& b) {
  return static_cast<int>(b.status) > static_cast<int>(a.status) ? b : a;
}

}  // namespace ib
