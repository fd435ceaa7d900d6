// Control points in the homogeneous form the rational evaluators read.
#pragma once

#include <vector>

#include <Eigen/Core>

namespace fairlines::detail {

/// Packs the #pts by dim control points (metres) with their #pts weights into `pw` as
/// (w x, w y, ..., w), dim + 1 doubles per point, in row order.
inline void pack_homogeneous(const Eigen::MatrixXd& points, const Eigen::VectorXd& weights, std::vector<double>& pw) {
  const Eigen::Index d = points.cols(), n = points.rows();
  pw.resize(static_cast<size_t>(n * (d + 1)));
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index c = 0; c < d; ++c) pw[i * (d + 1) + c] = points(i, c) * weights[i];
    pw[i * (d + 1) + d] = weights[i];
  }
}

}  // namespace fairlines::detail
