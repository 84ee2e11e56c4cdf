// What the harness costs on top of the engine: each engine's run through the Simulator interface
// (model built from the scenario, stepped with the harness's per-step observation: tip state, energy,
// instability checks, the StepRecorder's samples, peaks, episodes and impact zoom) against a bare loop
// that builds the same engine model with the adapter's own builders and steps it the way a user would,
// with the same forces (motor; the contact law's force where the adapter applies it) and no recording.
// Both are timed whole (model building included) in the thread's CPU time, one after the other in every
// iteration (in alternating order, after an untimed pair), so that a drift of the machine's speed hits
// both alike. Counters: each side's fastest run (harness_ms, bare_ms), overhead_percent = 100 (harness_ms
// / bare_ms - 1), and the median over the pairs of 100 (harness / bare - 1) as a check.
// The rig case of rig_case.h (resonance, 2 s, matched contact path, each engine's default step), every
// law. Target: < 5 %.
//   build/bench/harness_overhead_benchmark [--benchmark_filter=mujoco] [--benchmark_repetitions=3]
#include <benchmark/benchmark.h>

#include <time.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "adapters/common/injected_contact.h"
#include "adapters/common/rig.h"
#include "harness/jobs/run_job.h"
#include "model/simulator.h"
#include "rig_case.h"
#include "simulators/catalog.h"

#if IMPACTBENCH_WITH_MUJOCO
#include "adapters/mujoco/mujoco_engine.h"
#include "adapters/mujoco/mujoco_model.h"
#endif
#if IMPACTBENCH_WITH_ODE
#include "adapters/ode/ode_contact.h"
#include "adapters/ode/ode_library.h"
#include "adapters/ode/ode_rig.h"
#endif
#if IMPACTBENCH_WITH_BULLET
#include "adapters/bullet/bullet_world.h"
#endif

namespace {

// A bare loop: builds the engine model of (scenario, settings) at step h and steps it to the end of the
// scenario; returns frame 1's final tip displacement [m] (so that nothing is optimised away).
using BareLoop = std::function<double(const ib::Scenario&, const ib::RunSettings&, double h)>;

long long step_count(const ib::Scenario& s, double h) {
  return static_cast<long long>(std::ceil(s.duration_s / h - 1e-9));
}

#if IMPACTBENCH_WITH_MUJOCO
// mj_step1 (positions, velocities), the loads from that state, mj_step2 (forces, solve, Euler): MuJoCo's
// recommended loop for forces that depend on the state.
double bare_mujoco(const ib::Scenario& s, const ib::RunSettings& settings, double h) {
  const ib::MujocoRunPlan plan = ib::plan_mujoco_run(s, settings);
  if (plan.integrator != ib::MujocoIntegrator::euler) throw std::invalid_argument("bare MuJoCo loop: Euler only");
  const ib::MujocoModelPtr model = ib::compile_mjcf(ib::write_mjcf(plan));
  const ib::MujocoDataPtr data = ib::make_data(model.get());
  const mjModel* m = model.get();
  mjData* d = data.get();
  if (m->nkey > 0) mj_resetDataKeyframe(m, d, 0);
  std::array<int, 2> site{}, body{};
  for (int f = 0; f < 2; ++f) {
    site[f] = mj_name2id(m, mjOBJ_SITE, ib::mujoco_tip_site_name(f).c_str());
    body[f] = mj_name2id(m, mjOBJ_BODY, ib::mujoco_body_name(f, plan.links - 1).c_str());
  }
  auto push_tip = [&](int f, double force_x) {
    const mjtNum force[3] = {force_x, 0, 0}, torque[3] = {0, 0, 0};
    mj_applyFT(m, d, force, torque, d->site_xpos + 3 * site[f], body[f], d->qfrc_applied);
  };
  ib::InjectedContact injected(plan.rig);
  for (long long n = 0, steps = step_count(s, h); n < steps; ++n) {
    mj_step1(m, d);
    mju_zero(d->qfrc_applied, m->nv);
    if (plan.rig.motor) push_tip(0, plan.rig.motor->at(static_cast<double>(n) * h));
    if (plan.harness_contact_force) {
      std::array<double, 2> u{}, v{};
      for (int f = 0; f < 2; ++f) {
        mjtNum velocity[6];
        mj_objectVelocity(m, d, mjOBJ_SITE, site[f], velocity, 0);
        u[f] = d->site_xpos[3 * site[f]] - plan.rig.frames[f].base_x_m;
        v[f] = velocity[3];
      }
      const double force = injected.force(u[0], v[0], u[1], v[1], h);
      push_tip(0, -force);
      push_tip(1, force);
    }
    mj_step2(m, d);
  }
  mj_kinematics(m, d);
  return d->site_xpos[3 * site[0]];
}
#endif

#if IMPACTBENCH_WITH_ODE
// The ODE adapter's default model (implicit hinge springs, dWorldStep) with the matched path's contact.
double bare_ode(const ib::Scenario& s, const ib::RunSettings& settings, double h) {
  const ib::RigSpec rig = ib::build_rig(s, settings.law, ib::default_links(s));
  const ib::ode::ContactSetup contact = ib::ode::contact_setup(ib::ContactPath::matched, rig.law, h);
  ib::ode::OdeModelSettings model;
  model.time_step_s = h;
  model.tip_spheres = contact.ode_collision;
  ib::ode::ensure_initialised();
  ib::ode::OdeRig ode_rig(rig, model);
  ib::InjectedContact injected(rig);
  for (long long n = 0, steps = step_count(s, h); n < steps; ++n) {
    if (contact.force_from_tip_states) {
      const ib::ode::TipState a = ode_rig.tip(0), b = ode_rig.tip(1);
      const double force = injected.force(a.displacement_m, a.velocity_m_s, b.displacement_m, b.velocity_m_s, h);
      ode_rig.add_tip_force(0, -force);
      ode_rig.add_tip_force(1, force);
    }
    if (contact.ode_collision) ode_rig.make_tip_contact(contact.surface);
    if (rig.motor) ode_rig.add_tip_force(0, rig.motor->at(static_cast<double>(n) * h));
    ode_rig.step();
  }
  return ode_rig.tip(0).displacement_m;
}
#endif

#if IMPACTBENCH_WITH_BULLET
// The Bullet adapter's default world (one btMultiBody per frame) with the matched path's contact:
// Bullet's own for the spring-dashpot and Newton, the law's force from the tips for Hertz.
double bare_bullet(const ib::Scenario& s, const ib::RunSettings& settings, double h) {
  const ib::RigSpec rig = ib::build_rig(s, settings.law, ib::default_links(s));
  const bool injected_path = std::holds_alternative<ib::HertzLaw>(rig.law);
  ib::bullet::BulletRig bullet(rig, ib::bullet::Articulation::multibody, !injected_path);
  std::vector<std::pair<std::string, double>> unused;
  if (!injected_path) ib::bullet::configure_tip_contact(bullet, rig, ib::ContactPath::matched, h, unused);
  ib::InjectedContact injected(rig);
  for (long long n = 0, steps = step_count(s, h); n < steps; ++n) {
    for (int f = 0; f < 2; ++f) bullet.chain(f).add_joint_spring_torques();
    if (rig.motor) bullet.chain(0).add_tip_force_x(rig.motor->at(static_cast<double>(n) * h));
    if (injected_path) {
      std::array<double, 2> u{}, v{};
      for (int f = 0; f < 2; ++f) {
        const ib::bullet::BulletChain::TipMotion tip = bullet.chain(f).tip_motion();
        u[f] = tip.x_m - rig.frames[f].base_x_m;
        v[f] = tip.velocity_x_m_s;
      }
      const double force = injected.force(u[0], v[0], u[1], v[1], h);
      bullet.chain(0).add_tip_force_x(-force);
      bullet.chain(1).add_tip_force_x(force);
    }
    bullet.step(h);
  }
  return bullet.chain(0).tip_x_m();
}
#endif

double diagnostic(const ib::RunResult& r, const std::string& name) {
  for (const auto& [key, value] : r.diagnostics)
    if (key == name) return value;
  return 0;
}

// The calling thread's CPU time [s]: unlike the wall clock, it does not count the time another process
// holds the core, so that a loaded machine disturbs the comparison less.
double thread_cpu_s() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

void compare(benchmark::State& state, const std::string& engine, ib::ContactLaw law, const BareLoop& bare) {
  const ib::Scenario s = ib::bench::resonance_for_2_s();
  const ib::RunSettings settings = ib::bench::matched_path(law);
  const auto simulator = ib::make_simulator(engine);
  // An untimed pair first: the engine library's first use in the process (its initialisation, the pages
  // its code and data touch) belongs to neither side. It also gives the step the run takes (its default
  // when the settings give none), so that both loops step alike.
  const ib::RunResult warm_up = simulator->run(s, settings);
  if (warm_up.status != ib::RunStatus::ok) {
    state.SkipWithError(
        ("the run ended " + std::string(ib::to_string(warm_up.status)) + ": " + warm_up.reason).c_str());
    return;
  }
  const double h = diagnostic(warm_up, "time_step_s");
  double sink = bare(s, settings, h);
  std::vector<double> harness_s, bare_s, ratios;
  for (auto _ : state) {
    // which side goes first alternates, so that neither always runs on caches the other has just warmed
    const bool harness_first = harness_s.size() % 2 == 0;
    double harness = 0, bare_loop = 0;
    for (int side = 0; side < 2; ++side) {
      const double start = thread_cpu_s();
      if ((side == 0) == harness_first) {
        benchmark::DoNotOptimize(simulator->run(s, settings).trajectory.time_s.data());
        harness = thread_cpu_s() - start;
      } else {
        sink += bare(s, settings, h);
        bare_loop = thread_cpu_s() - start;
      }
    }
    harness_s.push_back(harness);
    bare_s.push_back(bare_loop);
    ratios.push_back(harness / bare_loop);
  }
  benchmark::DoNotOptimize(sink);
  // Other work on the machine only ever adds time, so each side's fastest run is the best estimate of its
  // own cost; the median of the pairs' ratios is kept beside it as a check.
  const double fastest_harness = *std::min_element(harness_s.begin(), harness_s.end());
  const double fastest_bare = *std::min_element(bare_s.begin(), bare_s.end());
  state.counters["harness_ms"] = 1e3 * fastest_harness;
  state.counters["bare_ms"] = 1e3 * fastest_bare;
  state.counters["overhead_percent"] = 100 * (fastest_harness / fastest_bare - 1);
  state.counters["median_pair_overhead_percent"] = 100 * (ib::median(ratios) - 1);
  state.counters["pairs"] = static_cast<double>(ratios.size());
}

void register_all() {
  std::vector<std::pair<std::string, BareLoop>> engines;
#if IMPACTBENCH_WITH_MUJOCO
  engines.emplace_back("mujoco", bare_mujoco);
#endif
#if IMPACTBENCH_WITH_ODE
  engines.emplace_back("ode", bare_ode);
#endif
#if IMPACTBENCH_WITH_BULLET
  engines.emplace_back("bullet", bare_bullet);
#endif
  for (const auto& [engine, bare] : engines)
    for (ib::ContactLaw law : {ib::ContactLaw::hertz, ib::ContactLaw::viscoelastic, ib::ContactLaw::newton})
      benchmark::RegisterBenchmark((engine + "/" + ib::to_string(law)).c_str(), [engine = engine, bare = bare,
                                                                                 law](benchmark::State& st) {
        compare(st, engine, law, bare);
      })->Unit(benchmark::kMillisecond);
}

// Registered before main runs, as Google Benchmark's own BENCHMARK() macros do.
const bool registered = (register_all(), true);

}  // namespace

BENCHMARK_MAIN();
