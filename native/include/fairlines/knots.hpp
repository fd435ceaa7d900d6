// Knot vectors and data parameterization (Piegl & Tiller 1997, ch. 2 and 9; Hartley &
// Judd 1980 as used for hull curves by Kim & Kim 1995).
#pragma once

#include <string>

#include <Eigen/Core>

namespace fairlines {

/// How data points are assigned parameter values before fitting.
enum class Parameterization {
  Uniform,     ///< u_i = i / m
  ChordLength, ///< proportional to cumulative chord length (Kim & Kim 1995)
  Centripetal, ///< proportional to cumulative sqrt of chord length (Lee 1989; Yoon 2007)
};

/// How interior knots of a fitted B-spline are placed.
enum class KnotMethod {
  Average,     ///< averaging of the data parameters (Piegl & Tiller 1997, eq. 9.8 / 9.69; Yoon 2007)
  HartleyJudd, ///< spacing proportional to sums of `degree` consecutive chords (Hartley & Judd 1980)
};

/// Parses "uniform" | "chord" | "centripetal"; throws InvalidInput naming the bad value.
Parameterization parse_parameterization(const std::string& name);
/// Parses "average" | "hartley_judd"; throws InvalidInput naming the bad value.
KnotMethod parse_knot_method(const std::string& name);
/// The names parse_parameterization and parse_knot_method accept for each value.
std::string parameterization_name(Parameterization method);
std::string knot_method_name(KnotMethod method);

/// Checks a knot vector for a B-spline of `degree` with `n_control` control points:
/// length n_control + degree + 1, finite, non-decreasing, no interior multiplicity
/// above degree + 1... (at most degree inside the domain), non-empty domain.
/// Throws InvalidInput whose message starts with `what` and names the bad entry.
void validate_knots(const Eigen::VectorXd& knots, int degree, int n_control,
                    const std::string& what = "knots");

/// Clamped (open) uniform knot vector: ends repeated degree + 1 times, interior equally
/// spaced on [t0, t1]. Length n_control + degree + 1.
Eigen::VectorXd clamped_uniform_knots(int n_control, int degree, double t0 = 0.0, double t1 = 1.0);

/// Unclamped (periodic-style) uniform knot vector t_i = i, rescaled so the valid
/// domain [t_degree, t_n] is [t0, t1]. Length n_control + degree + 1.
Eigen::VectorXd unclamped_uniform_knots(int n_control, int degree, double t0 = 0.0, double t1 = 1.0);

/// Parameter values in [0, 1] for the rows of `points` (m x dim, m >= 2). Coincident
/// consecutive points are rejected (InvalidInput) for chord and centripetal.
Eigen::VectorXd parameterize(const Eigen::MatrixXd& points, Parameterization method);

/// Clamped knot vector on [0, 1] for fitting `params` (m values, increasing) with
/// `n_control` control points of `degree` by averaging. n_control == m gives the
/// interpolation rule (P&T 9.8), n_control < m the approximation rule (P&T 9.69).
Eigen::VectorXd averaged_knots(const Eigen::VectorXd& params, int degree, int n_control);

/// Clamped knot vector on [0, 1] by Hartley–Judd: knot spacings proportional to the sum
/// of `degree` consecutive chords of the data polygon (resampled to n_control points when
/// n_control < rows of `points`). The chord measure follows `metric`: length (chord),
/// sqrt of length (centripetal, as Kim & Kim 1995 use it) or 1 (uniform).
Eigen::VectorXd hartley_judd_knots(const Eigen::MatrixXd& points, int degree, int n_control,
                                   Parameterization metric = Parameterization::ChordLength);

/// Greville abscissae (knot averages) of a knot vector: n_control values.
Eigen::VectorXd greville_abscissae(const Eigen::VectorXd& knots, int degree);

}  // namespace fairlines
