// How much the chains ring like the beam (issue 31, item 4): for the beam reference, the reference on the
// engines' K-link chain and every engine of the build (matched Hertz contact, 5e-5 s), each with the chain's damping
// modal and hinge (physics/link_chain.h):
//  - the 60 to 90 Hz content of frame 1's and frame 2's tip acceleration (the second mode's band, 74 Hz) on
//    the resonance case's default-study window (scenarios/paper/resonance.toml cut to 20 s, scored over the
//    last 10 s, studies/default.toml) as an RMS and as a share of the beam reference's;
//  - the free decay of modes 1 and 2 of frame 1 (no contact: gap 1 m, released from a 20 um static tip-load
//    shape, 0.4 s sampled at 5 kHz; the matrix pencil of tests/modal_identification.h on the tip velocity,
//    where mode 2 weighs omega_2 / omega_1 more than in the displacement), against the beam's zeta.
// Prints a table (Markdown) and, with --csv FILE, writes it as CSV. Nothing is asserted; CPU times are the
// runs' own (RunResult::cost), to be read with the machine's load.
//
// Usage: chain_ringing [--links K] [--only NAME,NAME] [--csv FILE] [--series DIR]
// (--series: each resonance run's window as DIR/<simulator>_<damping>.csv: t, both tip accelerations)
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "modal_identification.h"
#include "model/scenario.h"
#include "model/scenario_toml.h"
#include "physics/link_chain.h"
#include "reference/reference_simulator.h"
#include "simulators/catalog.h"

namespace {

constexpr double kBandLow_hz = 60, kBandHigh_hz = 90;
constexpr double kSeriesRate_hz = 4096;
constexpr double kStep_s = 5e-5;

// sqrt of the power of x between low and high [Hz] (one-sided, Parseval on the record's DFT bins, the
// mean removed): the RMS of x band-passed to [low, high] with an ideal filter.
double band_rms(const std::vector<double>& x, double rate_hz, double low_hz, double high_hz) {
  const std::size_t n = x.size();
  double mean = 0;
  for (double v : x) mean += v;
  mean /= static_cast<double>(n);
  const double bin_hz = rate_hz / static_cast<double>(n);
  double power = 0;
  for (auto k = static_cast<std::size_t>(std::ceil(low_hz / bin_hz)); k * bin_hz <= high_hz; ++k) {
    // Goertzel's recurrence for bin k
    const double w = 2 * M_PI * static_cast<double>(k) / static_cast<double>(n), coefficient = 2 * std::cos(w);
    double s1 = 0, s2 = 0;
    for (double v : x) {
      const double s0 = (v - mean) + coefficient * s1 - s2;
      s2 = s1;
      s1 = s0;
    }
    const double re = s1 - s2 * std::cos(w), im = s2 * std::sin(w);
    power += 2 * (re * re + im * im) / (static_cast<double>(n) * static_cast<double>(n));
  }
  return std::sqrt(power);
}

struct Row {
  std::string simulator, damping;
  std::string status;
  double rms_m_s2[2] = {NAN, NAN};
  double share[2] = {NAN, NAN};
  double frequency_hz[2] = {NAN, NAN};
  double zeta[2] = {NAN, NAN};
  double cpu_s = NAN;
};

ib::RunResult run(const std::string& simulator, const ib::Scenario& s, ib::RunSettings settings) {
  return ib::make_simulator(simulator)->run(s, settings);
}

// Modes 1 and 2 (by frequency, among the pencil's two most energetic) of frame 1's free decay.
void free_decay(const std::string& simulator, const std::map<std::string, std::string>& options, int order, Row& row) {
  ib::Scenario s = ib::load_scenario(std::string(IMPACTBENCH_SOURCE_DIR) + "/scenarios/paper/free_vibration.toml");
  s.gap_m = 1.0;
  s.initial.frame1_tip_displacement_m = -2e-5;
  s.duration_s = 0.4;
  s.scoring_window_s = s.duration_s;
  ib::RunSettings settings;
  settings.law = ib::ContactLaw::hertz;
  settings.time_step_s = simulator == "reference" ? 0 : kStep_s;
  settings.output_rate_hz = 5000;
  settings.series_start_s = 0;
  settings.options = options;
  const ib::RunResult r = run(simulator, s, settings);
  if (r.status != ib::RunStatus::ok) return;
  std::vector<ib::test::DampedMode> modes =
      ib::test::matrix_pencil_modes(r.trajectory.velocity_m_s[0], 1 / settings.output_rate_hz, order);
  if (modes.size() < 2) return;
  modes.resize(2);
  if (modes[1].frequency_hz < modes[0].frequency_hz) std::swap(modes[0], modes[1]);
  for (int n = 0; n < 2; ++n) {
    row.frequency_hz[n] = modes[n].frequency_hz;
    row.zeta[n] = modes[n].damping_ratio;
  }
}

std::string series_folder;  // --series

void write_series(const std::string& name, const ib::Trajectory& t) {
  std::string file = series_folder + "/" + name + ".csv";
  for (char& c : file)
    if (c == ' ' || c == '=') c = '_';
  std::ofstream out(file);
  out.precision(9);
  out << "t_s,frame1_acceleration_m_s2,frame2_acceleration_m_s2,frame1_displacement_m,frame2_displacement_m\n";
  for (std::size_t k = 0; k < t.time_s.size(); ++k)
    out << t.time_s[k] << "," << t.acceleration_m_s2[0][k] << "," << t.acceleration_m_s2[1][k] << ","
        << t.displacement_m[0][k] << "," << t.displacement_m[1][k] << "\n";
}

Row measure(const std::string& label, const std::string& simulator, const std::string& damping,
            const std::map<std::string, std::string>& options, int order, const double beam_rms[2]) {
  ib::Scenario s = ib::load_scenario(std::string(IMPACTBENCH_SOURCE_DIR) + "/scenarios/paper/resonance.toml");
  ib::cut_run(s, 20);
  s.scoring_window_s = 10;
  ib::RunSettings settings;
  settings.law = ib::ContactLaw::hertz;
  settings.time_step_s = simulator == "reference" ? 0 : kStep_s;
  settings.output_rate_hz = kSeriesRate_hz;
  settings.series_start_s = ib::scoring_window(s).start_s;
  settings.options = options;
  Row row{label, damping, "", {NAN, NAN}, {NAN, NAN}, {NAN, NAN}, {NAN, NAN}, NAN};
  const ib::RunResult r = run(simulator, s, settings);
  row.status = ib::to_string(r.status);
  row.cpu_s = r.cost.cpu_time_s;
  if (r.status == ib::RunStatus::ok)
    for (int f = 0; f < 2; ++f) {
      row.rms_m_s2[f] = band_rms(r.trajectory.acceleration_m_s2[f], kSeriesRate_hz, kBandLow_hz, kBandHigh_hz);
      row.share[f] = beam_rms ? row.rms_m_s2[f] / beam_rms[f] : 1.0;
    }
  if (!series_folder.empty() && r.status == ib::RunStatus::ok) write_series(label + "_" + damping, r.trajectory);
  free_decay(simulator, options, order, row);
  std::fprintf(stderr, "%s (%s): %s, %.1f s CPU, %zu impacts in the run\n", label.c_str(), damping.c_str(),
               row.status.c_str(), row.cpu_s, r.trajectory.events.size());
  return row;
}

}  // namespace

int main(int argc, char** argv) {
  int links = 8;
  std::string only, csv;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i];
    if (key == "--links")
      links = std::atoi(argv[i + 1]);
    else if (key == "--only")
      only = "," + std::string(argv[i + 1]) + ",";
    else if (key == "--csv")
      csv = argv[i + 1];
    else if (key == "--series")
      series_folder = argv[i + 1];
    else {
      std::fprintf(
          stderr,
          "chain_ringing: unknown argument %s; allowed: --links K, --only NAME,NAME, --csv FILE, --series DIR\n",
          argv[i]);
      return 2;
    }
  }
  auto wanted = [&](const std::string& name) {
    return only.empty() || only.find("," + name + ",") != std::string::npos;
  };
  std::vector<Row> rows;
  // the beam reference: 10 modes per frame, the pencil asked for 2 x 10 poles
  rows.push_back(measure("beam reference", "reference", "-", {}, 20, nullptr));
  const double beam_rms[2] = {rows[0].rms_m_s2[0], rows[0].rms_m_s2[1]};
  for (ib::ChainDamping damping : {ib::ChainDamping::hinge, ib::ChainDamping::modal}) {
    const std::string d = ib::to_string(damping);
    if (wanted("chain"))
      rows.push_back(measure("chain reference K=" + std::to_string(links), "reference", d,
                             ib::chain_reference_options_with_damping(links, damping), 2 * links, beam_rms));
    for (const std::string& engine : ib::simulator_catalog().names)  // the engines of this build, the catalog's order
      if (engine != "reference" && wanted(engine))
        rows.push_back(measure(engine, engine, d,
                               {{"contact", "matched"}, {"links", std::to_string(links)}, {ib::kChainDampingOption, d}},
                               2 * links, beam_rms));
  }
  std::printf(
      "| simulator | chain damping | 60-90 Hz RMS frame 1 [m/s^2] (share of beam) | frame 2 | mode 1 f [Hz], zeta | "
      "mode 2 f [Hz], zeta | CPU [s] |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  for (const Row& r : rows)
    std::printf("| %s | %s | %.3g (%.0f %%) | %.3g (%.0f %%) | %.3f, %.5f | %.2f, %.5f | %.1f%s |\n",
                r.simulator.c_str(), r.damping.c_str(), r.rms_m_s2[0], 100 * r.share[0], r.rms_m_s2[1],
                100 * r.share[1], r.frequency_hz[0], r.zeta[0], r.frequency_hz[1], r.zeta[1], r.cpu_s,
                r.status == "ok" ? "" : (" " + r.status).c_str());
  if (!csv.empty()) {
    std::ofstream out(csv);
    out << "simulator,chain_damping,status,rms_60_90_hz_frame1_m_s2,rms_60_90_hz_frame2_m_s2,share_of_beam_frame1,"
           "share_of_beam_frame2,mode1_frequency_hz,mode1_zeta,mode2_frequency_hz,mode2_zeta\n";
    out.precision(6);
    for (const Row& r : rows)
      out << r.simulator << "," << r.damping << "," << r.status << "," << r.rms_m_s2[0] << "," << r.rms_m_s2[1] << ","
          << r.share[0] << "," << r.share[1] << "," << r.frequency_hz[0] << "," << r.zeta[0] << "," << r.frequency_hz[1]
          << "," << r.zeta[1] << "\n";
  }
  return 0;
}
