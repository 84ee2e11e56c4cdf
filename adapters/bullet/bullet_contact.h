// The contact laws of rig.md section 3 in Bullet's own terms, in one tested place.
//
// Bullet keeps contact parameters per collision object and combines the two objects' values for each
// contact point (btManifoldResult): stiffness in series, 1 / (1/k_a + 1/k_b); damping summed,
// c_a + c_b; restitution multiplied, e_a e_b. Every object carries a damping of 0.1 N s/m and a
// stiffness of 1e30 N/m until set, so setting the law's k and c on one tip only would give c + 0.1.
// The functions here set both tips so that the combined values are the law's (to Bullet's rounding).
#pragma once

#include <array>

class btCollisionObject;
struct btContactSolverInfo;

namespace ib::bullet {

// What one collision object carries for btCollisionObject::setContactStiffnessAndDamping.
struct ContactStiffnessDamping {
  double stiffness_n_per_m = 0;
  double damping_n_s_per_m = 0;
};

// The values for the two tips whose Bullet combination is stiffness k and damping c: tip 1 carries
// k and c/2, tip 2 is rigid (infinite stiffness adds nothing in series) and carries c/2. The damping
// is then exactly c. The stiffness is k to the last bit where Bullet's formula can produce k at all,
// else the nearest value it can (1 ulp, 1e-16 relative): its final division 1 / (1/k_1 + 1/k_2) has
// sparser results than the doubles near k. Two equal springs of 2k each would add a second rounding.
// Throws std::invalid_argument for k <= 0 or c < 0.
std::array<ContactStiffnessDamping, 2> spring_dashpot_per_tip(double stiffness_n_per_m, double damping_n_s_per_m);

// Bullet's own combination rules for two collision objects (btManifoldResult), for checking.
double combined_contact_stiffness(const btCollisionObject& a, const btCollisionObject& b);
double combined_contact_damping(const btCollisionObject& a, const btCollisionObject& b);
double combined_restitution(const btCollisionObject& a, const btCollisionObject& b);

// Spring-dashpot through Bullet's soft contact: sets spring_dashpot_per_tip on both tips, no friction
// (the rig's contact is normal only) and no restitution (the law's damping is the only loss).
// Bullet then solves each contact with ERP = h k / (h k + c) and CFM = 1 / (h k + c): the force of a
// step is k delta + c delta' at the END of the step (an implicit, backward-Euler spring-dashpot), and
// never tensile (the impulse is clamped at zero), so the unclipped published law becomes the clipped one.
void set_spring_dashpot(btCollisionObject& tip1, btCollisionObject& tip2, double stiffness_n_per_m,
                        double damping_n_s_per_m);
// The solver settings the spring-dashpot needs: split impulse off, so that the spring's position term
// always acts on the real velocity (with split impulse on, Bullet moves it into a pseudo-velocity for
// penetrations deeper than the split threshold, and the spring vanishes there).
void configure_spring_dashpot_solver(btContactSolverInfo& info);

// Newton's restitution e: e on tip 1 and 1 on tip 2 (their product is e exactly), no friction.
void set_restitution(btCollisionObject& tip1, btCollisionObject& tip2, double restitution);
// The solver settings that make Bullet's restitution the law's (engines.md, measured here):
//  - restitution velocity threshold 0: by default no bounce below 0.2 m/s, which is most of the rig's impacts;
//  - split impulse on with an infinite penetration threshold: the penetration is removed through a
//    pseudo-velocity only; otherwise Baumgarte's push-out (ERP) adds to the rebound (e = 0.9 seen for 0.8);
//  - contact ERP 0: Bullet 3.24 does not apply split impulse to btMultiBody contacts, where the push-out
//    then still adds to the rebound (e = 0.914 at h = 1e-5 s for 0.8); with no push-out the tips part
//    by their rebound alone;
//  - contact processing threshold 0 on the tips: no speculative contact before they touch.
// Warm starting is left on: in Bullet 3.24 the applied impulse is written back to the contact points
// only with warm starting, so without it the contact force cannot be read; Bullet rebuilds a sphere
// pair's contact points every step, so there is never an old impulse to start from (the recipe in
// engines.md turns it off; the realised e is the same, measured).
void configure_restitution_solver(btContactSolverInfo& info);
void set_restitution_processing_threshold(btCollisionObject& tip1, btCollisionObject& tip2);

// The equivalent restitution of a spring-dashpot contact between masses with reduced mass m:
// exp(-zeta pi / sqrt(1 - zeta^2)), zeta = c / (2 sqrt(k m)) (0 when overdamped).
double spring_dashpot_restitution(double stiffness_n_per_m, double damping_n_s_per_m, double reduced_mass_kg);

}  // namespace ib::bullet
