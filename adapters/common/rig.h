// The rig as every engine builds it (rig.md section 4), derived from a scenario in one tested place:
// two chains of K rigid links with hinge springs, the tip masses merged into the last links, tip
// spheres placed so that the surface gap at rest is the scenario's gap, and the motor force on frame
// 1's tip. Plain data in SI units; the engines only translate it into their own terms.
//
// Geometry shared by all engines: the beams stand along +z from z = 0; they bend in the x-z plane
// (hinge axes along y); frame 1's clamp is at x = 0 and frame 2's at x = frame_spacing_m, so that a
// tip displacement u along +x is toward frame 2 for frame 1.
#pragma once

#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "model/scenario.h"
#include "model/simulator.h"
#include "model/simulator_options.h"
#include "physics/contact_laws.h"
#include "physics/link_chain.h"
#include "physics/modal_model.h"

namespace ib {

// One rigid body of a chain as an engine sees it: the link with, on the last one, the tip mass.
struct RigBody {
  double joint_z_m = 0;         // the hinge it hangs from, height above the clamp [m]
  double length_m = 0;          // from its hinge to the next (or to the tip) [m]
  double mass_kg = 0;           // link (+ tip mass on the last) [kg]
  double com_z_m = 0;           // centre of mass height [m]
  double inertia_y_kg_m2 = 0;   // about the centre of mass, around the hinge axis (y) [kg m^2]
  double inertia_xz_kg_m2 = 0;  // about the other two axes: the same slender-rod value (engines need 3) [kg m^2]
};

struct FrameRig {
  LinkChain chain;                     // the physics (physics/link_chain.h)
  std::vector<RigBody> bodies;         // K bodies, in hinge order from the clamp
  double base_x_m = 0;                 // clamp position along x [m]
  double tip_z_m = 0;                  // the tip point (= beam length) [m]
  Eigen::VectorXd initial_angles_rad;  // relative hinge angles at t = 0 (static tip-load shape, or zero)
  double tip_effective_mass_kg = 0;    // 1 / (g^T M^-1 g) of the linearised chain [kg]
};

struct RigSpec {
  std::array<FrameRig, 2> frames;
  double gap_m = 0;                      // surface gap of the tip spheres at rest [m]
  double sphere_radius_m = 0;            // both tip spheres [m]
  double frame_spacing_m = 0;            // frame 2's clamp x = gap + 2 radius [m]
  std::optional<MotorForce> motor;       // on frame 1's tip along x; absent without a motor
  ContactModel law;                      // the run's contact law with its parameters
  double contact_effective_mass_kg = 0;  // 1 / (1/m1 + 1/m2) of the two tips [kg]
  double duration_s = 0;
};

constexpr double kTipSphereRadius_m = 5e-3;

// The smallest K (up to 64) whose uniform chain (every joint EI / l) has its first frequency within 0.5 % of
// the continuous beam's, for both frames: the engines' default discretisation. (The tuned chain matches the
// first two frequencies at any K; the uniform chain's error says how well K links resolve the beam.)
int default_links(const Scenario& scenario);

// Both chains with the damping `damping` (physics/link_chain.h; the option chain_damping_option reads).
RigSpec build_rig(const Scenario& scenario, ContactLaw law, int links, ChainDamping damping = ChainDamping::modal);

// The option "links" of every engine that builds this rig: its help line (an engine's option_help) and its
// value, the option when given (checked: 1..64, named by the engine's reader), else default_links(scenario).
constexpr const char* kLinksOptionHelp =
    "links K per frame, 1..64 (default: the smallest K whose first frequency is within 0.5 % of the beam's)";
int links_option(const OptionReader& options, const RunSettings& settings, const Scenario& scenario);
// The option chain_damping of every engine that builds this rig (help: kChainDampingOptionHelp, with its name
// kChainDampingOption, physics/link_chain.h): modal (default) or hinge, checked by the engine's reader.
ChainDamping chain_damping_option(const OptionReader& options);

// Both frames' hinge angles or rates, zero: the size each chain's state has (K entries per frame).
std::array<Eigen::VectorXd, 2> zero_hinge_values(const RigSpec& rig);

// Frame f's chain as an engine's diagnostics name it: frameN_chain_first_frequency_hz,
// frameN_root_joint_stiffness_n_m_per_rad, frameN_joint_stiffness_scale, frameN_joint_stiffness_taper,
// frameN_root_joint_damping_n_m_s_per_rad (N = f + 1).
void add_chain_diagnostics(const RigSpec& rig, int f, std::vector<std::pair<std::string, double>>& diagnostics);

// The longest step at which explicit hinge springs and dampers stay stable [s], for engines that apply
// them as forces and integrate with semi-implicit (symplectic) Euler (ODE's springs=explicit, Bullet),
// the damping being either the hinge dampers or the modal damping torques -C theta' the fixed-step loop
// holds over a step from the rates at its start (fixed_step_loop.h). Both dampings keep the linearised
// chain's modes apart, and one mode (omega_n, zeta_n) is stable while (omega h)^2 + 4 zeta omega h < 4, i.e.
// omega h < 2 (sqrt(1 + zeta^2) - zeta): 2 / omega without damping. Hinge damping: the fastest modes are
// heavily damped, so the limit is below 2 / omega_max; K = 8: 7.5e-5 s, set by the fastest mode (1966 Hz,
// zeta 0.85). Modal damping: zeta_n = zeta (0.003) in every mode, so the limit is 2 (1 - zeta) / omega_max
// to first order, about twice the hinge damping's. Where the engine's springs are implicit (their force at
// the step's end) and only the modal damping is explicit, a mode's step matrix (x, h v) is
// [[1, 1 - 2 zeta a], [-a^2, 1 - 2 zeta a]] / (1 + a^2) with a = omega h, whose eigenvalues stay inside
// the unit circle at every a for zeta < 1 (Jury: a^2 - 2 zeta a + 2 > 0 and a^2 - 4 zeta a + 4 > 0): the
// explicit modal damping adds no step limit there. tests/rig_test.cpp checks both on the stepped chain.
double explicit_hinge_step_limit_s(const RigSpec& rig);

// Mechanical energy of the rig from its hinge angles and rates (linearised chain: kinetic
// 1/2 w^T M w plus spring 1/2 q^T K q per frame) plus the contact law's elastic energy at the
// indentation [J]. The same measure for every engine.
class RigEnergy {
 public:
  explicit RigEnergy(const RigSpec& rig);
  double operator()(const std::array<Eigen::VectorXd, 2>& angles, const std::array<Eigen::VectorXd, 2>& rates,
                    double indentation_m) const;

 private:
  std::array<ChainMatrices, 2> matrices_;
  ContactModel law_;
};

}  // namespace ib
