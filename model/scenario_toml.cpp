// Reading scenario files. The file is laid out for a reader who wants to know what a scenario may say:
//   2. THE SCHEMA: one table of keys per TOML table, with type, range and meaning with unit,
//   4. parse_scenario: the order of the tables and the few rules that tie keys together.
// Sections 1 (what a value may be: ranges) and 3 (the checker that holds a parsed document against the
// schema and words the messages) are generic and live in model/toml_schema.h.
// Everything a message says about a key (its type, its range, its unit, the list of allowed keys)
// comes from the schema tables in section 2; to add a key, add a row there.
#include "model/scenario_toml.h"

#include "model/toml_schema.h"

#include <toml++/toml.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <optional>
#include <sstream>
#include <type_traits>
#include <utility>

namespace ib {

namespace {

std::string location(const std::string& path, int line, int column) {
  std::string where = path;
  if (line > 0) where += ":" + std::to_string(line);
  if (line > 0 && column > 0) where += ":" + std::to_string(column);
  return where + ": ";
}

}  // namespace

ScenarioError::ScenarioError(std::string path, int line, std::string key, std::string message, int column)
    : std::runtime_error(location(path, line, column) + message),
      path_(std::move(path)),
      line_(line),
      column_(column),
      key_(std::move(key)),
      message_(std::move(message)) {}

namespace {

using namespace toml_schema;  // what a value may be, Key, Table and the Checker (model/toml_schema.h)

// ------------------------------------------------------------------------------------------------
// 2. THE SCHEMA: one table of keys per TOML table (model/toml_schema.h says what a row holds).

const std::vector<Key<Scenario>> kScenarioKeys = {
    {"name", &Scenario::name, required, identifier(), "short identifier of the scenario"},
    {"description", &Scenario::description, required, anything(), "what the scenario is and what it probes"},
    {"duration_s", &Scenario::duration_s, required, above_up_to(0, 3600),
     "simulated time [s], up to an hour of rig time"},
    {"scoring_window_s", &Scenario::scoring_window_s, required, above_up_to(0, 3600),
     "scoring window at the end of the run, where metrics are taken [s]"},
};

// [frame1] and [frame2]: the columns of a frame act as one clamped-free Euler-Bernoulli beam.
const std::vector<Key<FrameSpec>> kFrameKeys = {
    {"columns", &FrameSpec::columns, required, at_least(1), "number of columns acting as one beam [-]"},
    {"youngs_modulus_pa", &FrameSpec::youngs_modulus_pa, required, closed(1e5, 1.5e12),
     "Young's modulus E [Pa]: soft rubber to diamond"},
    {"density_kg_m3", &FrameSpec::density_kg_m3, required, closed(10, 25e3),
     "column density rho [kg/m^3]: foam to osmium"},
    {"column_thickness_m", &FrameSpec::column_thickness_m, required, closed(1e-5, 1),
     "column thickness h, in the bending direction [m] (and L/h >= 10: a slender beam)"},
    {"column_width_m", &FrameSpec::column_width_m, required, closed(1e-5, 10), "column width b [m]"},
    {"length_m", &FrameSpec::length_m, required, closed(1e-3, 100), "column length L [m]"},
    {"tip_mass_kg", &FrameSpec::tip_mass_kg, required, closed(0, 1e4), "tip mass [kg]"},
    {"damping_ratio", &FrameSpec::damping_ratio, required, half_open(0, 1), "damping ratio zeta of every mode [-]"},
};

// [rig]
const std::vector<Key<Scenario>> kRigKeys = {
    {"gap_m", &Scenario::gap_m, required, closed(0, 0.1), "surface gap d between the tips at rest [m]"},
};

// [motor]: the unbalanced motor on frame 1's tip. Exactly one of the two speeds is given
// (check_motor_speed below).
const std::vector<Key<MotorSpec>> kMotorKeys = {
    {"unbalance_mass_kg", &MotorSpec::unbalance_mass_kg, required, closed(0, 100), "unbalance mass m_u [kg]"},
    {"unbalance_radius_m", &MotorSpec::unbalance_radius_m, required, closed(0, 1), "unbalance radius e_u [m]"},
    {"speed_ratio_to_f1", &MotorSpec::speed_ratio_to_f1, optional, above_up_to(0, 100),
     "motor speed / frame 1's first natural frequency [-]"},
    {"frequency_hz", &MotorSpec::frequency_hz, optional, above_up_to(0, 1e4), "motor speed [Hz]"},
};

// [initial]: frame 1 released from rest in its static tip-load shape. The displacement is also
// limited to frame1.length_m / 10 (check_initial_displacement below).
const std::vector<Key<InitialSpec>> kInitialKeys = {
    {"frame1_tip_displacement_m", &InitialSpec::frame1_tip_displacement_m, optional, anything(),
     "frame 1's initial tip displacement, positive toward frame 2 [m]"},
};

// [contact.hertz]: F = k delta^n (1 + c/k delta'). c_h is either given (damping) or calibrated from
// restitution and approach_velocity_m_s, never both (check_hertz_damping below).
const std::vector<Key<HertzSpec>> kHertzKeys = {
    {"stiffness", &HertzSpec::stiffness, required, above_up_to(0, 1e15), "Hertz stiffness k_h [N/m^n]"},
    {"exponent", &HertzSpec::exponent, required, closed(1, 3), "Hertz exponent n [-]"},
    {"damping", &HertzSpec::damping, optional, closed(0, 1e15), "explicit Hertz damping c_h [N s/m^(n+1)]"},
    {"restitution", &HertzSpec::restitution, optional, closed(0, 1),
     "coefficient of restitution e, calibrates c_h [-]"},
    {"approach_velocity_m_s", &HertzSpec::approach_velocity_m_s, optional, above_up_to(0, 100),
     "mean approach velocity v_rel, calibrates c_h [m/s]"},
};

// [contact.viscoelastic]: F = k delta + c delta'.
const std::vector<Key<ViscoelasticSpec>> kViscoelasticKeys = {
    {"stiffness_n_per_m", &ViscoelasticSpec::stiffness_n_per_m, required, above_up_to(0, 1e13),
     "spring stiffness k_v [N/m]"},
    {"damping_n_s_per_m", &ViscoelasticSpec::damping_n_s_per_m, required, closed(0, 1e9),
     "dashpot damping c_v [N s/m]"},
    {"clip_tension", &ViscoelasticSpec::clip_tension, optional, anything(),
     "clip the force at zero rather than let it turn tensile; default false"},
};

// [contact.newton]: instantaneous impact.
const std::vector<Key<NewtonSpec>> kNewtonKeys = {
    {"restitution", &NewtonSpec::restitution, required, closed(0, 1), "coefficient of restitution e [-]"},
};

const std::vector<Table> kTopLevelTables = {
    {"scenario", required, "name, description, duration and scoring window"},
    {"frame1", required, "frame 1, which carries the motor"},
    {"frame2", required, "frame 2"},
    {"rig", required, "the gap between the frames"},
    {"motor", optional, "the unbalanced motor on frame 1; absent: no motor"},
    {"initial", optional, "the initial state; absent: everything at rest"},
    {"contact", required, "at least one contact law: [contact.hertz], [contact.viscoelastic], [contact.newton]"},
};

// Sub-tables of [contact]; at least one is given (check in parse_scenario).
const std::vector<Table> kContactTables = {
    {"hertz", optional, "Hertz contact with hysteresis damping"},
    {"viscoelastic", optional, "Kelvin-Voigt spring-dashpot contact"},
    {"newton", optional, "instantaneous impact with a coefficient of restitution"},
};

// ------------------------------------------------------------------------------------------------
// 4. The rules that tie keys together.

// The scoring window lies within the run.
void check_scoring_window(const Checker& checker, const Section& section, const Scenario& s) {
  if (s.scoring_window_s <= s.duration_s) return;
  const Rule rule = rule_named(section, kScenarioKeys, "scoring_window_s");
  const toml::node& node = *section.find("scoring_window_s");
  checker.fail(line_of(node), rule.dotted,
               checker.show(rule.dotted, node) + ": out of range; allowed: 0 < x <= " + section.dotted("duration_s") +
                   " = " + number_text(s.duration_s) + " (" + rule.meaning + ")");
}

// The motor speed is given exactly once: as a ratio of f_1 or in Hz.
void check_motor_speed(const Checker& checker, const Section& section) {
  const Rule ratio = rule_named(section, kMotorKeys, "speed_ratio_to_f1");
  const Rule hz = rule_named(section, kMotorKeys, "frequency_hz");
  const std::string allowed = "allowed: exactly one of " + ratio.dotted + " " + ratio.allowed_text() + " or " +
                              hz.dotted + " " + hz.allowed_text();
  const toml::node* ratio_node = section.find("speed_ratio_to_f1");
  const toml::node* hz_node = section.find("frequency_hz");
  if (!ratio_node && !hz_node) {
    checker.fail(section.line, section.name, section.name + ": the motor speed is missing; " + allowed);
  }
  if (ratio_node && hz_node) {
    // Report at the one written second.
    const bool hz_last = line_of(*hz_node) >= line_of(*ratio_node);
    const Rule& last = hz_last ? hz : ratio;
    const Rule& first = hz_last ? ratio : hz;
    const toml::node& last_node = hz_last ? *hz_node : *ratio_node;
    const toml::node& first_node = hz_last ? *ratio_node : *hz_node;
    checker.fail(line_of(last_node), last.dotted,
                 checker.show(last.dotted, last_node) + ": conflicts with " + checker.show(first.dotted, first_node) +
                     " (line " + std::to_string(line_of(first_node)) + "); " + allowed);
  }
}

// Small-deflection theory: the initial tip displacement is at most a tenth of the frame's length.
void check_initial_displacement(const Checker& checker, const Section& section, const Scenario& s) {
  const toml::node* node = section.find("frame1_tip_displacement_m");
  const double limit = s.frames[0].length_m / 10;
  if (!node || std::abs(s.initial.frame1_tip_displacement_m) <= limit) return;
  const Rule rule = rule_named(section, kInitialKeys, "frame1_tip_displacement_m");
  checker.fail(line_of(*node), rule.dotted,
               checker.show(rule.dotted, *node) + ": out of range; allowed: |x| <= frame1.length_m / 10 = " +
                   number_text(limit) + " (small-deflection theory; " + rule.meaning + ")");
}

// Euler-Bernoulli theory holds for slender columns (length at least 10 thicknesses); and the first natural
// frequency of each frame, estimated from the cantilever with a tip mass (Rayleigh: k = 3EI/L^3, mass
// M + 33/140 m), lies where a run of the rig can resolve it: 0.05 Hz (hours per cycle) to 5 kHz (its
// higher modes beyond any step an engine takes). Both fail for values each within its own range (a
// column 1 m thick, a tip mass of tonnes on a thin strip).
void check_frame_shape(const Checker& checker, const Section& section, const FrameSpec& f) {
  const toml::node* thickness = section.find("column_thickness_m");
  if (thickness && f.length_m < 10 * f.column_thickness_m)
    checker.fail(line_of(*thickness), section.dotted("column_thickness_m"),
                 checker.show(section.dotted("column_thickness_m"), *thickness) + ": out of range; allowed: x <= " +
                     section.dotted("length_m") + " / 10 = " + number_text(f.length_m / 10) +
                     " (a slender column, as Euler-Bernoulli theory assumes)");
  constexpr double kPi = 3.14159265358979323846;
  const double area = f.column_width_m * f.column_thickness_m,
               inertia = f.column_width_m * std::pow(f.column_thickness_m, 3) / 12;
  const double stiffness = f.columns * 3 * f.youngs_modulus_pa * inertia / std::pow(f.length_m, 3);
  const double mass = f.tip_mass_kg + 33.0 / 140.0 * f.columns * f.density_kg_m3 * area * f.length_m;
  const double f1_hz = std::sqrt(stiffness / mass) / (2 * kPi);
  if (f1_hz >= 0.05 && f1_hz <= 5e3) return;
  checker.fail(section.line, section.name,
               section.name + ": its first natural frequency would be about " + number_text(f1_hz) + " Hz (from " +
                   section.dotted("youngs_modulus_pa") + " = " + number_text(f.youngs_modulus_pa) + ", " +
                   section.dotted("column_thickness_m") + " = " + number_text(f.column_thickness_m) + ", " +
                   section.dotted("length_m") + " = " + number_text(f.length_m) + ", " + section.dotted("tip_mass_kg") +
                   " = " + number_text(f.tip_mass_kg) + "); allowed: 0.05 to 5000 Hz (the published rig: 6.95 Hz)");
}

// c_h is either given (damping) or calibrated (restitution and approach_velocity_m_s), not both.
void check_hertz_damping(const Checker& checker, const Section& section) {
  const std::vector<std::string> calibration = {"restitution", "approach_velocity_m_s"};
  const toml::node* damping = section.find("damping");
  if (damping) {
    for (const std::string& name : calibration) {
      const toml::node* other = section.find(name);
      if (!other) continue;
      const std::string dotted = section.dotted("damping");
      checker.fail(line_of(*damping), dotted,
                   checker.show(dotted, *damping) + ": ambiguous together with " +
                       checker.show(section.dotted(name), *other) + " (line " + std::to_string(line_of(*other)) +
                       "); allowed: either " + dotted + " alone (explicit c_h) or " + section.dotted("restitution") +
                       " with " + section.dotted("approach_velocity_m_s") + " (c_h = 3 k_h (1 - e^2) / (4 v_rel))");
    }
    return;
  }
  for (const std::string& name : calibration) {
    if (section.find(name)) continue;
    const Rule rule = rule_named(section, kHertzKeys, name);
    checker.fail(section.line, rule.dotted,
                 rule.dotted + ": missing required key; allowed: " + rule.allowed_text() +
                     "; it may be left out only when " + section.dotted("damping") + " is given");
  }
}

}  // namespace

Scenario parse_scenario(std::string_view toml_text, const std::string& source_path) {
  const Checker checker(source_path, toml_text);
  const toml::table document = checker.parse();
  const Section top{&document, "", 1};
  checker.reject_unknown(top, names_of(kTopLevelTables), allowed_tables(top, kTopLevelTables));

  Scenario s;
  s.source_path = source_path;

  const Section scenario = *checker.section(top, kTopLevelTables, "scenario");
  checker.read(scenario, kScenarioKeys, s);
  check_scoring_window(checker, scenario, s);

  for (int i = 0; i < 2; ++i) {
    const Section frame = *checker.section(top, kTopLevelTables, i == 0 ? "frame1" : "frame2");
    checker.read(frame, kFrameKeys, s.frames[i]);
    check_frame_shape(checker, frame, s.frames[i]);
  }
  checker.read(*checker.section(top, kTopLevelTables, "rig"), kRigKeys, s);

  if (const auto motor = checker.section(top, kTopLevelTables, "motor")) {
    checker.read(*motor, kMotorKeys, s.motor.emplace());
    check_motor_speed(checker, *motor);
  }

  if (const auto initial = checker.section(top, kTopLevelTables, "initial")) {
    checker.read(*initial, kInitialKeys, s.initial);
    check_initial_displacement(checker, *initial, s);
  }

  const Section contact = *checker.section(top, kTopLevelTables, "contact");
  checker.reject_unknown(contact, names_of(kContactTables), allowed_tables(contact, kContactTables));
  if (const auto hertz = checker.section(contact, kContactTables, "hertz")) {
    checker.read(*hertz, kHertzKeys, s.contact.hertz.emplace());
    check_hertz_damping(checker, *hertz);
  }
  if (const auto viscoelastic = checker.section(contact, kContactTables, "viscoelastic")) {
    checker.read(*viscoelastic, kViscoelasticKeys, s.contact.viscoelastic.emplace());
  }
  if (const auto newton = checker.section(contact, kContactTables, "newton")) {
    checker.read(*newton, kNewtonKeys, s.contact.newton.emplace());
  }
  if (!s.contact.hertz && !s.contact.viscoelastic && !s.contact.newton) {
    checker.fail(contact.line, contact.name,
                 contact.name + ": no contact law given; allowed: at least one of the tables " +
                     table_list(contact, kContactTables));
  }
  return s;
}

std::string read_toml_file(const std::string& path, const std::string& what) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw ScenarioError(path, 0, "", "cannot read " + what + ": it is a directory");
  }
  // A FIFO would block forever and /dev/zero never end: a scenario (or an inputs file) is a regular file of at
  // most 1 MB (the published ones are 2 kB).
  constexpr std::uintmax_t kMaxScenarioBytes = 1 << 20;
  if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec))
    throw ScenarioError(path, 0, "",
                        "cannot read " + what + ": not a regular file (a FIFO, a device?); allowed: a .toml file");
  if (std::filesystem::is_regular_file(path, ec) && std::filesystem::file_size(path, ec) > kMaxScenarioBytes)
    throw ScenarioError(path, 0, "",
                        "cannot read " + what + ": " + std::to_string(std::filesystem::file_size(path, ec)) +
                            " bytes; allowed: at most 1 MB");
  errno = 0;
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    const int error = errno;
    throw ScenarioError(path, 0, "",
                        "cannot read " + what + ": " + std::string(error != 0 ? std::strerror(error) : "cannot open"));
  }
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw ScenarioError(path, 0, "", "cannot read " + what + ": read error");
  return text.str();
}

Scenario load_scenario(const std::string& path) { return parse_scenario(read_toml_file(path, "scenario file"), path); }

std::vector<std::string> find_scenario_files(const std::string& folder) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) {
    throw ScenarioError(folder, 0, "",
                        "cannot read scenario folder: " +
                            (ec ? ec.message() : std::string(fs::exists(folder) ? "not a folder" : "no such folder")));
  }
  std::vector<std::string> files;
  for (fs::recursive_directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    std::error_code type_ec;
    // an *_inputs.toml beside the scenarios is a validation's uncertain inputs (model/uncertain_inputs.h)
    const std::string file_name = it->path().filename().string();
    const bool inputs_file = file_name.size() > 12 && file_name.compare(file_name.size() - 12, 12, "_inputs.toml") == 0;
    if (it->is_regular_file(type_ec) && it->path().extension() == ".toml" && !inputs_file) {
      files.push_back(it->path().string());
    }
  }
  if (ec) throw ScenarioError(folder, 0, "", "cannot read scenario folder: " + ec.message());
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace ib
