// Non-rational and rational B-spline (NURBS) curves in any dimension (2-D and 3-D used).
#pragma once

#include <utility>
#include <vector>

#include <Eigen/Core>

namespace fairlines {

/// A NURBS curve C(t) = sum w_i P_i N_{i,p}(t) / sum w_i N_{i,p}(t).
/// Immutable shape operations (insert_knot, elevate_degree, ...) return new curves;
/// set_control_point / set_weight edit in place.
class NurbsCurve {
 public:
  /// degree          p >= 1
  /// knots           n + p + 1 non-decreasing values (clamped or unclamped)
  /// control_points  n x dim, dim >= 1 (metres in hull use)
  /// weights         n positive values, or empty for a non-rational curve (all 1)
  /// Throws InvalidInput on any inconsistency, NaN or inf.
  NurbsCurve(int degree, Eigen::VectorXd knots, Eigen::MatrixXd control_points,
             Eigen::VectorXd weights = Eigen::VectorXd());

  int degree() const { return degree_; }
  int n_control() const { return static_cast<int>(points_.rows()); }
  int dim() const { return static_cast<int>(points_.cols()); }
  const Eigen::VectorXd& knots() const { return knots_; }
  const Eigen::MatrixXd& control_points() const { return points_; }
  const Eigen::VectorXd& weights() const { return weights_; }
  bool is_rational() const { return rational_; }
  /// Valid parameter range [t_p, t_n].
  std::pair<double, double> domain() const;

  /// Point at t (dim values). t outside the domain is clamped to it.
  Eigen::VectorXd evaluate(double t) const;
  /// Points at m parameters: m x dim.
  Eigen::MatrixXd evaluate(const Eigen::VectorXd& t) const;
  /// Derivatives 0..order at t: (order + 1) x dim (rational quotient rule, P&T A4.2).
  Eigen::MatrixXd derivatives(double t, int order) const;
  /// Derivatives at m parameters, stacked: row k*(order+1) + d is the d-th derivative at t_k.
  Eigen::MatrixXd derivatives(const Eigen::VectorXd& t, int order) const;

  /// Curvature at each t: signed (x'y'' - y'x'')/|C'|^3 for 2-D curves, |C' x C''|/|C'|^3
  /// otherwise (1/metre). Zero where |C'| vanishes is an error (InvalidInput: degenerate).
  Eigen::VectorXd curvature(const Eigen::VectorXd& t) const;
  /// Torsion (C' x C'').C''' / |C' x C''|^2 of a 3-D curve at each t (1/metre); 0 where
  /// the curvature vanishes (torsion undefined, the curve is locally straight).
  Eigen::VectorXd torsion(const Eigen::VectorXd& t) const;

  /// Closest point: global start from dense samples, Newton on C'(t).(C(t) - p), clamped
  /// to the domain. Returns (t, point).
  std::pair<double, Eigen::VectorXd> closest_point(const Eigen::VectorXd& p) const;

  /// Knot t inserted `times` times (Boehm, P&T A5.1). Shape unchanged.
  NurbsCurve insert_knot(double t, int times = 1) const;
  /// All knots of `new_knots` inserted (refinement, P&T A5.4). Shape unchanged.
  NurbsCurve refine_knots(const Eigen::VectorXd& new_knots) const;
  /// Degree raised by `times`, every knot multiplicity raised by `times`; the new
  /// control points solve the collocation system at the new Greville points (exact:
  /// the old curve lies in the new spline space). Shape unchanged up to round-off.
  NurbsCurve elevate_degree(int times = 1) const;
  /// Sub-curve on [a, b] within the domain (clamped ends).
  NurbsCurve split_range(double a, double b) const;

  void set_control_point(int i, const Eigen::VectorXd& p);
  void set_weight(int i, double w);

  /// Homogeneous control points (w x, w y, ..., w): n x (dim + 1).
  Eigen::MatrixXd homogeneous() const;
  /// Builds a curve from homogeneous control points (n x (dim + 1)).
  static NurbsCurve from_homogeneous(int degree, Eigen::VectorXd knots, const Eigen::MatrixXd& pw);

 private:
  void refresh();
  int degree_;
  Eigen::VectorXd knots_;
  Eigen::MatrixXd points_;
  Eigen::VectorXd weights_;
  bool rational_ = false;
  // Row-major homogeneous control points (dim + 1 per point) for fast evaluation.
  std::vector<double> pw_;
};

}  // namespace fairlines
