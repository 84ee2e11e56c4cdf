#include "harness/jobs/matrix_settings.h"

namespace ib {

void record_configurations(const MatrixSettings& settings, nlohmann::ordered_json& record) {
  record["engines"] = settings.engines;
  std::vector<std::string> laws;
  for (ContactLaw law : settings.laws) laws.push_back(to_string(law));
  record["laws"] = laws;
  record["time_steps_s"] = settings.time_steps_s;
  record["contact_paths"] = settings.contact_paths;
  record["engine_options"] = settings.engine_options;
  record["reference_options"] = settings.reference_options;
}

}  // namespace ib
