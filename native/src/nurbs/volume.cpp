#include "fairlines/volume.hpp"

#include <algorithm>

#include "checks.hpp"
#include "fairlines/basis.hpp"
#include "fairlines/knots.hpp"

namespace fairlines {

using detail::fail;

namespace {

/// Parameters (s, t, r) of the points to evaluate: finite, one of each per point.
void require_parameters(const Eigen::VectorXd& s, const Eigen::VectorXd& t, const Eigen::VectorXd& r) {
  if (s.size() != t.size() || s.size() != r.size())
    fail("s, t, r have ", s.size(), ", ", t.size(), ", ", r.size(), " values; expected equal lengths");
  detail::require_finite(s, "s");
  detail::require_finite(t, "t");
  detail::require_finite(r, "r");
}

}  // namespace

NurbsVolume::NurbsVolume(std::array<int, 3> degrees, std::array<Eigen::VectorXd, 3> knots, std::array<int, 3> counts,
                         Eigen::MatrixXd control_points, Eigen::VectorXd weights)
    : degrees_(degrees), knots_(std::move(knots)), counts_(counts), points_(std::move(control_points)),
      weights_(std::move(weights)) {
  static const char* names[3] = {"knots_s", "knots_t", "knots_r"};
  for (int a = 0; a < 3; ++a) {
    detail::require_degree(degrees_[a], std::string("degrees[") + std::to_string(a) + "]");
    validate_knots(knots_[a], degrees_[a], counts_[a], names[a]);
  }
  const Eigen::Index n = static_cast<Eigen::Index>(counts_[0]) * counts_[1] * counts_[2];
  if (points_.rows() != n || points_.cols() != 3)
    fail("control_points has shape (", points_.rows(), ", ", points_.cols(), "); expected (", n, ", 3)");
  detail::require_finite(points_, "control_points");
  weights_ = detail::weights_or_ones(std::move(weights_), n);
}

Eigen::MatrixXd NurbsVolume::evaluate(const Eigen::VectorXd& s, const Eigen::VectorXd& t, const Eigen::VectorXd& r) const {
  require_parameters(s, t, r);
  const auto& [ps, pt, pr] = degrees_;
  std::vector<double> Ns(ps + 1), Nt(pt + 1), Nr(pr + 1);
  Eigen::MatrixXd out(s.size(), 3);
  const int nt = counts_[1], nr = counts_[2];
  for (Eigen::Index k = 0; k < s.size(); ++k) {
    double x[3] = {s[k], t[k], r[k]};
    int span[3];
    double* N[3] = {Ns.data(), Nt.data(), Nr.data()};
    for (int a = 0; a < 3; ++a) {
      x[a] = std::clamp(x[a], knots_[a][degrees_[a]], knots_[a][counts_[a]]);
      span[a] = find_span(degrees_[a], knots_[a], x[a]);
      basis_functions(span[a], x[a], degrees_[a], knots_[a], N[a]);
    }
    Eigen::Vector4d acc = Eigen::Vector4d::Zero();
    for (int i = 0; i <= ps; ++i)
      for (int j = 0; j <= pt; ++j)
        for (int l = 0; l <= pr; ++l) {
          const Eigen::Index row =
              (static_cast<Eigen::Index>(span[0] - ps + i) * nt + (span[1] - pt + j)) * nr + (span[2] - pr + l);
          const double b = Ns[i] * Nt[j] * Nr[l] * weights_[row];
          acc.head<3>() += b * points_.row(row).transpose();
          acc[3] += b;
        }
    out.row(k) = (acc.head<3>() / acc[3]).transpose();
  }
  return out;
}

Eigen::MatrixXd NurbsVolume::derivatives(const Eigen::VectorXd& s, const Eigen::VectorXd& t, const Eigen::VectorXd& r) const {
  require_parameters(s, t, r);
  const int nt = counts_[1], nr = counts_[2];
  std::array<Eigen::MatrixXd, 3> D;
  for (int a = 0; a < 3; ++a) D[a].resize(2, degrees_[a] + 1);
  Eigen::MatrixXd out(4 * s.size(), 3);
  for (Eigen::Index k = 0; k < s.size(); ++k) {
    double x[3] = {s[k], t[k], r[k]};
    int span[3];
    for (int a = 0; a < 3; ++a) {
      x[a] = std::clamp(x[a], knots_[a][degrees_[a]], knots_[a][counts_[a]]);
      span[a] = find_span(degrees_[a], knots_[a], x[a]);
      basis_derivatives(span[a], x[a], degrees_[a], 1, knots_[a], D[a]);
    }
    // Homogeneous sums: A (w-weighted point) and w, and their three partials.
    Eigen::Matrix<double, 4, 4> H = Eigen::Matrix<double, 4, 4>::Zero();  // row: value, d/ds, d/dt, d/dr
    for (int i = 0; i <= degrees_[0]; ++i)
      for (int j = 0; j <= degrees_[1]; ++j)
        for (int l = 0; l <= degrees_[2]; ++l) {
          const Eigen::Index row =
              (static_cast<Eigen::Index>(span[0] - degrees_[0] + i) * nt + (span[1] - degrees_[1] + j)) * nr +
              (span[2] - degrees_[2] + l);
          Eigen::Vector4d pw;
          pw << weights_[row] * points_.row(row).transpose(), weights_[row];
          const double b0 = D[0](0, i), b1 = D[1](0, j), b2 = D[2](0, l);
          H.row(0) += (b0 * b1 * b2) * pw.transpose();
          H.row(1) += (D[0](1, i) * b1 * b2) * pw.transpose();
          H.row(2) += (b0 * D[1](1, j) * b2) * pw.transpose();
          H.row(3) += (b0 * b1 * D[2](1, l)) * pw.transpose();
        }
    const Eigen::RowVector3d V = H.block<1, 3>(0, 0) / H(0, 3);
    out.row(4 * k) = V;
    for (int a = 1; a <= 3; ++a) out.row(4 * k + a) = (H.block<1, 3>(a, 0) - H(a, 3) * V) / H(0, 3);
  }
  return out;
}

}  // namespace fairlines
