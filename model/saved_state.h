// A simulator's own state at the end of a run, from which another run continues (a frequency sweep's
// continuation, docs/sweeps.md): the reference keeps its modal coordinates and velocities, an engine its
// joint positions and velocities (or whatever it needs to continue its bodies exactly). Each simulator
// reads only what it wrote itself for the same rig and run settings, and refuses anything else.
#pragma once

#include <string>
#include <vector>

namespace ib {

struct SavedState {
  std::string simulator;       // the simulator that wrote it, e.g. "reference", "mujoco"
  std::string layout;          // what the values are, in the simulator's words (checked on reading)
  std::vector<double> values;  // SI units (m, rad, m/s, rad/s; modal: sqrt(kg) m and sqrt(kg) m/s)
};

// Throws std::invalid_argument unless state was written by `simulator` with `layout`, naming both.
void check_saved_state(const SavedState& state, const std::string& simulator, const std::string& layout);

// Text form: "simulator\nlayout\n" then one value per line with 17 significant digits (exact round trip).
std::string saved_state_text(const SavedState& state);
// Throws std::invalid_argument naming `where` and the line for a malformed text.
SavedState parse_saved_state(const std::string& text, const std::string& where);

}  // namespace ib
