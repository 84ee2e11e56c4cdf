// What a time step of each engine costs on the rig, through the one Simulator interface (the engine's
// step plus the harness's per-step recording): the resonance case for 2 s at the engine's default step,
// matched contact path, every law. Counters: us_per_step (the run's own wall time per step, as runs.csv
// reports it; the benchmark's Time column adds building the model), steps per run.
//   build/bench/engine_step_benchmark [--benchmark_filter=mujoco/hertz] [--benchmark_repetitions=5]
#include <benchmark/benchmark.h>

#include <string>

#include "model/simulator.h"
#include "rig_case.h"
#include "simulators/catalog.h"

namespace {

void run_engine(benchmark::State& state, const std::string& engine, ib::ContactLaw law) {
  const ib::Scenario s = ib::bench::resonance_for_2_s();
  const ib::RunSettings settings = ib::bench::matched_path(law);
  const auto simulator = ib::make_simulator(engine);
  long long steps = 0;
  double stepping_s = 0;  // the simulators' own clock around their stepping loops
  for (auto _ : state) {
    const ib::RunResult r = simulator->run(s, settings);
    if (r.status != ib::RunStatus::ok) {
      state.SkipWithError(("the run ended " + std::string(ib::to_string(r.status)) + ": " + r.reason).c_str());
      return;
    }
    steps += r.cost.steps;
    stepping_s += r.cost.wall_time_s;
    benchmark::DoNotOptimize(r.trajectory.time_s.data());
  }
  state.counters["us_per_step"] = steps > 0 ? 1e6 * stepping_s / static_cast<double>(steps) : 0;
  state.counters["steps"] = static_cast<double>(steps) / static_cast<double>(state.iterations());
}

void register_all() {
  for (const std::string& engine : ib::simulator_names()) {
    if (engine == "reference") continue;  // adaptive, no fixed step: see reference_benchmark
    for (ib::ContactLaw law : {ib::ContactLaw::hertz, ib::ContactLaw::viscoelastic, ib::ContactLaw::newton})
      benchmark::RegisterBenchmark((engine + "/" + ib::to_string(law)).c_str(), [engine, law](benchmark::State& st) {
        run_engine(st, engine, law);
      })->Unit(benchmark::kMillisecond);
  }
}

// Registered before main runs, as Google Benchmark's own BENCHMARK() macros do.
const bool registered = (register_all(), true);

}  // namespace

BENCHMARK_MAIN();
