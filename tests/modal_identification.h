// The damped modes in a sampled free decay, for tests that compare an engine's chain with the reference's:
// compiled once (modal_identification.cpp), since its Eigen decompositions cost a minute of compiling.
#pragma once

#include <vector>

namespace ib::test {

struct DampedMode {
  double frequency_hz = 0;   // undamped natural frequency |s| / 2 pi [Hz]
  double damping_ratio = 0;  // -Re(s) / |s| [-]
  double energy = 0;         // the mode's share of the signal's energy over the record [signal^2]
};

// The matrix pencil method (Hua and Sarkar 1990): the samples of a sum of damped exponentials
// y_n = sum a_i z_i^n make a Hankel matrix of rank `order` whose shifted right singular vectors give the z_i
// exactly (no noise beyond rounding). One mode per conjugate pair (real poles, overdamped modes, are left
// out), ranked by energy, largest first: a signal may carry weak harmonics besides its modes.
std::vector<DampedMode> matrix_pencil_modes(const std::vector<double>& samples, double sample_interval_s, int order);

}  // namespace ib::test
