// Reading scenario files. The file is laid out for a reader who wants to know what a scenario may say:
//   1. what a value may be (ranges),
//   2. THE SCHEMA: one table of keys per TOML table, with type, range and meaning with unit,
//   3. the checker that holds a parsed document against the schema and words the messages,
//   4. parse_scenario: the order of the tables and the few rules that tie keys together.
// Everything a message says about a key (its type, its range, its unit, the list of allowed keys)
// comes from the schema tables in section 2; to add a key, add a row there.
#include "model/scenario_toml.h"

#include <toml++/toml.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <functional>
#include <fstream>
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

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// ------------------------------------------------------------------------------------------------
// 1. What a value may be.

// For numbers, the range lo <= x (or lo < x) and x <= hi (or x < hi); infinite bounds are not checked.
// For strings, whether the value must be an identifier. Booleans take any value.
struct Allowed {
  double lo = -kInfinity;
  bool lo_included = false;
  double hi = kInfinity;
  bool hi_included = false;
  bool identifier = false;  // strings: non-empty, only a-z, 0-9 and _
};

Allowed at_least(double lo) { return {lo, true, kInfinity, false, false}; }          // x >= lo
Allowed above(double lo) { return {lo, false, kInfinity, false, false}; }            // x > lo
Allowed closed(double lo, double hi) { return {lo, true, hi, true, false}; }         // lo <= x <= hi
Allowed half_open(double lo, double hi) { return {lo, true, hi, false, false}; }     // lo <= x < hi
Allowed anything() { return {}; }  // any finite number, any string, true or false
Allowed identifier() {
  Allowed a;
  a.identifier = true;
  return a;
}

// ------------------------------------------------------------------------------------------------
// 2. THE SCHEMA.
//
// One row per key: its name in the file, the field it fills (whose C++ type is the TOML type asked
// for: double = a number, an integer being accepted; int = an integer; bool = true or false;
// std::string = a string), whether it must be given, what values are allowed, and what it is, with
// its unit. Keys that are not listed are rejected.

enum class Need { required, optional };
constexpr Need required = Need::required;
constexpr Need optional = Need::optional;

enum class Kind { number, integer, boolean, string };

template <class T>
constexpr Kind kind_for() {
  static_assert(std::is_same_v<T, double> || std::is_same_v<T, std::optional<double>> ||
                    std::is_same_v<T, int> || std::is_same_v<T, bool> || std::is_same_v<T, std::string>,
                "a scenario field is a double, an optional double, an int, a bool or a string");
  if constexpr (std::is_same_v<T, int>) return Kind::integer;
  if constexpr (std::is_same_v<T, bool>) return Kind::boolean;
  if constexpr (std::is_same_v<T, std::string>) return Kind::string;
  return Kind::number;
}

class Checker;
struct Rule;

// Check one value against its rule and store it in the field (defined in section 3).
void store(const Checker&, const Rule&, const toml::node&, double& field);
void store(const Checker&, const Rule&, const toml::node&, std::optional<double>& field);
void store(const Checker&, const Rule&, const toml::node&, int& field);
void store(const Checker&, const Rule&, const toml::node&, bool& field);
void store(const Checker&, const Rule&, const toml::node&, std::string& field);

template <class Spec>
struct Key {
  template <class T>
  Key(const char* name, T Spec::*field, Need need, Allowed allowed, const char* meaning)
      : name(name), kind(kind_for<T>()), need(need), allowed(allowed), meaning(meaning),
        fill([field](const Checker& checker, const Rule& rule, const toml::node& node, Spec& out) {
          store(checker, rule, node, out.*field);
        }) {}

  const char* name;
  Kind kind;  // from the field's C++ type
  Need need;
  Allowed allowed;
  const char* meaning;
  std::function<void(const Checker&, const Rule&, const toml::node&, Spec&)> fill;
};

// [scenario]
const std::vector<Key<Scenario>> kScenarioKeys = {
    {"name",             &Scenario::name,             required, identifier(), "short identifier of the scenario"},
    {"description",      &Scenario::description,      required, anything(),   "what the scenario is and what it probes"},
    {"duration_s",       &Scenario::duration_s,       required, above(0),     "simulated time [s]"},
    {"scoring_window_s", &Scenario::scoring_window_s, required, above(0),     "scoring window at the end of the run, where metrics are taken [s]"},
};

// [frame1] and [frame2]: the columns of a frame act as one clamped-free Euler-Bernoulli beam.
const std::vector<Key<FrameSpec>> kFrameKeys = {
    {"columns",            &FrameSpec::columns,            required, at_least(1),        "number of columns acting as one beam [-]"},
    {"youngs_modulus_pa",  &FrameSpec::youngs_modulus_pa,  required, above(0),           "Young's modulus E [Pa]"},
    {"density_kg_m3",      &FrameSpec::density_kg_m3,      required, above(0),           "column density rho [kg/m^3]"},
    {"column_thickness_m", &FrameSpec::column_thickness_m, required, above(0),           "column thickness h, in the bending direction [m]"},
    {"column_width_m",     &FrameSpec::column_width_m,     required, above(0),           "column width b [m]"},
    {"length_m",           &FrameSpec::length_m,           required, above(0),           "column length L [m]"},
    {"tip_mass_kg",        &FrameSpec::tip_mass_kg,        required, at_least(0),        "tip mass [kg]"},
    {"damping_ratio",      &FrameSpec::damping_ratio,      required, half_open(0, 1),    "damping ratio zeta of every mode [-]"},
};

// [rig]
const std::vector<Key<Scenario>> kRigKeys = {
    {"gap_m", &Scenario::gap_m, required, at_least(0), "surface gap d between the tips at rest [m]"},
};

// [motor]: the unbalanced motor on frame 1's tip. Exactly one of the two speeds is given
// (check_motor_speed below).
const std::vector<Key<MotorSpec>> kMotorKeys = {
    {"unbalance_mass_kg",  &MotorSpec::unbalance_mass_kg,  required, at_least(0), "unbalance mass m_u [kg]"},
    {"unbalance_radius_m", &MotorSpec::unbalance_radius_m, required, at_least(0), "unbalance radius e_u [m]"},
    {"speed_ratio_to_f1",  &MotorSpec::speed_ratio_to_f1,  optional, above(0),    "motor speed / frame 1's first natural frequency [-]"},
    {"frequency_hz",       &MotorSpec::frequency_hz,       optional, above(0),    "motor speed [Hz]"},
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
    {"stiffness",             &HertzSpec::stiffness,             required, above(0),    "Hertz stiffness k_h [N/m^n]"},
    {"exponent",              &HertzSpec::exponent,              required, closed(1, 3), "Hertz exponent n [-]"},
    {"damping",               &HertzSpec::damping,               optional, at_least(0), "explicit Hertz damping c_h [N s/m^(n+1)]"},
    {"restitution",           &HertzSpec::restitution,           optional, closed(0, 1), "coefficient of restitution e, calibrates c_h [-]"},
    {"approach_velocity_m_s", &HertzSpec::approach_velocity_m_s, optional, above(0),    "mean approach velocity v_rel, calibrates c_h [m/s]"},
};

// [contact.viscoelastic]: F = k delta + c delta'.
const std::vector<Key<ViscoelasticSpec>> kViscoelasticKeys = {
    {"stiffness_n_per_m", &ViscoelasticSpec::stiffness_n_per_m, required, above(0),    "spring stiffness k_v [N/m]"},
    {"damping_n_s_per_m", &ViscoelasticSpec::damping_n_s_per_m, required, at_least(0), "dashpot damping c_v [N s/m]"},
    {"clip_tension",      &ViscoelasticSpec::clip_tension,      optional, anything(),  "clip the force at zero rather than let it turn tensile; default false"},
};

// [contact.newton]: instantaneous impact.
const std::vector<Key<NewtonSpec>> kNewtonKeys = {
    {"restitution", &NewtonSpec::restitution, required, closed(0, 1), "coefficient of restitution e [-]"},
};

// The tables themselves.
struct Table {
  const char* name;
  Need need;
  const char* meaning;
};

const std::vector<Table> kTopLevelTables = {
    {"scenario", required, "name, description, duration and scoring window"},
    {"frame1",   required, "frame 1, which carries the motor"},
    {"frame2",   required, "frame 2"},
    {"rig",      required, "the gap between the frames"},
    {"motor",    optional, "the unbalanced motor on frame 1; absent: no motor"},
    {"initial",  optional, "the initial state; absent: everything at rest"},
    {"contact",  required, "at least one contact law: [contact.hertz], [contact.viscoelastic], [contact.newton]"},
};

// Sub-tables of [contact]; at least one is given (check in parse_scenario).
const std::vector<Table> kContactTables = {
    {"hertz",        optional, "Hertz contact with hysteresis damping"},
    {"viscoelastic", optional, "Kelvin-Voigt spring-dashpot contact"},
    {"newton",       optional, "instantaneous impact with a coefficient of restitution"},
};

// ------------------------------------------------------------------------------------------------
// 3. The checker: holds a parsed document against the schema and words the messages.

std::string number_text(double x) {
  std::ostringstream out;
  out << x;
  return out.str();
}

// ">= 0", "> 0", "0 <= x < 1", "1 <= x <= 3"; "" when unbounded.
std::string range_text(const Allowed& a) {
  const bool has_lo = std::isfinite(a.lo), has_hi = std::isfinite(a.hi);
  const std::string lo_op = a.lo_included ? "<=" : "<", hi_op = a.hi_included ? "<=" : "<";
  if (has_lo && has_hi) return number_text(a.lo) + " " + lo_op + " x " + hi_op + " " + number_text(a.hi);
  if (has_lo) return (a.lo_included ? ">= " : "> ") + number_text(a.lo);
  if (has_hi) return hi_op + " " + number_text(a.hi);
  return "";
}

bool in_range(double x, const Allowed& a) {
  if (std::isfinite(a.lo) && (a.lo_included ? x < a.lo : x <= a.lo)) return false;
  if (std::isfinite(a.hi) && (a.hi_included ? x > a.hi : x >= a.hi)) return false;
  return true;
}

bool is_identifier(const std::string& s) {
  if (s.empty()) return false;
  return std::all_of(s.begin(), s.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
  });
}

// One key as the checker sees it, whatever struct it fills.
struct Rule {
  std::string dotted;  // "frame1.tip_mass_kg"
  Kind kind;
  Allowed allowed;
  std::string meaning;

  // What follows "allowed: ": ">= 0 (tip mass [kg])".
  std::string allowed_text() const {
    std::string what;
    switch (kind) {
      case Kind::number:
      case Kind::integer: what = range_text(allowed); if (what.empty()) what = "any finite number"; break;
      case Kind::boolean: what = "true or false"; break;
      case Kind::string: what = allowed.identifier ? "a non-empty string of a-z, 0-9 and _" : "any string"; break;
    }
    return what + " (" + meaning + ")";
  }

  // What follows "expected ": "an integer >= 1", "a number with 0 <= x < 1".
  std::string expected_text() const {
    const std::string range = range_text(allowed);
    const bool two_sided = std::isfinite(allowed.lo) && std::isfinite(allowed.hi);
    const std::string suffix = range.empty() ? "" : (two_sided ? " with " : " ") + range;
    switch (kind) {
      case Kind::number: return "a number" + suffix;
      case Kind::integer: return "an integer" + suffix;
      case Kind::boolean: return "a boolean (true or false)";
      case Kind::string: return allowed.identifier ? "a string of a-z, 0-9 and _" : "a string";
    }
    return "";
  }
};

const char* type_name(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::table: return "table";
    case toml::node_type::array: return "array";
    case toml::node_type::string: return "string";
    case toml::node_type::integer: return "integer";
    case toml::node_type::floating_point: return "float";
    case toml::node_type::boolean: return "boolean";
    case toml::node_type::date: return "date";
    case toml::node_type::time: return "time";
    case toml::node_type::date_time: return "date-time";
    default: return "nothing";
  }
}

int line_of(const toml::node& node) { return static_cast<int>(node.source().begin.line); }
int line_of(const toml::key& key) { return static_cast<int>(key.source().begin.line); }

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const std::string& item : items) out += (out.empty() ? "" : ", ") + item;
  return out;
}

// A table of the document with its dotted name ("" for the document, "frame1", "contact.hertz") and
// the line of its header.
struct Section {
  const toml::table* table;
  std::string name;
  int line;

  const toml::node* find(const std::string& key) const { return table->get(key); }
  std::string dotted(const std::string& key) const { return name.empty() ? key : name + "." + key; }
};

class Checker {
 public:
  Checker(std::string path, std::string_view text) : path_(std::move(path)), text_(text) {}

  toml::table parse() const {
#if TOML_EXCEPTIONS
    try {
      return toml::parse(text_, std::string_view(path_));
    } catch (const toml::parse_error& error) {
      syntax_error(error);
    }
#else
    toml::parse_result result = toml::parse(text_, std::string_view(path_));
    if (!result) syntax_error(result.error());
    return std::move(result).table();
#endif
  }

  [[noreturn]] void fail(int line, const std::string& key, const std::string& message) const {
    throw ScenarioError(path_, line, key, message);
  }

  // "frame1.columns = 2.5": the key and its value as written in the file.
  std::string show(const std::string& dotted, const toml::node& node) const {
    const std::string value = as_written(node);
    return value.empty() ? dotted : dotted + " = " + value;
  }

  // Rejects every key of the section that is not in `names`; `allowed` lists what is allowed.
  void reject_unknown(const Section& section, const std::vector<std::string>& names,
                      const std::string& allowed) const {
    const toml::key* first = nullptr;
    const toml::node* first_node = nullptr;
    for (auto&& [key, node] : *section.table) {
      if (std::find(names.begin(), names.end(), std::string(key.str())) != names.end()) continue;
      if (!first || line_of(key) < line_of(*first)) {
        first = &key;
        first_node = &node;
      }
    }
    if (!first) return;
    const std::string dotted = section.dotted(std::string(first->str()));
    fail(line_of(*first), dotted,
         dotted + ": unknown " + (first_node->is_table() ? "table" : "key") + "; " + allowed);
  }

  // The sub-table `name` of `parent`, described in `tables`; nullopt if optional and absent.
  std::optional<Section> section(const Section& parent, const std::vector<Table>& tables,
                                 const std::string& name) const {
    const Table& table = *std::find_if(tables.begin(), tables.end(),
                                       [&](const Table& t) { return name == t.name; });
    const std::string dotted = parent.dotted(name);
    const toml::node* node = parent.find(name);
    if (!node) {
      if (table.need == Need::optional) return std::nullopt;
      fail(parent.line, dotted,
           dotted + ": missing required table [" + dotted + "] (" + table.meaning + ")");
    }
    if (!node->is_table()) {
      fail(line_of(*node), dotted,
           show(dotted, *node) + ": wrong type (" + type_name(*node) + "); expected a table [" +
               dotted + "] (" + table.meaning + ")");
    }
    return Section{node->as_table(), dotted, line_of(*node)};
  }

  // Fills `out` from the section, key by key as the schema says.
  template <class Spec>
  void read(const Section& section, const std::vector<Key<Spec>>& keys, Spec& out) const {
    reject_unknown(section, names_of(keys),
                   "allowed keys in [" + section.name + "]: " + join(names_of(keys)));
    for (const Key<Spec>& key : keys) {
      const Rule rule = rule_of(section, key);
      const toml::node* node = section.find(key.name);
      if (!node) {
        if (key.need == Need::required) {
          fail(section.line, rule.dotted,
               rule.dotted + ": missing required key; allowed: " + rule.allowed_text());
        }
        continue;
      }
      key.fill(*this, rule, *node, out);
    }
  }

  template <class Spec>
  static Rule rule_of(const Section& section, const Key<Spec>& key) {
    return Rule{section.dotted(key.name), key.kind, key.allowed, key.meaning};
  }

  template <class Spec>
  static std::vector<std::string> names_of(const std::vector<Key<Spec>>& keys) {
    std::vector<std::string> names;
    for (const Key<Spec>& key : keys) names.push_back(key.name);
    return names;
  }

 private:
  template <class ParseError>
  [[noreturn]] void syntax_error(const ParseError& error) const {
    throw ScenarioError(path_, static_cast<int>(error.source().begin.line), "",
                        "TOML syntax error: " + std::string(error.description()),
                        static_cast<int>(error.source().begin.column));
  }

  // The value as it is written in the file (so 200e9 stays 200e9), or as toml++ prints it when its
  // source cannot be cut out of one line; "" for a table.
  std::string as_written(const toml::node& node) const {
    if (node.is_table() || node.is_array_of_tables()) return "";
    const std::string raw = source_text(node.source());
    const bool plausible =
        !raw.empty() &&
        (node.is_string() ? raw.size() >= 2 && (raw[0] == '"' || raw[0] == '\'') && raw.back() == raw[0]
                          : raw.find_first_of(" \t#") == std::string::npos || node.is_array());
    if (plausible) return raw;
    if (node.is_string()) return "\"" + node.as_string()->get() + "\"";
    std::ostringstream out;
    node.visit([&](auto&& value) { out << value; });
    return out.str();
  }

  // The text of a one-line source region; toml++ counts columns in code points, from 1.
  std::string source_text(const toml::source_region& region) const {
    if (region.begin.line == 0 || region.begin.line != region.end.line || region.begin.column == 0 ||
        region.end.column <= region.begin.column) {
      return "";
    }
    std::size_t pos = 0;
    for (toml::source_index line = 1; line < region.begin.line; ++line) {
      pos = text_.find('\n', pos);
      if (pos == std::string_view::npos) return "";
      ++pos;
    }
    auto skip_code_points = [&](std::size_t from, toml::source_index count) {
      while (count > 0 && from < text_.size() && text_[from] != '\n') {
        ++from;
        while (from < text_.size() && (static_cast<unsigned char>(text_[from]) & 0xC0) == 0x80) ++from;
        --count;
      }
      return count == 0 ? from : std::string_view::npos;
    };
    const std::size_t begin = skip_code_points(pos, region.begin.column - 1);
    if (begin == std::string_view::npos) return "";
    const std::size_t end = skip_code_points(begin, region.end.column - region.begin.column);
    if (end == std::string_view::npos) return "";
    return std::string(text_.substr(begin, end - begin));
  }

  std::string path_;
  std::string_view text_;
};

// The checks of one value, by the type of the field it fills.

[[noreturn]] void wrong_type(const Checker& checker, const Rule& rule, const toml::node& node) {
  checker.fail(line_of(node), rule.dotted,
               checker.show(rule.dotted, node) + ": wrong type (" + type_name(node) + "); expected " +
                   rule.expected_text());
}

void check_number(const Checker& checker, const Rule& rule, const toml::node& node, double x) {
  if (!std::isfinite(x)) {
    checker.fail(line_of(node), rule.dotted,
                 checker.show(rule.dotted, node) + ": not a finite number; allowed: " + rule.allowed_text());
  }
  if (!in_range(x, rule.allowed)) {
    checker.fail(line_of(node), rule.dotted,
                 checker.show(rule.dotted, node) + ": out of range; allowed: " + rule.allowed_text());
  }
}

void store(const Checker& checker, const Rule& rule, const toml::node& node, double& field) {
  if (!node.is_number()) wrong_type(checker, rule, node);
  const double x = node.is_integer() ? static_cast<double>(node.as_integer()->get())
                                     : node.as_floating_point()->get();
  check_number(checker, rule, node, x);
  field = x;
}

void store(const Checker& checker, const Rule& rule, const toml::node& node, std::optional<double>& field) {
  double x = 0;
  store(checker, rule, node, x);
  field = x;
}

void store(const Checker& checker, const Rule& rule, const toml::node& node, int& field) {
  if (!node.is_integer()) wrong_type(checker, rule, node);
  const std::int64_t n = node.as_integer()->get();
  check_number(checker, rule, node, static_cast<double>(n));
  if (n < std::numeric_limits<int>::min() || n > std::numeric_limits<int>::max()) {
    checker.fail(line_of(node), rule.dotted,
                 checker.show(rule.dotted, node) + ": too large for an integer; allowed: " +
                     rule.allowed_text());
  }
  field = static_cast<int>(n);
}

void store(const Checker& checker, const Rule& rule, const toml::node& node, bool& field) {
  if (!node.is_boolean()) wrong_type(checker, rule, node);
  field = node.as_boolean()->get();
}

void store(const Checker& checker, const Rule& rule, const toml::node& node, std::string& field) {
  if (!node.is_string()) wrong_type(checker, rule, node);
  const std::string& text = node.as_string()->get();
  if (rule.allowed.identifier && !is_identifier(text)) {
    checker.fail(line_of(node), rule.dotted,
                 checker.show(rule.dotted, node) + ": not a valid name; allowed: " + rule.allowed_text());
  }
  field = text;
}

// "[contact.hertz], [contact.viscoelastic], [contact.newton]": the tables of `parent`.
std::string table_list(const Section& parent, const std::vector<Table>& tables) {
  std::vector<std::string> names;
  for (const Table& t : tables) names.push_back("[" + parent.dotted(t.name) + "]");
  return join(names);
}

// "allowed tables: [scenario], [frame1], ...".
std::string allowed_tables(const Section& parent, const std::vector<Table>& tables) {
  return (parent.name.empty() ? "allowed tables: " : "allowed tables in [" + parent.name + "]: ") +
         table_list(parent, tables);
}

std::vector<std::string> names_of(const std::vector<Table>& tables) {
  std::vector<std::string> names;
  for (const Table& t : tables) names.push_back(t.name);
  return names;
}

template <class Spec>
Rule rule_named(const Section& section, const std::vector<Key<Spec>>& keys, const std::string& name) {
  for (const Key<Spec>& key : keys) {
    if (name == key.name) return Checker::rule_of(section, key);
  }
  throw std::logic_error("scenario schema has no key " + name);
}

// ------------------------------------------------------------------------------------------------
// 4. The rules that tie keys together.

// The scoring window lies within the run.
void check_scoring_window(const Checker& checker, const Section& section, const Scenario& s) {
  if (s.scoring_window_s <= s.duration_s) return;
  const Rule rule = rule_named(section, kScenarioKeys, "scoring_window_s");
  const toml::node& node = *section.find("scoring_window_s");
  checker.fail(line_of(node), rule.dotted,
               checker.show(rule.dotted, node) + ": out of range; allowed: 0 < x <= " +
                   section.dotted("duration_s") + " = " + number_text(s.duration_s) + " (" +
                   rule.meaning + ")");
}

// The motor speed is given exactly once: as a ratio of f_1 or in Hz.
void check_motor_speed(const Checker& checker, const Section& section) {
  const Rule ratio = rule_named(section, kMotorKeys, "speed_ratio_to_f1");
  const Rule hz = rule_named(section, kMotorKeys, "frequency_hz");
  const std::string allowed = "allowed: exactly one of " + ratio.dotted + " " + ratio.allowed_text() +
                              " or " + hz.dotted + " " + hz.allowed_text();
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
                 checker.show(last.dotted, last_node) + ": conflicts with " +
                     checker.show(first.dotted, first_node) + " (line " +
                     std::to_string(line_of(first_node)) + "); " + allowed);
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
                       checker.show(section.dotted(name), *other) + " (line " +
                       std::to_string(line_of(*other)) + "); allowed: either " + dotted +
                       " alone (explicit c_h) or " + section.dotted("restitution") + " with " +
                       section.dotted("approach_velocity_m_s") + " (c_h = 3 k_h (1 - e^2) / (4 v_rel))");
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

  checker.read(*checker.section(top, kTopLevelTables, "frame1"), kFrameKeys, s.frames[0]);
  checker.read(*checker.section(top, kTopLevelTables, "frame2"), kFrameKeys, s.frames[1]);
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

Scenario load_scenario(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw ScenarioError(path, 0, "", "cannot read scenario file: it is a directory");
  }
  errno = 0;
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    const int error = errno;
    throw ScenarioError(path, 0, "",
                        "cannot read scenario file: " +
                            std::string(error != 0 ? std::strerror(error) : "cannot open"));
  }
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw ScenarioError(path, 0, "", "cannot read scenario file: read error");
  return parse_scenario(text.str(), path);
}

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
    if (it->is_regular_file(type_ec) && it->path().extension() == ".toml") {
      files.push_back(it->path().string());
    }
  }
  if (ec) throw ScenarioError(folder, 0, "", "cannot read scenario folder: " + ec.message());
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace ib
