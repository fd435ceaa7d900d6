// Interpolation and least-squares approximation ("inverse B-spline", Kim & Kim 1995;
// Piegl & Tiller 1997, sections 9.2 and 9.4)
// of curves and of surfaces from point grids.
#pragma once

#include <Eigen/Core>

#include "fairlines/curve.hpp"
#include "fairlines/knots.hpp"
#include "fairlines/surface.hpp"

namespace fairlines {

/// Options shared by curve and surface fits.
struct FitOptions {
  int degree = 3;
  int n_control = 0;
  Parameterization parameterization = Parameterization::ChordLength;
  KnotMethod knot_method = KnotMethod::Average;

  /// Each field with its name and meaning: f(name, member pointer, doc).
  template <typename F>
  static void fields(F&& f) {
    f("degree", &FitOptions::degree, "B-spline degree, 1 .. fairlines.limits.MAX_DEGREE");
    f("n_control", &FitOptions::n_control, "control points; 0 interpolates (one per datum)");
    f("parameterization", &FitOptions::parameterization, "data parameters: 'chord', 'centripetal' or 'uniform'");
    f("knots", &FitOptions::knot_method, "interior knots: 'average' or 'hartley_judd'");
  }
};

/// A fitted curve and how far it is from the data.
struct CurveFit {
  NurbsCurve curve;
  Eigen::VectorXd params;  ///< parameter of each datum (m values)
  double max_deviation;    ///< max_k |C(u_k) - P_k| (metres)
  double rms_deviation;    ///< sqrt(mean_k |C(u_k) - P_k|^2) (metres)
};

/// Fits points (m x dim, m >= degree + 1). Interpolation solves the collocation system
/// (LU); approximation interpolates the two end points and solves the rest in the least
/// squares sense by QR (never the explicit normal-equation inverse).
CurveFit fit_curve(const Eigen::MatrixXd& points, const FitOptions& options);

/// Same with given parameters and knots (no parameterization step).
CurveFit fit_curve_with(const Eigen::MatrixXd& points, const Eigen::VectorXd& params,
                        const Eigen::VectorXd& knots, int degree);

struct SurfaceFit {
  NurbsSurface surface;
  Eigen::VectorXd params_u, params_v;
  double max_deviation;
  double rms_deviation;
};

/// Fits a structured grid of rows x cols points (grid row-major (rows * cols) x 3, point
/// (r, c) at row r * cols + c). u runs over rows, v over columns. Parameters are averaged
/// over the grid lines (P&T 9.2.5); the fit is the tensor product of 1-D fits.
SurfaceFit fit_surface(const Eigen::MatrixXd& grid, int rows, int cols, const FitOptions& options_u,
                       const FitOptions& options_v);

}  // namespace fairlines
