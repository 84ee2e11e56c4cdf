// How fast a free vibration dies out: the logarithmic decrement of a tip's displacement peaks, the
// figure a damping error shows in (a simulator whose joints or contacts dissipate too much decays
// faster than the reference, whatever its peaks and contact durations say).
#pragma once

#include <vector>

namespace ib {

// The mean logarithmic decrement per cycle, delta = ln(A_k / A_{k+1}), of a displacement series over
// [start_s, end_s]: one peak per cycle (the largest displacement between two upward zero crossings, so
// that higher modes riding on the first do not count as peaks), delta the least-squares slope of
// -ln(peak) against the cycle's index. NaN with fewer than three whole cycles in the window or a
// non-positive peak. For u = A e^(-zeta omega t) sin(omega_d t): delta = 2 pi zeta / sqrt(1 - zeta^2).
double log_decrement(const std::vector<double>& time_s, const std::vector<double>& displacement_m, double start_s,
                     double end_s);

}  // namespace ib
