#include "reference/reference_simulator.h"

#include "model/run_clock.h"
#include "physics/modal_model.h"
#include "reference/modal_model_json.h"

#include <chrono>
#include <cmath>
#include <ctime>
#include <limits>
#include <stdexcept>
#include <string>

namespace ib {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

const std::vector<std::pair<std::string, std::string>> kOptions = {
    {"modes",
     "mode set: beam (continuous beam, default), beam_paper (the paper's eq. 2.5 shapes), chain (the engines' K-link "
     "chain)"},
    {"n", "modes per frame for the beam mode sets, 1..200 (default 10)"},
    {"links", "links K per frame for the chain mode set, 1..1000 (default 16)"},
    {kChainDampingOption, std::string("for the chain mode set, as the engines': ") + kChainDampingOptionHelp},
    {"rtol", "relative tolerance of the contact integrator, > 0 (default 1e-9)"},
    {"atol", "absolute tolerance on modal coordinates, > 0 (default 1e-12)"},
    {"grid", "free-flight scan points per period of the fastest mode, >= 4 (default 8)"},
    {"slow_modes",
     "modes per frame resolved by the coarse free-flight steps, taken where no contact can start, 0 = fine grid only "
     "(default 3)"},
    {"accumulation_time", "Newton law: stick when impacts would accumulate within this time [s], >= 0 (default 1e-6)"},
    {"energy", "keep the energy ledger: on (default) or off"},
};

double parse_number(const std::string& key, const std::string& text, const std::string& allowed) {
  std::size_t used = 0;
  double value = 0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || !std::isfinite(value))
    throw std::invalid_argument("reference option " + key + "=" + text + ": not a number; allowed: " + allowed);
  return value;
}

void require(bool ok, const std::string& key, const std::string& text, const std::string& allowed) {
  if (!ok) throw std::invalid_argument("reference option " + key + "=" + text + ": out of range; allowed: " + allowed);
}

int parse_integer(const std::string& key, const std::string& text, int low, int high) {
  const std::string allowed = "an integer " + std::to_string(low) + ".." + std::to_string(high);
  const double value = parse_number(key, text, allowed);
  require(value == std::floor(value) && value >= low && value <= high, key, text, allowed);
  return static_cast<int>(value);
}

// What the reference's saved state holds: its modal coordinates, then their velocities.
std::string state_layout(const ModalModel& model, const ModeSelection& modes) {
  return "modal q then v of " + std::to_string(model.mode_count()) + " modes (" + to_string(modes.set) + ")";
}

// Where a run starts: the scenario's initial state, or the saved state it continues from.
ModalState start_state(const Scenario& scenario, const ModalModel& model, const RunSettings& run,
                       const ModeSelection& modes) {
  if (!run.initial_state) return initial_state(scenario, model);
  check_saved_state(*run.initial_state, "reference", state_layout(model, modes));
  const int n = model.mode_count();
  if (static_cast<int>(run.initial_state->values.size()) != 2 * n)
    throw std::invalid_argument("a saved reference state of " + std::to_string(run.initial_state->values.size()) +
                                " values for " + std::to_string(n) + " modes (needs " + std::to_string(2 * n) + ")");
  ModalState x;
  x.q = Eigen::Map<const Eigen::VectorXd>(run.initial_state->values.data(), n);
  x.v = Eigen::Map<const Eigen::VectorXd>(run.initial_state->values.data() + n, n);
  return x;
}

// The impact zoom's margin before the onset and after the end [s].
constexpr double kZoomMargin_s = 1e-3;

// The first impact in the series window (the one every simulator's zoom shows: step_recorder.h) sampled at
// 1 MHz from 1 ms before its onset to 1 ms after its end, for the report's zoom: the run solved again from
// the last free flight that began before the zoom (the run kept its state there), or from the start when
// none did. The solver is deterministic: the same phases, the free flight's steps aside (its own output
// window decides where it scans finely), so the same motion to rounding. Empty when the window has no impact.
Trajectory zoom_on_first_impact(const ModalModel& model, const Scenario& scenario, const ReferenceSolution& run,
                                const OutputWindow& window, const ReferenceSettings& settings,
                                const ModalState& start) {
  const ContactEvent* first = nullptr;
  for (const ContactEvent& e : run.trajectory.events)
    if (e.onset_time_s >= window.start_s && (!first || e.onset_time_s < first->onset_time_s)) first = &e;
  if (!first) return {};
  const OutputWindow zoom{std::max(0.0, first->onset_time_s - kZoomMargin_s),
                          std::min(scenario.duration_s, first->end_time_s + kZoomMargin_s), 1e6};
  ReferenceSettings quiet = settings;
  quiet.track_energy = false;
  quiet.keep_flight_starts_from_s = kInf;
  const FlightStart* from = nullptr;
  for (const FlightStart& f : run.flight_starts)
    if (f.t_s <= zoom.start_s) from = &f;
  if (from) return solve_reference_after_contact(model, *from, zoom.end_s, zoom, quiet).trajectory;
  return solve_reference(model, start, zoom.end_s, zoom, quiet).trajectory;
}

// The reference's modal model as JSON (reference/modal_model_json.h), for the run `run` would make
// with the same scenario, law, options and --rate: for another solver to integrate the same equations.
std::string reference_model_json(const Scenario& scenario, const RunSettings& settings) {
  if (settings.time_step_s != 0)
    throw std::invalid_argument("--dt " + std::to_string(settings.time_step_s) +
                                ": the reference is adaptive; allowed: no --dt");
  if (!(settings.output_rate_hz > 0))
    throw std::invalid_argument("--rate " + std::to_string(settings.output_rate_hz) + ": allowed: > 0 Hz");
  const ReferenceSettings reference = reference_settings_from_options(settings.options);
  const ModalModel model = build_modal_model(scenario, settings.law, reference.modes);
  ModelRunInfo run;
  run.scenario_name = scenario.name;
  run.scenario_file = scenario.source_path;
  run.duration_s = scenario.duration_s;
  run.scoring_window = scoring_window(scenario);
  run.series_start_s = run.scoring_window.start_s;  // as `run` samples it
  run.output_rate_hz = settings.output_rate_hz;
  return modal_model_json(model, initial_state(scenario, model), run, reference);
}

class ReferenceSimulator final : public Simulator {
 public:
  std::string name() const override { return "reference"; }
  std::string version() const override { return "impactbench reference (modal, Dormand-Prince 5(4))"; }
  std::vector<std::pair<std::string, std::string>> option_help() const override { return kOptions; }

  void check_settings(const RunSettings& run) const override { reference_settings_from_options(run.options); }
  std::string export_model(const Scenario& scenario, const RunSettings& settings) const override {
    return reference_model_json(scenario, settings);
  }

  RunResult run(const Scenario& scenario, const RunSettings& run) override {
    const ReferenceSettings settings = reference_settings_from_options(run.options);
    const RunClock clock;
    const ModalModel model = build_modal_model(scenario, run.law, settings.modes);
    OutputWindow window;
    window.start_s = series_start_s(run, scenario);
    window.end_s = scenario.duration_s;
    window.rate_hz = run.output_rate_hz;
    const ModalState start = start_state(scenario, model, run, settings.modes);
    ReferenceSettings kept = settings;  // the free flights the impact zoom can start from
    kept.keep_flight_starts_from_s = window.start_s - kZoomMargin_s;
    kept.peaks_between_samples = run.peaks_between_samples;
    ReferenceSolution solution = solve_reference(model, start, scenario.duration_s, window, kept);
    RunResult result;
    clock.stop_into(result.cost);
    result.cost.steps = solution.integrator_steps + solution.grid_intervals + solution.coarse_intervals;
    // after the cost is taken: the zoom is the report's, not the run's
    result.impact_zoom = zoom_on_first_impact(model, scenario, solution, window, settings, start);
    if (solution.status == RunStatus::ok) {
      SavedState end{"reference", state_layout(model, settings.modes), {}};
      end.values.assign(solution.final_state.q.data(), solution.final_state.q.data() + model.mode_count());
      end.values.insert(end.values.end(), solution.final_state.v.data(),
                        solution.final_state.v.data() + model.mode_count());
      result.final_state = std::move(end);
    }
    result.trajectory = std::move(solution.trajectory);
    result.trajectory.initial_mechanical_energy_j = solution.energy.initial_energy_j;
    result.status = solution.status;
    result.reason = solution.reason;
    auto& d = result.diagnostics;
    d.emplace_back("frame1_first_frequency_hz", model.frames[0].omega_rad_s[0] / (2 * M_PI));
    d.emplace_back("frame2_first_frequency_hz", model.frames[1].omega_rad_s[0] / (2 * M_PI));
    d.emplace_back("motor_frequency_hz", motor_frequency_hz(scenario));
    d.emplace_back("modes_per_frame", model.frame_mode_count(0));
    d.emplace_back("grid_step_s", solution.grid_step_s);
    d.emplace_back("integrator_steps", static_cast<double>(solution.integrator_steps));
    d.emplace_back("grid_intervals", static_cast<double>(solution.grid_intervals));
    d.emplace_back("coarse_intervals", static_cast<double>(solution.coarse_intervals));
    d.emplace_back("sticking_phases", static_cast<double>(solution.sticking_phases));
    if (settings.track_energy) {
      const EnergyLedger& e = solution.energy;
      d.emplace_back("energy_initial_j", e.initial_energy_j);
      d.emplace_back("energy_final_j", e.final_energy_j);
      d.emplace_back("motor_work_j", e.motor_work_j);
      d.emplace_back("structural_dissipation_j", e.structural_dissipation_j);
      d.emplace_back("contact_dissipation_j", e.contact_dissipation_j);
      d.emplace_back("energy_balance_relative_residual", e.relative_residual());
    }
    return result;
  }
};

}  // namespace

ReferenceSettings reference_settings_from_options(const std::map<std::string, std::string>& options) {
  ReferenceSettings s;
  for (const auto& [key, text] : options) {
    if (key == "modes") {
      if (text == "beam")
        s.modes.set = ModeSet::beam;
      else if (text == "beam_paper")
        s.modes.set = ModeSet::beam_paper;
      else if (text == "chain")
        s.modes.set = ModeSet::chain;
      else
        throw std::invalid_argument("reference option modes=" + text +
                                    ": unknown mode set; allowed: beam, beam_paper, chain");
    } else if (key == "n") {
      s.modes.modes_per_frame = parse_integer(key, text, 1, 200);
    } else if (key == "links") {
      s.modes.chain_links = parse_integer(key, text, 1, 1000);
    } else if (key == kChainDampingOption) {
      const auto damping = chain_damping_from_string(text);
      if (!damping)
        throw std::invalid_argument("reference option " + key + "=" + text + ": allowed: " + kChainDampingValues);
      s.modes.chain_damping = *damping;
    } else if (key == "rtol" || key == "atol") {
      const double v = parse_number(key, text, "a number > 0");
      require(v > 0, key, text, "a number > 0");
      (key == "rtol" ? s.relative_tolerance : s.absolute_tolerance) = v;
    } else if (key == "grid") {
      s.grid_points_per_period = parse_integer(key, text, 4, 1000);
    } else if (key == "slow_modes") {
      s.slow_modes_per_frame = parse_integer(key, text, 0, 200);
    } else if (key == "accumulation_time") {
      s.accumulation_time_s = parse_number(key, text, "a time >= 0 [s]");
      require(s.accumulation_time_s >= 0, key, text, "a time >= 0 [s]");
    } else if (key == "energy") {
      if (text != "on" && text != "off")
        throw std::invalid_argument("reference option energy=" + text + ": allowed: on, off");
      s.track_energy = text == "on";
    } else {
      std::string names;
      for (const auto& option : kOptions) names += (names.empty() ? "" : ", ") + option.first;
      throw std::invalid_argument("unknown reference option '" + key + "'; allowed: " + names);
    }
  }
  return s;
}

std::map<std::string, std::string> chain_reference_options(int links) {
  return {{"modes", "chain"}, {"links", std::to_string(links)}};
}

std::map<std::string, std::string> chain_reference_options_with_damping(int links, ChainDamping damping) {
  auto options = chain_reference_options(links);
  if (damping != ChainDamping::modal) options[kChainDampingOption] = to_string(damping);
  return options;
}

std::unique_ptr<Simulator> make_reference_simulator() { return std::make_unique<ReferenceSimulator>(); }

}  // namespace ib
