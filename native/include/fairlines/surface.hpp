// Tensor-product NURBS surfaces S(u, v) = sum_ij w_ij P_ij N_i(u) N_j(v) / sum_ij w_ij N_i(u) N_j(v).
#pragma once

#include <array>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include <Eigen/Core>

#include "fairlines/curve.hpp"

namespace fairlines {

/// Parametric direction of a surface.
enum class Direction { U = 0, V = 1 };

/// Parses "u" | "v"; throws InvalidInput naming the bad value.
Direction parse_direction(const std::string& name);

class NurbsSurface {
 public:
  /// degree_u, degree_v  >= 1
  /// knots_u             nu + degree_u + 1 non-decreasing values (knots_v likewise)
  /// control_points      (nu * nv) x 3, row i * nv + j holds P_ij (metres)
  /// weights             nu * nv positive values in the same order, or empty (all 1)
  NurbsSurface(int degree_u, int degree_v, Eigen::VectorXd knots_u, Eigen::VectorXd knots_v,
               int nu, int nv, Eigen::MatrixXd control_points,
               Eigen::VectorXd weights = Eigen::VectorXd());

  int degree_u() const { return pu_; }
  int degree_v() const { return pv_; }
  int nu() const { return nu_; }
  int nv() const { return nv_; }
  const Eigen::VectorXd& knots_u() const { return ku_; }
  const Eigen::VectorXd& knots_v() const { return kv_; }
  const Eigen::MatrixXd& control_points() const { return points_; }
  const Eigen::VectorXd& weights() const { return weights_; }
  bool is_rational() const { return rational_; }
  std::pair<double, double> domain_u() const;
  std::pair<double, double> domain_v() const;

  Eigen::Vector3d evaluate(double u, double v) const;
  /// Points at m scattered (u_k, v_k): m x 3.
  Eigen::MatrixXd evaluate(const Eigen::VectorXd& u, const Eigen::VectorXd& v) const;
  /// Writes points at m scattered parameters into out (m x 3 row-major, 3m doubles).
  void evaluate_into(const double* u, const double* v, long m, double* out) const;
  /// Grid of points: row-major (len(us) * len(vs)) x 3, point (a, b) at row a * len(vs) + b.
  /// Basis values are computed once per grid line and control rows are contracted per u.
  Eigen::MatrixXd evaluate_grid(const Eigen::VectorXd& us, const Eigen::VectorXd& vs) const;
  void evaluate_grid_into(const double* us, long n_u, const double* vs, long n_v, double* out) const;
  /// Points and first partials at m scattered (u_k, v_k), without allocation (hot loops such
  /// as quadrature): out is m x 9 row-major, row k = [S, S_u, S_v] (metres, metres per unit
  /// parameter).
  void evaluate_first_derivatives_into(const double* u, const double* v, long m, double* out) const;

  /// Partial derivatives d^{k+l} S / du^k dv^l for k + l <= order, at (u, v):
  /// returns (order + 1)^2 x 3, row k * (order + 1) + l (P&T A3.6 / A4.4).
  Eigen::MatrixXd derivatives(double u, double v, int order) const;
  /// Unit normal S_u x S_v / |S_u x S_v| at each (u, v): m x 3. A degenerate point
  /// (parallel S_u, S_v, e.g. a pole) uses the limit from a nearby interior point.
  Eigen::MatrixXd normal(const Eigen::VectorXd& u, const Eigen::VectorXd& v) const;
  /// Gaussian K and mean H curvature (1/m^2, 1/m; H > 0 when the surface bends toward
  /// its normal S_u x S_v) at each (u, v).
  std::pair<Eigen::VectorXd, Eigen::VectorXd> curvature(const Eigen::VectorXd& u,
                                                        const Eigen::VectorXd& v) const;
  /// Closest point to p: sampled start, 2-D Newton clamped to the domain, boundary
  /// curves checked. Returns (u, v, point).
  std::tuple<double, double, Eigen::Vector3d> closest_point(const Eigen::Vector3d& p) const;
  /// Closest points of many points (m x 3, metres): closest_point's global search for each,
  /// the span patches' control-point boxes built once for the batch. Returns (u (m), v (m),
  /// points m x 3).
  std::tuple<Eigen::VectorXd, Eigen::VectorXd, Eigen::MatrixXd> closest_points(const Eigen::MatrixXd& points) const;
  /// Foot points of many points near known parameters: for each row k of `points` (m x 3,
  /// metres) the 2-D Newton of closest_point started at (u0[k], v0[k]) (clamped to the
  /// domain), which never moves the foot point further from the point. A local search: the
  /// starts must lie in the basin of the wanted foot point. Returns (u (m), v (m), feet m x 3).
  std::tuple<Eigen::VectorXd, Eigen::VectorXd, Eigen::MatrixXd> closest_points(const Eigen::MatrixXd& points,
                                                                              const Eigen::VectorXd& u0,
                                                                              const Eigen::VectorXd& v0) const;

  NurbsSurface insert_knot(Direction dir, double t, int times = 1) const;
  NurbsSurface refine_knots(Direction dir, const Eigen::VectorXd& new_knots) const;
  NurbsSurface elevate_degree(Direction dir, int times = 1) const;
  /// Iso-parametric curve: dir U fixes u = t (a curve in v), dir V fixes v = t.
  NurbsCurve iso_curve(Direction dir, double t) const;

  void set_control_point(int i, int j, const Eigen::Vector3d& p);
  void set_weight(int i, int j, double w);

  /// Homogeneous control points, (nu * nv) x 4.
  Eigen::MatrixXd homogeneous() const;
  static NurbsSurface from_homogeneous(int degree_u, int degree_v, Eigen::VectorXd knots_u,
                                       Eigen::VectorXd knots_v, int nu, int nv,
                                       const Eigen::MatrixXd& pw);

 private:
  void refresh();
  int pu_, pv_, nu_, nv_;
  Eigen::VectorXd ku_, kv_;
  Eigen::MatrixXd points_;
  Eigen::VectorXd weights_;
  bool rational_ = false;
  std::vector<double> pw_;  // 4 doubles per control point: w x, w y, w z, w
  // Reciprocal knot differences of the Cox-de Boor triangle, per span, so the hot
  // evaluation loops multiply instead of divide (see basis_table.hpp).
  std::vector<double> inv_u_, inv_v_;
  // Power-basis coefficients of the basis functions per span (scattered evaluation).
  std::vector<double> pow_u_, pow_v_;
  // O(1) knot-span lookup tables (std::shared_ptr keeps the public header free of the
  // internal type; they are rebuilt whenever the knots change).
  std::shared_ptr<const void> span_u_, span_v_;
};

}  // namespace fairlines
