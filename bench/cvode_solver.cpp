#include "cvode_solver.h"

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_version.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <ctime>
#include <limits>
#include <stdexcept>

namespace ib::bench {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double dot(const std::vector<double>& a, const double* x) {
  double s = 0;
  for (std::size_t i = 0; i < a.size(); ++i) s += a[i] * x[i];
  return s;
}

// What the right-hand side and the root functions need: the model and whether the contact force acts.
struct Problem {
  const ModalModel* model = nullptr;
  bool contact = false;
  std::size_t m = 0;  // modes; the state is [q (m), q' (m), contact impulse]

  double delta(const double* y) const { return dot(model->b, y) - model->gap; }
  double rate(const double* y) const { return dot(model->b, y + m); }
  double force(const double* y) const { return contact ? model->law.force(delta(y), rate(y)) : 0.0; }
  // delta'' = b . q'' with the force acting (or not)
  double delta_acceleration(double t, const double* y, double f) const {
    const ModalModel& mm = *model;
    const double fm = mm.motor(t);
    double s = 0;
    for (std::size_t i = 0; i < m; ++i)
      s += mm.b[i] * (mm.p[i] * fm - mm.damping_rate[i] * y[m + i] - mm.stiffness[i] * y[i] - mm.b[i] * f);
    return s;
  }
};

int rhs(sunrealtype t, N_Vector y_vector, N_Vector ydot_vector, void* data) {
  const Problem& p = *static_cast<const Problem*>(data);
  const ModalModel& mm = *p.model;
  const double* y = N_VGetArrayPointer(y_vector);
  double* ydot = N_VGetArrayPointer(ydot_vector);
  const double fm = mm.motor(t), f = p.force(y);
  for (std::size_t i = 0; i < p.m; ++i) {
    ydot[i] = y[p.m + i];
    ydot[p.m + i] = mm.p[i] * fm - mm.damping_rate[i] * y[p.m + i] - mm.stiffness[i] * y[i] - mm.b[i] * f;
  }
  ydot[2 * p.m] = f;  // the impulse: zero outside a contact
  return 0;
}

// Free flight: [delta]. Contact: [delta, delta', d/dt unclipped force, unclipped force] (the last for
// clipped laws only).
int roots(sunrealtype t, N_Vector y_vector, sunrealtype* g, void* data) {
  const Problem& p = *static_cast<const Problem*>(data);
  const double* y = N_VGetArrayPointer(y_vector);
  const double delta = p.delta(y);
  g[0] = delta;
  if (!p.contact) return 0;
  const ContactLaw& law = p.model->law;
  const double rate = p.rate(y);
  g[1] = rate;
  g[2] = law.unclipped_rate(delta, rate, p.delta_acceleration(t, y, law.force(delta, rate)));
  if (law.clipped) g[3] = law.unclipped(delta, rate);
  return 0;
}

class CvodeRun {
 public:
  CvodeRun(const ModalModel& model, const CvodeSettings& settings, bool record_samples)
      : model_(model), settings_(settings), record_(record_samples) {
    problem_.model = &model;
    problem_.m = model.modes();
    if (SUNContext_Create(nullptr, &context_) != 0) throw std::runtime_error("SUNContext_Create failed");
    y_ = N_VNew_Serial(static_cast<sunindextype>(2 * problem_.m + 1), context_);
    const bool bdf = settings.method == "bdf";
    if (!bdf && settings.method != "adams" && settings.method != "adams-newton")
      throw std::invalid_argument("--method " + settings.method + ": allowed: adams, adams-newton, bdf");
    memory_ = CVodeCreate(bdf ? CV_BDF : CV_ADAMS, context_);
    if (settings.method == "adams") {
      nonlinear_ = SUNNonlinSol_FixedPoint(y_, 0, context_);
    } else {
      matrix_ = SUNDenseMatrix(static_cast<sunindextype>(2 * problem_.m + 1),
                               static_cast<sunindextype>(2 * problem_.m + 1), context_);
      linear_ = SUNLinSol_Dense(y_, matrix_, context_);
    }
    if (record_) {
      const double span = model.duration - model.series_start;
      const long count = span >= 0 ? static_cast<long>(std::floor(span * model.output_rate + 1e-9)) + 1 : 0;
      result_.samples.reserve(static_cast<std::size_t>(count));
      sample_count_ = count;
    }
  }
  ~CvodeRun() {
    CVodeFree(&memory_);
    if (nonlinear_) SUNNonlinSolFree(nonlinear_);
    if (linear_) SUNLinSolFree(linear_);
    if (matrix_) SUNMatDestroy(matrix_);
    N_VDestroy(y_);
    SUNContext_Free(&context_);
  }
  CvodeRun(const CvodeRun&) = delete;
  CvodeRun& operator=(const CvodeRun&) = delete;

  CvodeResult run() {
    const std::clock_t cpu_start = std::clock();
    const auto wall_start = std::chrono::steady_clock::now();
    try {
      integrate();
    } catch (const std::runtime_error& error) {
      result_.ok = false;
      result_.reason = error.what();
    }
    collect_counters();
    result_.cpu_time_s = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
    result_.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    return std::move(result_);
  }

 private:
  double* y() { return N_VGetArrayPointer(y_); }

  void check(int flag, const char* what) const {
    if (flag >= 0) return;
    char* name = CVodeGetReturnFlagName(flag);  // allocated by CVODE, ours to free
    const std::string text = std::string(what) + " failed: " + (name ? name : "?");
    std::free(name);
    throw std::runtime_error(text);
  }

  // CVODE restarted at t from y() with the phase's right-hand side and roots: the contact force switches
  // on or off (a jump in the right-hand side), or the Newton map changed the velocities.
  void start_phase(double t, bool contact) {
    collect_counters();
    problem_.contact = contact;
    if (result_.phases == 0) {
      check(CVodeInit(memory_, rhs, t, y_), "CVodeInit");
      check(CVodeSetUserData(memory_, &problem_), "CVodeSetUserData");
      check(CVodeSStolerances(memory_, settings_.rtol, settings_.atol), "CVodeSStolerances");
      check(CVodeSetMaxNumSteps(memory_, 1000000000L), "CVodeSetMaxNumSteps");
      check(CVodeSetNoInactiveRootWarn(memory_), "CVodeSetNoInactiveRootWarn");
      if (nonlinear_) check(CVodeSetNonlinearSolver(memory_, nonlinear_), "CVodeSetNonlinearSolver");
      if (linear_) check(CVodeSetLinearSolver(memory_, linear_, matrix_), "CVodeSetLinearSolver");
    } else {
      check(CVodeReInit(memory_, t, y_), "CVodeReInit");
    }
    check(CVodeSetStopTime(memory_, model_.duration), "CVodeSetStopTime");
    const int count = !contact ? 1 : model_.law.clipped ? 4 : 3;
    check(CVodeRootInit(memory_, count, roots), "CVodeRootInit");
    int direction[4] = {contact ? -1 : 1, -1, -1, 0};  // onset up; separation, maxima down; force end/return both
    check(CVodeSetRootDirection(memory_, direction), "CVodeSetRootDirection");
    ++result_.phases;
  }

  // CVODE's counters restart at each CVodeReInit: added up before each.
  void collect_counters() {
    if (result_.phases == 0) return;
    long steps = 0, f = 0, g = 0, iterations = 0, jacobians = 0, f_jacobian = 0;
    CVodeGetNumSteps(memory_, &steps);
    CVodeGetNumRhsEvals(memory_, &f);
    CVodeGetNumGEvals(memory_, &g);
    CVodeGetNumNonlinSolvIters(memory_, &iterations);
    if (linear_) {
      CVodeGetNumJacEvals(memory_, &jacobians);
      CVodeGetNumLinRhsEvals(memory_, &f_jacobian);
    }
    result_.steps += steps;
    result_.rhs_evaluations += f + f_jacobian;
    result_.root_evaluations += g;
    result_.nonlinear_iterations += iterations;
    result_.jacobian_evaluations += jacobians;
  }

  double sample_time(long k) const { return model_.series_start + static_cast<double>(k) / model_.output_rate; }

  void record_samples_up_to(double t) {
    // a sample within rounding of t is taken at t: CVODE refuses an output time that close (CV_TOO_CLOSE)
    const double slack = 1e-14 * std::max(1.0, std::abs(t));
    while (record_ && next_sample_ < sample_count_ && sample_time(next_sample_) <= t + slack) {
      const double* s = y();
      const std::size_t m = problem_.m;
      result_.samples.push_back({sample_time(next_sample_), dot(model_.tip1, s), dot(model_.tip2, s),
                                 dot(model_.tip1, s + m), dot(model_.tip2, s + m)});
      ++next_sample_;
    }
  }

  void integrate() {
    const std::size_t m = problem_.m;
    std::copy(model_.q0.begin(), model_.q0.end(), y());
    std::copy(model_.v0.begin(), model_.v0.end(), y() + m);
    y()[2 * m] = 0;
    double t = 0;
    const double delta = problem_.delta(y()), rate = problem_.rate(y());
    bool contact = delta > 0 || (delta == 0 && rate > 0);
    if (contact && model_.law.instantaneous()) {
      if (delta > 0) throw std::runtime_error("the Newton law cannot start with the tips interpenetrating");
      newton_impact(t);
      contact = false;
    }
    if (contact) open_episode(t);
    start_phase(t, contact);
    int found[4] = {0, 0, 0, 0};
    while (true) {
      record_samples_up_to(t);
      const double target = record_ && next_sample_ < sample_count_
                                ? std::min(sample_time(next_sample_), model_.duration)
                                : model_.duration;
      if (t >= model_.duration) break;
      const int flag = CVode(memory_, target, y_, &t, CV_NORMAL);
      check(flag, "CVode");
      if (flag != CV_ROOT_RETURN) continue;
      check(CVodeGetRootInfo(memory_, found), "CVodeGetRootInfo");
      if (!problem_.contact) {  // the only free-flight root: an onset
        if (model_.law.instantaneous()) {
          newton_impact(t);
          start_phase(t, false);
        } else {
          y()[2 * m] = 0;
          open_episode(t);
          start_phase(t, true);
        }
        continue;
      }
      contact_roots(t, found);
      if (found[0] != 0) {  // the separation
        close_episode(t);
        start_phase(t, false);
      }
    }
    if (problem_.contact) close_episode(model_.duration);  // a contact still going at the end of the run
  }

  void open_episode(double t) {
    episode_ = CvodeEvent{};
    episode_.onset = t;
    episode_.approach = problem_.rate(y());
    problem_.contact = true;
    episode_.peak_force = std::max(0.0, problem_.force(y()));
    episode_.max_indentation = std::max(0.0, problem_.delta(y()));
    force_end_ = force_return_ = -1;
  }

  // The roots that need no restart: a largest indentation, a largest force, the clipped force ending or
  // returning.
  void contact_roots(double t, const int* found) {
    if (found[1] != 0) episode_.max_indentation = std::max(episode_.max_indentation, problem_.delta(y()));
    if (found[2] != 0) episode_.peak_force = std::max(episode_.peak_force, problem_.force(y()));
    if (model_.law.clipped && found[3] < 0) {
      force_end_ = t;
      force_end_rebound_ = -problem_.rate(y());
    }
    if (model_.law.clipped && found[3] > 0) force_return_ = t;
  }

  void close_episode(double t) {
    CvodeEvent& e = episode_;
    e.end = t;
    e.rebound = -problem_.rate(y());
    e.peak_force = std::max(e.peak_force, problem_.force(y()));
    e.max_indentation = std::max(e.max_indentation, problem_.delta(y()));
    // the force ended before the overlap did, and stayed zero: the episode ends there
    if (force_end_ >= 0 && force_return_ < force_end_) {
      e.end = force_end_;
      e.rebound = force_end_rebound_;
    }
    e.restitution = e.approach > 0 ? e.rebound / e.approach : 0.0;
    e.impulse = y()[2 * problem_.m];
    result_.events.push_back(e);
    problem_.contact = false;
  }

  // The reference's impulse map; stops where the reference would make the tips stick.
  void newton_impact(double t) {
    const std::size_t m = problem_.m;
    const double e = model_.law.restitution;
    const double approach = std::max(0.0, problem_.rate(y()));
    const double impulse = (1 + e) * approach / model_.lever_norm2;
    for (std::size_t i = 0; i < m; ++i) y()[m + i] -= model_.b[i] * impulse;
    result_.events.push_back({t, t, approach, e * approach, approach > 0 ? e : 0.0, kNaN, impulse, 0.0});
    problem_.contact = false;
    const double closing = problem_.delta_acceleration(t, y(), 0.0), rebound = -problem_.rate(y());
    if (closing > 0 && e < 1 && 2 * rebound / ((1 - e) * closing) < model_.accumulation_time)
      throw std::runtime_error("Newton impacts accumulate at t = " + std::to_string(t) +
                               " s (the reference makes the tips stick there); sticking is not implemented in "
                               "this CVODE solver: choose a case without it");
  }

  const ModalModel& model_;
  CvodeSettings settings_;
  bool record_;
  Problem problem_;
  SUNContext context_ = nullptr;
  N_Vector y_ = nullptr;
  void* memory_ = nullptr;
  SUNNonlinearSolver nonlinear_ = nullptr;
  SUNMatrix matrix_ = nullptr;
  SUNLinearSolver linear_ = nullptr;
  CvodeResult result_;
  CvodeEvent episode_;
  double force_end_ = -1, force_end_rebound_ = 0, force_return_ = -1;  // [s], [m/s], [s]
  long sample_count_ = 0, next_sample_ = 0;
};

}  // namespace

CvodeResult solve_with_cvode(const ModalModel& model, const CvodeSettings& settings, bool record_samples) {
  CvodeRun run(model, settings, record_samples);
  return run.run();
}

std::string sundials_version() {
  char text[64] = {0};
  SUNDIALSGetVersion(text, sizeof text);
  return text;
}

}  // namespace ib::bench
