// Knot refinement of a control net's rows (internal; NurbsCurve and NurbsSurface refine_knots).
#pragma once

#include <algorithm>
#include <utility>

#include <Eigen/Core>

#include "fairlines/basis.hpp"

namespace fairlines::detail {

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// Knot refinement (Piegl & Tiller 1997, A5.4): inserts the knots X (any order, inside the
/// domain of U) into degree-p B-splines whose control point i is row i of Pw (homogeneous
/// coordinates; a row may hold the points of many lines of a surface at once, all on U).
/// Returns (refined rows, refined knot vector).
inline std::pair<RowMatrix, Eigen::VectorXd> refine_rows(int p, const Eigen::VectorXd& U, Eigen::VectorXd X,
                                                         const RowMatrix& Pw) {
  std::sort(X.data(), X.data() + X.size());
  const int n = static_cast<int>(Pw.rows()) - 1, m = n + p + 1, r = static_cast<int>(X.size()) - 1;
  const int aa = find_span(p, U, X[0]);
  const int bb = find_span(p, U, X[r]) + 1;  // A5.4 wants the span after the one holding X[r]
  RowMatrix Qw(n + r + 2, Pw.cols());
  Eigen::VectorXd Ubar(m + r + 2);
  for (int j = 0; j <= aa - p; ++j) Qw.row(j) = Pw.row(j);
  for (int j = bb - 1; j <= n; ++j) Qw.row(j + r + 1) = Pw.row(j);
  for (int j = 0; j <= aa; ++j) Ubar[j] = U[j];
  for (int j = bb + p; j <= m; ++j) Ubar[j + r + 1] = U[j];
  int i = bb + p - 1, k = bb + p + r;
  for (int j = r; j >= 0; --j) {
    while (X[j] <= U[i] && i > aa) {
      Qw.row(k - p - 1) = Pw.row(i - p - 1);
      Ubar[k] = U[i];
      --k;
      --i;
    }
    Qw.row(k - p - 1) = Qw.row(k - p);
    for (int l = 1; l <= p; ++l) {
      const int ind = k - p + l;
      double alfa = Ubar[k + l] - X[j];
      if (std::abs(alfa) == 0.0) {
        Qw.row(ind - 1) = Qw.row(ind);
      } else {
        alfa = alfa / (Ubar[k + l] - U[i - p + l]);
        Qw.row(ind - 1) = alfa * Qw.row(ind - 1) + (1.0 - alfa) * Qw.row(ind);
      }
    }
    Ubar[k] = X[j];
    --k;
  }
  return {std::move(Qw), std::move(Ubar)};
}

}  // namespace fairlines::detail
