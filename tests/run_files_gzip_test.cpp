// The gzipped tables of a run (harness/records/run_files.h, a path ending in .gz) hold the text of the plain
// file, byte for byte, as zlib (the harness's own reader), zcat and Python's gzip module (what pandas opens
// a .gz with) read it: for an empty table (its header alone) and for a series of several MB, as long runs
// write. The writer and the readers are different libraries, so each reader is asked, not assumed.
#include <gtest/gtest.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "harness/records/run_files.h"

namespace ib {
namespace run_files_gzip_test {

namespace fs = std::filesystem;

class RunFilesGzip : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("impactbench_run_files_gzip_" + std::to_string(getpid()) + "_" +
                                         ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
    fs::create_directories(root_);
  }
  void TearDown() override { fs::remove_all(root_); }
  std::string path(const std::string& name) const { return (root_ / name).string(); }
  fs::path root_;
};

// A series whose columns vary as a run's do (a constant would compress to almost nothing and hide a
// writer that loses data past its first block).
Trajectory varying_series(std::size_t samples) {
  Trajectory t;
  t.output_rate_hz = 4096;
  for (std::size_t k = 0; k < samples; ++k) {
    const double time = static_cast<double>(k) / 4096;
    t.time_s.push_back(time);
    for (int f = 0; f < 2; ++f) {
      const double phase = (f + 1) * 61.0 * time;
      t.displacement_m[f].push_back(1e-3 * std::sin(phase));
      t.velocity_m_s[f].push_back(0.06 * std::cos(phase));
      t.acceleration_m_s2[f].push_back(-3.7 * std::sin(phase) + 1e-3 * static_cast<double>(k % 97));
      t.peak_abs_acceleration_m_s2[f].push_back(std::abs(t.acceleration_m_s2[f].back()));
    }
    t.contact_force_n.push_back(k % 40 < 3 ? 125.0 * static_cast<double>(k % 40) : 0.0);
    t.peak_contact_force_n.push_back(t.contact_force_n.back());
    t.mechanical_energy_j.push_back(1.5e-3 - 1e-9 * static_cast<double>(k));
  }
  return t;
}

// The whole text of a gzip file through zlib's own reader; "<unreadable>" when zlib reports an error,
// including the one gzread lets pass: a file cut short (Z_BUF_ERROR, "unexpected end of file").
std::string zlib_text(const std::string& gz) {
  gzFile f = gzopen(gz.c_str(), "rb");
  if (!f) return "<unreadable>";
  std::string text;
  char buffer[1 << 16];
  int n = 0;
  while ((n = gzread(f, buffer, sizeof buffer)) > 0) text.append(buffer, static_cast<std::size_t>(n));
  int error = Z_OK;
  gzerror(f, &error);
  gzclose(f);
  return n < 0 || error != Z_OK ? "<unreadable>" : text;
}

// zcat's exit status as well as its output: it writes what it could decode of a file cut short.
bool zcat_reads_as(const std::string& gz, const std::string& plain) {
  return std::system(("zcat '" + gz + "' > '" + gz + ".text' && cmp -s '" + gz + ".text' '" + plain + "'").c_str()) ==
         0;
}

bool python_gzip_reads_as(const std::string& gz, const std::string& plain) {
  const std::string script =
      R"(import gzip, sys; sys.exit(gzip.open(sys.argv[1]).read() != open(sys.argv[2], "rb").read()))";
  return std::system((std::string(IMPACTBENCH_PYTHON) + " -c '" + script + "' '" + gz + "' '" + plain + "'").c_str()) ==
         0;
}

TEST_F(RunFilesGzip, AnEmptyTableIsItsHeaderInEveryReader) {
  const Trajectory no_events;
  write_events_csv(path("events.csv.gz"), no_events);
  write_events_csv(path("events.csv"), no_events);
  const std::string plain = read_text_file(path("events.csv"));
  ASSERT_EQ(std::count(plain.begin(), plain.end(), '\n'), 1);  // the header only
  EXPECT_EQ(zlib_text(path("events.csv.gz")), plain);
  EXPECT_TRUE(zcat_reads_as(path("events.csv.gz"), path("events.csv")));
  EXPECT_TRUE(python_gzip_reads_as(path("events.csv.gz"), path("events.csv")));
  Trajectory read_back;
  read_back.events.push_back(ContactEvent{});
  read_events_csv(path("events.csv.gz"), read_back);
  EXPECT_TRUE(read_back.events.empty());
}

TEST_F(RunFilesGzip, ASeriesOfSeveralMegabytesReadsBackEqualInEveryReader) {
  const Trajectory series = varying_series(40000);
  write_series_csv(path("series.csv.gz"), series);
  write_series_csv(path("series.csv"), series);
  const std::string plain = read_text_file(path("series.csv"));
  ASSERT_GT(plain.size(), 4u << 20);
  EXPECT_LT(fs::file_size(path("series.csv.gz")), plain.size() / 2);  // compressed, not stored
  EXPECT_TRUE(zlib_text(path("series.csv.gz")) == plain);             // not EXPECT_EQ, which prints both texts (MB)
  EXPECT_TRUE(zcat_reads_as(path("series.csv.gz"), path("series.csv")));
  EXPECT_TRUE(python_gzip_reads_as(path("series.csv.gz"), path("series.csv")));

  Trajectory from_gzip, from_plain;
  read_series_csv(path("series.csv.gz"), from_gzip);
  read_series_csv(path("series.csv"), from_plain);
  ASSERT_EQ(from_gzip.size(), series.size());
  // Compared whole, not with EXPECT_EQ, which would print 40000 numbers.
  EXPECT_TRUE(from_gzip.time_s == series.time_s);  // written exactly
  EXPECT_TRUE(from_gzip.time_s == from_plain.time_s);
  for (int f = 0; f < 2; ++f) {
    EXPECT_TRUE(from_gzip.displacement_m[f] == from_plain.displacement_m[f]) << "frame " << f + 1;
    EXPECT_TRUE(from_gzip.velocity_m_s[f] == from_plain.velocity_m_s[f]) << "frame " << f + 1;
    EXPECT_TRUE(from_gzip.acceleration_m_s2[f] == from_plain.acceleration_m_s2[f]) << "frame " << f + 1;
    EXPECT_TRUE(from_gzip.peak_abs_acceleration_m_s2[f] == from_plain.peak_abs_acceleration_m_s2[f])
        << "frame " << f + 1;
  }
  EXPECT_TRUE(from_gzip.contact_force_n == from_plain.contact_force_n);
  EXPECT_TRUE(from_gzip.peak_contact_force_n == from_plain.peak_contact_force_n);
  EXPECT_TRUE(from_gzip.mechanical_energy_j == from_plain.mechanical_energy_j);
}

// A series cut short (a run stopped while writing it) is refused with its path, not read as a shorter series: a
// resumed study must not take it for a whole one. zlib's gzread alone would hand back what it could decode.
TEST_F(RunFilesGzip, ASeriesCutShortIsRefusedNotReadShort) {
  write_series_csv(path("series.csv.gz"), varying_series(4000));
  fs::resize_file(path("series.csv.gz"), fs::file_size(path("series.csv.gz")) - 9);  // the trailer's CRC and size
  Trajectory read_back;
  try {
    read_series_csv(path("series.csv.gz"), read_back);
    ADD_FAILURE() << "a series cut short was read as " << read_back.size() << " samples";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find(path("series.csv.gz")), std::string::npos) << e.what();
  }
}

}  // namespace run_files_gzip_test
}  // namespace ib
