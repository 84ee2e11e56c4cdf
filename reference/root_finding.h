// Root finding on a bracket, for the reference's event times and extrema (event_solver.h).
#pragma once

#include <boost/math/tools/toms748_solve.hpp>
#include <cmath>
#include <cstdint>

namespace ib::reference_internal {

// First root of f on [a, b] given f(a), f(b) of opposite signs (or one of them zero), to `bits` bits.
// Event times need full precision; the location of an extremum much less, as the value there is
// flat in it (a relative location error e changes the value by order e^2).
constexpr int kEventBits = 50, kExtremumBits = 26;
template <class F>
double find_root(F&& f, double a, double b, double fa, double fb, int bits = kEventBits) {
  if (fa == 0) return a;
  if (fb == 0) return b;
  if ((fa > 0) == (fb > 0)) return std::abs(fa) < std::abs(fb) ? a : b;  // no sign change: nearest end
  std::uintmax_t iterations = 60;
  const auto bracket =
      boost::math::tools::toms748_solve(f, a, b, fa, fb, boost::math::tools::eps_tolerance<double>(bits), iterations);
  return 0.5 * (bracket.first + bracket.second);
}

// The same, located in the time from a: an extremum's location needs its bits of the interval, not of the run's
// clock, which they would be in t itself (26 bits of t = 100 s are 1.5 us: a tenth of a 14 us Hertz contact's
// rise, a peak force low by 1e-4).
template <class F>
double find_root_after(F&& f, double a, double b, double fa, double fb, int bits) {
  return a + find_root([&](double u) { return f(a + u); }, 0.0, b - a, fa, fb, bits);
}

}  // namespace ib::reference_internal
