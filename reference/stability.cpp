// Stability limits of the explicit cycles K18 and K19 for one damped contact (refs §1.4-1.5).
#include "ref/stability.hpp"

#include <algorithm>
#include <cmath>

#include "ref/require.hpp"

namespace ref {

double stability_limit(Scheme scheme, double damping_ratio) {
  detail::require_non_negative("ref::stability_limit", "damping_ratio", damping_ratio);
  const double zeta = damping_ratio;
  if (scheme == Scheme::K18) {
    return 2.0 / (std::sqrt(1.0 + zeta * zeta) + zeta);  // flip: 4 - W^2 - 4 zeta W = 0
  }
  const double hopf = 2.0 * zeta;                                   // third root 1/2: W = 2 zeta
  const double flip = 6.0 / (std::sqrt(zeta * zeta + 3.0) + zeta);  // W^2 + 4 zeta W - 12 = 0
  return std::min(hopf, flip);
}

double stability_limit_time_step(Scheme scheme, const Oscillator& contact) {
  return stability_limit(scheme, contact.damping_ratio()) / contact.natural_frequency();
}

double kiyama_time_step_limit(double stiffness, double damping) {
  detail::require_positive("ref::kiyama_time_step_limit", "stiffness", stiffness);
  detail::require_non_negative("ref::kiyama_time_step_limit", "damping", damping);
  return damping / stiffness;  // (K26)
}

namespace {

void require_step(const char* where, double W, double zeta) {
  detail::require_non_negative(where, "W", W);
  detail::require_non_negative(where, "damping_ratio", zeta);
}

}  // namespace

Eigen::Matrix2d amplification_matrix_K18(double W, double damping_ratio) {
  require_step("ref::amplification_matrix_K18", W, damping_ratio);
  const double w2 = W * W;
  const double d = 2.0 * damping_ratio * W;  // eta dt / m
  Eigen::Matrix2d a;
  a << 1.0 - w2, 1.0 - d,  // x_{k+1} = x_k + p_k
      -w2, 1.0 - d;        // p_k = p_{k-1} - W^2 x_k - 2 zeta W p_{k-1}   (K17, K18)
  return a;
}

Eigen::Matrix3d amplification_matrix_K19(double W, double damping_ratio) {
  require_step("ref::amplification_matrix_K19", W, damping_ratio);
  const double w2 = W * W;
  const double d = 2.0 * damping_ratio * W;
  Eigen::Matrix3d a;
  a << 1.0 - 0.5 * w2, 0.5, 0.5 * (1.0 - d),  // x_{k+1} = x_k + q_{k+1}
      -w2, 1.0, -d,                           // p_k = p_{k-1} - W^2 x_k - 2 zeta W q_k  (K17)
      -0.5 * w2, 0.5, 0.5 * (1.0 - d);        // q_{k+1} = (q_k + p_k)/2                  (K19)
  return a;
}

Eigen::MatrixXd amplification_matrix(Scheme scheme, double W, double damping_ratio) {
  if (scheme == Scheme::K18) return amplification_matrix_K18(W, damping_ratio);
  return amplification_matrix_K19(W, damping_ratio);
}

double spectral_radius(const Eigen::MatrixXd& matrix) {
  if (matrix.rows() == 0 || matrix.rows() != matrix.cols() || !matrix.allFinite())
    throw std::invalid_argument(
        "ref::spectral_radius: matrix must be square, non-empty and finite");
  const Eigen::EigenSolver<Eigen::MatrixXd> solver(matrix, /*computeEigenvectors=*/false);
  return solver.eigenvalues().cwiseAbs().maxCoeff();
}

double stability_limit_spectral(Scheme scheme, double damping_ratio, double tolerance) {
  constexpr const char* where = "ref::stability_limit_spectral";
  detail::require_non_negative(where, "damping_ratio", damping_ratio);
  detail::require_positive(where, "tolerance", tolerance);
  const auto unstable = [&](double W) {
    return spectral_radius(amplification_matrix(scheme, W, damping_ratio)) > 1.0 + 1e-12;
  };
  double lo = 0.0;
  double hi = 4.0;  // both schemes are unstable at W = 4 for every zeta >= 0 (limits <= 2 sqrt 3)
  if (!unstable(hi)) detail::fail(where, "no instability found below W = 4", damping_ratio);
  while (hi - lo > tolerance) {
    const double mid = 0.5 * (lo + hi);
    if (unstable(mid))
      hi = mid;
    else
      lo = mid;
  }
  return 0.5 * (lo + hi);
}

double numerical_damping_ratio(Scheme scheme, double damping_ratio, double W) {
  require_step("ref::numerical_damping_ratio", W, damping_ratio);
  const double zeta = damping_ratio;
  if (scheme == Scheme::K18) return zeta + zeta * zeta * W;
  return zeta - (1.0 - 6.0 * zeta * zeta) * W / 2.0;
}

}  // namespace ref
