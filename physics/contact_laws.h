// The three contact laws of rig.md section 3, as built for one run: only the chosen law, with only
// its own parameters. Shared by the reference and by every engine adapter that applies a law as a
// force computed from the tip states, so that all of them use the same physics.
#pragma once

#include <variant>

#include "model/scenario.h"

namespace ib {

// F = k delta^n + c delta^n delta' (Hunt-Crossley with Lankarani-Nikravesh damping), zero where negative.
struct HertzLaw {
  double stiffness = 0;   // k_h [N/m^n]
  double exponent = 1.5;  // n [-]
  double damping = 0;     // c_h [N s/m^(n+1)]
};

// F = k delta + c delta'; optionally clipped at zero (no tension).
struct ViscoelasticLaw {
  double stiffness_n_per_m = 0;
  double damping_n_s_per_m = 0;
  bool clip_tension = false;
};

// Instantaneous impact with restitution e.
struct NewtonLaw {
  double restitution = 0.8;
};

using ContactModel = std::variant<HertzLaw, ViscoelasticLaw, NewtonLaw>;

// The law a run asked for, from the scenario's parameters. Throws std::invalid_argument naming the
// scenario file when the scenario has no parameters for that law.
ContactModel make_contact_model(const Scenario& scenario, ContactLaw law);

bool is_instantaneous(const ContactModel& model);

// Contact force [N] for indentation delta [m] (> 0: penetration) and its rate delta' [m/s].
// Zero when delta <= 0. Not defined for the Newton law (returns 0).
double contact_force(const ContactModel& model, double indentation_m, double indentation_rate_m_s);

// The elastic part of the force and its potential: k delta^n and k delta^(n+1) / (n+1) (Hertz) or
// k delta and k delta^2 / 2 (spring-dashpot); zero when delta <= 0. Used for energy balances.
double elastic_contact_force(const ContactModel& model, double indentation_m);
double elastic_contact_energy(const ContactModel& model, double indentation_m);

// The force continued smoothly to delta < 0 (an attractive "ghost" force, never applied): used only
// inside the integrator step that crosses a separation so that its dense output stays smooth there.
double contact_force_continued(const ContactModel& model, double indentation_m, double indentation_rate_m_s);

// The law's expression before it is clipped at zero (Hertz: k delta^n (1 + c/k delta'); clipped
// spring-dashpot: k delta + c delta'), for locating where a clipped force ends; equal to
// contact_force_continued for laws that are not clipped.
double contact_force_unclipped(const ContactModel& model, double indentation_m, double indentation_rate_m_s);

// dF/dt [N/s] of the (continued) law along a motion with indentation delta, delta' and delta''.
double contact_force_rate(const ContactModel& model, double indentation_m, double indentation_rate_m_s,
                          double indentation_acceleration_m_s2);

}  // namespace ib
