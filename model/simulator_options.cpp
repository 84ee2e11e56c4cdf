#include "model/simulator_options.h"

#include <charconv>
#include <cmath>
#include <optional>
#include <stdexcept>

namespace ib {

const char* to_string(ContactPath path) {
  switch (path) {
    case ContactPath::matched:
      return "matched";
    case ContactPath::injected:
      return "injected";
    case ContactPath::native:
      return "native";
  }
  return "?";
}

std::optional<ContactPath> contact_path_from_string(const std::string& name) {
  for (ContactPath p : kContactPaths)
    if (name == to_string(p)) return p;
  return std::nullopt;
}

std::string contact_path_names() {
  std::string names;
  for (ContactPath p : kContactPaths) names += (names.empty() ? "" : ", ") + std::string(to_string(p));
  return names;
}

OptionReader::OptionReader(std::string engine, const std::map<std::string, std::string>& options,
                           const std::vector<std::pair<std::string, std::string>>& allowed)
    : engine_(std::move(engine)), options_(options) {
  for (const auto& [name, value] : options) {
    bool known = false;
    std::string names;
    for (const auto& option : allowed) {
      known = known || option.first == name;
      names += (names.empty() ? "" : ", ") + option.first;
    }
    if (!known) throw std::invalid_argument("unknown " + engine_ + " option '" + name + "'; allowed: " + names);
  }
}

const std::string* OptionReader::find(const std::string& name) const {
  const auto it = options_.find(name);
  return it == options_.end() ? nullptr : &it->second;
}

void OptionReader::reject(const std::string& name, const std::string& value, const std::string& allowed) const {
  throw std::invalid_argument(engine_ + " option " + name + "=" + value + ": allowed: " + allowed);
}

std::string OptionReader::choice(const std::string& name, const std::string& fallback,
                                 const std::vector<std::string>& values) const {
  const std::string* value = find(name);
  if (!value) return fallback;
  std::string list;
  for (const auto& v : values) {
    if (v == *value) return v;
    list += (list.empty() ? "" : ", ") + v;
  }
  reject(name, *value, list);
}

namespace {

// A bound as a person writes it: the shortest text that reads back as the same double (64, 0.001, 1e-06),
// not std::to_string's six fixed decimals.
std::string bound_text(double bound) {
  char text[32];
  return std::string(text, std::to_chars(text, text + sizeof text, bound).ptr);
}

// VALUE as a finite number, or nothing when it is not one in full ("2x", "nan", "").
std::optional<double> finite_number(const std::string& value) {
  std::size_t used = 0;
  double v = 0;
  try {
    v = std::stod(value, &used);
  } catch (const std::exception&) {
    return std::nullopt;
  }
  if (used != value.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

}  // namespace

double OptionReader::number(const std::string& name, double fallback, double low, double high) const {
  const std::string* value = find(name);
  if (!value) return fallback;
  const std::optional<double> v = finite_number(*value);
  if (!v || *v < low || *v > high) reject(name, *value, "a number from " + bound_text(low) + " to " + bound_text(high));
  return *v;
}

int OptionReader::integer(const std::string& name, int fallback, int low, int high) const {
  const std::string* value = find(name);
  if (!value) return fallback;
  const std::optional<double> v = finite_number(*value);
  if (!v || *v != std::floor(*v) || *v < low || *v > high)
    reject(name, *value, "an integer from " + std::to_string(low) + " to " + std::to_string(high));
  return static_cast<int>(*v);
}

ContactPath OptionReader::contact_path() const {
  std::vector<std::string> names;
  for (ContactPath p : kContactPaths) names.push_back(to_string(p));
  return *contact_path_from_string(choice("contact", "matched", names));
}

}  // namespace ib
