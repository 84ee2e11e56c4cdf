#include "adapters/simbody/simbody_contact.h"

#include <cmath>
#include <variant>

namespace ib::simbody {

using namespace SimTK;

HuntCrossleyMaterial hertz_material(const HertzLaw& law, double sphere_radius_m) {
  const double effective_radius_m = sphere_radius_m / 2;  // two equal spheres
  return {std::pow(2.0, 1.5) * 3 * law.stiffness / (4 * std::sqrt(effective_radius_m)),
          law.damping / (1.5 * law.stiffness)};
}

HuntCrossleyMaterial steel_material() {
  return {ContactMaterial::calcPlaneStrainStiffness(kSteelYoungsModulus_pa, kSteelPoissonRatio),
          kSteelDissipation_s_per_m};
}

double hunt_crossley_force_n(const HuntCrossleyMaterial& m, double sphere_radius_m, double indentation_m,
                             double indentation_rate_m_s) {
  if (indentation_m <= 0) return 0;
  // each surface stores E^(2/3); equal surfaces combine to k = E^(2/3) / 2, the Hertz modulus is k^1.5
  const double k = std::pow(m.stiffness_pa, 2.0 / 3.0) / 2;
  const double elastic = 4.0 / 3.0 * std::pow(k, 1.5) * std::sqrt(sphere_radius_m / 2) * std::pow(indentation_m, 1.5);
  return std::max(0.0, elastic * (1 + 1.5 * m.dissipation_s_per_m * indentation_rate_m_s));
}

ContactSetup contact_setup(ContactPath path, const ContactModel& law) {
  ContactSetup setup;
  if (path == ContactPath::injected) return setup;
  if (path == ContactPath::native) {
    setup.kind = ContactKind::hunt_crossley;
    setup.material = steel_material();
    return setup;
  }
  if (const auto* hertz = std::get_if<HertzLaw>(&law)) {
    if (hertz->exponent == 1.5) {
      setup.kind = ContactKind::hunt_crossley;
      setup.material = hertz_material(*hertz, kTipSphereRadius_m);
    } else {
      setup.note = "Hertz exponent " + std::to_string(hertz->exponent) +
                   " has no form in Simbody's Hunt-Crossley contact (1.5 only): the law's force is injected";
    }
  } else if (std::holds_alternative<ViscoelasticLaw>(law)) {
    setup.kind = ContactKind::spring_dashpot;
  } else {
    setup.kind = ContactKind::rigid_newton;
  }
  return setup;
}

double SpringDashpotContact::force_n(const State& state) const {
  const Vec3 d = chain_.tip_position_m(state, 1) - chain_.tip_position_m(state, 0);
  const double distance_m = d.norm();
  const double indentation_m = 2 * radius_m_ - distance_m;
  if (indentation_m <= 0) return 0;
  const Vec3 normal = d / distance_m;  // from frame 1's centre to frame 2's
  const double rate_m_s = -dot(chain_.tip_velocity_m_s(state, 1) - chain_.tip_velocity_m_s(state, 0), normal);
  const double force = law_.stiffness_n_per_m * indentation_m + law_.damping_n_s_per_m * rate_m_s;
  return law_.clip_tension ? std::max(0.0, force) : force;
}

void SpringDashpotContact::calcForce(const State& state, Vector_<SpatialVec>& body_forces, Vector_<Vec3>&,
                                     Vector&) const {
  const double force = force_n(state);
  if (force == 0) return;
  const Vec3 d = chain_.tip_position_m(state, 1) - chain_.tip_position_m(state, 0);
  const Vec3 on_frame2 = force * d / d.norm();
  chain_.tip_body(0).applyForceToBodyPoint(state, chain_.tip_station_m(0), -on_frame2, body_forces);
  chain_.tip_body(1).applyForceToBodyPoint(state, chain_.tip_station_m(1), on_frame2, body_forces);
}

Real SpringDashpotContact::calcPotentialEnergy(const State& state) const {
  const double indentation_m =
      2 * radius_m_ - (chain_.tip_position_m(state, 1) - chain_.tip_position_m(state, 0)).norm();
  return indentation_m > 0 ? 0.5 * law_.stiffness_n_per_m * indentation_m * indentation_m : 0.0;
}

SimbodyContact::SimbodyContact(SimbodyChain& chain, const ContactSetup& setup, const RigSpec& rig)
    : chain_(chain), kind_(setup.kind) {
  switch (kind_) {
    case ContactKind::injected:
      break;
    case ContactKind::hunt_crossley: {
      tracker_ = std::make_unique<ContactTrackerSubsystem>(chain.system());  // the system owns the subsystems
      compliant_ = std::make_unique<CompliantContactSubsystem>(chain.system(), *tracker_);
      // frictionless (static, dynamic, viscous friction 0)
      const ContactMaterial material(setup.material.stiffness_pa, setup.material.dissipation_s_per_m, 0, 0, 0);
      for (int f = 0; f < 2; ++f)
        chain.tip_body(f).updBody().addContactSurface(
            Transform(Vec3(chain.tip_station_m(f))),
            ContactSurface(ContactGeometry::Sphere(rig.sphere_radius_m), material));
      break;
    }
    case ContactKind::spring_dashpot: {
      auto* law = new SpringDashpotContact(chain, std::get<ViscoelasticLaw>(rig.law), rig.sphere_radius_m);
      spring_dashpot_ = law;
      Force::Custom(chain.forces(), law);  // the force subsystem owns it
      break;
    }
    case ContactKind::rigid_newton: {
      const double e = std::get<NewtonLaw>(rig.law).restitution;
      // SphereSphereContact(body F, centre, radius, body B, centre, radius, minCOR, mu_s, mu_d, mu_v):
      // the COR is e above the stepper's minCOR speed (set small in SimbodyStepper), frictionless
      chain.matter().adoptUnilateralContact(
          new SphereSphereContact(chain.tip_body(0), chain.tip_station_m(0), rig.sphere_radius_m, chain.tip_body(1),
                                  chain.tip_station_m(1), rig.sphere_radius_m, e, 0, 0, 0));
      break;
    }
  }
}

double SimbodyContact::force_n(const State& state) const {
  if (kind_ == ContactKind::spring_dashpot) return spring_dashpot_->force_n(state);
  if (kind_ != ContactKind::hunt_crossley) return 0;
  chain_.system().realize(state, Stage::Dynamics);
  double force = 0;
  for (int i = 0; i < compliant_->getNumContactForces(state); ++i)
    force += compliant_->getContactForce(state, i).getForceOnSurface2()[1].norm();  // [1]: the force, [0] the moment
  return force;
}

}  // namespace ib::simbody
