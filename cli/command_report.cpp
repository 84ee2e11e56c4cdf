#include "cli/commands.h"

#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <stdexcept>

#include "harness/records/reporters.h"
#include "harness/records/run_files.h"

namespace cli {

// The report is made by reports/make_report.py with Debian's matplotlib (python3-matplotlib), from
// the saved results alone.
int command_report(const std::string& suite_folder, const std::string& out) {
  // An unwritable report folder is said here, in the words of every other write error, not as a traceback.
  // (A folder without runs.csv is left to make_report.py, which says so.)
  const std::string folder = out.empty() ? suite_folder + "/report" : out;
  if (!std::filesystem::is_directory(suite_folder))
    throw std::invalid_argument(suite_folder + ": " +
                                (std::filesystem::exists(suite_folder) ? "not a folder" : "no such folder") +
                                "; expected a suite's or a sweep's output folder");
  // One record per job, run folders present: a damaged folder is said here, with what repairs it.
  if (std::filesystem::exists(suite_folder + "/runs.jsonl") || std::filesystem::exists(suite_folder + "/runs.csv")) {
    const std::vector<std::string> problems = ib::runs_table_problems(suite_folder);
    if (!problems.empty()) {
      std::string text;
      for (std::size_t i = 0; i < problems.size() && i < 5; ++i) text += (i ? "; " : "") + problems[i];
      if (problems.size() > 5) text += "; and " + std::to_string(problems.size() - 5) + " more";
      throw std::invalid_argument(
          suite_folder + ": its results are damaged (" + text +
          "); continue the suite with --resume, which repairs its records and runs again what they lack");
    }
  }
  if (std::filesystem::exists(suite_folder + "/runs.csv")) {
    std::error_code error;
    std::filesystem::create_directories(folder, error);
    if (error) throw ib::OutputError(ib::output_error_text(folder, "create the report folder", error.value()));
    if (access(folder.c_str(), W_OK) != 0)
      throw ib::OutputError(ib::output_error_text(folder, "write into the report folder", errno));
  }
  std::string command =
      std::string(IMPACTBENCH_PYTHON) + " " + IMPACTBENCH_SOURCE_DIR + "/reports/make_report.py '" + suite_folder + "'";
  if (!out.empty()) command += " --out '" + out + "'";
  const int status = std::system(command.c_str());
  if (status != 0) throw std::runtime_error("the report could not be made (" + command + " failed)");
  return kExitOk;
}

Command add_report_command(CLI::App& app) {
  auto folders = std::make_shared<std::pair<std::string, std::string>>();  // the suite's, the report's
  CLI::App* report =
      app.add_subcommand("report", "make the report (index.html, summary.md, figures) from a suite's saved results");
  report->add_option("suite", folders->first, "a suite's output folder")->required();
  report->add_option("--out", folders->second, "report folder; default: SUITE/report");
  return {report, [folders] { return command_report(folders->first, folders->second); }};
}

}  // namespace cli
