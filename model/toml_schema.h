// A TOML schema checker: a parsed document held against tables of keys (type, range, meaning with
// unit), with messages that name the file, the line, the key, the value and what is allowed. Generic:
// model/scenario_toml.cpp holds the scenario's schema (its tables of keys) and the rules that tie keys
// together. The key tables and the Checker's rule lookup are templates over the record a table fills, so
// they stay in this header; the rest is in toml_schema.cpp.
#pragma once

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "model/scenario_toml.h"

namespace ib::toml_schema {

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
  bool identifier = false;  // strings: 1 to kIdentifierMaxLength characters, only a-z, 0-9 and _
};

inline Allowed at_least(double lo) { return {lo, true, kInfinity, false, false}; }         // x >= lo
inline Allowed above(double lo) { return {lo, false, kInfinity, false, false}; }           // x > lo
inline Allowed closed(double lo, double hi) { return {lo, true, hi, true, false}; }        // lo <= x <= hi
inline Allowed half_open(double lo, double hi) { return {lo, true, hi, false, false}; }    // lo <= x < hi
inline Allowed above_up_to(double lo, double hi) { return {lo, false, hi, true, false}; }  // lo < x <= hi
inline Allowed anything() { return {}; }  // any finite number, any string, true or false
constexpr std::size_t kIdentifierMaxLength = 64;
Allowed identifier();

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
  static_assert(std::is_same_v<T, double> || std::is_same_v<T, std::optional<double>> || std::is_same_v<T, int> ||
                    std::is_same_v<T, bool> || std::is_same_v<T, std::string>,
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
      : name(name),
        kind(kind_for<T>()),
        need(need),
        allowed(allowed),
        meaning(meaning),
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
// The tables themselves.
struct Table {
  const char* name;
  Need need;
  const char* meaning;
};

// ------------------------------------------------------------------------------------------------
// 3. The checker: holds a parsed document against the schema and words the messages.

std::string number_text(double x);

// ">= 0", "> 0", "0 <= x < 1", "1 <= x <= 3"; "" when unbounded.
std::string range_text(const Allowed& a);

bool in_range(double x, const Allowed& a);

bool is_identifier(const std::string& s);

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
      case Kind::integer:
        what = range_text(allowed);
        if (what.empty()) what = "any finite number";
        break;
      case Kind::boolean:
        what = "true or false";
        break;
      case Kind::string:
        what = allowed.identifier ? "1 to 64 characters of a-z, 0-9 and _" : "any string";
        break;
    }
    return what + " (" + meaning + ")";
  }

  // What follows "expected ": "an integer >= 1", "a number with 0 <= x < 1".
  std::string expected_text() const {
    const std::string range = range_text(allowed);
    const bool two_sided = std::isfinite(allowed.lo) && std::isfinite(allowed.hi);
    const std::string suffix = range.empty() ? "" : (two_sided ? " with " : " ") + range;
    switch (kind) {
      case Kind::number:
        return "a number" + suffix;
      case Kind::integer:
        return "an integer" + suffix;
      case Kind::boolean:
        return "a boolean (true or false)";
      case Kind::string:
        return allowed.identifier ? "a string of 1 to 64 characters of a-z, 0-9 and _" : "a string";
    }
    return "";
  }
};

const char* type_name(const toml::node& node);

inline int line_of(const toml::node& node) { return static_cast<int>(node.source().begin.line); }
inline int line_of(const toml::key& key) { return static_cast<int>(key.source().begin.line); }

std::string join(const std::vector<std::string>& items);

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
  void reject_unknown(const Section& section, const std::vector<std::string>& names, const std::string& allowed) const {
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
    fail(line_of(*first), dotted, dotted + ": unknown " + (first_node->is_table() ? "table" : "key") + "; " + allowed);
  }

  // The sub-table `name` of `parent`, described in `tables`; nullopt if optional and absent.
  std::optional<Section> section(const Section& parent, const std::vector<Table>& tables,
                                 const std::string& name) const {
    const Table& table = *std::find_if(tables.begin(), tables.end(), [&](const Table& t) { return name == t.name; });
    const std::string dotted = parent.dotted(name);
    const toml::node* node = parent.find(name);
    if (!node) {
      if (table.need == Need::optional) return std::nullopt;
      fail(parent.line, dotted, dotted + ": missing required table [" + dotted + "] (" + table.meaning + ")");
    }
    if (!node->is_table()) {
      fail(line_of(*node), dotted,
           show(dotted, *node) + ": wrong type (" + type_name(*node) + "); expected a table [" + dotted + "] (" +
               table.meaning + ")");
    }
    return Section{node->as_table(), dotted, line_of(*node)};
  }

  // Fills `out` from the section, key by key as the schema says.
  template <class Spec>
  void read(const Section& section, const std::vector<Key<Spec>>& keys, Spec& out) const {
    reject_unknown(section, names_of(keys), "allowed keys in [" + section.name + "]: " + join(names_of(keys)));
    for (const Key<Spec>& key : keys) {
      const Rule rule = rule_of(section, key);
      const toml::node* node = section.find(key.name);
      if (!node) {
        if (key.need == Need::required) {
          fail(section.line, rule.dotted, rule.dotted + ": missing required key; allowed: " + rule.allowed_text());
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
        !raw.empty() && (node.is_string() ? raw.size() >= 2 && (raw[0] == '"' || raw[0] == '\'') && raw.back() == raw[0]
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

[[noreturn]] void wrong_type(const Checker& checker, const Rule& rule, const toml::node& node);

void check_number(const Checker& checker, const Rule& rule, const toml::node& node, double x);

void store(const Checker& checker, const Rule& rule, const toml::node& node, double& field);

void store(const Checker& checker, const Rule& rule, const toml::node& node, std::optional<double>& field);

void store(const Checker& checker, const Rule& rule, const toml::node& node, int& field);

void store(const Checker& checker, const Rule& rule, const toml::node& node, bool& field);

void store(const Checker& checker, const Rule& rule, const toml::node& node, std::string& field);

// "[contact.hertz], [contact.viscoelastic], [contact.newton]": the tables of `parent`.
std::string table_list(const Section& parent, const std::vector<Table>& tables);

// "allowed tables: [scenario], [frame1], ...".
std::string allowed_tables(const Section& parent, const std::vector<Table>& tables);

std::vector<std::string> names_of(const std::vector<Table>& tables);

template <class Spec>
Rule rule_named(const Section& section, const std::vector<Key<Spec>>& keys, const std::string& name) {
  for (const Key<Spec>& key : keys) {
    if (name == key.name) return Checker::rule_of(section, key);
  }
  throw std::logic_error("scenario schema has no key " + name);
}

}  // namespace ib::toml_schema
