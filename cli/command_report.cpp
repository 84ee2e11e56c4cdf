#include "cli/commands.h"

#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>

#include "harness/run_files.h"

namespace cli {

// The report is made by reports/make_report.py with Debian's matplotlib (python3-matplotlib), from
// the saved results alone.
int command_report(const std::string& suite_folder, const std::string& out) {
  // An unwritable report folder is said here, in the words of every other write error, not as a traceback.
  // (A folder without runs.csv is left to make_report.py, which says so.)
  const std::string folder = out.empty() ? suite_folder + "/report" : out;
  if (std::filesystem::exists(suite_folder + "/runs.csv")) {
    std::error_code error;
    std::filesystem::create_directories(folder, error);
    if (error) throw ib::OutputError(ib::output_error_text(folder, "create the report folder", error.value()));
    if (access(folder.c_str(), W_OK) != 0)
      throw ib::OutputError(ib::output_error_text(folder, "write into the report folder", errno));
  }
  std::string command = std::string(IMPACTBENCH_PYTHON) + " " + IMPACTBENCH_SOURCE_DIR + "/reports/make_report.py '" +
                        suite_folder + "'";
  if (!out.empty()) command += " --out '" + out + "'";
  const int status = std::system(command.c_str());
  if (status != 0) throw std::runtime_error("the report could not be made (" + command + " failed)");
  return kExitOk;
}

}  // namespace cli
