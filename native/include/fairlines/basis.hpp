// B-spline basis functions (Piegl & Tiller, The NURBS Book, algorithms A2.1-A2.3).
#pragma once

#include <Eigen/Core>

namespace fairlines {

/// Largest degree the fixed-size fast paths support; higher degrees still work
/// through the general code paths.
inline constexpr int kMaxFastDegree = 7;

/// Knot span index i with knots[i] <= t < knots[i+1] for a B-spline of `degree`
/// with knots.size() - degree - 1 basis functions. t at the end of the domain
/// maps to the last non-empty span; t outside the domain is clamped to it.
///   degree  p >= 0
///   knots   non-decreasing knot vector, length n + p + 1
int find_span(int degree, const Eigen::VectorXd& knots, double t);

/// Same, on a raw knot array of `n_knots` entries (hot loops).
int find_span(int degree, const double* knots, int n_knots, double t);

/// The degree + 1 non-zero basis functions N_{span-p..span, p}(t), written to N.
void basis_functions(int span, double t, int degree, const Eigen::VectorXd& knots, double* N);
void basis_functions(int span, double t, int degree, const double* knots, double* N);

/// Non-zero basis functions and their derivatives up to n_deriv (A2.3).
///   ders  (n_deriv + 1) x (degree + 1); row k holds the k-th derivatives. Derivatives
///         above the degree are zero.
void basis_derivatives(int span, double t, int degree, int n_deriv, const Eigen::VectorXd& knots,
                       Eigen::Ref<Eigen::MatrixXd> ders);

/// All n = knots.size() - degree - 1 basis functions (or their order-th derivatives) at t,
/// as one row: 1 x n, zero outside the degree + 1 non-zero ones. For building collocation
/// and constraint matrices; t must lie in the domain.
Eigen::RowVectorXd basis_row(const Eigen::VectorXd& knots, int degree, double t, int order = 0);

}  // namespace fairlines
