#include "adapters/siconos/siconos_rig.h"

#include <SiconosAlgebraProd.hpp>
#include <SiconosKernel.hpp>
#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <tuple>

#include "physics/contact_laws.h"
#include "physics/link_chain.h"

namespace ib::siconos {
namespace {

SP::SimpleMatrix matrix_of(const Eigen::MatrixXd& m) {
  auto out = std::make_shared<SimpleMatrix>(static_cast<unsigned>(m.rows()), static_cast<unsigned>(m.cols()));
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    for (Eigen::Index j = 0; j < m.cols(); ++j) (*out)(i, j) = m(i, j);
  return out;
}

SP::SiconosVector vector_of(const Eigen::VectorXd& v) {
  auto out = std::make_shared<SiconosVector>(static_cast<unsigned>(v.size()));
  for (Eigen::Index i = 0; i < v.size(); ++i) (*out)(i) = v(i);
  return out;
}

Eigen::Map<const Eigen::VectorXd> eigen_of(const SiconosVector& v) {
  return {v.getArray(), static_cast<Eigen::Index>(v.size())};
}

// Both frames' chains as one linear system in their 2K hinge angles (block-diagonal M, K, C): one system, so
// that a smooth contact force, which couples the frames, can be a force of the system.
struct BothChains {
  Eigen::MatrixXd mass, stiffness, damping;
  Eigen::VectorXd gap_gradient;  // dy/dq of the gap y = gap - u1 + u2: (-tip lever 1, +tip lever 2) [m/rad]
};

BothChains both_chains(const RigSpec& rig) {
  const ChainMatrices m1 = linearise(rig.frames[0].chain), m2 = linearise(rig.frames[1].chain);
  const Eigen::Index k1 = m1.tip_lever.size(), n = k1 + m2.tip_lever.size();
  BothChains both{Eigen::MatrixXd::Zero(n, n), Eigen::MatrixXd::Zero(n, n), Eigen::MatrixXd::Zero(n, n),
                  Eigen::VectorXd(n)};
  for (auto [block, a, b] : {std::tuple{&BothChains::mass, &m1.mass, &m2.mass},
                             std::tuple{&BothChains::stiffness, &m1.stiffness, &m2.stiffness},
                             std::tuple{&BothChains::damping, &m1.damping, &m2.damping}}) {
    (both.*block).topLeftCorner(k1, k1) = *a;
    (both.*block).bottomRightCorner(n - k1, n - k1) = *b;
  }
  both.gap_gradient << -m1.tip_lever, m2.tip_lever;
  return both;
}

// The law's slopes dF/d delta and dF/d delta' at a state, by central differences of physics/contact_laws.h's force
// (the one place of the law): only Moreau-Jean's iteration matrix uses them, so they decide how fast its Newton
// loop converges, not where it converges to.
struct ContactSlopes {
  double per_indentation_n_per_m = 0, per_rate_n_s_per_m = 0;
};
ContactSlopes contact_slopes(const ContactModel& law, double indentation_m, double rate_m_s) {
  const double step_m = std::max(1e-13, 1e-6 * std::abs(indentation_m));
  const double step_m_s = std::max(1e-10, 1e-6 * std::abs(rate_m_s));
  return {
      (contact_force(law, indentation_m + step_m, rate_m_s) - contact_force(law, indentation_m - step_m, rate_m_s)) /
          (2 * step_m),
      (contact_force(law, indentation_m, rate_m_s + step_m_s) -
       contact_force(law, indentation_m, rate_m_s - step_m_s)) /
          (2 * step_m_s)};
}

// The chains with the contact law as a smooth force of the system (Hertz, the spring-dashpot), which
// Moreau-Jean integrates implicitly, its Newton loop solving for the force at the step's theta point:
// M q'' + f_int(q, q') = f_ext with f_int = K q + C q' - F(delta, delta') dy/dq, delta = -y.
class SmoothContactChains final : public LagrangianDS {
 public:
  SmoothContactChains(const BothChains& chains, double gap_m, const ContactModel& law, SP::SiconosVector q0,
                      SP::SiconosVector v0)
      : LagrangianDS(q0, v0, matrix_of(chains.mass)), chains_(chains), gap_m_(gap_m), law_(law) {
    const unsigned n = q0->size();
    setFIntPtr(std::make_shared<SiconosVector>(n));  // gives the system its internal force and Jacobians
    setJacobianFIntqPtr(std::make_shared<SimpleMatrix>(n, n));
    setJacobianFIntqDotPtr(std::make_shared<SimpleMatrix>(n, n));
    _jacobianqForces = std::make_shared<SimpleMatrix>(n, n);
    _jacobianqDotForces = std::make_shared<SimpleMatrix>(n, n);
  }

  void computeFInt(double, SP::SiconosVector q, SP::SiconosVector v) override {
    const auto qe = eigen_of(*q), ve = eigen_of(*v);
    const auto [indentation_m, rate_m_s] = indentation(qe, ve);
    Eigen::Map<Eigen::VectorXd>(fInt()->getArray(), qe.size()) =
        chains_.stiffness * qe + chains_.damping * ve -
        contact_force(law_, indentation_m, rate_m_s) * chains_.gap_gradient;
  }
  // The forces' Jacobians that Moreau-Jean's iteration matrix W = M - h theta dF/dq' - h^2 theta^2 dF/dq is built
  // from, at the current state. Siconos's own computeJacobianqForces reaches computeJacobianFIntq only through a
  // plugin, so without these overrides W would be M alone: the Newton loop then converges only while
  // omega h theta < 1 for the chain's fastest mode, and costs an iteration per factor (omega h theta)^2.
  void computeJacobianqForces(double) override {
    const auto [indentation_m, rate_m_s] = indentation(eigen_of(*q()), eigen_of(*velocity()));
    const double slope_n_per_m = contact_slopes(law_, indentation_m, rate_m_s).per_indentation_n_per_m;
    set(*_jacobianqForces,
        -(chains_.stiffness + slope_n_per_m * chains_.gap_gradient * chains_.gap_gradient.transpose()));
  }
  void computeJacobianvForces(double) override {
    const auto [indentation_m, rate_m_s] = indentation(eigen_of(*q()), eigen_of(*velocity()));
    const double slope_n_s_per_m = contact_slopes(law_, indentation_m, rate_m_s).per_rate_n_s_per_m;
    set(*_jacobianqDotForces,
        -(chains_.damping + slope_n_s_per_m * chains_.gap_gradient * chains_.gap_gradient.transpose()));
  }

 private:
  std::pair<double, double> indentation(const Eigen::Map<const Eigen::VectorXd>& q,
                                        const Eigen::Map<const Eigen::VectorXd>& v) const {
    return {-(gap_m_ + chains_.gap_gradient.dot(q)), -chains_.gap_gradient.dot(v)};
  }
  // into the dense matrix's own column-major array, as Eigen's: element by element through Boost.uBLAS costs
  // a fifth of the step
  static void set(SiconosMatrix& out, const Eigen::MatrixXd& m) {
    Eigen::Map<Eigen::MatrixXd>(out.getArray(), m.rows(), m.cols()) = m;
  }

  const BothChains chains_;
  const double gap_m_;
  const ContactModel law_;
};

}  // namespace

struct SiconosRig::Objects {
  std::array<Eigen::Index, 2> first{}, size{};  // frame f's hinges in the system's coordinates
  std::array<Eigen::VectorXd, 2> tip_lever_m;   // tip displacement per hinge angle [m/rad]
  SP::LagrangianDS chains;
  SP::SiconosVector external_torques_n_m;  // f_ext = tip lever * tip force, held over a step
  SP::Interaction tip_gap;                 // y = gap - u1 + u2 with Newton's law (absent without it)
  SP::TimeStepping simulation;
  double time_step_s = 0;
};

SiconosRig::SiconosRig(const RigSpec& rig, const SiconosModelSettings& settings,
                       const std::array<Eigen::VectorXd, 2>& angles_rad,
                       const std::array<Eigen::VectorXd, 2>& rates_rad_s,
                       const std::array<double, 2>& previous_tip_forces_n)
    : objects_(std::make_unique<Objects>()) {
  Objects& o = *objects_;
  const BothChains chains = both_chains(rig);
  const Eigen::Index k1 = angles_rad[0].size(), n = k1 + angles_rad[1].size();
  o.first = {0, k1};
  o.size = {k1, n - k1};
  for (int f = 0; f < 2; ++f)
    o.tip_lever_m[f] = (f == 0 ? -1.0 : 1.0) * chains.gap_gradient.segment(o.first[f], o.size[f]);
  Eigen::VectorXd q0(n), v0(n);
  q0 << angles_rad[0], angles_rad[1];
  v0 << rates_rad_s[0], rates_rad_s[1];
  if (settings.contact == SystemContact::smooth_force)
    o.chains = std::make_shared<SmoothContactChains>(chains, rig.gap_m, rig.law, vector_of(q0), vector_of(v0));
  else
    o.chains = std::make_shared<LagrangianLinearTIDS>(vector_of(q0), vector_of(v0), matrix_of(chains.mass),
                                                      matrix_of(chains.stiffness), matrix_of(chains.damping));
  o.external_torques_n_m = std::make_shared<SiconosVector>(static_cast<unsigned>(n));
  o.external_torques_n_m->zero();
  o.chains->setFExtPtr(o.external_torques_n_m);
  set_tip_forces_n(previous_tip_forces_n[0], previous_tip_forces_n[1]);
  // no end time: the loop decides when to stop (with a step that does not divide the duration, Siconos's own end
  // would leave the last step without a next time, and it aborts on that)
  auto system = std::make_shared<NonSmoothDynamicalSystem>(0.0, std::numeric_limits<double>::infinity());
  system->insertDynamicalSystem(o.chains);
  if (settings.contact == SystemContact::newton_impact) {
    auto gap_at_rest = std::make_shared<SiconosVector>(1);
    (*gap_at_rest)(0) = rig.gap_m;
    auto relation = std::make_shared<LagrangianLinearTIR>(matrix_of(chains.gap_gradient.transpose()), gap_at_rest);
    o.tip_gap = std::make_shared<Interaction>(std::make_shared<NewtonImpactNSL>(settings.impact_restitution), relation);
    system->link(o.tip_gap, o.chains);
  }
  auto steps = std::make_shared<TimeDiscretisation>(0.0, settings.time_step_s);
  // the LCP with Siconos's default solver (Lemke's), solved where the tips' predicted gap closes
  o.simulation = std::make_shared<TimeStepping>(system, steps, std::make_shared<MoreauJeanOSI>(settings.theta),
                                                std::make_shared<LCP>());
  if (settings.contact == SystemContact::smooth_force) o.simulation->setNewtonTolerance(settings.newton_tolerance);
  o.simulation->initialize();
  o.time_step_s = o.simulation->timeStep();
}

SiconosRig::~SiconosRig() = default;

void SiconosRig::set_tip_forces_n(double frame1_n, double frame2_n) {
  const double force_n[2] = {frame1_n, frame2_n};
  for (int f = 0; f < 2; ++f)
    for (Eigen::Index j = 0; j < objects_->size[f]; ++j)
      (*objects_->external_torques_n_m)(objects_->first[f] + j) = objects_->tip_lever_m[f](j) * force_n[f];
}

std::optional<std::string> SiconosRig::step() {
  try {
    objects_->simulation->computeOneStep();
    // the step's impulse before nextStep, which clears it where the gap leaves the active set
    impulse_n_s_ = objects_->tip_gap ? (*objects_->tip_gap->lambda(1))(0) : 0.0;
    objects_->simulation->nextStep();
  } catch (const std::exception& e) {
    return std::string("Siconos threw: ") + e.what();
  }
  return std::nullopt;
}

void SiconosRig::hinge_state(int f, Eigen::VectorXd& angles_rad, Eigen::VectorXd& rates_rad_s) const {
  const SiconosVector& q = *objects_->chains->q();
  const SiconosVector& v = *objects_->chains->velocity();
  angles_rad.resize(objects_->size[f]);
  rates_rad_s.resize(objects_->size[f]);
  for (Eigen::Index j = 0; j < objects_->size[f]; ++j) {
    angles_rad(j) = q(objects_->first[f] + j);
    rates_rad_s(j) = v(objects_->first[f] + j);
  }
}

double SiconosRig::impulse_n_s() const { return impulse_n_s_; }

double SiconosRig::time_step_s() const { return objects_->time_step_s; }

int SiconosRig::newton_iterations() const { return objects_->simulation->getNewtonNbIterations(); }

const void* kernel_library_function() {
  void (*product)(const SiconosMatrix&, const SiconosVector&, SiconosVector&, bool) = &prod;
  return reinterpret_cast<const void*>(product);
}

double default_impact_restitution() { return NewtonImpactNSL().e(); }

double default_theta() { return MoreauJeanOSI().theta(); }

}  // namespace ib::siconos
