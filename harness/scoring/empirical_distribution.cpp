// Quantiles, W1 and KS of empirical samples by one sorted merge: linear in the samples once sorted.
#include "harness/scoring/empirical_distribution.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

namespace ib {
namespace {

constexpr double kNoDistribution = std::numeric_limits<double>::quiet_NaN();

std::vector<double> sorted_finite(std::vector<double> sample) {
  sample.erase(std::remove_if(sample.begin(), sample.end(), [](double v) { return !std::isfinite(v); }), sample.end());
  std::sort(sample.begin(), sample.end());
  return sample;
}

// Walks the union of two sorted samples in increasing order. At each distinct value x it calls
// step(x_previous, x, gap) with gap = |F_a - F_b| on [x_previous, x) (the CDFs are constant there), and
// returns the largest gap after any value: the KS statistic. Ties inside or across samples are one step.
template <typename Step>
double merge_walk(const std::vector<double>& a, const std::vector<double>& b, Step step) {
  const double n = static_cast<double>(a.size()), m = static_cast<double>(b.size());
  std::size_t i = 0, j = 0;
  double x_previous = std::min(a.front(), b.front()), largest_gap = 0;
  while (i < a.size() || j < b.size()) {
    const double x = std::min(i < a.size() ? a[i] : std::numeric_limits<double>::infinity(),
                              j < b.size() ? b[j] : std::numeric_limits<double>::infinity());
    step(x_previous, x, std::abs(static_cast<double>(i) / n - static_cast<double>(j) / m));
    while (i < a.size() && a[i] == x) ++i;
    while (j < b.size() && b[j] == x) ++j;
    largest_gap = std::max(largest_gap, std::abs(static_cast<double>(i) / n - static_cast<double>(j) / m));
    x_previous = x;
  }
  return largest_gap;
}

}  // namespace

double quantile(std::vector<double> sample, double q) {
  const std::vector<double> s = sorted_finite(std::move(sample));
  if (s.empty() || !(q >= 0 && q <= 1)) return kNoDistribution;
  const double position = q * static_cast<double>(s.size() - 1);
  const auto below = static_cast<std::size_t>(std::floor(position));
  if (below + 1 >= s.size()) return s.back();
  const double fraction = position - static_cast<double>(below);
  return s[below] + fraction * (s[below + 1] - s[below]);
}

double wasserstein1_distance(std::vector<double> a, std::vector<double> b) {
  const std::vector<double> sa = sorted_finite(std::move(a)), sb = sorted_finite(std::move(b));
  if (sa.empty() || sb.empty()) return kNoDistribution;
  double area = 0;
  merge_walk(sa, sb, [&](double x_previous, double x, double gap) { area += gap * (x - x_previous); });
  return area;
}

double kolmogorov_smirnov_statistic(std::vector<double> a, std::vector<double> b) {
  const std::vector<double> sa = sorted_finite(std::move(a)), sb = sorted_finite(std::move(b));
  if (sa.empty() || sb.empty()) return kNoDistribution;
  return merge_walk(sa, sb, [](double, double, double) {});
}

}  // namespace ib
