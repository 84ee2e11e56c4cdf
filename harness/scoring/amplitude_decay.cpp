#include "harness/scoring/amplitude_decay.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ib {

double log_decrement(const std::vector<double>& time_s, const std::vector<double>& displacement_m, double start_s,
                     double end_s) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::size_t n = std::min(time_s.size(), displacement_m.size());
  // peaks of whole cycles: from one upward zero crossing to the next
  std::vector<double> peaks;
  bool in_cycle = false;
  double peak = 0;
  for (std::size_t k = 1; k < n; ++k) {
    if (time_s[k] < start_s) continue;
    if (time_s[k] > end_s) break;
    const bool crosses_upward = displacement_m[k - 1] <= 0 && displacement_m[k] > 0 && time_s[k - 1] >= start_s;
    if (crosses_upward) {
      if (in_cycle) peaks.push_back(peak);
      in_cycle = true;
      peak = displacement_m[k];
    } else if (in_cycle) {
      peak = std::max(peak, displacement_m[k]);
    }
  }
  if (peaks.size() < 3) return nan;
  // least squares of y_i = ln(peak_i) against i: slope = sum (i - i_mean)(y_i - y_mean) / sum (i - i_mean)^2
  const double count = static_cast<double>(peaks.size()), i_mean = (count - 1) / 2;
  double y_mean = 0;
  for (double p : peaks) {
    if (!(p > 0)) return nan;
    y_mean += std::log(p) / count;
  }
  double covariance = 0, variance = 0;
  for (std::size_t i = 0; i < peaks.size(); ++i) {
    const double di = static_cast<double>(i) - i_mean;
    covariance += di * (std::log(peaks[i]) - y_mean);
    variance += di * di;
  }
  return -covariance / variance;
}

}  // namespace ib
