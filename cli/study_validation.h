// A study file's [[validation]] parts (docs/studies.md, "Study files"; harness/validation/validation_part.h): their
// own keys read beyond a suite's, and the part as the study runs it.
#pragma once

#include <string>

#include "cli/study_part_options.h"

namespace cli {

// A [[validation]]'s own keys beyond a suite's: its name (its folder), its inputs file, its sample size and the
// nominal cases' starts; a mistake fails through the checker, naming its line.
void read_validation_keys(const ib::toml_schema::Checker& checker, GivenKeys& given, const std::string& dotted,
                          PartOptions& part);

// The part, checked as a suite's and more (its inputs file read, every case movable by it), before anything runs.
ib::StudyPart validation_part(const PartOptions& part);

}  // namespace cli
