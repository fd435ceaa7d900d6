// Fairest spline functions y = f(x) meeting form parameters: the basic curves of a hull (SAC,
// design waterline, deck line, centre profile, section fullness, angles along the ship).
//
// f is a clamped B-spline FUNCTION of x (knots in metres): a NurbsCurve of dimension 1 whose
// parameter is x itself. Every condition used here -- values and derivatives at a point, flat
// parts, weighted integrals and moments, bounds, and the sign of f' or f'' over a range -- is
// linear in the coefficients, so the fairest f is one convex QP (fairlines/qp.hpp): minimise
// e2 int f''^2 dx + e3 h^2 int f'''^2 dx + sum_j w_j (f(x_j) - y_j)^2 (h the mean knot span)
// subject to the conditions. Bounds and signs act on the coefficients of f, f' or f'' (the
// control polygon bounds the spline), which is sufficient and keeps the problem linear.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "fairlines/curve.hpp"

namespace fairlines {

/// f^(derivative)(x) = value; derivative 0..3 (degree >= derivative). With `combination`
/// (c_0, c_1, ...) the condition is sum_k c_k f^(k)(x) = value instead (e.g. the slope of a
/// product f w: w f' + w' f), `derivative` unused.
struct SplineCondition {
  double x = 0;
  int derivative = 0;
  double value = 0;
  std::string name;  ///< named in error messages ("yE", "entrance angle", ...)
  std::vector<double> combination;
};

/// int_{from}^{to} x^power f(x) w(x) dx = value, w the product of `factors` (each a
/// 1-D spline function of x, e.g. a half-breadth curve; empty: w = 1). power 0 or 1 (area,
/// first moment). With `centroid` set, the condition is the centroid instead:
/// int x f w dx - centroid int f w dx = 0 (then `value` and `power` are unused).
struct SplineIntegral {
  double from = 0, to = 0;
  int power = 0;
  std::vector<NurbsCurve> factors;
  double value = 0;
  double centroid = std::numeric_limits<double>::quiet_NaN();
  std::string name;
};

/// f = value on [from, to] exactly: every coefficient whose support meets (from, to) equals
/// value, so f leaves the flat part with degree - 1 continuous derivatives (G2 for cubics).
struct SplineFlat {
  double from = 0, to = 0;
  double value = 0;
  std::string name;
};

/// lower <= f <= upper on [from, to] (NaN: no bound on that side): on the coefficients whose
/// support meets the range (so on the whole control polygon there). from == to bounds the value
/// f(from) itself.
struct SplineBound {
  double from = 0, to = 0;
  double lower = std::numeric_limits<double>::quiet_NaN();
  double upper = std::numeric_limits<double>::quiet_NaN();
  std::string name;
};

/// sign x f^(derivative) >= margin on [from, to]; derivative 1 (monotone) or 2 (convex /
/// concave), sign +1 or -1; margin >= 0 (a definite slope or curvature, in f's units per m^k).
struct SplineShape {
  double from = 0, to = 0;
  int derivative = 2;
  int sign = -1;
  std::string name;
  double margin = 0.0;
};

/// Pass near (x, y) with weight w (least squares, in the objective).
struct SplineFitPoint {
  double x = 0, y = 0, weight = 1;
};

struct SplineDesignRequest {
  std::string name = "curve";  ///< prefix of error messages
  int degree = 3;              ///< 2..5
  Eigen::VectorXd knots;       ///< clamped knot vector in x (metres), n_control + degree + 1 values
  std::vector<SplineCondition> conditions;
  std::vector<SplineIntegral> integrals;
  std::vector<SplineFlat> flats;
  std::vector<SplineBound> bounds;
  std::vector<SplineShape> shapes;
  std::vector<SplineFitPoint> fit;
  /// Linear terms added to the objective: each integral's `value` is its weight (minimised;
  /// a negative weight maximises). With e2, e3 tiny this finds the extremes of an integral.
  std::vector<SplineIntegral> linear;
  double e2 = 1.0;  ///< weight of int (f - reference)''^2 dx
  double e3 = 0.0;  ///< weight of h^2 int (f - reference)'''^2 dx
  /// Optional coefficients (one per control point, on `knots`) of a reference function: the
  /// fairness terms measure f - reference, so f is the reference changed as fairly as
  /// possible to meet the conditions. Empty: none (the plain fairest function).
  Eigen::VectorXd reference;
};

/// The fairest spline function meeting the request. Throws InvalidInput for malformed input
/// (naming the request and the field) and InfeasibleFormParameters when the conditions
/// contradict each other; the message lists the named conditions found in conflict.
NurbsCurve design_spline_function(const SplineDesignRequest& request);

/// int_{from}^{to} x^power f_1(x) f_2(x) ... f_m(x) dx for spline functions f_i of x (non-rational
/// NurbsCurves of dimension 1 whose parameter is x; no factors: the product is 1), exact: the
/// integrand is a polynomial between the knots of the factors, so Gauss-Legendre on every such
/// piece with enough points for the product's degree integrates it to round-off (the rule the
/// SplineIntegral conditions use). from <= to, both inside every factor's domain (to
/// kDomainTolerance of its size); power >= 0, the product's degree at most kMaxProductDegree.
/// Throws InvalidInput otherwise.
double spline_product_integral(const std::vector<NurbsCurve>& factors, double from, double to, int power);

/// Relative slack of spline_product_integral's range beyond a factor's domain (times
/// max(1, |x0| + |x1|)): the ends of a basic curve found by root finding lie within it.
inline constexpr double kDomainTolerance = 1e-9;
/// Largest degree of an integrand the cached Gauss rules (up to 32 points) integrate exactly.
inline constexpr int kMaxProductDegree = 63;

/// Knots for a spline function on [x0, x1] with interior breakpoints `breaks` (e.g. the ends of
/// a flat part, kept as knots so the flat is exact) and about `spans` equal spans in total,
/// spread over the pieces between breakpoints in proportion to their length, at least
/// `min_piece_spans` each (4 by default: a cubic piece next to a flat part has its first three
/// coefficients fixed for G2 and needs room for its own conditions). Clamped, degree `degree`.
inline constexpr int kKnotSpans = 8, kKnotDegree = 3, kMinPieceSpans = 4;  ///< its defaults
Eigen::VectorXd spline_function_knots(double x0, double x1, const std::vector<double>& breaks, int spans = kKnotSpans,
                                      int degree = kKnotDegree, int min_piece_spans = kMinPieceSpans);

}  // namespace fairlines
