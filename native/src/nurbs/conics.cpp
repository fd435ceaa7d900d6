#include "fairlines/conics.hpp"

#include <cmath>
#include <numbers>

#include <Eigen/Dense>

#include "checks.hpp"

namespace fairlines {

using detail::fail;

namespace {

// Image of the unit-circle arc [a0, a1] under p(theta) = O + cos(theta) A + sin(theta) B.
// An affine image of an exact rational circle is exact, so this yields circles (A, B
// orthogonal of equal length) and ellipses alike.
NurbsCurve affine_arc(const Eigen::Vector3d& O, const Eigen::Vector3d& A, const Eigen::Vector3d& B, double a0, double a1) {
  const double theta = a1 - a0;
  if (!(theta > 0.0) || theta > 2.0 * std::numbers::pi + 1e-12)
    fail("arc angle a1 - a0 is ", theta, " rad; expected 0 < angle <= 2 pi");
  const int narcs = std::min(4, std::max(1, static_cast<int>(std::ceil(theta / (0.5 * std::numbers::pi) - 1e-12))));
  const double dtheta = theta / narcs;
  const double wm = std::cos(0.5 * dtheta);
  Eigen::MatrixXd P(2 * narcs + 1, 3);
  Eigen::VectorXd w(2 * narcs + 1);
  for (int i = 0; i <= narcs; ++i) {
    const double ang = a0 + i * dtheta;
    P.row(2 * i) = (O + std::cos(ang) * A + std::sin(ang) * B).transpose();
    w[2 * i] = 1.0;
    if (i < narcs) {
      // Middle point: intersection of the end tangents, at 1/cos(dtheta/2) along the bisector.
      const double mid = ang + 0.5 * dtheta;
      P.row(2 * i + 1) = (O + (std::cos(mid) * A + std::sin(mid) * B) / wm).transpose();
      w[2 * i + 1] = wm;
    }
  }
  Eigen::VectorXd U(2 * narcs + 4);
  for (int i = 0; i < 3; ++i) {
    U[i] = 0.0;
    U[U.size() - 1 - i] = 1.0;
  }
  for (int j = 1; j < narcs; ++j) U[1 + 2 * j] = U[2 + 2 * j] = static_cast<double>(j) / narcs;
  return NurbsCurve(2, U, P, w);
}

Eigen::Vector3d any_perpendicular(const Eigen::Vector3d& n) {
  const Eigen::Vector3d trial = (std::abs(n.x()) < 0.9) ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  return (trial - trial.dot(n) * n).normalized();
}

Eigen::Vector3d unit(const Eigen::Vector3d& v, const char* what) {
  detail::require_finite(v, what);
  const double len = v.norm();
  if (!(len > 0.0)) fail(what, " is the zero vector; expected a direction");
  return v / len;
}

}  // namespace

NurbsCurve arc(const Eigen::Vector3d& center, const Eigen::Vector3d& x_axis, const Eigen::Vector3d& y_axis, double radius,
               double a0, double a1) {
  detail::require_finite(center, "center");
  detail::require_positive(radius, "radius");
  detail::require_finite(a0, "start angle");
  detail::require_finite(a1, "end angle");
  const Eigen::Vector3d X = unit(x_axis, "x_axis");
  Eigen::Vector3d Y = unit(y_axis, "y_axis");
  Y = Y - Y.dot(X) * X;
  if (Y.norm() < 1e-12) fail("x_axis and y_axis are parallel; expected two independent in-plane directions");
  Y.normalize();
  return affine_arc(center, radius * X, radius * Y, a0, a1);
}

NurbsCurve circle(const Eigen::Vector3d& center, double radius, const Eigen::Vector3d& normal) {
  const Eigen::Vector3d n = unit(normal, "normal");
  const Eigen::Vector3d X = any_perpendicular(n);
  return arc(center, X, n.cross(X), radius, 0.0, 2.0 * std::numbers::pi);
}

NurbsCurve ellipse(const Eigen::Vector3d& center, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  detail::require_finite(center, "center");
  unit(a, "semi_axis_a");
  unit(b, "semi_axis_b");
  // Perpendicular to within round-off of the given axes.
  if (std::abs(a.normalized().dot(b.normalized())) > 1e-9)
    fail("ellipse semi-axes are not perpendicular (cosine ", a.normalized().dot(b.normalized()), "); expected 0");
  return affine_arc(center, a, b, 0.0, 2.0 * std::numbers::pi);
}

NurbsSurface revolve(const NurbsCurve& profile, const Eigen::Vector3d& axis_point, const Eigen::Vector3d& axis_dir,
                     double angle) {
  if (profile.dim() != 3) fail("profile has dimension ", profile.dim(), "; expected a 3-D curve");
  detail::require_finite(axis_point, "axis_point");
  const Eigen::Vector3d S = unit(axis_dir, "axis_dir");
  if (!(angle > 0.0) || angle > 2.0 * std::numbers::pi + 1e-12)
    fail("revolution angle is ", angle, " rad; expected 0 < angle <= 2 pi");
  // The arc of the unit circle supplies the u knots, weights and the affine coefficients.
  const NurbsCurve unit_arc = affine_arc(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), 0.0, angle);
  const int nu = unit_arc.n_control(), nv = profile.n_control();
  Eigen::MatrixXd P(static_cast<Eigen::Index>(nu) * nv, 3);
  Eigen::VectorXd W(static_cast<Eigen::Index>(nu) * nv);
  for (int j = 0; j < nv; ++j) {
    const Eigen::Vector3d Pj = profile.control_points().row(j).transpose();
    const Eigen::Vector3d Oj = axis_point + (Pj - axis_point).dot(S) * S;
    const Eigen::Vector3d X = Pj - Oj;  // radius vector (zero for points on the axis)
    const Eigen::Vector3d Y = S.cross(X);
    for (int i = 0; i < nu; ++i) {
      const Eigen::Vector3d c = unit_arc.control_points().row(i).transpose();
      P.row(static_cast<Eigen::Index>(i) * nv + j) = (Oj + c.x() * X + c.y() * Y).transpose();
      W[static_cast<Eigen::Index>(i) * nv + j] = unit_arc.weights()[i] * profile.weights()[j];
    }
  }
  return NurbsSurface(2, profile.degree(), unit_arc.knots(), profile.knots(), nu, nv, P, W);
}

NurbsSurface cylinder(const Eigen::Vector3d& base, const Eigen::Vector3d& axis_dir, double radius, double height) {
  detail::require_positive(radius, "radius");
  detail::require_positive(height, "height");
  const Eigen::Vector3d S = unit(axis_dir, "axis_dir");
  const Eigen::Vector3d X = any_perpendicular(S);
  Eigen::MatrixXd line(2, 3);
  line.row(0) = (base + radius * X).transpose();
  line.row(1) = (base + radius * X + height * S).transpose();
  Eigen::VectorXd U(4);
  U << 0, 0, 1, 1;
  return revolve(NurbsCurve(1, U, line), base, S, 2.0 * std::numbers::pi);
}

NurbsSurface sphere(const Eigen::Vector3d& center, double radius) {
  detail::require_positive(radius, "radius");
  const NurbsCurve half = arc(center, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ(), radius,
                              -0.5 * std::numbers::pi, 0.5 * std::numbers::pi);
  return revolve(half, center, Eigen::Vector3d::UnitZ(), 2.0 * std::numbers::pi);
}

}  // namespace fairlines
