// A new metric is one entry of the catalog (harness/scoring/metric_catalog.h) as far as the result folder and
// the report are concerned: a toy metric added to the catalog reaches metrics.json, and the report's reader
// (reports/impactbench_report/metric_catalog.py) scores with it: its columns, unit, kind, tolerance and step
// search, and the report's case table lists it. The other places a real metric touches (its value and error,
// its tolerance, the verdict): docs/layout.md, "A new metric".
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "harness/records/metrics_file.h"
#include "harness/records/run_files.h"
#include "harness/scoring/metric_catalog.h"

namespace ib {
namespace new_metric_test {

namespace fs = std::filesystem;

// The mean restitution of the impacts, scored as a difference; a toy: a real metric has its own tolerance in
// AccuracyTolerances and its error in MetricErrors, where this one borrows impacts per cycle's.
ScoredMetric toy_metric() {
  ScoredMetric m;
  m.name = "toy_restitution";
  m.label = "toy restitution";
  m.column = "mean_restitution";
  m.unit = "-";
  m.error_column = "toy_restitution_difference";
  m.kind = ErrorKind::difference;
  m.tolerance_key = "toy_restitution_difference";
  m.tolerance = &AccuracyTolerances::impacts_per_cycle_difference;
  m.error_of = [](const MetricErrors& e) { return e.impacts_per_cycle_difference; };
  m.step_searched = true;
  m.scored_against = {"beam"};
  return m;
}

// What the Python reader makes of DIR/metrics.json: one line per answer.
std::string python_reads(const std::string& dir) {
  const std::string script =
      "import sys; sys.path.insert(0, sys.argv[1] + '/reports'); "
      "from impactbench_report import metric_catalog as c, tables; c.use(sys.argv[2]); "
      "m = c.by_name('toy_restitution'); "
      "print(m.column, m.unit, m.kind, m.tolerance_key, m.default_tolerance, m.scored_against, m.step_prefix); "
      "print(len(c.SCORED), c.DEFAULT_TOLERANCES['toy_restitution_difference'], m in c.STEP_SEARCHED); "
      "print(tables.case_metrics()[-1][0])";
  const std::string command =
      std::string(IMPACTBENCH_PYTHON) + " -c \"" + script + "\" '" + IMPACTBENCH_SOURCE_DIR + "' '" + dir + "' 2>&1";
  std::string out;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return "popen failed";
  char buffer[512];
  while (std::fgets(buffer, sizeof buffer, pipe) != nullptr) out += buffer;
  ::pclose(pipe);
  return out;
}

TEST(NewMetric, TheCatalogsEntryReachesMetricsJsonAndTheReport) {
  std::vector<ScoredMetric> catalog = scored_metrics();
  catalog.push_back(toy_metric());
  AccuracyTolerances defaults;
  defaults.impacts_per_cycle_difference = 0.05;
  const fs::path dir = fs::temp_directory_path() / ("impactbench_new_metric_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  replace_text_file((dir / "metrics.json").string(), metrics_json(catalog, defaults));
  const std::string read = python_reads(dir.string());
  fs::remove_all(dir);
  EXPECT_EQ(read,
            "mean_restitution - difference toy_restitution_difference 0.05 ('beam',) toy_restitution\n"
            "6 0.05 True\n"
            "toy restitution [-]\n");
}

}  // namespace new_metric_test
}  // namespace ib
