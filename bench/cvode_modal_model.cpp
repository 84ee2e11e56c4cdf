#include "cvode_modal_model.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace ib::bench {
namespace {

using Json = nlohmann::json;

// Every message names the file and the key, as bench/scipy_modal_model.py's do.
[[noreturn]] void fail(const std::string& path, const std::string& text) {
  throw std::runtime_error(path + ": " + text);
}

const Json& get(const Json& data, const std::string& key, const std::string& path, const std::string& where = "") {
  if (!data.is_object() || !data.contains(key)) fail(path, "missing key '" + where + key + "'");
  return data.at(key);
}

enum class Sign { any, positive, non_negative };

double number(const Json& data, const std::string& key, const std::string& path, const std::string& where = "",
              Sign sign = Sign::any) {
  const Json& value = get(data, key, path, where);
  if (!value.is_number() || !std::isfinite(value.get<double>()))
    fail(path, "'" + where + key + "' = " + value.dump() + ": allowed: a finite number");
  const double x = value.get<double>();
  if (sign == Sign::positive && !(x > 0))
    fail(path, "'" + where + key + "' = " + value.dump() + ": allowed: a number > 0");
  if (sign == Sign::non_negative && !(x >= 0))
    fail(path, "'" + where + key + "' = " + value.dump() + ": allowed: a number >= 0");
  return x;
}

std::vector<double> numbers(const Json& data, const std::string& key, const std::string& path, std::size_t size,
                            const std::string& where = "") {
  const Json& value = get(data, key, path, where);
  bool ok = value.is_array() && (size == 0 ? !value.empty() : value.size() == size);
  std::vector<double> out;
  for (const Json& x : value) {
    if (!x.is_number() || !std::isfinite(x.get<double>())) ok = false;
    if (ok) out.push_back(x.get<double>());
  }
  if (!ok)
    fail(path, "'" + where + key + "': allowed: a list of " +
                   (size ? std::to_string(size) : std::string("one or more")) +
                   " finite numbers (one per stacked mode)");
  return out;
}

ContactLaw read_law(const Json& data, const std::string& path) {
  const std::string w = "contact_law.";
  ContactLaw law;
  const Json& name = get(data, "name", path, w);
  law.name = name.is_string() ? name.get<std::string>() : name.dump();
  if (law.name == "hertz") {
    law.kind = ContactLaw::Kind::hertz;
    law.stiffness = number(data, "stiffness_n_per_m_pow_n", path, w, Sign::positive);
    law.exponent = number(data, "exponent", path, w, Sign::positive);
    law.damping = number(data, "damping_n_s_per_m_pow_n_plus_1", path, w, Sign::non_negative);
    law.clipped = true;
  } else if (law.name == "viscoelastic") {
    law.kind = ContactLaw::Kind::viscoelastic;
    law.stiffness = number(data, "stiffness_n_per_m", path, w, Sign::positive);
    law.damping = number(data, "damping_n_s_per_m", path, w, Sign::non_negative);
    const Json& clip = get(data, "clip_tension", path, w);
    if (!clip.is_boolean()) fail(path, "'contact_law.clip_tension' = " + clip.dump() + ": allowed: true or false");
    law.clipped = clip.get<bool>();
  } else if (law.name == "newton") {
    law.kind = ContactLaw::Kind::newton;
    law.restitution = number(data, "restitution", path, w, Sign::non_negative);
    if (law.restitution > 1)
      fail(path, "'contact_law.restitution' = " + std::to_string(law.restitution) + ": allowed: 0 <= e <= 1");
  } else {
    fail(path, "'contact_law.name' = " + name.dump() + ": allowed: hertz, viscoelastic, newton");
  }
  return law;
}

double dot(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0;
  for (std::size_t i = 0; i < a.size(); ++i) s += a[i] * b[i];
  return s;
}

}  // namespace

double ContactLaw::unclipped(double delta, double rate) const {
  if (kind == Kind::hertz)
    return stiffness * std::copysign(std::pow(std::abs(delta), exponent), delta) * (1 + damping / stiffness * rate);
  return stiffness * delta + damping * rate;
}

double ContactLaw::force(double delta, double rate) const {
  if (kind == Kind::newton) return 0;
  if (kind == Kind::hertz)
    return stiffness * std::copysign(std::pow(std::abs(delta), exponent), delta) *
           std::max(0.0, 1 + damping / stiffness * rate);
  const double f = stiffness * delta + damping * rate;
  return clipped ? std::max(0.0, f) : f;
}

double ContactLaw::unclipped_rate(double delta, double rate, double acceleration) const {
  if (kind == Kind::hertz) {
    const double magnitude = std::abs(delta);
    const double power = std::copysign(std::pow(magnitude, exponent), delta);
    const double d_power = exponent * std::pow(magnitude, exponent - 1);
    return stiffness * d_power * (1 + damping / stiffness * rate) * rate + damping * power * acceleration;
  }
  return stiffness * rate + damping * acceleration;
}

double ModalModel::motor(double t) const { return motor_amplitude * std::cos(motor_omega * t); }

ModalModel read_modal_model(const std::string& path) {
  std::ifstream in(path);
  if (!in) fail(path, "cannot read");
  Json data;
  try {
    data = Json::parse(in);
  } catch (const Json::parse_error& error) {
    fail(path, std::string("not JSON: ") + error.what());
  }
  if (!data.is_object() || data.value("format", std::string()) != "impactbench modal model 1")
    fail(path,
         "'format': allowed: 'impactbench modal model 1' (write it with: impactbench export SCENARIO --engine "
         "reference --law LAW --out FILE)");
  ModalModel m;
  m.path = path;
  m.scenario = data.value("scenario", std::string());
  m.omega = numbers(data, "omega_rad_s", path, 0);
  for (double w : m.omega)
    if (!(w > 0)) fail(path, "'omega_rad_s': allowed: a non-empty list of frequencies > 0 rad/s");
  const std::size_t n = m.modes();
  m.zeta = numbers(data, "zeta", path, n);
  m.b = numbers(data, "contact_lever_per_sqrt_kg", path, n);
  m.p = numbers(data, "motor_lever_per_sqrt_kg", path, n);
  const Json& recorded = get(data, "recorded", path);
  m.tip1 = numbers(recorded, "frame1_tip_lever_per_sqrt_kg", path, n, "recorded.");
  m.tip2 = numbers(recorded, "frame2_tip_lever_per_sqrt_kg", path, n, "recorded.");
  m.gap = number(data, "gap_m", path);
  if (data.contains("motor")) {  // absent when the scenario has no motor
    m.motor_amplitude = number(data["motor"], "amplitude_n", path, "motor.");
    m.motor_omega = number(data["motor"], "omega_rad_s", path, "motor.", Sign::non_negative);
  }
  m.law = read_law(get(data, "contact_law", path), path);
  const Json& initial = get(data, "initial", path);
  m.q0 = numbers(initial, "q_m_sqrt_kg", path, n, "initial.");
  m.v0 = numbers(initial, "v_m_s_sqrt_kg", path, n, "initial.");
  m.duration = number(data, "duration_s", path, "", Sign::positive);
  m.series_start = number(data, "series_start_s", path, "", Sign::non_negative);
  m.output_rate = number(data, "output_rate_hz", path, "", Sign::positive);
  const Json& settings = get(data, "reference_settings", path);
  m.rtol = number(settings, "rtol", path, "reference_settings.", Sign::positive);
  m.atol = number(settings, "atol_m_sqrt_kg", path, "reference_settings.", Sign::positive);
  m.accumulation_time = number(settings, "accumulation_time_s", path, "reference_settings.", Sign::non_negative);
  for (std::size_t i = 0; i < n; ++i) {
    m.damping_rate.push_back(2 * m.zeta[i] * m.omega[i]);
    m.stiffness.push_back(m.omega[i] * m.omega[i]);
  }
  m.lever_norm2 = dot(m.b, m.b);
  return m;
}

}  // namespace ib::bench
