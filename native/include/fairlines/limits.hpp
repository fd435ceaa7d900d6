// Limits on the sizes and orders a caller can ask for. Each one is checked where the
// argument enters the engine, before anything is allocated, and a request beyond it
// raises InvalidInput naming the value and the limit. They bound the work of one call
// (no call runs for minutes or exhausts memory on a mistyped number); none of them is
// near what a hull design needs.
#pragma once

namespace fairlines::limits {

/// B-spline degree in any direction (curves, surfaces, volumes, fits). Bases of higher
/// degree lose all precision in double arithmetic long before this.
inline constexpr int kMaxDegree = 30;

/// Order of derivatives asked of a curve, surface or basis (0 = the point itself).
inline constexpr int kMaxDerivativeOrder = 30;

/// Control points per parametric direction in a generated knot vector
/// (clamped_uniform_knots, unclamped_uniform_knots).
inline constexpr int kMaxControlPoints = 1'000'000;

/// Values (doubles) in one array a call returns whose size is a product of the caller's
/// sizes (evaluate_grid, basis_functions, derivatives of many parameters): 400 MB.
inline constexpr long kMaxResultValues = 50'000'000;

/// Points along one fitted line (fit_curve; rows and columns of fit_surface). The fit
/// solves a dense collocation system of this order, memory ~ m^2, time ~ m^3.
inline constexpr int kMaxFitPoints = 2000;

/// Control points of a form-parameter curve (dense Newton systems of order ~dim * n).
inline constexpr int kMaxFormCurveControlPoints = 200;

/// Offset points a form-parameter curve passes through or approaches.
inline constexpr int kMaxFormCurvePoints = 1000;

/// Newton iterations per start of the form-parameter solver.
inline constexpr int kMaxFormCurveIterations = 100'000;

/// Extra random starts of the form-parameter solver (each one a full solve).
inline constexpr int kMaxFormCurveMultistart = 100;

/// Largest magnitude of a form-parameter length (coordinates, centroid), in the unit of
/// the offsets: a million metres is no ship; millimetres of a large ship stay below it.
inline constexpr double kMaxFormCurveLength = 1e6;

/// Largest magnitude of a form-parameter tangent angle, degrees.
inline constexpr double kMaxAngleDegrees = 360.0;

}  // namespace fairlines::limits
