#include "physics/contact_laws.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace ib {
namespace {

template <class... F>
struct overloaded : F... {
  using F::operator()...;
};
template <class... F>
overloaded(F...) -> overloaded<F...>;

}  // namespace

ContactModel make_contact_model(const Scenario& scenario, ContactLaw law) {
  if (!scenario.contact.has(law))
    throw std::invalid_argument((scenario.source_path.empty() ? scenario.name : scenario.source_path) +
                                ": the scenario has no [contact." + to_string(law) + "] table, so the " +
                                to_string(law) + " law cannot be run on it");
  switch (law) {
    case ContactLaw::hertz: {
      const HertzSpec& s = *scenario.contact.hertz;
      return HertzLaw{s.stiffness, s.exponent, s.damping_coefficient()};
    }
    case ContactLaw::viscoelastic: {
      const ViscoelasticSpec& s = *scenario.contact.viscoelastic;
      return ViscoelasticLaw{s.stiffness_n_per_m, s.damping_n_s_per_m, s.clip_tension};
    }
    case ContactLaw::newton:
      return NewtonLaw{scenario.contact.newton->restitution};
  }
  throw std::logic_error("unknown contact law");
}

bool is_instantaneous(const ContactModel& model) { return std::holds_alternative<NewtonLaw>(model); }

double contact_force_continued(const ContactModel& model, double delta, double rate) {
  return std::visit(overloaded{[&](const HertzLaw& h) {
                                 // k sign(delta) |delta|^n max(0, 1 + c/k delta'): equal to the law for delta > 0.
                                 const double spring =
                                     h.stiffness * std::copysign(std::pow(std::abs(delta), h.exponent), delta);
                                 return spring * std::max(0.0, 1 + h.damping / h.stiffness * rate);
                               },
                               [&](const ViscoelasticLaw& v) {
                                 const double f = v.stiffness_n_per_m * delta + v.damping_n_s_per_m * rate;
                                 return v.clip_tension ? std::max(0.0, f) : f;
                               },
                               [&](const NewtonLaw&) { return 0.0; }},
                    model);
}

double contact_force_unclipped(const ContactModel& model, double delta, double rate) {
  return std::visit(
      overloaded{[&](const HertzLaw& h) {
                   const double spring = h.stiffness * std::copysign(std::pow(std::abs(delta), h.exponent), delta);
                   return spring * (1 + h.damping / h.stiffness * rate);
                 },
                 [&](const ViscoelasticLaw& v) { return v.stiffness_n_per_m * delta + v.damping_n_s_per_m * rate; },
                 [&](const NewtonLaw&) { return 0.0; }},
      model);
}

double contact_force_rate(const ContactModel& model, double delta, double rate, double acceleration) {
  return std::visit(overloaded{[&](const HertzLaw& h) {
                                 const double factor = 1 + h.damping / h.stiffness * rate;
                                 if (factor <= 0) return 0.0;
                                 const double power = std::copysign(std::pow(std::abs(delta), h.exponent), delta);
                                 const double d_power =
                                     h.exponent *
                                     std::pow(std::abs(delta), h.exponent - 1);  // d|delta|^n sign / d delta
                                 return h.stiffness * d_power * factor * rate + h.damping * power * acceleration;
                               },
                               [&](const ViscoelasticLaw& v) {
                                 if (v.clip_tension && v.stiffness_n_per_m * delta + v.damping_n_s_per_m * rate <= 0)
                                   return 0.0;
                                 return v.stiffness_n_per_m * rate + v.damping_n_s_per_m * acceleration;
                               },
                               [&](const NewtonLaw&) { return 0.0; }},
                    model);
}

double contact_force(const ContactModel& model, double delta, double rate) {
  if (delta <= 0) return 0;
  return contact_force_continued(model, delta, rate);
}

double elastic_contact_force(const ContactModel& model, double delta) {
  if (delta <= 0) return 0;
  return std::visit(overloaded{[&](const HertzLaw& h) { return h.stiffness * std::pow(delta, h.exponent); },
                               [&](const ViscoelasticLaw& v) { return v.stiffness_n_per_m * delta; },
                               [&](const NewtonLaw&) { return 0.0; }},
                    model);
}

double elastic_contact_energy(const ContactModel& model, double delta) {
  if (delta <= 0) return 0;
  return std::visit(
      overloaded{[&](const HertzLaw& h) { return h.stiffness * std::pow(delta, h.exponent + 1) / (h.exponent + 1); },
                 [&](const ViscoelasticLaw& v) { return 0.5 * v.stiffness_n_per_m * delta * delta; },
                 [&](const NewtonLaw&) { return 0.0; }},
      model);
}

}  // namespace ib
