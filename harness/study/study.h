// A study (docs/studies.md, "Study files"): suites, step searches and frequency sweeps run into one folder as
// one plan on one pool of workers. The command line reads a study file into these typed parts
// (cli/study_file.h); what runs them is here, so that no option text reaches the harness.
//
// A new kind of part is a class implementing PartOfItsOwnKind (below): its settings, its source of units, its
// plan line and how it ended; this file places it, runs it with the others and counts its end in the study's,
// unchanged (tests/study_part_kind_test.cpp adds a toy). On the command line it is its table's keys
// (cli/study_keys.*) and its reader (cli/study_file.cpp).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "harness/jobs/campaign_folder.h"
#include "harness/jobs/shard_plan.h"
#include "harness/jobs/unit_source.h"
#include "harness/suite/suite.h"
#include "harness/sweep/sweep.h"

namespace ib {

// A study file's kinds of part, and `other`: a part of a kind of its own (PartOfItsOwnKind). `validation` is a
// study file's table ([[validation]]) whose part is of a kind of its own (harness/validation/validation_part.h).
enum class StudyPartKind { suite, search, sweep, other, validation };
const char* to_string(
    StudyPartKind kind);  // "suite", "search", "sweep", "validation": the study file's tables; "other"

struct StudySettings;

// A part of a kind of its own: its settings are its own, it is its own source of units on the study's pool, and
// it writes into OUT/KIND/NAME.
class PartOfItsOwnKind {
 public:
  virtual ~PartOfItsOwnKind() = default;
  virtual std::string kind() const = 0;  // its name (a-z): its folder below OUT, its plan line's first word
  // Checks its settings and prepares its folder, throwing std::invalid_argument before anything of the study
  // runs; its units then run on the study's pool with every other part's (study: workers, shard, resume).
  virtual std::unique_ptr<UnitSource> prepare(const std::string& folder, const StudySettings& study) const = 0;
  virtual std::string plan(const std::string& folder) const = 0;  // --plan's line after `KIND "NAME": `
  // --plan's count under that line: the runs it records and their estimated CPU time [s] (study_cost.h), none
  // where the kind cannot say before it runs (the plan then names it as not counted).
  struct Work {
    int runs = 0;
    double cpu_s = 0;
  };
  virtual std::optional<Work> planned_work() const { return std::nullopt; }
  // How it ended (campaign_folder.h), asked once the study's units have run, with the source prepare made: the
  // study's exit code counts it as it counts a suite's or a sweep's.
  virtual CampaignEnd finish(UnitSource& source) const = 0;
};

// One part: a suite and a search run SuiteSettings (a search's step_search set), a sweep SweepSettings, a part of
// kind `other` its own. The settings are checked already; the study-wide ones in them (folder, workers, shard,
// resume, reference cache, extend) are StudySettings' and are set by place_study_parts.
struct StudyPart {
  StudyPartKind kind = StudyPartKind::suite;
  std::string name;  // a sweep's: its folder below OUT/sweeps/; a suite's or search's: for messages
  std::variant<SuiteSettings, SweepSettings, std::shared_ptr<const PartOfItsOwnKind>> settings;
};

// What applies to every part (`study`'s own options).
struct StudySettings {
  std::string out;  // the study's folder: the suites and searches write into it, each sweep into OUT/sweeps/NAME
  int jobs = 1;     // worker processes, one pool for every part
  std::optional<Shard> shard;           // every part's shard
  bool resume = false;                  // continue what every part recorded
  std::string reference_cache;          // the suites' and searches' (suite.h): sweeps' rows are not cached
  std::vector<StudyPartKind> left_out;  // kinds of parts not run (--skip)
};

// The parts as the study runs them, in their order: the kinds left out dropped, each part's folder set (the
// suites and searches OUT, each after the first with extend, as `suite --extend` adds one to a folder; each
// sweep OUT/sweeps/NAME) and the study-wide settings copied into each (a part of its own kind: folder_of).
std::vector<StudyPart> place_study_parts(const std::vector<StudyPart>& parts, const StudySettings& settings);

// What a study's run did. The suites and searches are one source of units into one folder (a job two parts
// plan runs once), so they have one outcome together; each sweep has its own.
struct StudyOutcome {
  std::optional<SuiteOutcome> suites;  // none: the study ran no suite or search
  struct Sweep {
    std::string name;
    SweepOutcome outcome;
  };
  std::vector<Sweep> sweeps;  // in the parts' order
  struct Other {              // a part of a kind of its own that ran
    std::string name;
    CampaignEnd end;  // PartOfItsOwnKind::finish
  };
  std::vector<Other> others;  // in the parts' order
};

// How the study ended: the worst of its parts' ends (campaign_folder.h), which the command line turns into its
// exit code.
CampaignResult result_of(const StudyOutcome& outcome);

// The folder of a part of a kind of its own: OUT/KIND/NAME.
std::string folder_of(const PartOfItsOwnKind& part, const std::string& name, const StudySettings& settings);

// Runs the parts (placed as place_study_parts does) as one plan on one pool of settings.jobs workers: no part
// waits for another, the costliest ready unit starts first. Then each folder's engines.json and
// provenance.json are written (with_engines_file: the suites' from the first suite's catalog). Installs the
// InterruptionHandler (worker_process.h) for its run: SIGINT or SIGTERM stops the workers and the outcomes say
// so. Throws as prepare_suites and prepare_sweep do before anything runs (std::invalid_argument), and
// OutputError (run_files.h) when a result cannot be written.
StudyOutcome run_study(const std::vector<StudyPart>& parts, const StudySettings& settings);

// `study --plan`: one line per part as placed (no newline): what it runs, "all" spelled out as the settings
// hold it, and what decides its runs beyond that (window, rates, what is kept, options, time limit), so that
// two studies with equal lines run the same runs. The suites and searches first, then the sweeps, then the
// parts of kinds of their own.
std::vector<std::string> describe_study(const std::vector<StudyPart>& parts, const StudySettings& settings);

// `study --plan`'s counts, one line per part in describe_study's order, then a total line: the runs each part
// records (a suite's or search's rows of runs.csv, a job two parts plan counted in the first alone, as it runs
// there; a sweep's rows) and the CPU time they are estimated to take (study_cost.h: within a factor of about 2);
// a step search's probes, planned as it goes, and a part of its own kind are named, not counted. The total line
// also gives the wall time on settings.jobs workers, the report not included. The whole study, whatever the shard.
std::vector<std::string> describe_study_work(const std::vector<StudyPart>& parts, const StudySettings& settings);

}  // namespace ib
