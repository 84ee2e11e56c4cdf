#include "harness/scoring/plausibility.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace ib {

namespace {

std::string text(double x) {
  std::ostringstream out;
  out << x;
  return out.str();
}

}  // namespace

void check_option(const std::string& option, double value, double lo, double hi, const std::string& unit,
                  bool lo_included) {
  const bool above = lo_included ? value >= lo : value > lo;
  if (std::isfinite(value) && above && value <= hi) return;
  throw std::invalid_argument(option + " " + text(value) + ": allowed: " + text(lo) +
                              (lo_included ? " <= x <= " : " < x <= ") + text(hi) + (unit.empty() ? "" : " " + unit));
}

void check_run_size(const Scenario& scenario, const RunSettings& settings) {
  const std::string where = scenario.source_path.empty() ? scenario.name : scenario.source_path;
  const double duration_s = scenario.duration_s;
  if (settings.time_step_s > 0) {
    check_option("--dt", settings.time_step_s, Plausible::kMinTimeStep_s, Plausible::kMaxTimeStep_s, "s", true);
    if (settings.time_step_s > duration_s / 10)
      throw std::invalid_argument("--dt " + text(settings.time_step_s) + ": allowed: at most a tenth of the run (" +
                                  where + ": duration_s = " + text(duration_s) + " s)");
    const double steps = duration_s / settings.time_step_s;
    if (steps > Plausible::kMaxSteps)
      throw std::invalid_argument("--dt " + text(settings.time_step_s) + ": " + text(steps) + " steps for the " +
                                  text(duration_s) + " s of " + where + "; allowed: at most " +
                                  text(Plausible::kMaxSteps) + " steps (a larger step, or a shorter --duration)");
  }
  check_option("--rate", settings.output_rate_hz, Plausible::kMinRate_hz, Plausible::kMaxRate_hz, "Hz", true);
  if (settings.series_start_s >= duration_s)
    throw std::invalid_argument("--series-start " + text(settings.series_start_s) +
                                ": allowed: before the run's end (" + where + ": duration_s = " + text(duration_s) +
                                " s)");
  const double start_s = series_start_s(settings, scenario);
  const double samples = settings.output_rate_hz * (duration_s - start_s);
  if (samples > Plausible::kMaxSamples)
    throw std::invalid_argument("--rate " + text(settings.output_rate_hz) + ": " + text(samples) +
                                " samples over the " + text(duration_s - start_s) + " s of " + where +
                                "; allowed: at most " + text(Plausible::kMaxSamples) +
                                " (a lower --rate, a later --series-start or a shorter --duration)");
}

}  // namespace ib
