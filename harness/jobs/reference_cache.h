// Reference results shared between output folders (suite --reference-cache DIR): a rerun, a comparison or
// an ensemble in a new folder copies a reference run it has already computed instead of solving it again.
//
// An entry is keyed, and checked on every hit, by everything that decides the reference's result: the
// scenario file's content (and its path, so that a moved file is a miss, never a wrong hit), the scenario
// as cut (duration, scoring window), the law, the reference's options, the output rate, the measurement
// (window, sensor rate, merge window, series kept, verdict settings) and the executable itself (a digest of
// its bytes: any rebuild starts a new cache). A job's name plays no part. DIR/<key>/ holds a copy of the
// run's folder and key.json, the key in words; a hit whose key.json differs is a miss.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "harness/jobs/run_job.h"
#include "model/scenario.h"

namespace ib {

// The key of a reference job: what decides its result, as above.
nlohmann::ordered_json reference_cache_key(const Scenario& scenario, const JobSpec& spec,
                                           const Measurement& measurement);

// Copies the cached run into run_folder (emptied first) and returns true when DIR holds this key; false
// (nothing copied) otherwise, also when the entry is damaged.
bool restore_cached_reference(const std::string& cache_folder, const nlohmann::ordered_json& key,
                              const std::string& run_folder);

// Stores a finished reference run's folder (its record files included) under its key; an entry already
// there is kept. A cache that cannot be written is said on stderr and otherwise ignored: it only saves time.
void store_cached_reference(const std::string& cache_folder, const nlohmann::ordered_json& key,
                            const std::string& run_folder);

}  // namespace ib
