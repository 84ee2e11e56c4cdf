// The sweep's plan: its ratios, its chains and rows in planned order.
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#include "harness/sweep/sweep.h"
#include "model/simulator_options.h"

namespace ib {

const char* to_string(SweepStart start) {
  switch (start) {
    case SweepStart::rest:
      return "rest";
    case SweepStart::up:
      return "up";
    case SweepStart::down:
      return "down";
  }
  return "?";
}

namespace {

double parse_ratio_part(const std::string& part, const std::string& text) {
  errno = 0;
  char* end = nullptr;
  const double value = std::strtod(part.c_str(), &end);
  if (part.empty() || *end != '\0' || errno == ERANGE || !std::isfinite(value))
    throw std::invalid_argument("--ratios " + text + ": '" + part +
                                "' is not a number; allowed: FROM:TO:STEP, e.g. 0.85:1.20:0.01");
  return value;
}

}  // namespace

std::vector<double> parse_ratios(const std::string& text) {
  const auto first = text.find(':'), second = first == std::string::npos ? first : text.find(':', first + 1);
  if (second == std::string::npos || text.find(':', second + 1) != std::string::npos)
    throw std::invalid_argument("--ratios " + text + ": allowed: FROM:TO:STEP, e.g. 0.85:1.20:0.01");
  const double from = parse_ratio_part(text.substr(0, first), text);
  const double to = parse_ratio_part(text.substr(first + 1, second - first - 1), text);
  const double step = parse_ratio_part(text.substr(second + 1), text);
  // the motor speed over f_1: a physical rig is driven from well below to a few times its resonance
  constexpr double kLowest = 0.05, kHighest = 20;
  if (!(from >= kLowest && to <= kHighest && from <= to))
    throw std::invalid_argument("--ratios " + text + ": allowed: 0.05 <= FROM <= TO <= 20");
  if (!(step > 0) && from != to) throw std::invalid_argument("--ratios " + text + ": allowed: STEP > 0");
  const double count = from == to ? 1 : std::floor((to - from) / step + 1e-3) + 1;
  if (count > 10000)
    throw std::invalid_argument("--ratios " + text + ": " + std::to_string(static_cast<long long>(count)) +
                                " ratios; allowed: at most 10000");
  std::vector<double> ratios;
  for (int k = 0; k < static_cast<int>(count); ++k) ratios.push_back(std::round((from + k * step) * 1e9) / 1e9);
  return ratios;
}

std::vector<double> parse_ensemble_ratios(const std::string& text, const std::vector<double>& sweep_ratios) {
  std::vector<double> ratios;
  std::size_t from = 0;
  while (from <= text.size()) {
    const std::size_t comma = std::min(text.find(',', from), text.size());
    const std::string part = text.substr(from, comma - from);
    // one ratio alone ("0.94") is the range 0.94:0.94:0
    for (double ratio : parse_ratios(part.find(':') == std::string::npos ? part + ":" + part + ":0" : part)) {
      // both on parse_ratios' 1e-9 grid: one ratio is one double
      if (std::find(sweep_ratios.begin(), sweep_ratios.end(), ratio) == sweep_ratios.end())
        throw std::invalid_argument("--ensemble-ratios " + text + ": " + ratio_text(ratio) +
                                    " is not one of the sweep's ratios (--ratios); allowed: ratios the sweep runs");
      if (std::find(ratios.begin(), ratios.end(), ratio) == ratios.end()) ratios.push_back(ratio);
    }
    from = comma + 1;
  }
  std::sort(ratios.begin(), ratios.end());
  return ratios;
}

std::string ratio_text(double ratio) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", ratio);
  return text;
}

std::vector<SweepChain> plan_sweep(const SweepSettings& s, const std::string& scenario_name) {
  std::vector<SweepChain> chains;
  const auto in_ensemble = [&](double ratio) {
    if (s.ensemble.reference_starts <= 1) return false;
    const auto& ratios = s.ensemble.ratios;  // parse_ensemble_ratios': the sweep's own doubles
    return ratios.empty() || std::find(ratios.begin(), ratios.end(), ratio) != ratios.end();
  };
  const std::vector<std::string> no_path = {""};
  const std::vector<double> default_step = {0};
  for (const std::string& engine : s.engines) {
    const bool reference = engine == "reference";
    for (ContactLaw law : s.laws) {
      for (const std::string& path : reference || s.contact_paths.empty() ? no_path : s.contact_paths) {
        for (double dt : reference || s.time_steps_s.empty() ? default_step : s.time_steps_s) {
          JobSpec job;
          job.scenario_path = s.scenario_path;
          job.engine = engine;
          job.settings.law = law;
          job.settings.output_rate_hz = s.output_rate_hz;
          job.settings.time_step_s = dt;
          if (reference) {
            job.settings.options = s.reference_options;
          } else {
            const auto options = s.engine_options.find(engine);
            if (options != s.engine_options.end()) job.settings.options = options->second;
            if (!path.empty()) job.settings.options["contact"] = path;
          }
          const std::string configuration = job_id(scenario_name, job);
          for (SweepStart start : s.starts) {
            auto row_of = [&](double ratio, bool first) {
              SweepRow row;
              row.job = job;
              row.start = start;
              row.ratio = ratio;
              row.first_of_chain = first;
              row.id = configuration + "/" + to_string(start) + "/r=" + ratio_text(ratio);
              return row;
            };
            if (start == SweepStart::rest) {
              for (double ratio : s.ratios) {
                SweepRow row = row_of(ratio, true);
                row.chain = row.id;
                const bool ensemble = reference && in_ensemble(ratio);
                const int count = s.ensemble.reference_starts;
                if (ensemble) row.job.start.count = count;  // start 0 of count: the scenario as written
                chains.push_back({row.id, {row}});
                if (!ensemble) continue;
                // the reference's other starts at this ratio, each a chain of its own (start 0 is the row above)
                for (int k = 1; k < count; ++k) {
                  SweepRow member = row;
                  member.job.start = {k, count, k * s.ensemble.displacement_step_m};
                  member.id = row.id + "/start=" + std::to_string(k);
                  member.chain = member.id;
                  chains.push_back({member.id, {member}});
                }
              }
              continue;
            }
            SweepChain chain{configuration + "/" + to_string(start), {}};
            for (std::size_t k = 0; k < s.ratios.size(); ++k) {
              const double ratio = start == SweepStart::up ? s.ratios[k] : s.ratios[s.ratios.size() - 1 - k];
              chain.rows.push_back(row_of(ratio, k == 0));
              chain.rows.back().chain = chain.id;
            }
            chains.push_back(std::move(chain));
          }
        }
      }
    }
  }
  return chains;
}

}  // namespace ib
