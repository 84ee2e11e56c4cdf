#include "model/toml_schema.h"

namespace ib::toml_schema {

const char* type_name(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::table:
      return "table";
    case toml::node_type::array:
      return "array";
    case toml::node_type::string:
      return "string";
    case toml::node_type::integer:
      return "integer";
    case toml::node_type::floating_point:
      return "float";
    case toml::node_type::boolean:
      return "boolean";
    case toml::node_type::date:
      return "date";
    case toml::node_type::time:
      return "time";
    case toml::node_type::date_time:
      return "date-time";
    default:
      return "nothing";
  }
}

[[noreturn]] void wrong_type(const Checker& checker, const Rule& rule, const toml::node& node) {
  checker.fail(
      line_of(node), rule.dotted,
      checker.show(rule.dotted, node) + ": wrong type (" + type_name(node) + "); expected " + rule.expected_text());
}

Allowed identifier() {
  Allowed a;
  a.identifier = true;
  return a;
}

std::string number_text(double x) {
  std::ostringstream out;
  out << x;
  return out.str();
}

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
  // a name becomes a folder name (runs/<name>/...) and a file name's part: 64 characters fit every file system
  if (s.empty() || s.size() > kIdentifierMaxLength) return false;
  return std::all_of(s.begin(), s.end(),
                     [](char c) { return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_'; });
}

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const std::string& item : items) out += (out.empty() ? "" : ", ") + item;
  return out;
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
  const double x = node.is_integer() ? static_cast<double>(node.as_integer()->get()) : node.as_floating_point()->get();
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
                 checker.show(rule.dotted, node) + ": too large for an integer; allowed: " + rule.allowed_text());
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

std::string table_list(const Section& parent, const std::vector<Table>& tables) {
  std::vector<std::string> names;
  for (const Table& t : tables) names.push_back("[" + parent.dotted(t.name) + "]");
  return join(names);
}

std::string allowed_tables(const Section& parent, const std::vector<Table>& tables) {
  return (parent.name.empty() ? "allowed tables: " : "allowed tables in [" + parent.name + "]: ") +
         table_list(parent, tables);
}

std::vector<std::string> names_of(const std::vector<Table>& tables) {
  std::vector<std::string> names;
  for (const Table& t : tables) names.push_back(t.name);
  return names;
}

}  // namespace ib::toml_schema
