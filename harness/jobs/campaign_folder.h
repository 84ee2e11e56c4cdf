// A campaign's folder: what a suite and a sweep (and so every part of a study) do with their output folder the
// same way, in one place. A campaign creates its folder and holds its lock while it writes; it refuses a folder
// that holds the other kind's results, or another shard's; its settings record decides what --resume continues
// (a suite's suite.jsonl, a sweep's sweep.json: their keys are their own, the refusals below are shared); a shard
// records its plan for merge (shard_plan.h); when it returns it writes engines.json and provenance.json
// (records/engines_file.h); and its outcome ends in one of the statuses below, which the command line turns into its
// exit code.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "harness/jobs/shard_plan.h"
#include "harness/records/folder_lock.h"

namespace ib {

enum class CampaignKind { suite, sweep };
const char* to_string(CampaignKind kind);  // "suite", "sweep"

// Creates DIR (and DIR/runs), checks that it can be written into and locks it for `kind` (folder_lock.h).
// Throws OutputError (run_files.h) naming the folder when it cannot be created or written, FolderBusy when
// another process holds it, std::invalid_argument when it holds the other kind's results (a sweep's folder
// for a suite, a suite's for a sweep).
std::unique_ptr<FolderLock> open_campaign_folder(const std::string& dir, CampaignKind kind);

// A shard's folder holds that shard alone, and a whole campaign's folder no shard: another shard's plan (or a
// whole campaign's results) in the same folder would leave it holding neither. Throws std::invalid_argument
// naming the shard the folder holds and how to resume it. holds_results: the folder has results recorded.
void check_same_shard(const std::string& dir, CampaignKind kind, const std::optional<Shard>& shard, bool holds_results);

// A folder holding this kind's results (a suite's runs.jsonl, a sweep's sweep.json) is continued by --resume only
// (or a suite's --extend, which the caller passes as `resume`): run into without it, the campaign would run twice
// what the folder holds. Throws std::invalid_argument saying so.
void refuse_results_without_resume(const std::string& dir, CampaignKind kind, bool resume);

// A --resume continues the same campaign only. Throws std::invalid_argument naming the settings record's keys
// that differ from the folder's (differing_keys, jsonl_table.h), the command that recorded those (when known),
// the record's file in DIR (suite.jsonl, sweep.json), and the way out (for a suite, --extend).
[[noreturn]] void refuse_other_settings(const std::string& dir, CampaignKind kind, const std::string& keys,
                                        const std::string& recorded_by);

// How a campaign (or a whole study: the worst of its parts) ended, for its exit code: interrupted by a signal
// to the campaign (SIGINT, SIGTERM: --resume continues), some units stopped by a signal from outside (not
// recorded: --resume runs them), else whether every result recorded in the folder is ok (a resumed campaign's
// status covers the results of its earlier invocations too).
struct CampaignEnd {
  int interrupted_by = 0;   // the signal that stopped the campaign; 0: it ran to its end
  int units_stopped = 0;    // units a signal from outside stopped
  int stopped_by = 0;       // that signal (the last one seen)
  int not_ok_recorded = 0;  // unstable or failed results among all those recorded in the folder
};
enum class CampaignStatus { ok, not_ok, stopped };  // stopped: by `signal` (interrupted or from outside)
struct CampaignResult {
  CampaignStatus status = CampaignStatus::ok;
  int signal = 0;
};
CampaignResult result_of(const CampaignEnd& end);
// The worse of two: stopped over not ok over ok (a study's parts).
CampaignResult worse(const CampaignResult& a, const CampaignResult& b);

}  // namespace ib
