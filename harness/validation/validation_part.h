// The reference against the experiment (docs/validation.md): a study part, [[validation]] in a study file, that
// draws a sample of a rig's uncertain inputs (input_sample.h), writes each published case's scenario at every
// point and runs them, one run per point, with the nominal cases' ensemble and tight reference beside, as suites
// of their own in OUT/validation/NAME (so the study's own tables keep only the published cases), on the study's
// pool. The report sets the sample's distributions beside the
// experiment's values (reports/impactbench_report/validation.py).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "harness/study/study.h"
#include "model/uncertain_inputs.h"

namespace ib {

// Three suites into one folder, each checked as a suite's: the sample (its inputs the published cases' files,
// which prepare replaces by the points' files), the nominal rig from several starts (its chaos, kept apart from
// the inputs' spread) and the nominal rig at tight tolerances from one (the reference's numerical error).
struct ValidationSettings {
  SuiteSettings sample;
  SuiteSettings nominal;
  SuiteSettings tight;
  UncertainInputs inputs;  // what the sample draws from
  int points = 64;         // sample points per case, >= 1
};

class ValidationPart final : public PartOfItsOwnKind {
 public:
  explicit ValidationPart(ValidationSettings settings);
  std::string kind() const override { return "validation"; }
  std::unique_ptr<UnitSource> prepare(const std::string& folder, const StudySettings& study) const override;
  std::string plan(const std::string& folder) const override;
  // every case at every point, from its nominal starts and once at tight tolerances; the reference's CPU from its
  // measured cost over each case as cut (a post-resonance point costs far more than it: no impacts, its tips near)
  std::optional<Work> planned_work() const override;
  CampaignEnd finish(UnitSource& source) const override;

 private:
  ValidationSettings settings_;
};

}  // namespace ib
