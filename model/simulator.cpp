#include "model/simulator.h"

namespace ib {

double series_start_s(const RunSettings& settings, const Scenario& scenario) {
  return settings.series_start_s >= 0 ? settings.series_start_s : scenario.scoring_start_s();
}

}  // namespace ib
