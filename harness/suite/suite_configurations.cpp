// Which configurations of an engine a suite part runs for one law (suite_runner.h): its contact paths crossed
// with its time steps, or the engine's authors' recommended configuration (descriptor.json, docs/engines.md).
#include "harness/suite/suite_runner.h"

namespace ib::suite_internal {

std::vector<EngineConfiguration> engine_configurations(const SuiteSettings& part, const SimulatorCatalog& catalog,
                                                       const std::string& engine, ContactLaw law,
                                                       const std::map<std::string, std::string>& engine_options) {
  std::vector<EngineConfiguration> configurations;
  if (part.recommended) {
    // The part's own per-engine options lie beneath the authors' settings, which win where both name one.
    const SimulatorDescriptor descriptor = descriptor_of(catalog, engine);
    for (const RecommendedConfiguration& r : descriptor.recommended) {
      if (r.law != to_string(law)) continue;
      auto options = engine_options;
      for (const auto& [name, value] : r.options) options[name] = value;
      configurations.emplace_back(options, r.time_step_s);
    }
    return configurations;
  }
  const std::vector<double> steps =
      part.time_steps_s.empty() || part.step_search ? std::vector<double>{0} : part.time_steps_s;
  const std::vector<std::string> paths = part.contact_paths.empty() ? std::vector<std::string>{""} : part.contact_paths;
  for (const std::string& path : paths)
    for (double dt : steps) {
      auto options = engine_options;
      if (!path.empty()) options["contact"] = path;
      configurations.emplace_back(options, dt);
    }
  return configurations;
}

}  // namespace ib::suite_internal
