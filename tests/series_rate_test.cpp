// What a run's series file keeps at a lower rate (series_at_rate, harness/records/run_files.h): every k-th sample,
// each peak column the largest peak since the last kept sample, the events whole; and a run that writes its
// series at 2048 Hz measures exactly what it measures writing every 4096 Hz sample (the metrics read the full
// series first), while its file reads back at 2048 Hz with the same largest peaks.
#include <gtest/gtest.h>

#include <unistd.h>
#include <algorithm>
#include <filesystem>
#include <string>

#include "harness/jobs/run_job.h"
#include "harness/records/run_files.h"
#include "model/scenario_toml.h"
#include "simulators/catalog.h"

namespace ib {
namespace series_rate_test {

namespace fs = std::filesystem;

Trajectory nine_samples() {
  Trajectory t;
  t.output_rate_hz = 4096;
  t.events.push_back(ContactEvent{});
  for (int k = 0; k < 9; ++k) {
    t.time_s.push_back(k / 4096.0);
    for (int f = 0; f < 2; ++f) {
      t.displacement_m[f].push_back(1e-4 * k);
      t.velocity_m_s[f].push_back(0.01 * k);
      t.acceleration_m_s2[f].push_back(k);
      t.peak_abs_acceleration_m_s2[f].push_back(k % 2 == 1 ? 100.0 * (k + f)
                                                           : 1.0);  // the peaks fall between kept samples
    }
    t.contact_force_n.push_back(0.5 * k);
    t.peak_contact_force_n.push_back(k == 3 ? 40.0 : 0.0);
    t.mechanical_energy_j.push_back(2.0);
  }
  return t;
}

TEST(SeriesRate, EveryKthSampleWithThePeaksBetween) {
  const Trajectory full = nine_samples();
  const Trajectory kept = series_at_rate(full, 2048);
  EXPECT_DOUBLE_EQ(kept.output_rate_hz, 2048);
  ASSERT_EQ(kept.size(), 5u);  // samples 0, 2, 4, 6, 8
  EXPECT_EQ(kept.events.size(), 1u);
  for (std::size_t j = 0; j < kept.size(); ++j) {
    EXPECT_DOUBLE_EQ(kept.time_s[j], full.time_s[2 * j]);
    EXPECT_DOUBLE_EQ(kept.displacement_m[0][j], full.displacement_m[0][2 * j]);
    EXPECT_DOUBLE_EQ(kept.mechanical_energy_j[j], 2.0);
  }
  EXPECT_DOUBLE_EQ(kept.peak_abs_acceleration_m_s2[0][0], 1.0);              // the first sample closes no interval
  EXPECT_DOUBLE_EQ(kept.peak_abs_acceleration_m_s2[0][1], 100.0);            // sample 1's peak, closed by sample 2
  EXPECT_DOUBLE_EQ(kept.peak_abs_acceleration_m_s2[1][4], 100.0 * (7 + 1));  // sample 7's peak, closed by sample 8
  EXPECT_DOUBLE_EQ(kept.peak_contact_force_n[2], 40.0);                      // sample 3's, closed by sample 4
  for (int f = 0; f < 2; ++f)
    EXPECT_DOUBLE_EQ(
        *std::max_element(kept.peak_abs_acceleration_m_s2[f].begin(), kept.peak_abs_acceleration_m_s2[f].end()),
        *std::max_element(full.peak_abs_acceleration_m_s2[f].begin(), full.peak_abs_acceleration_m_s2[f].end()));
}

TEST(SeriesRate, ARateThatIsNotLowerKeepsEverySample) {
  const Trajectory full = nine_samples();
  EXPECT_EQ(series_at_rate(full, 0).size(), 9u);
  EXPECT_EQ(series_at_rate(full, 4096).size(), 9u);
  EXPECT_EQ(series_at_rate(full, 3000).size(), 9u);  // 4096 / 3000 samples: one output sample per kept one
  EXPECT_EQ(series_at_rate(full, 1024).size(), 3u);  // samples 0, 4, 8
}

TEST(SeriesRate, TheRunMeasuresTheSameAndItsFileReadsBackAtTheLowerRate) {
  Scenario scenario = load_scenario(std::string(IMPACTBENCH_SOURCE_DIR) + "/scenarios/paper/free_vibration.toml");
  scenario.duration_s = 0.5;
  scenario.scoring_window_s = 0.5;
  JobSpec job;
  job.engine = "reference";
  job.settings.law = ContactLaw::hertz;
  const fs::path root = fs::temp_directory_path() / ("impactbench_series_rate_" + std::to_string(::getpid()));
  Measurement every, halved;
  every.series = halved.series = SeriesOutput::all;
  halved.series_rate_hz = 2048;
  const RunRecord a =
      run_job(scenario, job, every, nullptr, nullptr, (root / "every").string(), nullptr, simulator_catalog().make);
  const RunRecord b =
      run_job(scenario, job, halved, nullptr, nullptr, (root / "halved").string(), nullptr, simulator_catalog().make);
  ASSERT_TRUE(a.metrics && b.metrics);
  for (int f = 0; f < 2; ++f) {
    EXPECT_EQ(a.metrics->frames[f].sensor_peak_acceleration_g, b.metrics->frames[f].sensor_peak_acceleration_g);
    EXPECT_EQ(a.metrics->frames[f].true_peak_acceleration_g, b.metrics->frames[f].true_peak_acceleration_g);
    EXPECT_EQ(a.metrics->frames[f].rms_acceleration_g, b.metrics->frames[f].rms_acceleration_g);
  }
  EXPECT_EQ(a.metrics->impacts, b.metrics->impacts);
  EXPECT_EQ(a.metrics->contact_duration_mean_s, b.metrics->contact_duration_mean_s);
  Trajectory ta, tb;
  read_series_csv(series_file((root / "every").string()), ta);
  read_series_csv(series_file((root / "halved").string()), tb);
  EXPECT_NEAR(ta.output_rate_hz, 4096, 1e-6);
  EXPECT_NEAR(tb.output_rate_hz, 2048, 1e-6);
  EXPECT_EQ(tb.size(), (ta.size() + 1) / 2);
  for (int f = 0; f < 2; ++f)
    EXPECT_EQ(*std::max_element(ta.peak_abs_acceleration_m_s2[f].begin(), ta.peak_abs_acceleration_m_s2[f].end()),
              *std::max_element(tb.peak_abs_acceleration_m_s2[f].begin(), tb.peak_abs_acceleration_m_s2[f].end()));
  EXPECT_GT(fs::file_size(root / "every" / "series.csv.gz"), fs::file_size(root / "halved" / "series.csv.gz"));
  fs::remove_all(root);
}

}  // namespace series_rate_test
}  // namespace ib
