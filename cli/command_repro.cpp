#include "cli/commands.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "harness/jobs/shard_plan.h"
#include "harness/records/number_text.h"
#include "harness/records/run_files.h"
#include "model/scenario_toml.h"
#include "simulators/catalog.h"

namespace cli {

namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

// A run's record (RUN/summary.json, written by every run), or bad input naming what is wrong.
Json read_summary(const std::string& run_folder) {
  const std::string path = run_folder + "/summary.json";
  if (!fs::is_directory(run_folder))
    throw std::invalid_argument(run_folder + ": " + (fs::exists(run_folder) ? "not a folder" : "no such folder") +
                                "; expected a run's folder (SUITE/runs/<job id>, or a run's --out)");
  std::ifstream in(path);
  if (!in)
    throw std::invalid_argument(run_folder +
                                ": not a run's folder: it has no summary.json (a suite keeps one per run in "
                                "SUITE/runs/<job id>/)");
  const Json summary = Json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (!summary.is_object() || !summary.contains("engine") || !summary.contains("law") ||
      !summary.contains("scenario_file"))
    throw std::invalid_argument(path +
                                ": not a run's record (expected a JSON object with engine, law and scenario_file); "
                                "the folder is damaged");
  return summary;
}

std::string text_of(const Json& summary, const char* key) {
  const auto found = summary.find(key);
  return found != summary.end() && found->is_string() ? found->get<std::string>() : "";
}

double number_of(const Json& summary, const char* key) {
  const auto found = summary.find(key);
  return found != summary.end() && found->is_number() ? found->get<double>() : NAN;
}

std::string quoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// The scenario file to rerun: --scenario, else the run's own as recorded (a path as the suite was given it,
// so relative to where the suite ran), else its absolute path at run time: repro works from any folder.
std::string scenario_file_of(const Json& summary, const std::string& run_folder, const std::string& given) {
  if (!given.empty()) {
    if (!fs::exists(given)) throw std::invalid_argument("--scenario " + given + ": no such file");
    return given;
  }
  const std::string recorded = text_of(summary, "scenario_file"), absolute = text_of(summary, "scenario_file_absolute");
  if (fs::exists(recorded)) return recorded;
  if (!absolute.empty() && fs::exists(absolute)) return absolute;
  throw std::invalid_argument(run_folder + "/summary.json: scenario_file '" + recorded + "' is not there" +
                              (absolute.empty() ? "" : " (nor " + absolute + ")") + "; name it with --scenario");
}

// The run's scenario, refused when the file is not the one the run ran: another scenario (its name), or the
// same name with other content (the digest the run recorded; a run recorded before digests: its name alone).
ib::Scenario checked_scenario(const Json& summary, const std::string& run_folder, const std::string& file) {
  const ib::Scenario scenario = ib::load_scenario(file);
  const std::string ran = text_of(summary, "scenario"), digest = text_of(summary, "scenario_digest");
  if (!ran.empty() && scenario.name != ran)
    throw std::invalid_argument(file + ": scenario '" + scenario.name + "', but " + run_folder + " ran '" + ran +
                                "'; allowed: the scenario file the run ran (its summary.json: scenario_file)");
  if (digest.empty() || digest == "unreadable") return scenario;
  if (const std::string now = ib::file_digest(file); now != digest)
    throw std::invalid_argument(file + ": its content (digest " + now + ") is not the file " + run_folder +
                                " ran (summary.json scenario_digest " + digest +
                                "); allowed: that file as it was, unchanged");
  return scenario;
}

// repro.sh's lines that find impactbench: $IMPACTBENCH (a relative path taken from where the script is run, before
// it changes to its own folder), else next to the script, else on PATH, so the folder runs on another machine and
// after a rebuild elsewhere; then into the script's folder, where the run writes ./rerun.
const char* const kFindImpactbench =
    "folder=$(cd \"$(dirname \"$0\")\" && pwd)\n"
    "if [ -n \"$IMPACTBENCH\" ]; then\n"
    "  case $IMPACTBENCH in\n"
    "    */*) impactbench=$(cd \"$(dirname \"$IMPACTBENCH\")\" && pwd)/$(basename \"$IMPACTBENCH\") ;;\n"
    "    *) impactbench=$IMPACTBENCH ;;\n"
    "  esac\n"
    "elif [ -x \"$folder/impactbench\" ]; then impactbench=$folder/impactbench\n"
    "elif command -v impactbench >/dev/null 2>&1; then impactbench=impactbench\n"
    "else\n"
    "  echo \"repro.sh: impactbench not found: put it on PATH or next to this script, or set IMPACTBENCH\" >&2\n"
    "  exit 127\n"
    "fi\n"
    "cd \"$folder\"\n";

void write_file(const std::string& path, const std::string& text) {
  std::ofstream file(path);
  if (!file) throw ib::OutputError(ib::output_error_text(path, "create", errno));
  file << text;
  file.close();
  if (!file) throw ib::OutputError(ib::output_error_text(path, "write", errno));
}

// The run's options ("a=b;c=d" in its record) as the name=value pairs --option takes.
std::vector<std::string> option_pairs_of(const Json& summary) {
  std::vector<std::string> pairs;
  std::stringstream options(text_of(summary, "options"));
  for (std::string option; std::getline(options, option, ';');)
    if (!option.empty()) pairs.push_back(option);
  return pairs;
}

// The `impactbench run` arguments that rerun the recorded run from OUT/scenario.toml, into OUT/rerun.
std::vector<std::string> rerun_arguments(const Json& summary, const ib::Scenario& scenario,
                                         const std::vector<std::string>& option_pairs) {
  std::vector<std::string> arguments = {"run",   "scenario.toml",        "--engine", text_of(summary, "engine"),
                                        "--law", text_of(summary, "law")};
  const double step_s = number_of(summary, "time_step_s");
  if (step_s > 0) arguments.insert(arguments.end(), {"--dt", ib::exact_number_text(step_s)});
  for (const std::string& option : option_pairs) arguments.insert(arguments.end(), {"--option", option});
  const double duration_s = number_of(summary, "duration_s");
  if (duration_s > 0 && duration_s < scenario.duration_s)
    arguments.insert(arguments.end(), {"--duration", ib::exact_number_text(duration_s)});
  const double window_s = number_of(summary, "window_end_s") - number_of(summary, "window_start_s");
  if (window_s > 0) arguments.insert(arguments.end(), {"--window", ib::exact_number_text(window_s)});
  const double offset_m = number_of(summary, "initial_displacement_offset_m");
  if (offset_m != 0 && std::isfinite(offset_m))
    arguments.insert(arguments.end(), {"--start-offset", ib::exact_number_text(offset_m)});
  arguments.insert(arguments.end(), {"--out", "rerun", "--force"});  // its own scratch folder: each rerun replaces it
  return arguments;
}

// `repro RUN_FOLDER OUT`: one run of a result folder made ready to run alone and to file with an engine's
// authors: OUT/scenario.toml (the scenario it ran), OUT/repro.sh (the one command that reruns it, with its
// engine, law, step, options, start and length), OUT/repro.json (what it was: job, verdict, reason, engine
// version, the folder it came from) and, where the engine exports one, its model (MuJoCo: OUT/model.xml).
// scenario_path: the scenario file where the run's own record names one that is no longer there.
int command_repro(const std::string& run_folder, const std::string& out, const std::string& scenario_path) {
  const Json summary = read_summary(run_folder);
  const std::string scenario_file = scenario_file_of(summary, run_folder, scenario_path);
  const ib::Scenario scenario = checked_scenario(summary, run_folder, scenario_file);
  const std::string engine = text_of(summary, "engine");
  require_engine(engine);

  std::error_code error;
  fs::create_directories(out, error);
  if (error) throw ib::OutputError(ib::output_error_text(out, "create the folder", error.value()));
  fs::copy_file(scenario_file, out + "/scenario.toml", fs::copy_options::overwrite_existing, error);
  if (error)
    throw ib::OutputError(ib::output_error_text(out + "/scenario.toml", "copy " + scenario_file, error.value()));

  const std::vector<std::string> option_pairs = option_pairs_of(summary);
  const std::vector<std::string> arguments = rerun_arguments(summary, scenario, option_pairs);
  std::string command = "exec \"$impactbench\"";
  for (const std::string& a : arguments) command += " " + quoted(a);
  write_file(out + "/repro.sh", "#!/bin/sh\n# Reruns " + text_of(summary, "job_id") +
                                    " alone (impactbench repro; repro.json says what it was). The run goes to ./rerun,"
                                    " replacing an earlier rerun.\n" +
                                    kFindImpactbench + command + "\n");
  fs::permissions(out + "/repro.sh", fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec,
                  fs::perm_options::add, error);

  ib::RunSettings settings;
  settings.law = parse_law(text_of(summary, "law"));
  settings.time_step_s = std::max(0.0, number_of(summary, "time_step_s"));
  settings.options = parse_engine_options(option_pairs, engine);
  const std::string model = ib::make_simulator(engine)->export_model(scenario, settings);
  const std::string model_file = model.empty() ? "" : model.front() == '<' ? "model.xml" : "model.json";
  if (!model.empty()) write_file(out + "/" + model_file, model);

  const Json record = {{"job_id", text_of(summary, "job_id")},
                       {"engine", engine},
                       {"engine_version", text_of(summary, "engine_version")},
                       {"verdict", text_of(summary, "verdict")},
                       {"reason", text_of(summary, "reason")},
                       {"from_run_folder", fs::absolute(run_folder).lexically_normal().string()},
                       {"scenario_file", scenario_file},
                       {"scenario_digest", ib::file_digest(scenario_file)},
                       {"command", arguments},
                       {"model_file", model_file}};
  write_file(out + "/repro.json", record.dump(2) + "\n");
  std::error_code no_path;
  const std::string executable = fs::read_symlink("/proc/self/exe", no_path).string();
  std::printf(
      "repro: %s (%s%s) in %s\n  rerun it with: IMPACTBENCH=%s sh %s/repro.sh (without IMPACTBENCH it finds "
      "impactbench on PATH or next to itself)\n",
      text_of(summary, "job_id").c_str(), text_of(summary, "verdict").c_str(),
      text_of(summary, "reason").empty() ? "" : (": " + text_of(summary, "reason")).c_str(), out.c_str(),
      quoted(executable.empty() ? "impactbench" : executable).c_str(), out.c_str());
  return kExitOk;
}

struct ReproOptions {
  std::string run_folder, out, scenario_path;
};

}  // namespace

Command add_repro_command(CLI::App& app) {
  auto o = std::make_shared<ReproOptions>();
  CLI::App* repro =
      app.add_subcommand("repro",
                         "make one run of a result folder ready to rerun alone and to file: its "
                         "scenario, the one command that reruns it, its model where the engine exports one");
  repro->add_option("run", o->run_folder, "the run's folder (SUITE/runs/<job id>, or a run's --out)")->required();
  repro->add_option("out", o->out, "the folder to write")->required();
  repro->add_option("--scenario", o->scenario_path,
                    "the scenario file, where the one the run names is no longer there");
  return {repro, [o] { return command_repro(o->run_folder, o->out, o->scenario_path); }};
}

}  // namespace cli
