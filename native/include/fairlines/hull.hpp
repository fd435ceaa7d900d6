// Basic curves of the bare hull (Kim and Hwangbo 2008) and plane cuts for its fairness
// check. The sections themselves are in fairlines/sections.hpp.
//
// Every basic curve is a form-parameter curve: the E2-fairest clamped uniform B-spline
// meeting its form parameters exactly. With the control-point abscissae fixed in advance
// (equally spaced Greville abscissae, so x(t) is linear in t), every parameter used here --
// end points, end slopes, end curvatures at a given slope, pass-through points, the area under
// the curve over a sub-range and its centroid -- is LINEAR in the free ordinates, and the
// fairest curve is one symmetric KKT solve: microseconds per curve, no iteration, no start
// guess. (Parameters that are nonlinear in the ordinates -- the lateral centroid yC, or an end
// curvature without its end slope -- are left to the general solver of fairlines/form_curve.hpp.)
#pragma once

#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "fairlines/curve.hpp"
#include "fairlines/sections.hpp"
#include "fairlines/surface.hpp"

namespace fairlines {

/// A plane curve y(x) with fixed control abscissae; NaN means "not requested".
struct LinearFormRequest {
  std::string name = "curve";  ///< used in error messages
  int degree = 3;              ///< p >= 2
  /// n >= degree + 1 control abscissae (same unit as x), non-decreasing, first < last; only
  /// runs at the start or the end may coincide (a tangent normal to the abscissa there; a run
  /// of degree + 1 makes the end piece a straight segment normal to the abscissa).
  Eigen::VectorXd abscissae;
  double yB = std::numeric_limits<double>::quiet_NaN();      ///< y at the start
  double yE = std::numeric_limits<double>::quiet_NaN();      ///< y at the end
  double slopeB = std::numeric_limits<double>::quiet_NaN();  ///< dy/dx at the start (tan alphaB)
  double slopeE = std::numeric_limits<double>::quiet_NaN();  ///< dy/dx at the end (tan alphaE)
  /// Signed curvature (1/unit of x) at the start / end, CAB / CAE. Linear only with the slope
  /// at that end known (or for zero curvature), so a nonzero value needs slopeB / slopeE.
  double curvB = std::numeric_limits<double>::quiet_NaN();
  double curvE = std::numeric_limits<double>::quiet_NaN();
  double area = std::numeric_limits<double>::quiet_NaN();    ///< int y dx over [area_from, x_end]
  double xC = std::numeric_limits<double>::quiet_NaN();      ///< (1/area) int x y dx, same range
  double area_from = -std::numeric_limits<double>::infinity();  ///< start of the area range
  std::vector<Eigen::Vector2d> points;  ///< (x, y) the curve passes through
  std::vector<Eigen::Vector2d> param_points;  ///< (t, y): y(t) = y at curve parameter t in [0, 1]
  std::vector<std::pair<int, double>> fixed;  ///< (i, y): control ordinate i is y (flat parts)
  /// Bounds on the interior control ordinates (NaN: none). The control polygon bounds the
  /// curve, so lower <= y(t) <= upper everywhere. Solved by a primal active-set method on the
  /// same KKT system; where an upper bound is active over degree + 1 consecutive control
  /// points the curve is exactly flat there (a flat of side appears where the area needs it).
  double y_lower = std::numeric_limits<double>::quiet_NaN();
  double y_upper = std::numeric_limits<double>::quiet_NaN();
  /// From this abscissa on, the control polygon is concave (non-increasing slopes), so the
  /// curve has no inflection there. NaN: no shape condition.
  double concave_from = std::numeric_limits<double>::quiet_NaN();
};

/// The fairest curve (min int |C''(t)|^2 dt, t in [0, 1]) meeting the request: a 2-D
/// clamped uniform B-spline with the given abscissae. Throws InvalidInput for malformed
/// requests (naming `name` and the field) and InfeasibleFormParameters when the
/// conditions contradict each other (the message lists them).
NurbsCurve design_linear_form_curve(const LinearFormRequest& request);

/// A plane cut of a hull surface for the fairness check: a waterline (plane
/// z = value), buttock (y = value) or frame (x = value), sampled densely, with its curvature
/// computed ANALYTICALLY from the surface's first and second derivatives (implicit
/// differentiation of the cut condition; no fitting, no finite differences).
struct PlaneCut {
  int axis = 2;                ///< 0: frame x = value, 1: buttock y = value, 2: waterline z = value
  double value = 0;            ///< plane position (m)
  Eigen::MatrixXd points;      ///< m x 3 points on the surface and the plane, in march order
  Eigen::VectorXd curvature;   ///< signed curvature (1/m) in the plane's coordinates: (x, y) for a
                               ///< waterline, (x, z) for a buttock, (y, z) for a frame
  double bending_energy = 0;   ///< int k^2 ds (1/m), trapezoidal over the samples
  double e2 = 0;               ///< int |c''(w)|^2 dw, w the marching parameter rescaled to [0, 1] (m^2)
  int sign_changes = 0;        ///< curvature sign changes, ignoring |k| <= threshold
  double threshold = 0;        ///< 1e-6 x max |k| + 1e-9 (1/m): smaller curvature counts as straight
  Eigen::MatrixXd inflections; ///< one row (x, y, z) per sign change (midpoint of the bracketing samples)
};

/// Cut `surface` by a coordinate plane. Frames march along u and solve x(u, v) = value for v
/// (x monotone in v); waterlines and buttocks march along v and solve for u (z or y monotone
/// along u, as on sections running deck to keel). Lines that miss the plane are skipped; a
/// cut with fewer than 3 points is returned empty. `samples` >= 10 marching lines.
inline constexpr int kPlaneCutSamples = 401;  ///< plane_cut's samples unless told otherwise
PlaneCut plane_cut(const NurbsSurface& surface, int axis, double value, int samples = kPlaneCutSamples);

}  // namespace fairlines
