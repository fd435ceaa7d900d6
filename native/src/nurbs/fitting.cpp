#include "fairlines/fitting.hpp"

#include <cmath>

#include <Eigen/Dense>

#include "checks.hpp"
#include "fairlines/basis.hpp"

namespace fairlines {

using detail::fail;

namespace {

// Collocation matrix N(k, i) = N_i(u_k), m x n.
Eigen::MatrixXd collocation(const Eigen::VectorXd& u, const Eigen::VectorXd& U, int p, int n) {
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(u.size(), n);
  std::vector<double> N(p + 1);
  for (Eigen::Index k = 0; k < u.size(); ++k) {
    const int span = find_span(p, U, u[k]);
    basis_functions(span, u[k], p, U, N.data());
    for (int j = 0; j <= p; ++j) A(k, span - p + j) = N[j];
  }
  return A;
}

// Control points for data D (m x dim) at parameters u with knots U. n == m interpolates
// (LU of the square collocation matrix); n < m interpolates the two ends and fits the
// interior rows in the least-squares sense by column-pivoted QR.
Eigen::MatrixXd solve_control_points(const Eigen::MatrixXd& D, const Eigen::VectorXd& u, const Eigen::VectorXd& U, int p) {
  const Eigen::Index m = D.rows();
  const int n = static_cast<int>(U.size()) - p - 1;
  const Eigen::MatrixXd A = collocation(u, U, p, n);
  if (n == m) {
    Eigen::PartialPivLU<Eigen::MatrixXd> lu(A);
    // A singular collocation matrix means the Schoenberg-Whitney condition fails.
    const Eigen::MatrixXd Q = lu.solve(D);
    // Below this reciprocal condition number the interpolant is meaningless.
    constexpr double kMinRcond = 1e-13;
    const double rcond = lu.rcond();
    if (!(rcond > kMinRcond) || !Q.allFinite())
      fail("interpolation matrix is singular (rcond ", rcond, "): parameters and knots violate the Schoenberg-Whitney condition");
    return Q;
  }
  Eigen::MatrixXd Q(n, D.cols());
  Q.row(0) = D.row(0);
  Q.row(n - 1) = D.row(m - 1);
  if (n == 2) return Q;
  const Eigen::MatrixXd R = D.middleRows(1, m - 2) - A.block(1, 0, m - 2, 1) * D.row(0) - A.block(1, n - 1, m - 2, 1) * D.row(m - 1);
  const Eigen::MatrixXd Ai = A.block(1, 1, m - 2, n - 2);
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(Ai);
  if (qr.rank() < n - 2) fail("least-squares system is rank deficient (rank ", qr.rank(), " of ", n - 2, "): some knot span holds no data; use fewer control points");
  Q.middleRows(1, n - 2) = qr.solve(R);
  return Q;
}

void check_fit_sizes(Eigen::Index m, const FitOptions& o, const char* what) {
  detail::require_degree(o.degree);
  if (m < o.degree + 1) fail(what, " has ", m, " points; a degree-", o.degree, " fit needs at least ", o.degree + 1);
  if (m > limits::kMaxFitPoints)
    fail(what, " has ", m, " points; the limit is ", limits::kMaxFitPoints,
         " per fitted line (a dense collocation solve): thin the data first");
  if (o.n_control != 0 && (o.n_control < o.degree + 1 || o.n_control > m))
    fail("n_control is ", o.n_control, "; expected between degree + 1 = ", o.degree + 1, " and the number of points ", m);
}

// Parameters averaged over several lines of points (P&T 9.2.5), skipping lines of zero length.
Eigen::VectorXd averaged_params(const std::vector<Eigen::MatrixXd>& lines, Parameterization method) {
  const Eigen::Index m = lines[0].rows();
  if (method == Parameterization::Uniform) return Eigen::VectorXd::LinSpaced(m, 0.0, 1.0);
  Eigen::VectorXd acc = Eigen::VectorXd::Zero(m);
  int used = 0;
  for (const auto& L : lines) {
    Eigen::VectorXd c(m);
    c[0] = 0.0;
    for (Eigen::Index i = 1; i < m; ++i) {
      double d = (L.row(i) - L.row(i - 1)).norm();
      if (method == Parameterization::Centripetal) d = std::sqrt(d);
      c[i] = c[i - 1] + d;
    }
    if (!(c[m - 1] > 0.0)) continue;
    acc += c / c[m - 1];
    ++used;
  }
  if (used == 0) fail("every grid line has zero length; expected distinct points");
  acc /= used;
  acc[0] = 0.0;
  acc[m - 1] = 1.0;
  for (Eigen::Index i = 1; i < m; ++i)
    if (!(acc[i] > acc[i - 1])) fail("grid points ", i - 1, " and ", i, " coincide on every line; expected distinct points");
  return acc;
}

Eigen::VectorXd knots_for(const Eigen::VectorXd& u, const Eigen::MatrixXd& shape, const FitOptions& o) {
  const int n = o.n_control == 0 ? static_cast<int>(u.size()) : o.n_control;
  if (o.knot_method == KnotMethod::HartleyJudd) return hartley_judd_knots(shape, o.degree, n, o.parameterization);
  return averaged_knots(u, o.degree, n);
}

}  // namespace

CurveFit fit_curve_with(const Eigen::MatrixXd& points, const Eigen::VectorXd& params, const Eigen::VectorXd& knots, int degree) {
  detail::require_finite(points, "points");
  detail::require_finite(params, "params");
  if (params.size() != points.rows()) fail("params has ", params.size(), " values; expected one per point (", points.rows(), ")");
  const int n = static_cast<int>(knots.size()) - degree - 1;
  validate_knots(knots, degree, n);
  if (n > points.rows()) fail("knots define ", n, " control points; expected at most the number of points ", points.rows());
  if (points.rows() > limits::kMaxFitPoints)
    fail("points has ", points.rows(), " rows; the limit is ", limits::kMaxFitPoints, " per fitted line");
  NurbsCurve curve(degree, knots, solve_control_points(points, params, knots, degree));
  const Eigen::MatrixXd e = curve.evaluate(params) - points;
  const Eigen::VectorXd d = e.rowwise().norm();
  return {std::move(curve), params, d.maxCoeff(), std::sqrt(d.squaredNorm() / d.size())};
}

CurveFit fit_curve(const Eigen::MatrixXd& points, const FitOptions& o) {
  if (points.cols() < 1) fail("points has no coordinates; expected an (m, dim) array");
  check_fit_sizes(points.rows(), o, "points");
  detail::require_finite(points, "points");
  Eigen::VectorXd u = parameterize(points, o.parameterization);
  const Eigen::VectorXd U = knots_for(u, points, o);
  // Hartley-Judd fixes the knots first; interpolation then takes the Greville abscissae as
  // data parameters, which always satisfy the Schoenberg-Whitney condition.
  if (o.knot_method == KnotMethod::HartleyJudd && U.size() - o.degree - 1 == u.size()) u = greville_abscissae(U, o.degree);
  return fit_curve_with(points, u, U, o.degree);
}

SurfaceFit fit_surface(const Eigen::MatrixXd& grid, int rows, int cols, const FitOptions& ou, const FitOptions& ov) {
  if (rows < 2 || cols < 2 || grid.rows() != static_cast<Eigen::Index>(rows) * cols || grid.cols() != 3)
    fail("grid has shape (", grid.rows(), ", ", grid.cols(), ") for ", rows, " x ", cols, "; expected a (rows, cols, 3) array with rows, cols >= 2");
  detail::require_finite(grid, "grid");
  check_fit_sizes(rows, ou, "grid rows (u direction)");
  check_fit_sizes(cols, ov, "grid columns (v direction)");
  std::vector<Eigen::MatrixXd> ulines(cols), vlines(rows);
  for (int c = 0; c < cols; ++c) {
    ulines[c].resize(rows, 3);
    for (int r = 0; r < rows; ++r) ulines[c].row(r) = grid.row(static_cast<Eigen::Index>(r) * cols + c);
  }
  for (int r = 0; r < rows; ++r) vlines[r] = grid.middleRows(static_cast<Eigen::Index>(r) * cols, cols);
  Eigen::VectorXd u = averaged_params(ulines, ou.parameterization);
  Eigen::VectorXd v = averaged_params(vlines, ov.parameterization);
  // Hartley-Judd spacing follows the averaged parameter increments (a 1-D polyline that
  // already carries the chosen chord measure); interpolation then uses Greville points.
  auto knots_and_params = [](Eigen::VectorXd& t, const FitOptions& o) {
    const int n = o.n_control == 0 ? static_cast<int>(t.size()) : o.n_control;
    if (o.knot_method != KnotMethod::HartleyJudd) return averaged_knots(t, o.degree, n);
    Eigen::VectorXd K = hartley_judd_knots(Eigen::MatrixXd(t), o.degree, n, Parameterization::ChordLength);
    if (n == t.size()) t = greville_abscissae(K, o.degree);
    return K;
  };
  const Eigen::VectorXd Uu = knots_and_params(u, ou);
  const Eigen::VectorXd Uv = knots_and_params(v, ov);
  const int nu = static_cast<int>(Uu.size()) - ou.degree - 1, nv = static_cast<int>(Uv.size()) - ov.degree - 1;
  // Tensor product: every column fitted in u, then every row of the result in v. The lines
  // of one direction share their collocation matrix, so they are solved together as the
  // columns of one right-hand side (one factorization per direction).
  Eigen::MatrixXd Du(rows, 3 * static_cast<Eigen::Index>(cols));
  for (int c = 0; c < cols; ++c) Du.middleCols(3 * c, 3) = ulines[c];
  const Eigen::MatrixXd Qu = solve_control_points(Du, u, Uu, ou.degree);  // nu x 3 cols
  Eigen::MatrixXd Dv(cols, 3 * static_cast<Eigen::Index>(nu));
  for (int i = 0; i < nu; ++i)
    for (int c = 0; c < cols; ++c) Dv.block(c, 3 * i, 1, 3) = Qu.block(i, 3 * c, 1, 3);
  const Eigen::MatrixXd Qv = solve_control_points(Dv, v, Uv, ov.degree);  // nv x 3 nu
  Eigen::MatrixXd P(static_cast<Eigen::Index>(nu) * nv, 3);
  for (int i = 0; i < nu; ++i) P.middleRows(static_cast<Eigen::Index>(i) * nv, nv) = Qv.middleCols(3 * i, 3);
  NurbsSurface s(ou.degree, ov.degree, Uu, Uv, nu, nv, P);
  const Eigen::MatrixXd fitted = s.evaluate_grid(u, v);
  const Eigen::VectorXd d = (fitted - grid).rowwise().norm();
  return {std::move(s), u, v, d.maxCoeff(), std::sqrt(d.squaredNorm() / d.size())};
}

}  // namespace fairlines
