// Linear form-parameter curves (the bare hull's basic curves): see fairlines/hull.hpp.
//
// Notation (design_linear_form_curve and its steps):
//   p       degree                    n   number of control points
//   a       control abscissae (n)     y   control ordinates (n), the unknowns
//   U       clamped uniform knots     t   curve parameter in [0, 1]
//   N, dN   basis row N_j(t) and its derivative (1 x n)
//   G       Gram matrix of N'' (n x n): the fairness E2 = y^T G y
//   m       number of equality conditions, row . y = rhs
//   g, h    inequality rows g . y <= h (bounds, concave polygon)
//   K       the KKT matrix [2G A^T; A 0] of the equalities and the active inequalities
#include "fairlines/hull.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include <Eigen/Dense>

#include "fairlines/basis.hpp"
#include "fairlines/errors.hpp"
#include "fairlines/knots.hpp"
#include "nurbs/checks.hpp"
#include "nurbs/gauss.hpp"

namespace fairlines {

namespace {

using detail::fail;

constexpr double kFeasibleTol = 1e-9;      // relative residual above which conditions are in conflict

/// t in [0, 1] with x(t) = x for the monotone abscissa function x(t) = sum N_j(t) a_j.
double invert_abscissa(const Eigen::VectorXd& U, int p, const Eigen::VectorXd& a, double x) {
  double lo = 0, hi = 1;
  if (x <= a[0]) return 0;
  if (x >= a[a.size() - 1]) return 1;
  for (int it = 0; it < 100 && hi - lo > 1e-16; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (basis_row(U, p, mid).dot(a) < x) lo = mid;
    else hi = mid;
  }
  return 0.5 * (lo + hi);
}

std::string fmt(double v) { return detail::format_number(v, 10); }

/// The curve being designed: its name (for messages), degree, abscissae and knots.
struct FormCurve {
  const std::string& name;
  int p, n;
  const Eigen::VectorXd& a;
  Eigen::VectorXd U;
};

/// Linear conditions row . y = rhs, each named for the infeasibility message.
struct Conditions {
  std::vector<Eigen::RowVectorXd> rows;
  std::vector<double> rhs;
  std::vector<std::string> names;
  void add(Eigen::RowVectorXd row, double b, const std::string& what) {
    rows.push_back(std::move(row));
    rhs.push_back(b);
    names.push_back(what);
  }
  int size() const { return static_cast<int>(rows.size()); }
};

/// Inequalities g . y <= h, each named for the infeasibility message.
struct Inequalities {
  std::vector<Eigen::RowVectorXd> g;
  std::vector<double> h;
  std::vector<std::string> names;
  double yscale = 1.0;  ///< size of the bounds, for the relative violation
  void add(Eigen::RowVectorXd row, double b, const std::string& what) {
    g.push_back(std::move(row));
    h.push_back(b);
    names.push_back(what);
  }
  int size() const { return static_cast<int>(g.size()); }
  double scale(int j) const { return yscale * g[j].cwiseAbs().sum(); }
  /// Violation of inequality j at y, relative to its scale (> 0: violated).
  double violation(int j, const Eigen::VectorXd& y) const { return (g[j].dot(y) - h[j]) / scale(j); }
};

/// The unit row e_i (1 x n).
Eigen::RowVectorXd unit_row(int n, int i) {
  Eigen::RowVectorXd e = Eigen::RowVectorXd::Zero(n);
  e[i] = 1;
  return e;
}

/// True when the optional field v is given (not NaN); throws when it is given but infinite.
bool given(const std::string& name, double v, const char* field) {
  if (std::isnan(v)) return false;
  if (!std::isfinite(v)) fail(name, ": ", field, " is ", v, "; expected a finite number or not given");
  return true;
}

/// Degree, control count and abscissae checked; the clamped uniform knots.
FormCurve check_abscissae(const LinearFormRequest& r) {
  const std::string& nm = r.name;
  const int p = r.degree;
  if (p < 2) fail(nm, ": degree is ", p, "; expected an integer >= 2 (E2 needs C'')");
  const int n = static_cast<int>(r.abscissae.size());
  if (n < p + 1) fail(nm, ": ", n, " control points; expected at least degree + 1 = ", p + 1);
  detail::require_finite(r.abscissae, nm + ": abscissae");
  const Eigen::VectorXd& a = r.abscissae;
  for (int i = 0; i + 1 < n; ++i) {
    if (a[i + 1] < a[i]) fail(nm, ": abscissae decrease at index ", i + 1, "; expected non-decreasing values");
    if (a[i + 1] == a[i] && a[i] != a[0] && a[i + 1] != a[n - 1])
      fail(nm, ": abscissae ", i, " and ", i + 1, " coincide; only runs at the start or the end may");
  }
  if (!(a[n - 1] > a[0])) fail(nm, ": the curve has zero extent (", a[0], " to ", a[n - 1], "); expected start < end");
  return {nm, p, n, a, clamped_uniform_knots(n, p)};
}

/// End ordinates yB, yE and end slopes (as control-polygon differences).
void add_end_values(const FormCurve& c, const LinearFormRequest& r, Conditions& eq) {
  const int n = c.n;
  const Eigen::VectorXd& a = c.a;
  if (given(c.name, r.yB, "yB")) eq.add(unit_row(n, 0), r.yB, "yB");
  if (given(c.name, r.yE, "yE")) eq.add(unit_row(n, n - 1), r.yE, "yE");
  if (given(c.name, r.slopeB, "slopeB")) {
    if (a[1] == a[0]) fail(c.name, ": slopeB is given but the start tangent is normal to the abscissa (first two abscissae coincide)");
    Eigen::RowVectorXd e = Eigen::RowVectorXd::Zero(n);
    e[0] = -1, e[1] = 1;
    eq.add(e, r.slopeB * (a[1] - a[0]), "alphaB");
  }
  if (given(c.name, r.slopeE, "slopeE")) {
    if (a[n - 1] == a[n - 2]) fail(c.name, ": slopeE is given but the end tangent is normal to the abscissa (last two abscissae coincide)");
    Eigen::RowVectorXd e = Eigen::RowVectorXd::Zero(n);
    e[n - 2] = -1, e[n - 1] = 1;
    eq.add(e, r.slopeE * (a[n - 1] - a[n - 2]), "alphaE");
  }
}

/// End curvature k = (x' y'' - y' x'') / (x'^2 + y'^2)^1.5 at parameter t: with the end slope
/// s known, y' = s x' and the denominator is |x'|^3 (1 + s^2)^1.5, so k is linear in y.
void add_end_curvature(const FormCurve& c, double k, double slope, double t, const char* field,
                       const char* slope_field, Conditions& eq) {
  if (!given(c.name, k, field)) return;
  const double s = std::isnan(slope) ? 0.0 : slope;
  if (std::isnan(slope) && k != 0.0)
    fail(c.name, ": ", field, " is ", k, " without ", slope_field, "; expected the end slope too (or ", field, " = 0)");
  const Eigen::RowVectorXd d1 = basis_row(c.U, c.p, t, 1), d2 = basis_row(c.U, c.p, t, 2);
  const double xt = d1.dot(c.a), xtt = d2.dot(c.a);
  if (!(std::abs(xt) > 0)) fail(c.name, ": ", field, " is given but the curve's abscissa does not advance at that end");
  // x' y'' - y' x'' = k |x'|^3 (1 + s^2)^1.5, y' = d1 . y
  eq.add(xt * d2 - xtt * d1, k * std::abs(xt) * xt * xt * std::pow(1.0 + s * s, 1.5), field);
}

/// Area int y dx and its moment int x y dx over [area_from, x_end] as rows in y: Gauss
/// quadrature of y(t) x'(t) dt on every knot span from t(area_from) on (exact, degree 2p).
void add_area(const FormCurve& c, const LinearFormRequest& r, Conditions& eq) {
  const bool want_area = given(c.name, r.area, "Area"), want_xc = given(c.name, r.xC, "xC");
  if (!want_area && !want_xc) return;
  if (std::isnan(r.area_from) || r.area_from == std::numeric_limits<double>::infinity())
    fail(c.name, ": area_from is ", r.area_from, "; expected a number or -inf");
  const int p = c.p, n = c.n;
  const double t0 = invert_abscissa(c.U, p, c.a, r.area_from);
  Eigen::RowVectorXd ar = Eigen::RowVectorXd::Zero(n), mr = Eigen::RowVectorXd::Zero(n);
  const auto& g = detail::gauss_rule(2 * p);
  std::vector<double> br{t0};
  for (int i = p + 1; i < n; ++i)
    if (c.U[i] > t0) br.push_back(c.U[i]);
  br.push_back(1.0);
  for (std::size_t k = 0; k + 1 < br.size(); ++k) {
    const double h = 0.5 * (br[k + 1] - br[k]), m = 0.5 * (br[k + 1] + br[k]);
    if (!(h > 0)) continue;
    for (std::size_t q = 0; q < g.x.size(); ++q) {
      const double t = m + h * g.x[q];
      const Eigen::RowVectorXd N = basis_row(c.U, p, t), dN = basis_row(c.U, p, t, 1);
      const double x = N.dot(c.a), dx = dN.dot(c.a);
      ar += g.w[q] * h * dx * N;
      mr += g.w[q] * h * x * dx * N;
    }
  }
  if (want_area) eq.add(ar, r.area, "Area");
  if (want_xc) eq.add(mr - r.xC * ar, 0.0, "xC");
}

/// Points (x, y) and (t, y) the curve passes through, and fixed control ordinates.
void add_points(const FormCurve& c, const LinearFormRequest& r, Conditions& eq) {
  const std::string& nm = c.name;
  const int n = c.n;
  const Eigen::VectorXd& a = c.a;
  for (std::size_t k = 0; k < r.points.size(); ++k) {
    const Eigen::Vector2d& q = r.points[k];
    if (!std::isfinite(q[0]) || !std::isfinite(q[1])) fail(nm, ": points[", k, "] is (", q[0], ", ", q[1], "); expected finite values");
    if (q[0] < a[0] || q[0] > a[n - 1])
      fail(nm, ": points[", k, "] x = ", q[0], " is outside the curve (", a[0], " to ", a[n - 1], ")");
    eq.add(basis_row(c.U, c.p, invert_abscissa(c.U, c.p, a, q[0])), q[1], "points[" + std::to_string(k) + "]");
  }
  for (std::size_t k = 0; k < r.param_points.size(); ++k) {
    const Eigen::Vector2d& q = r.param_points[k];
    if (!(q[0] >= 0 && q[0] <= 1) || !std::isfinite(q[1])) fail(nm, ": param_points[", k, "] is (", q[0], ", ", q[1], "); expected t in [0, 1] and a finite y");
    eq.add(basis_row(c.U, c.p, q[0]), q[1], "param_points[" + std::to_string(k) + "]");
  }
  for (std::size_t k = 0; k < r.fixed.size(); ++k) {
    const auto [i, v] = r.fixed[k];
    if (i < 0 || i >= n || !std::isfinite(v)) fail(nm, ": fixed[", k, "] is (", i, ", ", v, "); expected an index 0..", n - 1, " and a finite y");
    eq.add(unit_row(n, i), v, "fixed[" + std::to_string(i) + "]");
  }
}

/// Every equality condition of the request, checked; throws when there are more than n.
Conditions equality_conditions(const FormCurve& c, const LinearFormRequest& r) {
  Conditions eq;
  add_end_values(c, r, eq);
  add_end_curvature(c, r.curvB, r.slopeB, 0.0, "CAB", "alphaB / slopeB", eq);
  add_end_curvature(c, r.curvE, r.slopeE, 1.0, "CAE", "alphaE / slopeE", eq);
  add_area(c, r, eq);
  add_points(c, r, eq);
  const int m = eq.size();
  if (m > c.n) fail(c.name, ": ", m, " conditions need at least ", m, " control points; the curve has ", c.n);
  return eq;
}

/// Fairness E2 of the y ordinates (x(t) is fixed): G = int N''^T N'' dt by Gauss per span.
Eigen::MatrixXd fairness_matrix(const FormCurve& c) {
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(c.n, c.n);
  const auto& g = detail::gauss_rule(c.p);
  for (int s = c.p; s < c.n; ++s) {
    const double h = 0.5 * (c.U[s + 1] - c.U[s]), mid = 0.5 * (c.U[s + 1] + c.U[s]);
    if (!(h > 0)) continue;
    for (std::size_t q = 0; q < g.x.size(); ++q) {
      const Eigen::RowVectorXd d2 = basis_row(c.U, c.p, mid + h * g.x[q], 2);
      G += g.w[q] * h * d2.transpose() * d2;
    }
  }
  return G;
}

/// Inequalities g . y <= h: bounds on the interior ordinates 1..n-2 that are not fixed and,
/// from abscissa concave_from on, a concave control polygon (non-increasing slopes) -- which
/// makes the curve concave there (no inflection).
Inequalities shape_inequalities(const FormCurve& c, const LinearFormRequest& r) {
  const int n = c.n;
  const Eigen::VectorXd& a = c.a;
  const bool lower_on = !std::isnan(r.y_lower), upper_on = !std::isnan(r.y_upper);
  if (lower_on) detail::require_finite(r.y_lower, c.name + ": y_lower");
  if (upper_on) detail::require_finite(r.y_upper, c.name + ": y_upper");
  Inequalities in;
  auto is_fixed = [&](int i) { return std::any_of(r.fixed.begin(), r.fixed.end(), [&](const auto& f) { return f.first == i; }); };
  for (int i = 1; i < n - 1; ++i) {
    if (is_fixed(i)) continue;
    Eigen::RowVectorXd e = Eigen::RowVectorXd::Zero(n);
    if (upper_on) {
      e[i] = 1;
      in.add(e, r.y_upper, "y <= " + fmt(r.y_upper));
    }
    if (lower_on) {
      e[i] = -1;
      in.add(e, -r.y_lower, "y >= " + fmt(r.y_lower));
    }
  }
  if (!std::isnan(r.concave_from)) {
    for (int i = 1; i < n - 1; ++i) {
      const double h0 = a[i] - a[i - 1], h1 = a[i + 1] - a[i];
      if (a[i - 1] < r.concave_from || !(h0 > 0) || !(h1 > 0)) continue;
      Eigen::RowVectorXd g = Eigen::RowVectorXd::Zero(n);
      g[i + 1] = 1 / h1, g[i] = -1 / h1 - 1 / h0, g[i - 1] = 1 / h0;
      in.add(g, 0.0, "concave below x = " + fmt(r.concave_from));
    }
  }
  in.yscale = std::max({1.0, upper_on ? std::abs(r.y_upper) : 0.0, lower_on ? std::abs(r.y_lower) : 0.0});
  return in;
}

/// Minimiser of y^T G y under the equalities and the active inequalities: solution of the KKT
/// system K [y; multipliers] = [0; rhs; h_active] (full-pivot LU: K may be singular).
Eigen::VectorXd solve_kkt(const Eigen::MatrixXd& G, const Conditions& eq, const Inequalities& in,
                          const std::vector<int>& active) {
  const int n = static_cast<int>(G.rows()), m = eq.size(), ma = static_cast<int>(active.size());
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n + m + ma, n + m + ma);
  K.topLeftCorner(n, n) = 2.0 * G;
  Eigen::VectorXd b = Eigen::VectorXd::Zero(n + m + ma);
  for (int i = 0; i < m; ++i) {
    K.block(n + i, 0, 1, n) = eq.rows[i];
    K.block(0, n + i, n, 1) = eq.rows[i].transpose();
    b[n + i] = eq.rhs[i];
  }
  for (int k = 0; k < ma; ++k) {
    K.block(n + m + k, 0, 1, n) = in.g[active[k]];
    K.block(0, n + m + k, n, 1) = in.g[active[k]].transpose();
    b[n + m + k] = in.h[active[k]];
  }
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(K);
  return lu.solve(b);
}

/// The fairest ordinates by a primal active-set method: add the most violated inactive
/// inequality, else release the active one with the most negative multiplier, until neither.
Eigen::VectorXd solve_active_set(const Eigen::MatrixXd& G, const Conditions& eq, const Inequalities& in) {
  const int n = static_cast<int>(G.rows()), m = eq.size(), ni = in.size();
  std::vector<int> active;
  Eigen::VectorXd y;
  for (int iter = 0; iter <= 4 * (n + ni); ++iter) {
    const int ma = static_cast<int>(active.size());
    const Eigen::VectorXd sol = solve_kkt(G, eq, in, active);
    y = sol.head(n);
    // Most violated inactive inequality (relative to its scale).
    int worst = -1;
    double worst_v = 1e-12;
    for (int j = 0; j < ni; ++j) {
      if (std::find(active.begin(), active.end(), j) != active.end()) continue;
      const double v = in.violation(j, y);
      if (v > worst_v) worst = j, worst_v = v;
    }
    if (worst >= 0) {
      active.push_back(worst);
      continue;
    }
    // Multipliers: 2 G y + sum mu_k g_k = 0 with mu_k >= 0 for g . y <= h. Release the most
    // negative one.
    int release = -1;
    double release_v = ma ? 1e-10 * (1.0 + sol.tail(ma).cwiseAbs().maxCoeff()) : 0.0;
    for (int k = 0; k < ma; ++k)
      if (-sol[n + m + k] > release_v) release = k, release_v = -sol[n + m + k];
    if (release < 0) break;
    active.erase(active.begin() + release);
  }
  return y;
}

/// Throws InfeasibleFormParameters when y misses a condition: conflicting conditions show as
/// a residual the solve cannot remove, or an inequality the active-set loop left violated.
void check_feasible(const FormCurve& c, const LinearFormRequest& r, const Conditions& eq, const Inequalities& in,
                    const Eigen::VectorXd& y) {
  const int m = eq.size();
  double scale = 1e-300;
  for (int i = 0; i < m; ++i) scale = std::max(scale, std::abs(eq.rhs[i]) + eq.rows[i].cwiseAbs().sum() * y.cwiseAbs().maxCoeff());
  std::vector<std::string> bad;
  for (int i = 0; i < m; ++i)
    if (!std::isfinite(eq.rows[i].dot(y)) || std::abs(eq.rows[i].dot(y) - eq.rhs[i]) > kFeasibleTol * scale)
      bad.push_back(eq.names[i]);
  for (int j = 0; j < in.size() && bad.empty(); ++j)
    if (in.violation(j, y) > 1e-9) bad.push_back(in.names[j]);
  if (bad.empty()) return;
  const bool lower_on = !std::isnan(r.y_lower), upper_on = !std::isnan(r.y_upper);
  std::string list;
  for (const auto& s : eq.names) list += (list.empty() ? "" : ", ") + s;
  if (!std::isnan(r.concave_from)) list += ", a concave shape below " + fmt(r.concave_from);
  if (upper_on || lower_on) list += std::string(", and ") + (upper_on ? "y <= " + fmt(r.y_upper) : "") +
                               (upper_on && lower_on ? " / " : "") + (lower_on ? "y >= " + fmt(r.y_lower) : "");
  throw InfeasibleFormParameters(c.name + ": the conditions " + list + " contradict each other on a curve with " +
                                 std::to_string(c.n) + " control points (not met: " + bad.front() + ")");
}

}  // namespace

NurbsCurve design_linear_form_curve(const LinearFormRequest& r) {
  const FormCurve c = check_abscissae(r);
  const Conditions eq = equality_conditions(c, r);
  const Eigen::MatrixXd G = fairness_matrix(c);
  const Inequalities in = shape_inequalities(c, r);
  const Eigen::VectorXd y = solve_active_set(G, eq, in);
  check_feasible(c, r, eq, in, y);
  Eigen::MatrixXd P(c.n, 2);
  P.col(0) = c.a;
  P.col(1) = y;
  return NurbsCurve(c.p, c.U, P);
}

}  // namespace fairlines
