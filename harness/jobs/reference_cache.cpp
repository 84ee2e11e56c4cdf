// The reference cache (reference_cache.h).
#include "harness/jobs/reference_cache.h"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "harness/jobs/shard_plan.h"
#include "harness/records/run_files.h"
#include "harness/scoring/metric_catalog.h"

namespace ib {

namespace {

namespace fs = std::filesystem;

// The digest and size of a file's bytes: what its content is, whatever its name.
std::string content_digest(const std::string& path) {
  std::error_code error;
  if (!fs::is_regular_file(path, error)) return "unreadable";
  const std::string bytes = read_text_file(path);
  return plan_digest({bytes}) + "/" + std::to_string(bytes.size());
}

// This executable's bytes: the reference's code and everything that writes its results.
const std::string& executable_digest() {
  static const std::string digest = content_digest("/proc/self/exe");
  return digest;
}

const char* series_name(SeriesOutput series) {
  return series == SeriesOutput::all ? "all" : series == SeriesOutput::none ? "none" : "window";
}

// Copies the regular files of one folder into another (made if missing).
void copy_files(const fs::path& from, const fs::path& to) {
  fs::create_directories(to);
  for (const fs::directory_entry& entry : fs::directory_iterator(from))
    if (entry.is_regular_file())
      fs::copy_file(entry.path(), to / entry.path().filename(), fs::copy_options::overwrite_existing);
}

}  // namespace

nlohmann::ordered_json reference_cache_key(const Scenario& scenario, const JobSpec& spec, const Measurement& m) {
  nlohmann::ordered_json key;
  key["scenario_file"] = spec.scenario_path;
  key["scenario_content"] = content_digest(spec.scenario_path);
  key["duration_s"] = scenario.duration_s;
  key["scoring_window_s"] = scenario.scoring_window_s;
  key["engine"] = spec.engine;
  key["law"] = to_string(spec.settings.law);
  key["options"] = options_text(spec.settings.options);
  key["output_rate_hz"] = spec.settings.output_rate_hz;
  key["time_step_s"] = spec.settings.time_step_s;
  if (spec.start.initial_displacement_offset_m != 0)  // an ensemble's start: a different run of the same scenario
    key["initial_displacement_offset_m"] = spec.start.initial_displacement_offset_m;
  key["window_s"] = m.window_s ? nlohmann::ordered_json(*m.window_s) : nlohmann::ordered_json(nullptr);
  key["sensor_rate_hz"] = m.sensor_rate_hz;
  key["merge_window_s"] = m.merge_window_s;
  key["series"] = series_name(m.series);
  key["timed_repeats"] = m.timed_repeats;
  key["verdict_tolerances"] = tolerance_values(m.verdicts.accuracy);  // the metric catalog's, in its order
  key["stability_bounds"] = {
      m.verdicts.stability.displacement_bound_fraction_of_length, m.verdicts.stability.penetration_bound_gaps,
      m.verdicts.stability.penetration_bound_floor_m, m.verdicts.stability.energy_growth_tolerance};
  key["executable"] = executable_digest();
  return key;
}

bool restore_cached_reference(const std::string& cache_folder, const nlohmann::ordered_json& key,
                              const std::string& run_folder) {
  const fs::path entry = fs::path(cache_folder) / plan_digest({key.dump()});
  const std::string held = read_text_file((entry / "key.json").string());
  if (held.empty()) return false;
  const auto held_key = nlohmann::ordered_json::parse(held, nullptr, /*allow_exceptions=*/false);
  // (a discarded value compares unequal to nothing: ask for it first)
  if (held_key.is_discarded() || !(held_key == key) || !fs::exists(entry / "row.jsonl") ||
      !fs::exists(entry / "row.csv"))
    return false;
  std::error_code error;
  clear_run_folder(run_folder);  // its own files only: the runs below its id (ensemble starts, chain) are others'
  try {
    copy_files(entry, run_folder);
    fs::remove(fs::path(run_folder) / "key.json");
    std::ofstream(fs::path(run_folder) / "log.txt", std::ios::app)
        << "restored from the reference cache " << entry.string() << " (its costs are the cached run's)\n";
  } catch (const fs::filesystem_error& e) {
    std::fprintf(stderr, "suite: the reference cache %s could not be read (%s); the reference runs\n", entry.c_str(),
                 e.what());
    clear_run_folder(run_folder);
    return false;
  }
  return true;
}

void store_cached_reference(const std::string& cache_folder, const nlohmann::ordered_json& key,
                            const std::string& run_folder) {
  const fs::path entry = fs::path(cache_folder) / plan_digest({key.dump()});
  std::error_code error;
  if (nlohmann::ordered_json::parse(read_text_file((entry / "key.json").string()), nullptr,
                                    /*allow_exceptions=*/false) == key)
    return;
  // written beside and renamed into place, so that a reader never sees half an entry
  const fs::path partial =
      fs::path(cache_folder) / (".partial-" + std::to_string(::getpid()) + "-" + entry.filename().string());
  try {
    fs::remove_all(partial);
    copy_files(run_folder, partial);
    std::ofstream(partial / "key.json") << key.dump(2) << "\n";
    fs::remove_all(entry, error);       // a damaged entry (a miss above) is replaced
    fs::rename(partial, entry, error);  // another process may have stored it first: theirs is kept
    if (error) fs::remove_all(partial);
  } catch (const fs::filesystem_error& e) {
    std::fprintf(stderr, "suite: the reference cache %s cannot be written (%s); going on without it\n",
                 cache_folder.c_str(), e.what());
    fs::remove_all(partial, error);
  }
}

}  // namespace ib
