#include "siconos_event_driven.h"

#include <SiconosKernel.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <stdexcept>

namespace ib::bench {
namespace {

// The modal system with the motor's force p A cos(Omega t) as its external force. Overriding computeFExt
// keeps the model's numbers in the object (a plugin would have to carry them through the z vector).
class MotorDrivenModes : public LagrangianLinearTIDS {
 public:
  MotorDrivenModes(const ModalModel& model, SP::SiconosVector q0, SP::SiconosVector v0, SP::SiconosMatrix mass,
                   SP::SiconosMatrix stiffness, SP::SiconosMatrix damping)
      : LagrangianLinearTIDS(q0, v0, mass, stiffness, damping), model_(model) {
    setFExtPtr(SP::SiconosVector(new SiconosVector(model.modes())));
    _hasConstantFExt = false;  // setFExtPtr marks it constant; it is not, and computeFExt fills it
  }
  void computeFExt(double time) override {
    const double force_n = model_.motor(time);
    for (std::size_t i = 0; i < model_.modes(); ++i) (*_fExt)(i) = model_.p[i] * force_n;
  }

 private:
  const ModalModel& model_;
};

double dot(const std::vector<double>& lever, const SiconosVector& x) {
  double s = 0;
  for (std::size_t i = 0; i < lever.size(); ++i) s += lever[i] * x(i);
  return s;
}

// delta'' [m/s^2] at the state (q, q') away from contact: b . (p F_m - C q' - K q).
double closing_acceleration(const ModalModel& m, double t, const SiconosVector& q, const SiconosVector& v) {
  double s = 0;
  for (std::size_t i = 0; i < m.modes(); ++i)
    s += m.b[i] * (m.p[i] * m.motor(t) - m.damping_rate[i] * v(i) - m.stiffness[i] * q(i));
  return s;
}

struct Rig {
  SP::LagrangianLinearTIDS modes;
  SP::Interaction contact;
  SP::LsodarOSI lsodar;
  SP::EventDriven simulation;
};

Rig build(const ModalModel& m, const SiconosSettings& settings, double duration_s) {
  const unsigned n = static_cast<unsigned>(m.modes());
  SP::SiconosVector q0(new SiconosVector(n)), v0(new SiconosVector(n));
  SP::SiconosMatrix mass(new SimpleMatrix(n, n)), stiffness(new SimpleMatrix(n, n)), damping(new SimpleMatrix(n, n));
  for (unsigned i = 0; i < n; ++i) {
    (*q0)(i) = m.q0[i];
    (*v0)(i) = m.v0[i];
    (*mass)(i, i) = 1.0;  // modal coordinates in m sqrt(kg): unit modal masses
    (*stiffness)(i, i) = m.stiffness[i];
    (*damping)(i, i) = m.damping_rate[i];
  }
  Rig rig;
  rig.modes.reset(new MotorDrivenModes(m, q0, v0, mass, stiffness, damping));
  // y = gap - b . q >= 0: the gap left between the tips, -delta
  SP::SimpleMatrix lever(new SimpleMatrix(1, n));
  for (unsigned i = 0; i < n; ++i) (*lever)(0, i) = -m.b[i];
  SP::SiconosVector gap(new SiconosVector(1));
  (*gap)(0) = m.gap;
  SP::NonSmoothLaw newton(new NewtonImpactNSL(m.law.restitution));
  SP::Relation relation(new LagrangianLinearTIR(lever, gap));
  rig.contact.reset(new Interaction(newton, relation));

  SP::NonSmoothDynamicalSystem nsds(new NonSmoothDynamicalSystem(0.0, duration_s));
  nsds->insertDynamicalSystem(rig.modes);
  nsds->link(rig.contact, rig.modes);
  // Output events at the samples' rate, or one at the end: Lsodar interpolates to them without restarting.
  const double step_s = settings.record_samples ? 1.0 / m.output_rate : duration_s;
  SP::TimeDiscretisation time(new TimeDiscretisation(0.0, step_s));
  rig.lsodar.reset(new LsodarOSI());
  rig.simulation.reset(new EventDriven(nsds, time));
  rig.simulation->insertIntegrator(rig.lsodar);
  rig.simulation->insertNonSmoothProblem(SP::OneStepNSProblem(new LCP()), SICONOS_OSNSP_ED_IMPACT);
  rig.simulation->insertNonSmoothProblem(SP::OneStepNSProblem(new LCP()), SICONOS_OSNSP_ED_SMOOTH_ACC);
  rig.simulation->initialize();
  return rig;
}

// Lsodar's tolerances, set after initialize() (which resets them). The array overload: the scalar one
// of 4.4.0 copies rtol into atol. itol 4: an rtol and an atol for each of the 2n state components.
void set_tolerances(LsodarOSI& lsodar, std::size_t modes, const SiconosSettings& settings) {
  const std::size_t size = 2 * modes;
  SA::doublereal rtol(new doublereal[size]), atol(new doublereal[size]);
  for (std::size_t i = 0; i < size; ++i) {
    rtol[i] = settings.rtol;
    atol[i] = settings.atol;
  }
  lsodar.setTol(4, rtol, atol);
  lsodar.setMaxNstep(100000000);  // between two events (the default 500 ends a long event-free stretch)
}

void record_sample(const ModalModel& m, double t, const LagrangianDS& modes, SiconosResult& out) {
  const SiconosVector &q = *modes.q(), &v = *modes.velocity();
  out.samples.push_back({t, dot(m.tip1, q), dot(m.tip2, q), dot(m.tip1, v), dot(m.tip2, v)});
}

}  // namespace

SiconosResult solve_with_siconos(const ModalModel& m, const SiconosSettings& settings) {
  if (!m.law.instantaneous())
    throw std::invalid_argument(m.path + ": contact law '" + m.law.name +
                                "': allowed: newton (Siconos's event-driven scheme treats Newton impacts only)");
  const double duration_s = settings.duration > 0 ? std::min(settings.duration, m.duration) : m.duration;
  Rig rig = build(m, settings, duration_s);
  set_tolerances(*rig.lsodar, m.modes(), settings);
  EventDriven& s = *rig.simulation;
  SP::EventsManager events = s.eventsManager();
  SiconosResult out;
  out.stop = "duration";
  // the sample grid's spacing, to tell samples from events that merely fall near them
  const double sample_tolerance_s = 1e-9 / m.output_rate;
  if (settings.record_samples && m.series_start <= 0) record_sample(m, 0.0, *rig.modes, out);

  const std::clock_t cpu_start = std::clock();
  const auto wall_start = std::chrono::steady_clock::now();
  try {
    while (s.hasNextEvent()) {
      s.advanceToEvent();
      // the state is the one at the event, before any impact: delta' there is the approach velocity
      const bool impact = events->nextEvent()->getType() == NS_EVENT;
      const double approach_m_s = dot(m.b, *rig.modes->velocity());
      s.processEvents();
      ++out.events_processed;
      const double t = s.startingTime();
      out.end_time_s = std::min(t, duration_s);
      // the time discretisation's events run on past the end (its last one lies a step beyond)
      if (t > duration_s) break;
      if (impact) {
        const double rebound_m_s = -dot(m.b, *rig.modes->velocity());
        const double impulse_n_s = (*rig.contact->lambda(1))(0);
        out.impacts.push_back(
            {t, approach_m_s, rebound_m_s, approach_m_s > 0 ? rebound_m_s / approach_m_s : 0.0, impulse_n_s});
        const double closing = closing_acceleration(m, t, *rig.modes->q(), *rig.modes->velocity());
        const double e = m.law.restitution;
        // The reference's criterion (reference/: the impacts' geometric series sums to less than the
        // accumulation time): it makes the tips stick there; this comparator stops instead.
        if (closing > 0 && e < 1 && 2 * rebound_m_s / ((1 - e) * closing) < m.accumulation_time) {
          out.stop = "accumulation";
          out.reason = "Newton impacts accumulate at t = " + std::to_string(t) + " s (the reference sticks there)";
          break;
        }
        if (static_cast<int>(out.impacts.size()) >= settings.max_impacts) {
          out.stop = "max_impacts";
          break;
        }
      } else if (settings.record_samples && t >= m.series_start - sample_tolerance_s) {
        record_sample(m, t, *rig.modes, out);
      }
    }
    out.ok = true;
  } catch (const std::exception& error) {
    out.reason = std::string("Siconos stopped at t = ") + std::to_string(s.startingTime()) + " s: " + error.what();
  } catch (...) {
    out.reason = "Siconos stopped at t = " + std::to_string(s.startingTime()) + " s (a Siconos exception)";
  }
  out.cpu_time_s = double(std::clock() - cpu_start) / CLOCKS_PER_SEC;
  out.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return out;
}

std::string siconos_version() { return IMPACTBENCH_SICONOS_VERSION; }

}  // namespace ib::bench
