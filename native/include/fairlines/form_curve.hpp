// Form-parameter curve design (Kim, Shin & Kim 2002: the fairest B-spline control points
// meeting the form parameters).
//
// A clamped, uniform, non-rational B-spline curve of a given degree and number of
// control points is found that is as fair as possible,
//
//     min  F(P) = e1 E1 + e2 E2 + e3 E3 + s S + sum_j w_j |C(t_j) - Q_j|^2
//     s.t. c(P) = 0            (the requested form parameters, exactly)
//          G P >= h            (section conditions: monotone, y >= 0, tangent sense)
//
// with E_k = integral_0^1 |C^(k)(t)|^2 dt, S the arc length, and the parameter t in [0, 1].
// Form parameters are equality constraints solved to machine precision by a
// Lagrange-Newton (SQP) method with analytic gradients and Hessians; the linear
// inequalities are kept strictly satisfied by a logarithmic barrier whose weight is
// driven to (numerically) zero. Hard requests are reached by continuation: the
// targets move from the values the start curve already has to the requested ones in
// adaptively sized steps.
//
// Units: lengths in the unit of the offsets, angles in degrees from the +x axis,
// curvature in 1/length, Area in length^2.
#pragma once

#include <Eigen/Core>

#include <limits>
#include <map>
#include <string>
#include <vector>

namespace fairlines {

/// Names of the scalar form parameters accepted in FormCurveRequest::params.
///   xB, yB, zB, xE, yE, zE  start / end point coordinates (zB, zE only when dim == 3)
///   alphaB, alphaE          tangent angle at start / end, degrees from +x, of the
///                           projection onto the x-y plane; the tangent points along it
///   CAB, CAE                signed curvature of the x-y projection at start / end,
///                           k = (x'y'' - y'x'') / (x'^2 + y'^2)^1.5
///   Area                    integral of y dx along the curve (start to end)
///   xC, yC                  centroid of that area: (1/A) int x y dx, (1/A) int y^2/2 dx
const std::vector<std::string>& form_parameter_names();

/// Weights of the fairness objective. All >= 0, at least one of e1, e2, e3 > 0.
struct FairnessWeights {
  double e1 = 0.0;
  double e2 = 1.0;
  double e3 = 0.0;
  double length = 0.0;

  /// Each field with its name and meaning: f(name, member pointer, doc).
  template <typename F>
  static void fields(F&& f) {
    f("e1", &FairnessWeights::e1, "weight of E1 = int |C'|^2 dt");
    f("e2", &FairnessWeights::e2, "weight of E2 = int |C''|^2 dt");
    f("e3", &FairnessWeights::e3, "weight of E3 = int |C'''|^2 dt");
    f("length", &FairnessWeights::length, "weight of the arc length");
  }
};

/// An offset point the curve must pass through (weight = +inf) or approach
/// (finite weight w > 0 adds w |C(t) - Q|^2 to the objective). The curve parameter t
/// of the point is a free variable of the problem (orthogonal fit).
struct FormPoint {
  Eigen::VectorXd position;  ///< length dim
  double weight = std::numeric_limits<double>::infinity();
};

/// Conditions that keep a section a section. Enforced on the control polygon
/// (a sufficient condition for the curve): monotone control coordinates make the
/// curve monotone and free of self-intersections, non-negative control y makes y >= 0.
struct FormBounds {
  int monotone_axis = 0;
  bool y_nonnegative = true;
  /// Where an end tangent direction is given (alphaB/alphaE, tangent_start/end): the
  /// end derivative along it is at least this fraction of |end - start| (the speed of
  /// the straight chord). Keeps the end curvature well defined: without it E2 favours
  /// vanishing end derivatives, where a prescribed end curvature degenerates.
  double min_end_speed = 0.2;

  /// Each field with its name and meaning: f(name, member pointer, doc).
  template <typename F>
  static void fields(F&& f) {
    f("monotone_axis", &FormBounds::monotone_axis, "0: x monotone, 1: y monotone, -1: none; the direction from the end coordinates if given, else increasing");
    f("y_nonnegative", &FormBounds::y_nonnegative, "all control y >= 0");
    f("min_end_speed", &FormBounds::min_end_speed, "where an end tangent is given, the end derivative along it is at least this fraction of the chord");
  }
};

/// Solver options.
struct FormSolverOptions {
  double tolerance = 1e-12;
  int max_iterations = 400;
  bool continuation = true;
  int multistart = 0;
  unsigned seed = 1;

  /// Each field with its name and meaning: f(name, member pointer, doc).
  template <typename F>
  static void fields(F&& f) {
    f("tolerance", &FormSolverOptions::tolerance, "bound on the scaled constraint residuals, 0 < tol < 1e-3");
    f("max_iterations", &FormSolverOptions::max_iterations, "Newton iterations per start, 1 .. fairlines.limits.MAX_FORM_CURVE_ITERATIONS");
    f("continuation", &FormSolverOptions::continuation, "False: aim at the requested values directly");
    f("multistart", &FormSolverOptions::multistart, "extra randomised starts (fairest kept), 0 .. fairlines.limits.MAX_FORM_CURVE_MULTISTART");
    f("seed", &FormSolverOptions::seed, "random seed of the multistart");
  }
};

/// A complete request.
struct FormCurveRequest {
  int dim = 2;
  int n_control = 8;
  int degree = 3;
  std::map<std::string, double> params;
  /// Space-curve tangent directions (dim == 3): when non-empty (length 3, non-zero),
  /// the start / end tangent is parallel to and points along this vector.
  Eigen::VectorXd tangent_start, tangent_end;
  std::vector<FormPoint> points;
  FairnessWeights fairness;
  FormBounds bounds;
  FormSolverOptions options;
  /// Optional start control points (n_control x dim). Must satisfy the bounds
  /// strictly; it is projected onto the linear form parameters first.
  Eigen::MatrixXd initial_control_points;

  /// The fields set by name (the points, tangents and start curve are passed on their own):
  /// f(name, member pointer, doc).
  template <typename F>
  static void fields(F&& f) {
    f("dim", &FormCurveRequest::dim, "2 (plane curve) or 3 (space curve)");
    f("n_control", &FormCurveRequest::n_control, "control points, degree + 1 .. fairlines.limits.MAX_FORM_CURVE_CONTROL_POINTS");
    f("degree", &FormCurveRequest::degree, "B-spline degree, 2 .. 15");
    f("params", &FormCurveRequest::params, "form parameters by name (fairlines.FORM_PARAMETERS)");
    f("fairness", &FormCurveRequest::fairness, "FairnessWeights");
    f("bounds", &FormCurveRequest::bounds, "FormBounds");
    f("options", &FormCurveRequest::options, "FormSolverOptions");
  }
};

/// Fairness measures of a curve (parametric, t in [0, 1]).
struct FairnessMeasures {
  double E1 = 0, E2 = 0, E3 = 0, length = 0;
};

/// Result of design_form_curve.
struct FormCurveResult {
  int degree = 3;
  Eigen::VectorXd knots;            ///< clamped uniform on [0, 1], n_control + degree + 1
  Eigen::MatrixXd control_points;   ///< n_control x dim
  std::map<std::string, double> achieved;   ///< value of each requested parameter
  std::map<std::string, double> residuals;  ///< achieved - requested, per parameter
  Eigen::VectorXd point_parameters;         ///< t of each FormPoint on the curve
  Eigen::VectorXd point_residuals;          ///< |C(t_j) - Q_j| per point
  FairnessMeasures fairness;
  double objective = 0;   ///< F at the solution
  int iterations = 0;     ///< Newton / Levenberg-Marquardt iterations (all stages, all starts)
  int continuation_steps = 0;
  bool converged = false; ///< KKT stationarity met to 1e-6 relative (the form parameters
                          ///< and bounds are met whenever a result is returned)
};

/// Design the fairest curve meeting the request.
/// Throws InvalidInput on malformed input (unknown name, NaN, bad sizes, too few
/// control points for the number of conditions), InfeasibleFormParameters (an
/// InvalidInput) when no curve of the requested kind can meet the parameters -- the
/// message names the parameters in conflict and, where computable (closed-form
/// necessary conditions, e.g. the Cauchy-Schwarz bound on yC), the achievable range;
/// otherwise the values reached before the solver stalled -- and ConvergenceError
/// when the requested values were reached but not to tolerance. Never returns a
/// curve that misses the request.
///
/// Strategy: (1) fairest curve meeting the linear parameters (one KKT solve) as the
/// start; (2) Levenberg-Marquardt to the requested values; (3) Lagrange-Newton with a
/// primal-dual log barrier, barrier weight driven to ~1e-12 of the objective;
/// fallbacks: continuation in the requested values from the start curve's own
/// values, then up to 6 randomised start curves. options.multistart adds random
/// starts and keeps the fairest result.
FormCurveResult design_form_curve(const FormCurveRequest& request);

/// Evaluate every scalar form parameter of a 2-D (or the x-y projection of a 3-D)
/// clamped uniform B-spline with the given control points (n x dim), by exact
/// Gauss-Legendre quadrature per knot span. Keys: form_parameter_names() (without
/// zB/zE when dim == 2).
std::map<std::string, double> form_parameters_of(int degree, const Eigen::MatrixXd& control_points);

/// Fairness measures of a clamped uniform B-spline with control points (n x dim).
FairnessMeasures fairness_of(int degree, const Eigen::MatrixXd& control_points);

/// Necessary conditions any curve meeting `request` must satisfy (closed form).
/// Throws InfeasibleFormParameters naming the conflicting parameters and the
/// achievable range; returns normally when no conflict is found.
void check_form_parameters_feasible(const FormCurveRequest& request);

namespace form_curve_detail {
/// Exposed for testing: the constraint functions c(z), their Jacobian and the
/// Hessian of lambda^T c, and the objective with its gradient and Hessian, for the
/// variable vector z = [x_0..x_{n-1}, y_0..y_{n-1}, (z_..), t_points...].
struct Derivatives {
  Eigen::VectorXd c;       ///< m
  Eigen::MatrixXd J;       ///< m x nv
  Eigen::MatrixXd HL;      ///< nv x nv, sum_i lambda_i d2 c_i
  double f = 0;
  Eigen::VectorXd g;       ///< nv
  Eigen::MatrixXd H;       ///< nv x nv
  std::vector<std::string> names;  ///< m constraint names
};
Derivatives evaluate_problem(const FormCurveRequest& request, const Eigen::VectorXd& z,
                             const Eigen::VectorXd& lambda);
}  // namespace form_curve_detail

}  // namespace fairlines
