#include "harness/records/metrics_file.h"

#include <nlohmann/json.hpp>

#include "harness/records/run_files.h"

namespace ib {

std::string metrics_json(const std::vector<ScoredMetric>& metrics, const AccuracyTolerances& defaults) {
  using Json = nlohmann::ordered_json;
  Json references = Json::array();
  for (const ScoringReference& r : scoring_references())
    references.push_back({{"name", r.name}, {"error_prefix", r.error_prefix}, {"meaning", r.meaning}});
  Json listed = Json::array();
  for (const ScoredMetric& m : metrics)
    listed.push_back({{"name", m.name},
                      {"label", m.label},
                      {"column", m.column},
                      {"unit", m.unit},
                      {"error_column", m.error_column},
                      {"kind", to_string(m.kind)},
                      {"tolerance_key", m.tolerance_key},
                      {"default_tolerance", tolerance_of(m, defaults)},
                      {"better", kSmallerErrorIsBetter},
                      {"scored_against", m.scored_against},
                      {"step_searched", m.step_searched}});
  // the defaults, not one part's: the parts of a study that share a folder may judge with other tolerances
  const Json document = {{"tolerances",
                          "default_tolerance is the harness's default; the tolerances each command's verdicts used "
                          "are its line's verdict_tolerances in commands.jsonl"},
                         {"references", references},
                         {"metrics", listed}};
  return document.dump(2) + "\n";
}

void write_metrics_file(const std::string& dir) { replace_text_file(dir + "/metrics.json", metrics_json()); }

}  // namespace ib
