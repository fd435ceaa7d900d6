// Quality of a structured grid: end spacings, stretching, orthogonality, skewness, aspect ratio.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <Eigen/Geometry>

#include "fairlines/grids.hpp"
#include "nurbs/checks.hpp"

namespace fairlines {

namespace {

constexpr double kDegenerate = 1e-9;  ///< a side shorter than this x the grid size is degenerate

struct LineStats {
  double first_min = std::numeric_limits<double>::infinity(), first_max = 0;
  double last_min = std::numeric_limits<double>::infinity(), last_max = 0;
  double stretching = 1.0;
};

/// Spacings along the lines of one index direction: point (line, k) at at(line, k).
template <typename At>
LineStats lines(int n_lines, int n_points, At at, double tiny) {
  LineStats st;
  for (int l = 0; l < n_lines; ++l) {
    std::vector<double> ds(n_points - 1);
    for (int k = 0; k + 1 < n_points; ++k) ds[k] = (at(l, k + 1) - at(l, k)).norm();
    if (*std::max_element(ds.begin(), ds.end()) <= tiny) continue;  // a pole
    st.first_min = std::min(st.first_min, ds.front());
    st.first_max = std::max(st.first_max, ds.front());
    st.last_min = std::min(st.last_min, ds.back());
    st.last_max = std::max(st.last_max, ds.back());
    for (int k = 0; k + 2 < n_points; ++k)
      if (ds[k] > tiny && ds[k + 1] > tiny) st.stretching = std::max(st.stretching, std::max(ds[k] / ds[k + 1], ds[k + 1] / ds[k]));
  }
  return st;
}

}  // namespace

GridQuality grid_quality(const Eigen::MatrixXd& points, int ni, int nj) {
  if (ni < 2 || nj < 2) detail::fail("ni, nj are ", ni, ", ", nj, "; expected >= 2 each");
  if (points.cols() != 3 || points.rows() != static_cast<Eigen::Index>(ni) * nj)
    detail::fail("points is ", points.rows(), " x ", points.cols(), "; expected (ni * nj) x 3 = ", ni * nj, " x 3");
  detail::require_finite(points, "points");
  const double tiny = kDegenerate * (points.colwise().maxCoeff() - points.colwise().minCoeff()).norm();
  auto P = [&](int i, int j) -> Eigen::Vector3d { return points.row(static_cast<Eigen::Index>(i) * nj + j).transpose(); };
  const LineStats si = lines(nj, ni, [&](int j, int i) { return P(i, j); }, tiny);
  const LineStats sj = lines(ni, nj, [&](int i, int j) { return P(i, j); }, tiny);
  GridQuality q;
  q.first_min = si.first_min, q.first_max = si.first_max, q.last_min = si.last_min, q.last_max = si.last_max;
  q.first_min_j = sj.first_min, q.first_max_j = sj.first_max, q.last_min_j = sj.last_min, q.last_max_j = sj.last_max;
  q.max_stretching = std::max(si.stretching, sj.stretching);
  double sum = 0.0;
  long corners = 0;
  for (int i = 0; i + 1 < ni; ++i)
    for (int j = 0; j + 1 < nj; ++j) {
      const Eigen::Vector3d c[4] = {P(i, j), P(i + 1, j), P(i + 1, j + 1), P(i, j + 1)};
      double side[4];
      for (int k = 0; k < 4; ++k) side[k] = (c[(k + 1) % 4] - c[k]).norm();
      const double lo = *std::min_element(side, side + 4), hi = *std::max_element(side, side + 4);
      if (lo <= tiny) {
        ++q.degenerate_cells;
        continue;
      }
      q.max_aspect_ratio = std::max(q.max_aspect_ratio, hi / lo);
      double tmin = 180.0, tmax = 0.0;
      for (int k = 0; k < 4; ++k) {
        const Eigen::Vector3d e1 = c[(k + 1) % 4] - c[k], e0 = c[(k + 3) % 4] - c[k];
        const double t = std::atan2(e1.cross(e0).norm(), e1.dot(e0)) * 180.0 / std::numbers::pi;
        tmin = std::min(tmin, t);
        tmax = std::max(tmax, t);
        q.max_orthogonality_deg = std::max(q.max_orthogonality_deg, std::abs(t - 90.0));
        sum += std::abs(t - 90.0);
        ++corners;
      }
      q.max_skewness = std::max(q.max_skewness, std::max((tmax - 90.0) / 90.0, (90.0 - tmin) / 90.0));
    }
  q.mean_orthogonality_deg = corners ? sum / corners : 0.0;
  return q;
}

}  // namespace fairlines
