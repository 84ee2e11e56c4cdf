// The rig of adapters/common/rig.h in Simbody terms: per frame a chain of MobilizedBody::Pin links
// (axis along ground y) with Force::MobilityLinearSpring and Force::MobilityLinearDamper at every hinge,
// the tip mass merged into the last link as RigSpec gives it, and one Force::Custom element carrying the
// loads that come from outside the chain (the motor, evaluated at every stage time; the injected tip
// forces, held between the loop's steps). With modal chain damping (physics/link_chain.h) the hinge dampers
// are 0 and a second Force::Custom element applies the damping matrix, -C theta' from the rates of the state
// it is evaluated at: Simbody integrates it like its own dampers (the shared loop's held torques are for
// engines without a force element of their own). The contact is added by simbody_contact.h.
#pragma once

#include <Simbody.h>

#include <Eigen/Core>
#include <array>
#include <optional>
#include <vector>

#include "adapters/common/rig.h"

namespace ib::simbody {

// One tip as the loop reads it: along x from the clamp, positive toward frame 2.
struct TipReading {
  double displacement_m = 0;
  double velocity_m_s = 0;
};

// Forces from outside the chain, one Force::Custom element. Its members are read at every evaluation:
// the motor is a function of the stage time (exact inside Runge-Kutta stages and between error-controlled
// steps); the injected tip forces are values the adapter sets between steps (the integrator must then be
// told the state changed: SimbodyStepping::loads_changed).
class TipLoads : public SimTK::Force::Custom::Implementation {
 public:
  TipLoads(std::array<SimTK::MobilizedBody, 2> tips, std::array<SimTK::Vec3, 2> stations_m,
           std::optional<MotorForce> motor)
      : tips_(tips), stations_m_(stations_m), motor_(motor) {}
  void set_tip_forces_n(double frame1_n, double frame2_n) { tip_force_n_ = {frame1_n, frame2_n}; }
  double motor_force_n(double t_s) const { return motor_ ? motor_->at(t_s) : 0.0; }

  void calcForce(const SimTK::State& state, SimTK::Vector_<SimTK::SpatialVec>& body_forces,
                 SimTK::Vector_<SimTK::Vec3>&, SimTK::Vector&) const override;
  SimTK::Real calcPotentialEnergy(const SimTK::State&) const override { return 0; }

 private:
  std::array<SimTK::MobilizedBody, 2> tips_;
  std::array<SimTK::Vec3, 2> stations_m_;  // the tip point on each last link, in its body frame
  std::optional<MotorForce> motor_;
  std::array<double, 2> tip_force_n_{};  // along ground x
};

// The chains' modal damping matrices as mobility forces on the pins, -C theta' per frame, evaluated at every
// stage (no potential energy: it only dissipates).
class HingeDampingMatrix : public SimTK::Force::Custom::Implementation {
 public:
  HingeDampingMatrix(std::array<std::vector<SimTK::MobilizedBody::Pin>, 2> links,
                     std::array<Eigen::MatrixXd, 2> damping)
      : links_(std::move(links)), damping_(std::move(damping)) {}
  void calcForce(const SimTK::State& state, SimTK::Vector_<SimTK::SpatialVec>&, SimTK::Vector_<SimTK::Vec3>&,
                 SimTK::Vector& mobility_forces) const override;
  SimTK::Real calcPotentialEnergy(const SimTK::State&) const override { return 0; }

 private:
  std::array<std::vector<SimTK::MobilizedBody::Pin>, 2> links_;
  std::array<Eigen::MatrixXd, 2> damping_;  // C of each frame [N m s/rad]
};

class SimbodyChain {
 public:
  // Builds both frames of the rig into the system (not yet realised: the contact is added afterwards).
  explicit SimbodyChain(const RigSpec& rig);
  SimbodyChain(const SimbodyChain&) = delete;
  SimbodyChain& operator=(const SimbodyChain&) = delete;

  SimTK::MultibodySystem& system() { return system_; }
  SimTK::SimbodyMatterSubsystem& matter() { return matter_; }
  SimTK::GeneralForceSubsystem& forces() { return forces_; }
  const SimTK::MobilizedBody& tip_body(int f) const { return frames_[f].links.back(); }
  SimTK::MobilizedBody& tip_body(int f) { return frames_[f].links.back(); }
  // The tip point (the sphere's centre) in the last link's frame [m].
  const SimTK::Vec3& tip_station_m(int f) const { return frames_[f].tip_station_m; }
  TipLoads& loads() { return *loads_; }

  // Realises the topology and returns the initial state: the rig's initial hinge angles, at rest.
  SimTK::State initial_state();

  // Sets one hinge's angle [rad] and rate [rad/s] (j from the clamp); for tests that pose the rig.
  void set_hinge(SimTK::State& state, int f, int j, double angle_rad, double rate_rad_s);

  // Read from a state realised to Stage::Velocity.
  TipReading tip(const SimTK::State& state, int f) const;
  SimTK::Vec3 tip_position_m(const SimTK::State& state, int f) const;
  SimTK::Vec3 tip_velocity_m_s(const SimTK::State& state, int f) const;
  void hinge_state(const SimTK::State& state, int f, Eigen::VectorXd& angles_rad, Eigen::VectorXd& rates_rad_s) const;

 private:
  struct Frame {
    std::vector<SimTK::MobilizedBody::Pin> links;  // from the clamp
    SimTK::Vec3 tip_station_m;
    double base_x_m = 0;
  };
  void build_frame(const FrameRig& spec, Frame& frame);

  const RigSpec& rig_;
  SimTK::MultibodySystem system_;
  SimTK::SimbodyMatterSubsystem matter_;
  SimTK::GeneralForceSubsystem forces_;
  std::array<Frame, 2> frames_;
  TipLoads* loads_ = nullptr;  // owned by the Force::Custom element (the force subsystem)
};

}  // namespace ib::simbody
