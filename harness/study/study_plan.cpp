// `study --plan`: what each part runs, one line each (study.h, describe_study).
#include <string>
#include <vector>

#include "harness/records/number_text.h"
#include "harness/study/study.h"

namespace ib {

namespace {

// As the command line's lists read: comma-separated, no spaces.
std::string comma_list(const std::vector<std::string>& items) {
  std::string text;
  for (const std::string& item : items) text += (text.empty() ? "" : ",") + item;
  return text;
}

std::string laws_text(const std::vector<ContactLaw>& laws) {
  std::vector<std::string> names;
  for (ContactLaw law : laws) names.push_back(to_string(law));
  return comma_list(names);
}

std::string steps_text(const std::vector<double>& steps_s) {
  std::vector<std::string> texts;
  for (double dt : steps_s) texts.push_back(number_text(dt));
  return texts.empty() ? std::string("default") : comma_list(texts);
}

// What decides a part's runs beyond its matrix: the window, the rates, what is kept, the options and the time
// limit, so that two study files with the same plan lines run the same runs. (A sweep's window is its own:
// with_window false.)
std::string measured_text(const MatrixSettings& s, bool with_window = true) {
  const Measurement& m = s.measurement;
  std::string text = "; rate " + number_text(s.output_rate_hz) + " Hz, sensor " + number_text(m.sensor_rate_hz) +
                     " Hz" +
                     (!with_window ? ""
                      : m.window_s ? "; window " + number_text(*m.window_s) + " s"
                                   : std::string("; window the scenario's")) +
                     "; series " +
                     (m.series == SeriesOutput::none  ? "none"
                      : m.series == SeriesOutput::all ? "all"
                                                      : "window");
  if (m.series_rate_hz > 0) text += " at " + number_text(m.series_rate_hz) + " Hz";
  std::vector<std::string> options;
  for (const auto& [name, value] : s.reference_options) options.push_back("reference." + name + "=" + value);
  for (const auto& [engine, set] : s.engine_options)
    for (const auto& [name, value] : set) options.push_back(engine + "." + name + "=" + value);
  if (!options.empty()) text += "; options " + comma_list(options);
  return text + "; time limit " + number_text(s.time_limit_s) + " s";
}

std::string suite_line(const std::string& name, const SuiteSettings& s) {
  const std::string starts = s.ensemble.reference_starts == 1
                                 ? ""
                                 : "; starts " + std::to_string(s.ensemble.engine_starts) + " (references " +
                                       std::to_string(s.ensemble.reference_starts) + ")";
  std::vector<std::string> links;
  for (int k : s.reference_chain_links) links.push_back(std::to_string(k));
  const std::string chains = links.empty() ? "" : "; the reference on chains of " + comma_list(links) + " links";
  std::string more =
      (s.max_duration_s > 0 ? "; cut to " + number_text(s.max_duration_s) + " s" : "") + measured_text(s);
  if (s.ensemble.reference_starts > 1) more += "; start step " + number_text(s.ensemble.displacement_step_m) + " m";
  if (s.step_search)
    more += "; " + std::string(s.step_search->walk ? "walk" : "bisection") + " over " +
            number_text(s.step_search->min_step_s) + " to " + number_text(s.step_search->max_step_s) + " s, " +
            std::to_string(s.step_search->points_per_octave) + " per octave" +
            (s.keep_probe_series ? ", probes' series kept" : "");
  const std::string paths = s.recommended             ? "recommended"
                            : s.contact_paths.empty() ? "default"
                                                      : comma_list(s.contact_paths);
  const std::string steps = s.step_search ? "searched" : s.recommended ? "recommended" : steps_text(s.time_steps_s);
  return std::string(s.step_search ? "search" : "suite") + " \"" + name + "\": " + comma_list(s.inputs) + "; engines " +
         comma_list(s.engines) + "; laws " + laws_text(s.laws) + "; paths " + paths + "; dt_s " + steps + starts +
         chains + more;
}

std::string sweep_line(const std::string& name, const SweepSettings& s) {
  std::vector<std::string> starts, ratios;
  for (SweepStart start : s.starts) starts.push_back(to_string(start));
  for (double ratio : s.ensemble.ratios) ratios.push_back(number_text(ratio));
  std::string more = "; starts " + comma_list(starts) + "; from rest " +
                     (s.rest_duration_s ? number_text(*s.rest_duration_s) + " s" : std::string("the scenario's")) +
                     ", continued " + number_text(s.continuation_duration_s) + " s, window " + number_text(s.window_s) +
                     " s";
  if (s.ensemble.reference_starts > 1)
    more += "; the reference from " + std::to_string(s.ensemble.reference_starts) + " starts " +
            number_text(s.ensemble.displacement_step_m) + " m apart at " +
            (ratios.empty() ? std::string("every ratio") : comma_list(ratios));
  more += measured_text(s, false);
  return "sweep \"" + name + "\": " + s.scenario_path + "; " + std::to_string(s.ratios.size()) + " ratios; engines " +
         comma_list(s.engines) + "; laws " + laws_text(s.laws) + "; paths " +
         (s.contact_paths.empty() ? "default" : comma_list(s.contact_paths)) + "; dt_s " + steps_text(s.time_steps_s) +
         more + " -> " + s.out;
}

}  // namespace

std::vector<std::string> describe_study(const std::vector<StudyPart>& parts, const StudySettings& settings) {
  const std::vector<StudyPart> placed = place_study_parts(parts, settings);
  std::vector<std::string> lines;
  for (const StudyPart& part : placed)
    if (const auto* suite = std::get_if<SuiteSettings>(&part.settings)) lines.push_back(suite_line(part.name, *suite));
  for (const StudyPart& part : placed)
    if (const auto* sweep = std::get_if<SweepSettings>(&part.settings)) lines.push_back(sweep_line(part.name, *sweep));
  for (const StudyPart& part : placed)
    if (const auto* own = std::get_if<std::shared_ptr<const PartOfItsOwnKind>>(&part.settings))
      lines.push_back((*own)->kind() + " \"" + part.name +
                      "\": " + (*own)->plan(folder_of(**own, part.name, settings)));
  return lines;
}

}  // namespace ib
