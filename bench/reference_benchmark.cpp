// How fast the reference is: each published case and law over its full duration at the default
// settings (rtol 1e-9, 10 modes per frame). Counter sim_s_per_wall_s: simulated seconds per second.
//   build/bench/reference_benchmark [--benchmark_filter=resonance/hertz]
#include <benchmark/benchmark.h>

#include <string>

#include "model/scenario_toml.h"
#include "physics/modal_model.h"
#include "reference/reference_solver.h"

namespace {

void run_case(benchmark::State& state, const std::string& name, ib::ContactLaw law) {
  const ib::Scenario s = ib::load_scenario(std::string(IMPACTBENCH_SOURCE_DIR) + "/scenarios/paper/" + name + ".toml");
  const ib::ReferenceSettings settings;  // the defaults every run uses
  const ib::ModalModel model = ib::build_modal_model(s, law, settings.modes);
  const ib::ScoringWindow scored = ib::scoring_window(s);
  const ib::OutputWindow window{scored.start_s, scored.end_s, 4096};
  long long impacts = 0;
  for (auto _ : state) {
    const ib::ReferenceSolution r =
        ib::solve_reference(model, ib::initial_state(s, model), s.duration_s, window, settings);
    impacts = r.impacts;
    benchmark::DoNotOptimize(r.trajectory.time_s.data());
  }
  state.counters["sim_s_per_wall_s"] =
      benchmark::Counter(s.duration_s * state.iterations(), benchmark::Counter::kIsRate);
  state.counters["impacts"] = static_cast<double>(impacts);
}

void register_all() {
  for (const char* name : {"resonance", "pre_resonance", "post_resonance", "free_vibration"})
    for (ib::ContactLaw law : {ib::ContactLaw::hertz, ib::ContactLaw::viscoelastic, ib::ContactLaw::newton})
      benchmark::RegisterBenchmark((std::string(name) + "/" + ib::to_string(law)).c_str(), [name,
                                                                                            law](benchmark::State& st) {
        run_case(st, name, law);
      })->Unit(benchmark::kMillisecond);
}

// Registered before main runs, as Google Benchmark's own BENCHMARK() macros do.
const bool registered = (register_all(), true);

}  // namespace

BENCHMARK_MAIN();
