// Gram matrices of B-spline bases (internal; fair skinning and the hull sections use them for
// the fairness integrals E_r = int |C^(r)|^2 dt = c' G c).
#pragma once

#include <Eigen/Core>

#include "fairlines/basis.hpp"
#include "nurbs/gauss.hpp"

namespace fairlines::detail {

/// Gram matrix int N_i^(r) N_j^(r) dt of a B-spline basis (n x n), exact by Gauss-Legendre.
inline Eigen::MatrixXd derivative_gram(const Eigen::VectorXd& U, int degree, int r) {
  const int n = static_cast<int>(U.size()) - degree - 1;
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(n, n);
  if (r > degree) return G;
  const auto& g = detail::gauss_rule(degree + 1);
  Eigen::MatrixXd ders(r + 1, degree + 1);
  for (int s = degree; s < n; ++s) {
    const double a = U[s], b = U[s + 1];
    if (!(b > a)) continue;
    const double h = 0.5 * (b - a), m = 0.5 * (a + b);
    for (std::size_t k = 0; k < g.x.size(); ++k) {
      const double t = m + h * g.x[k];
      basis_derivatives(s, t, degree, r, U, ders);
      for (int i = 0; i <= degree; ++i)
        for (int j = 0; j <= degree; ++j)
          G(s - degree + i, s - degree + j) += g.w[k] * h * ders(r, i) * ders(r, j);
    }
  }
  return G;
}

}  // namespace fairlines::detail
