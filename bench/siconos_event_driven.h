// The reference's modal model with the Newton law integrated by Siconos's event-driven scheme (LsodarOSI
// between events, an impact LCP at each event, an acceleration LCP for the contact's status): a second
// Newton reference written in another library, beside the CVODE one (bench/cvode_solver.h). It reads the
// same exported model (cvode_modal_model.h) and writes the same records, so the two compare event by event.
//
// Only bench/siconos_reference.cpp uses it; no header here names a Siconos type, so that the rest of the
// comparator compiles without the library's headers (which need C++17 at most).
#pragma once

#include <string>
#include <vector>

#include "cvode_modal_model.h"

namespace ib::bench {

struct SiconosSettings {
  double rtol = 1e-12;   // Lsodar's relative tolerance [-]
  double atol = 1e-14;   // Lsodar's absolute tolerance on every state component [m sqrt(kg)], [m/s sqrt(kg)]
  int max_impacts = 20;  // the run stops after this many impacts
  double duration = 0;   // [s]; 0: the model's
  bool record_samples = false;
};

// One Newton impact: zero duration, the velocities of delta (b . q') before and after it.
struct SiconosImpact {
  double time_s = 0;
  double approach_velocity_m_s = 0;  // delta' before, > 0 when the tips close
  double rebound_velocity_m_s = 0;   // -delta' after, > 0 when they separate
  double restitution = 0;            // rebound / approach [-]
  double impulse_n_s = 0;            // Siconos's percussion on the contact (lambda at velocity level) [N s]
};

struct SiconosSample {
  double time_s = 0;
  double displacement1_m = 0, displacement2_m = 0;
  double velocity1_m_s = 0, velocity2_m_s = 0;
};

struct SiconosResult {
  bool ok = false;
  std::string reason;  // why the run stopped early or failed
  std::string stop;    // "duration", "max_impacts" or "accumulation"
  double end_time_s = 0;
  std::vector<SiconosImpact> impacts;
  std::vector<SiconosSample> samples;
  double cpu_time_s = 0, wall_time_s = 0;  // the integration alone (the model built before the clocks start)
  long events_processed = 0;               // Siconos's events: impacts and output (time-discretisation) events
};

// Throws std::invalid_argument when the model's law is not Newton.
SiconosResult solve_with_siconos(const ModalModel& model, const SiconosSettings& settings);

// The Debian package's version the comparator was built against (the headers carry none).
std::string siconos_version();

}  // namespace ib::bench
