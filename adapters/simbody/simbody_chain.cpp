#include "adapters/simbody/simbody_chain.h"

#include <cmath>

namespace ib::simbody {

using namespace SimTK;

namespace {
// A Pin mobilizer turns about the z axis of its frames; this rotation takes that axis to ground (and
// parent) y, the rig's hinge axis. Used for both the inboard (F) and outboard (M) frames, so that the
// links are straight at q = 0 and a positive q turns the link from +z toward +x (as rig.md's angles).
const Rotation kZToY(-Pi / 2, XAxis);
}  // namespace

void TipLoads::calcForce(const State& state, Vector_<SpatialVec>& body_forces, Vector_<Vec3>&, Vector&) const {
  const double frame1_n = tip_force_n_[0] + motor_force_n(state.getTime());
  tips_[0].applyForceToBodyPoint(state, stations_m_[0], Vec3(frame1_n, 0, 0), body_forces);
  tips_[1].applyForceToBodyPoint(state, stations_m_[1], Vec3(tip_force_n_[1], 0, 0), body_forces);
}

void HingeDampingMatrix::calcForce(const State& state, Vector_<SpatialVec>&, Vector_<Vec3>&,
                                   Vector& mobility_forces) const {
  for (int f = 0; f < 2; ++f) {
    const Eigen::Index k = damping_[f].rows();
    if (k == 0) continue;
    Eigen::VectorXd rates(k);
    for (Eigen::Index j = 0; j < k; ++j) rates[j] = links_[f][static_cast<std::size_t>(j)].getRate(state);
    const Eigen::VectorXd torques = -damping_[f] * rates;
    for (Eigen::Index j = 0; j < k; ++j)
      links_[f][static_cast<std::size_t>(j)].applyOneMobilityForce(state, 0, torques[j], mobility_forces);
  }
}

SimbodyChain::SimbodyChain(const RigSpec& rig) : rig_(rig), matter_(system_), forces_(system_) {
  system_.setUseUniformBackground(true);  // no gravity: the rig has none (rig.md)
  for (int f = 0; f < 2; ++f) build_frame(rig.frames[f], frames_[f]);
  auto* loads = new TipLoads({tip_body(0), tip_body(1)}, {tip_station_m(0), tip_station_m(1)}, rig.motor);
  loads_ = loads;
  Force::Custom(forces_, loads);  // the subsystem owns it
  if (rig.frames[0].chain.modal_damping_n_m_s_per_rad.size() > 0 ||
      rig.frames[1].chain.modal_damping_n_m_s_per_rad.size() > 0)
    Force::Custom(forces_, new HingeDampingMatrix({frames_[0].links, frames_[1].links},
                                                  {rig.frames[0].chain.modal_damping_n_m_s_per_rad,
                                                   rig.frames[1].chain.modal_damping_n_m_s_per_rad}));
}

// Body frames sit at each link's hinge; the centre of mass and the inertia (about it, as RigBody gives
// them) are shifted there, so a child's hinge is at (0, 0, its joint height - this one's) in the parent.
void SimbodyChain::build_frame(const FrameRig& spec, Frame& frame) {
  frame.base_x_m = spec.base_x_m;
  MobilizedBody parent = matter_.Ground();
  double parent_joint_z_m = 0;
  for (std::size_t j = 0; j < spec.bodies.size(); ++j) {
    const RigBody& b = spec.bodies[j];
    const Vec3 com_m(0, 0, b.com_z_m - b.joint_z_m);
    const Inertia about_com(Vec3(b.inertia_xz_kg_m2, b.inertia_y_kg_m2, b.inertia_xz_kg_m2));
    const Body::Rigid body(MassProperties(b.mass_kg, com_m, about_com.shiftFromMassCenter(com_m, b.mass_kg)));
    const Vec3 hinge_in_parent_m =
        j == 0 ? Vec3(spec.base_x_m, 0, b.joint_z_m) : Vec3(0, 0, b.joint_z_m - parent_joint_z_m);
    MobilizedBody::Pin link(parent, Transform(kZToY, hinge_in_parent_m), body, Transform(kZToY, Vec3(0)));
    // the hinge's spring (rest angle 0: the straight beam) and damper, on the pin's one coordinate
    const double k = spec.chain.joint_stiffness_n_m_per_rad[j], c = spec.chain.joint_damping_n_m_s_per_rad[j];
    Force::MobilityLinearSpring(forces_, link, MobilizerQIndex(0), k, 0);
    if (c > 0) Force::MobilityLinearDamper(forces_, link, MobilizerUIndex(0), c);  // hinge damping only
    frame.links.push_back(link);
    parent = link;
    parent_joint_z_m = b.joint_z_m;
  }
  frame.tip_station_m = Vec3(0, 0, spec.tip_z_m - spec.bodies.back().joint_z_m);
}

State SimbodyChain::initial_state() {
  State state = system_.realizeTopology();
  for (int f = 0; f < 2; ++f) {
    const Eigen::VectorXd& angles = rig_.frames[f].initial_angles_rad;
    for (std::size_t j = 0; j < frames_[f].links.size(); ++j) {
      frames_[f].links[j].setAngle(state, angles[static_cast<Eigen::Index>(j)]);
      frames_[f].links[j].setRate(state, 0);
    }
  }
  system_.realize(state, Stage::Velocity);
  return state;
}

void SimbodyChain::set_hinge(State& state, int f, int j, double angle_rad, double rate_rad_s) {
  frames_[f].links[j].setAngle(state, angle_rad);
  frames_[f].links[j].setRate(state, rate_rad_s);
}

Vec3 SimbodyChain::tip_position_m(const State& state, int f) const {
  return tip_body(f).findStationLocationInGround(state, frames_[f].tip_station_m);
}

Vec3 SimbodyChain::tip_velocity_m_s(const State& state, int f) const {
  return tip_body(f).findStationVelocityInGround(state, frames_[f].tip_station_m);
}

TipReading SimbodyChain::tip(const State& state, int f) const {
  return {tip_position_m(state, f)[0] - frames_[f].base_x_m, tip_velocity_m_s(state, f)[0]};
}

void SimbodyChain::hinge_state(const State& state, int f, Eigen::VectorXd& angles_rad,
                               Eigen::VectorXd& rates_rad_s) const {
  for (std::size_t j = 0; j < frames_[f].links.size(); ++j) {
    angles_rad[static_cast<Eigen::Index>(j)] = frames_[f].links[j].getAngle(state);
    rates_rad_s[static_cast<Eigen::Index>(j)] = frames_[f].links[j].getRate(state);
  }
}

}  // namespace ib::simbody
