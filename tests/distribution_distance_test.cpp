// Quantiles and the distances between two empirical distributions (harness/scoring/empirical_distribution.h)
// on samples whose answers are known in closed form: a shifted sample is W1 = shift away, identical samples
// have KS 0 and samples that do not overlap KS 1.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "harness/scoring/empirical_distribution.h"
#include "harness/scoring/impact_statistics.h"

namespace ib {
namespace distribution_distance_test {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// An irregular sample with a tie, in no particular order.
const std::vector<double> kSample = {0.7, -1.3, 2.9, 0.7, 5.25, 1.1, -0.4};

std::vector<double> shifted(std::vector<double> sample, double shift) {
  for (double& v : sample) v += shift;
  return sample;
}

TEST(DistributionDistance, AShiftedSampleIsItsShiftAwayInWassersteinOne) {
  for (double shift : {0.0, 0.25, -3.5, 17.0}) {
    EXPECT_NEAR(wasserstein1_distance(kSample, shifted(kSample, shift)), std::abs(shift), 1e-12) << shift;
    EXPECT_NEAR(wasserstein1_distance(shifted(kSample, shift), kSample), std::abs(shift), 1e-12) << shift;
  }
  // two points: the distance between them
  EXPECT_DOUBLE_EQ(wasserstein1_distance({2.0}, {-1.5}), 3.5);
}

// Samples of different sizes: F_a = 1/2 and F_b = 2/5 on [0, 1), equal elsewhere.
TEST(DistributionDistance, SamplesOfDifferentSizesCompareTheirCumulativeFractions) {
  const std::vector<double> a = {0, 1}, b = {1, 0, 1, 0, 1};
  EXPECT_NEAR(wasserstein1_distance(a, b), 0.1, 1e-15);
  EXPECT_NEAR(kolmogorov_smirnov_statistic(a, b), 0.1, 1e-15);
}

TEST(DistributionDistance, KolmogorovSmirnovIsZeroForEqualSamplesAndOneForDisjointOnes) {
  EXPECT_EQ(kolmogorov_smirnov_statistic(kSample, kSample), 0.0);
  EXPECT_EQ(kolmogorov_smirnov_statistic(kSample, shifted(kSample, 10)), 1.0);
  // {1,2,3,4} against {3,4,5,6}: on [2, 3) half of the first and none of the second lie below
  EXPECT_DOUBLE_EQ(kolmogorov_smirnov_statistic({1, 2, 3, 4}, {3, 4, 5, 6}), 0.5);
  EXPECT_DOUBLE_EQ(wasserstein1_distance({1, 2, 3, 4}, {3, 4, 5, 6}), 2.0);
}

TEST(DistributionDistance, QuantilesInterpolateBetweenOrderStatistics) {
  EXPECT_DOUBLE_EQ(quantile({3, 1, 2}, 0.5), 2.0);
  EXPECT_DOUBLE_EQ(quantile({3, 1, 2}, 0.95), 2.9);  // (n - 1) q = 1.9: 2 + 0.9 (3 - 2)
  EXPECT_DOUBLE_EQ(quantile({4, 1}, 0.5), 2.5);
  EXPECT_DOUBLE_EQ(quantile({7}, 0.95), 7.0);
  EXPECT_DOUBLE_EQ(quantile({3, kNaN, 1, 2}, 0.5), 2.0);  // NaN is no value
}

TEST(DistributionDistance, AnEmptySampleHasNoStatistic) {
  EXPECT_TRUE(std::isnan(quantile({}, 0.5)));
  EXPECT_TRUE(std::isnan(quantile({kNaN}, 0.5)));
  EXPECT_TRUE(std::isnan(wasserstein1_distance({}, kSample)));
  EXPECT_TRUE(std::isnan(kolmogorov_smirnov_statistic(kSample, {})));
}

// A run whose contacts all last 0.2 ms longer than the reference's: W1 is that, relative to the
// reference's median; its identical restitutions are 0 apart; the run's peaks, disjoint from the
// reference's, have KS 1; and a reference without impacts gives no distance.
TEST(DistributionDistance, RunAgainstReferenceDistributionsByName) {
  ImpactSamples reference, run;
  reference.contact_duration_s = {2.0e-4, 2.5e-4, 3.0e-4};
  run.contact_duration_s = shifted(reference.contact_duration_s, 2e-4);
  reference.restitution = run.restitution = {0.6, 0.7, 0.8};
  reference.sensor_peak_g[0] = {10, 20, 30};
  run.sensor_peak_g[0] = {40, 50};
  const DistributionDistances d = distribution_distances(run, reference);
  const auto names = impact_distributions(run);
  for (std::size_t i = 0; i < kImpactDistributions; ++i) {
    if (names[i].stem == "contact_duration") {
      EXPECT_NEAR(d[i].wasserstein1, 2e-4, 1e-15);
      EXPECT_NEAR(d[i].wasserstein1_relative, 2e-4 / 2.5e-4, 1e-12);
      EXPECT_EQ(d[i].kolmogorov_smirnov, 1.0);  // every run contact is longer than the longest reference one
    } else if (names[i].stem == "restitution") {
      EXPECT_EQ(d[i].wasserstein1, 0.0);
      EXPECT_EQ(d[i].kolmogorov_smirnov, 0.0);
    } else if (names[i].stem == "frame1_sensor_peak") {
      EXPECT_DOUBLE_EQ(d[i].wasserstein1, 25.0);  // means 45 and 20, and every run value lies above
      EXPECT_DOUBLE_EQ(d[i].wasserstein1_relative, 25.0 / 20.0);
      EXPECT_EQ(d[i].kolmogorov_smirnov, 1.0);
    } else {
      EXPECT_TRUE(std::isnan(d[i].wasserstein1) && std::isnan(d[i].kolmogorov_smirnov)) << names[i].stem;
    }
  }
  const auto columns = flatten(d, "vs_reference_");
  ASSERT_EQ(columns.size(), 3 * kImpactDistributions);
  EXPECT_EQ(columns[0].first, "vs_reference_frame1_sensor_peak_w1_g");
  EXPECT_EQ(columns[1].first, "vs_reference_frame1_sensor_peak_w1_relative");
  EXPECT_EQ(columns[2].first, "vs_reference_frame1_sensor_peak_ks");
  EXPECT_EQ(columns.back().first, "vs_reference_restitution_ks");
}

}  // namespace distribution_distance_test
}  // namespace ib
