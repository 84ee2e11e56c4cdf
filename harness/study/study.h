// A study (docs/studies.md, "Study files"): suites, step searches and frequency sweeps run into one folder as
// one plan on one pool of workers. The command line reads a study file into these typed parts
// (cli/study_file.h); what runs them is here, so that no option text reaches the harness.
//
// A new kind of part touches: StudyPartKind and to_string (below), the settings it runs with (the variant of
// StudyPart), its folder (place_study_parts), its source of units and outcome (run_study, study.cpp) and its
// plan line (describe_study, study_plan.cpp); on the command line its table's keys (cli/study_keys.*), its
// reader (cli/study_file.cpp) and its exit code (cli/command_study.cpp).
#pragma once

#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "harness/jobs/shard_plan.h"
#include "harness/suite/suite.h"
#include "harness/sweep/sweep.h"

namespace ib {

enum class StudyPartKind { suite, search, sweep };
const char* to_string(StudyPartKind kind);  // "suite", "search", "sweep": the study file's table names

// One part: a suite and a search run SuiteSettings (a search's step_search set), a sweep SweepSettings. The
// settings are checked already; the study-wide ones in them (folder, workers, shard, resume, reference cache,
// extend) are StudySettings' and are set by place_study_parts.
struct StudyPart {
  StudyPartKind kind = StudyPartKind::suite;
  std::string name;  // a sweep's: its folder below OUT/sweeps/; a suite's or search's: for messages
  std::variant<SuiteSettings, SweepSettings> settings;
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
// sweep OUT/sweeps/NAME) and the study-wide settings copied into each.
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
};

// How the study ended: the worst of its parts' ends (campaign_folder.h), which the command line turns into its
// exit code.
CampaignResult result_of(const StudyOutcome& outcome);

// Runs the parts (placed as place_study_parts does) as one plan on one pool of settings.jobs workers: no part
// waits for another, the costliest ready unit starts first. Then each folder's engines.json and
// provenance.json are written (with_engines_file: the suites' from the first suite's catalog). Installs the
// InterruptionHandler (worker_process.h) for its run: SIGINT or SIGTERM stops the workers and the outcomes say
// so. Throws as prepare_suites and prepare_sweep do before anything runs (std::invalid_argument), and
// OutputError (run_files.h) when a result cannot be written.
StudyOutcome run_study(const std::vector<StudyPart>& parts, const StudySettings& settings);

// `study --plan`: one line per part as placed (no newline): what it runs, "all" spelled out as the settings
// hold it, and what decides its runs beyond that (window, rates, what is kept, options, time limit), so that
// two studies with equal lines run the same runs. The suites and searches first, then the sweeps.
std::vector<std::string> describe_study(const std::vector<StudyPart>& parts, const StudySettings& settings);

}  // namespace ib
