// `study --plan`'s CPU estimate (study_cost.h).
#include "harness/study/study_cost.h"

#include <cmath>
#include <exception>
#include <string>
#include <utility>
#include <vector>

namespace ib {

namespace {

// The cost per simulated second on a K-link chain: log-log between the two measured K around it (beyond the
// measured ones, along the nearest two; one measured K alone: that cost).
double chain_cost_s(const std::vector<std::pair<int, double>>& measured, int links) {
  if (measured.size() == 1) return measured.front().second;
  std::size_t upper = 1;
  while (upper + 1 < measured.size() && measured[upper].first < links) ++upper;
  const auto& [k0, c0] = measured[upper - 1];
  const auto& [k1, c1] = measured[upper];
  const double slope = std::log(c1 / c0) / std::log(static_cast<double>(k1) / k0);
  return c0 * std::pow(static_cast<double>(links) / k0, slope);
}

}  // namespace

std::optional<double> estimated_cpu_s(const SimulatorCatalog& catalog, const std::string& engine,
                                      const std::map<std::string, std::string>& options, double time_step_s,
                                      double simulated_s) {
  const SimulatorDescriptor d = descriptor_of(catalog, engine);
  if (d.cpu_s_per_simulated_s <= 0) return std::nullopt;
  double per_simulated_s = d.cpu_s_per_simulated_s;
  const auto links = options.find("links");
  if (links != options.end() && !d.chain_cpu_s_per_simulated_s.empty()) {
    try {
      per_simulated_s = chain_cost_s(d.chain_cpu_s_per_simulated_s, std::stoi(links->second));
    } catch (const std::exception&) {  // not a number: the option's own check refuses it before any run
    }
  }
  // A fixed-step engine's work is its steps: a smaller step costs more in proportion.
  if (d.default_time_step_s > 0 && time_step_s > 0) per_simulated_s *= d.default_time_step_s / time_step_s;
  return per_simulated_s * simulated_s;
}

}  // namespace ib
