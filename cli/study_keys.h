// The keys of a study file's parts (docs/studies.md, "Study files"): what each takes, the command option it
// stands for (whose checking code decides its range) and what it means. cli/study_file.cpp reads them.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "harness/study/study.h"

namespace cli {

// What a key takes; the option it stands for (its messages start with that option) and what it means.
enum class Type { text, number, integer, boolean, texts, numbers, texts_or_all };
struct KeySpec {
  const char* key;
  Type type;
  const char* option;  // the command's option the value is checked as ("" for a key of the study alone)
  const char* meaning;
  const char* also = "";  // another start of the messages about it ("engine 'x': not in this build")
};

// The kinds of part a study file's tables hold, in the order it reads them ([[suite]], [[search]], [[sweep]],
// [[validation]]): each named by ib::to_string, as --skip names them too.
const std::vector<ib::StudyPartKind>& study_file_kinds();

// The keys of one kind of part: those every kind has, then its own.
std::vector<KeySpec> keys_of(ib::StudyPartKind kind);

// The keys [defaults] may hold: every kind's, but a part's own name and scenarios. A part takes from [defaults]
// each key its kind has and it does not set itself.
std::vector<KeySpec> default_keys();

// Which key of a part a command's message is about: the given key (key_lines: each key given, by its line) whose
// option starts the message ("--dt 0: ..."); null when none does (the message is then the part's).
const KeySpec* key_of_message(ib::StudyPartKind kind, const std::map<std::string, int>& key_lines,
                              const std::string& message);

// "all" spelled out for the key (engines: every simulator of the build; laws; paths); any other value as it is.
std::string expand_all(const std::string& key, const std::string& value, const std::vector<std::string>& engines);

// A part's engines as --engines takes them: `engines` ("all", or not given: every engine of the build) less
// `skip_engines`; "" when neither key is given (the command's default). Throws std::invalid_argument when the list
// leaves no engine: a part with nothing to run is a mistake in the file, not a study that passed.
std::string part_engines(const std::map<std::string, std::string>& given, const std::vector<std::string>& engines);

}  // namespace cli
