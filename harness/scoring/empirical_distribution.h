// Statistics of a sample and distances between two samples' empirical distributions, for the per-impact
// figures (impact_statistics.h). Written here: neither Eigen nor Boost.Math has a two-sample Wasserstein or
// Kolmogorov-Smirnov distance of empirical data. Non-finite values are left out of every sample; an empty
// sample gives NaN.
#pragma once

#include <vector>

namespace ib {

// The q-quantile (0 <= q <= 1) by linear interpolation between the order statistics at (n - 1) q, the
// rule of NumPy's default percentile ("linear", Hyndman-Fan type 7): q = 0.5 is the median.
double quantile(std::vector<double> sample, double q);

// Wasserstein-1 (earth mover's) distance of the two empirical distributions, the integral of
// |F_a(x) - F_b(x)| over x, in the samples' unit: a sample shifted by s is s away from itself.
double wasserstein1_distance(std::vector<double> a, std::vector<double> b);

// Two-sample Kolmogorov-Smirnov statistic, max over x of |F_a(x) - F_b(x)| in [0, 1]: 0 for equal
// samples, 1 for samples that do not overlap.
double kolmogorov_smirnov_statistic(std::vector<double> a, std::vector<double> b);

}  // namespace ib
