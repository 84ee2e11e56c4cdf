#include "modal_identification.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>

namespace ib::test {

std::vector<DampedMode> matrix_pencil_modes(const std::vector<double>& y, double dt, int order) {
  const int n = static_cast<int>(y.size()), l = n / 3;
  Eigen::MatrixXd hankel(n - l, l + 1);
  for (int i = 0; i < n - l; ++i)
    for (int j = 0; j <= l; ++j) hankel(i, j) = y[i + j];
  Eigen::BDCSVD<Eigen::MatrixXd> svd(hankel, Eigen::ComputeThinV);
  const Eigen::MatrixXd v = svd.matrixV().leftCols(order);
  const Eigen::MatrixXd shift = v.topRows(l).completeOrthogonalDecomposition().pseudoInverse() * v.bottomRows(l);
  const Eigen::VectorXcd z = Eigen::EigenSolver<Eigen::MatrixXd>(shift).eigenvalues();
  // amplitudes by least squares on the Vandermonde matrix, then each pole's energy over the record
  Eigen::MatrixXcd vandermonde(n, order);
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < order; ++k) vandermonde(i, k) = std::pow(z[k], i);
  const Eigen::VectorXcd amplitude = vandermonde.colPivHouseholderQr().solve(
      Eigen::Map<const Eigen::VectorXd>(y.data(), n).cast<std::complex<double>>());
  std::vector<DampedMode> modes;
  for (int k = 0; k < order; ++k) {
    if (z[k].imag() <= 0) continue;  // one of each conjugate pair; real poles are overdamped modes
    const std::complex<double> s = std::log(z[k]) / dt;
    DampedMode mode;
    mode.frequency_hz = std::abs(s) / (2 * M_PI);
    mode.damping_ratio = -s.real() / std::abs(s);
    mode.energy = (vandermonde.col(k) * amplitude[k]).squaredNorm();
    modes.push_back(mode);
  }
  std::sort(modes.begin(), modes.end(), [](const DampedMode& a, const DampedMode& b) { return a.energy > b.energy; });
  return modes;
}

}  // namespace ib::test
