// A test engine that runs the reference on a 4-link chain under another name: it builds a 4-link chain (so
// a chain reference is planned for it) and agrees exactly with the reference on that chain.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "model/simulator.h"
#include "reference/reference_simulator.h"

namespace ib::test {

class Mirror final : public Simulator {
 public:
  std::string name() const override { return "mirror"; }
  std::string version() const override { return "test"; }
  std::vector<std::pair<std::string, std::string>> option_help() const override { return {}; }
  RunResult run(const Scenario& s, const RunSettings& settings) override {
    RunSettings chain = settings;
    chain.options = chain_reference_options(4);
    return make_reference_simulator()->run(s, chain);
  }
  std::optional<int> chain_links(const Scenario&, const RunSettings&) const override { return 4; }
};

}  // namespace ib::test
