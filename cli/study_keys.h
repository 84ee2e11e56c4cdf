// The keys of a study file's parts (docs/studies.md, "Study files"): what each takes, the command option it
// stands for (whose checking code decides its range) and what it means. cli/study_file.cpp reads them.
#pragma once

#include <vector>

#include "cli/study_file.h"

namespace cli {

const char* kind_name(StudyPart::Kind kind);

// What a key takes; the option it stands for (its messages start with that option) and what it means.
enum class Type { text, number, integer, boolean, texts, numbers, texts_or_all };
struct KeySpec {
  const char* key;
  Type type;
  const char* option;  // the command's option the value is checked as ("" for a key of the study alone)
  const char* meaning;
  const char* also = "";  // another start of the messages about it ("engine 'x': not in this build")
};

// The keys of one kind of part: those every kind has, then its own.
std::vector<KeySpec> keys_of(StudyPart::Kind kind);

// The keys [defaults] may hold: every kind's, but a part's own name and scenarios. A part takes from [defaults]
// each key its kind has and it does not set itself.
std::vector<KeySpec> default_keys();

}  // namespace cli
