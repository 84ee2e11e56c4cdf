// How the contact between the tips is made in Simbody for each path and law (model/simulator_options.h):
//  matched  - Hertz (n = 1.5): Simbody's Hunt-Crossley contact (CompliantContactSubsystem, its HertzCircular
//             generator) on the two tip spheres, the material mapped so that F = k_h delta^1.5 (1 + c_h/k_h
//             delta') exactly; Hertz with another exponent: no form in Simbody, the law's force from the tip
//             states (injected); spring-dashpot: a Force::Custom element computing k delta + c delta' between
//             the tip spheres' centres (clipped at zero when the law is); Newton: Simbody's rigid contact
//             (SphereSphereContact, SemiExplicitEulerTimeStepper, Newton restitution e);
//  injected - every law's force from the tip states (adapters/common/injected_contact.h), no Simbody contact;
//  native   - Simbody's Hunt-Crossley contact with physical steel (Simbody has no default material).
// Every contact is frictionless: the rig has none (rig.md).
#pragma once

#include <Simbody.h>

#include <memory>
#include <string>

#include "adapters/simbody/simbody_chain.h"
#include "model/simulator_options.h"
#include "physics/contact_laws.h"

namespace ib::simbody {

enum class ContactKind {
  injected,        // the harness's law applied as tip forces; Simbody makes no contact
  hunt_crossley,   // CompliantContactSubsystem, two ContactSurface spheres
  spring_dashpot,  // Force::Custom between the tip stations
  rigid_newton,    // SphereSphereContact + SemiExplicitEulerTimeStepper
};

// One surface's ContactMaterial: Simbody stores its stiffness as E^(2/3) and combines two surfaces as
// s1 = k2 / (k1 + k2), k = k1 s1, c = c1 s1 + c2 s2 (engines.md); both tips carry the same material.
struct HuntCrossleyMaterial {
  double stiffness_pa = 0;         // ContactMaterial stiffness [Pa]
  double dissipation_s_per_m = 0;  // ContactMaterial dissipation c [s/m]
};

// Physical steel for the native path: E = 200 GPa, Poisson 0.3, as ContactMaterial's plane-strain
// stiffness E / (1 - nu^2) (its own helper), and a Hunt-Crossley dissipation of 0.2 s/m, i.e. alpha =
// 1.5 c = 0.3 s/m, the upper end of Hunt and Crossley's 0.08 to 0.32 s/m for steel; restitution about
// 1 - 2/3 alpha v (0.98 at 0.1 m/s).
constexpr double kSteelYoungsModulus_pa = 200e9;
constexpr double kSteelPoissonRatio = 0.3;
constexpr double kSteelDissipation_s_per_m = 0.2;

// The material that makes Simbody's sphere-sphere Hunt-Crossley force between two equal spheres of
// radius r equal to the law's k_h delta^1.5 + c_h delta^1.5 delta': with R = r / 2 and the combined
// stiffness E0 / 2^1.5, (4/3) (E0 / 2^1.5) sqrt(R) = k_h gives E0 = 2^1.5 3 k_h / (4 sqrt(R)); and
// F_H 1.5 c delta' = c_h delta^1.5 delta' gives c = c_h / (1.5 k_h). Requires n = 1.5.
HuntCrossleyMaterial hertz_material(const HertzLaw& law, double sphere_radius_m);
HuntCrossleyMaterial steel_material();

// Simbody's Hunt-Crossley force for two equal spheres of radius r with that material as engines.md states
// its formula (F = (4/3) k^1.5 sqrt(R) delta^1.5 (1 + 1.5 c delta'), k = E^(2/3) / 2, R = r / 2), in
// closed form; tests/simbody_contact_mapping_test.cpp checks it against Simbody's own force on the rig.
double hunt_crossley_force_n(const HuntCrossleyMaterial& material, double sphere_radius_m, double indentation_m,
                             double indentation_rate_m_s);

struct ContactSetup {
  ContactKind kind = ContactKind::injected;
  HuntCrossleyMaterial material;  // hunt_crossley only
  std::string note;               // why the law is injected on the matched path (empty otherwise)
};

// Throws std::invalid_argument for nothing: every law has a path (Hertz n != 1.5 falls back to injected).
ContactSetup contact_setup(ContactPath path, const ContactModel& law);

// The spring-dashpot law as a Simbody force element between the sphere centres: delta = 2 r - |p2 - p1|,
// delta' its rate, the force along the line of centres (-F on frame 1's tip, +F on frame 2's).
class SpringDashpotContact : public SimTK::Force::Custom::Implementation {
 public:
  SpringDashpotContact(const SimbodyChain& chain, const ViscoelasticLaw& law, double sphere_radius_m)
      : chain_(chain), law_(law), radius_m_(sphere_radius_m) {}
  // The compressive force [N] (> 0 pushing the tips apart; < 0 pulling where the law is not clipped).
  double force_n(const SimTK::State& state) const;
  void calcForce(const SimTK::State& state, SimTK::Vector_<SimTK::SpatialVec>& body_forces,
                 SimTK::Vector_<SimTK::Vec3>&, SimTK::Vector&) const override;
  SimTK::Real calcPotentialEnergy(const SimTK::State& state) const override;

 private:
  const SimbodyChain& chain_;
  ViscoelasticLaw law_;
  double radius_m_;
};

// The contact made in the chain's system; call before SimbodyChain::initial_state().
class SimbodyContact {
 public:
  SimbodyContact(SimbodyChain& chain, const ContactSetup& setup, const RigSpec& rig);
  // The force between the tips in this state [N], > 0 compressive (the state realisable to Dynamics).
  // Newton: the impulses are not exposed; see SimbodyStepper (the velocity jump over the step).
  double force_n(const SimTK::State& state) const;

 private:
  SimbodyChain& chain_;
  ContactKind kind_;
  // Simbody's compliant contact keeps a reference to the tracker's handle: both live as long as the contact
  std::unique_ptr<SimTK::ContactTrackerSubsystem> tracker_;
  std::unique_ptr<SimTK::CompliantContactSubsystem> compliant_;
  const SpringDashpotContact* spring_dashpot_ = nullptr;  // owned by its Force::Custom
};

}  // namespace ib::simbody
