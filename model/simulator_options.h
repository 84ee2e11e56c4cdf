// Options every engine adapter reads from RunSettings::options, checked in one place: an unknown name
// or a value out of range is an error naming the engine, the option, the value and what is allowed.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace ib {

// How the contact between the tips is produced (the same three paths in every engine):
//  matched  - the engine's own contact, set to the scenario's law where it has a form for it;
//  injected - the harness computes the law's force from the tip states and applies it each step;
//  native   - the engine's own recommended contact settings, as its users would leave them.
enum class ContactPath { matched, injected, native };
const char* to_string(ContactPath path);
// Every path by name, in the order above ("matched", "injected", "native"), and a name read back.
constexpr ContactPath kContactPaths[] = {ContactPath::matched, ContactPath::injected, ContactPath::native};
std::optional<ContactPath> contact_path_from_string(const std::string& name);
// "matched, injected, native": what an option naming a path allows.
std::string contact_path_names();

class OptionReader {
 public:
  // allowed: every option name with a one-line description (the engine's option_help()).
  OptionReader(std::string engine, const std::map<std::string, std::string>& options,
               const std::vector<std::pair<std::string, std::string>>& allowed);
  std::string choice(const std::string& name, const std::string& fallback,
                     const std::vector<std::string>& values) const;
  int integer(const std::string& name, int fallback, int low, int high) const;
  double number(const std::string& name, double fallback, double low, double high) const;
  ContactPath contact_path() const;  // option "contact", default matched

 private:
  const std::string* find(const std::string& name) const;
  [[noreturn]] void reject(const std::string& name, const std::string& value, const std::string& allowed) const;
  std::string engine_;
  std::map<std::string, std::string> options_;
};

}  // namespace ib
