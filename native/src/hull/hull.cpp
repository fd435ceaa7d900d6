// Linear form-parameter curves (the bare hull's basic curves): see fairlines/hull.hpp.
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

std::string fmt(double v) {
  std::ostringstream os;
  os.precision(10);
  os << v;
  return os.str();
}

}  // namespace

NurbsCurve design_linear_form_curve(const LinearFormRequest& r) {
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
  const Eigen::VectorXd U = clamped_uniform_knots(n, p);

  std::vector<Eigen::RowVectorXd> rows;
  std::vector<double> rhs;
  std::vector<std::string> names;
  auto add = [&](Eigen::RowVectorXd row, double b, const std::string& what) {
    rows.push_back(std::move(row));
    rhs.push_back(b);
    names.push_back(what);
  };
  auto given = [&](double v, const char* field) {
    if (std::isnan(v)) return false;
    if (!std::isfinite(v)) fail(nm, ": ", field, " is ", v, "; expected a finite number or not given");
    return true;
  };
  if (given(r.yB, "yB")) {
    Eigen::RowVectorXd e = Eigen::RowVectorXd::Zero(n);
    e[0] = 1;
    add(e, r.yB, "yB");
  }
  if (given(r.yE, "yE")) {
    Eigen::RowVectorXd e = Eigen::RowVectorXd::Zero(n);
    e[n - 1] = 1;
    add(e, r.yE, "yE");
  }
  if (given(r.slopeB, "slopeB")) {
    if (a[1] == a[0]) fail(nm, ": slopeB is given but the start tangent is normal to the abscissa (first two abscissae coincide)");
    Eigen::RowVectorXd e = Eigen::RowVectorXd::Zero(n);
    e[0] = -1, e[1] = 1;
    add(e, r.slopeB * (a[1] - a[0]), "alphaB");
  }
  if (given(r.slopeE, "slopeE")) {
    if (a[n - 1] == a[n - 2]) fail(nm, ": slopeE is given but the end tangent is normal to the abscissa (last two abscissae coincide)");
    Eigen::RowVectorXd e = Eigen::RowVectorXd::Zero(n);
    e[n - 2] = -1, e[n - 1] = 1;
    add(e, r.slopeE * (a[n - 1] - a[n - 2]), "alphaE");
  }
  // End curvature k = (x' y'' - y' x'') / (x'^2 + y'^2)^1.5: with the end slope s known,
  // y' = s x' and the denominator is |x'|^3 (1 + s^2)^1.5, so k is linear in the ordinates.
  auto add_curvature = [&](double k, double slope, double t, const char* field, const char* slope_field) {
    if (!given(k, field)) return;
    const double s = std::isnan(slope) ? 0.0 : slope;
    if (std::isnan(slope) && k != 0.0)
      fail(nm, ": ", field, " is ", k, " without ", slope_field, "; expected the end slope too (or ", field, " = 0)");
    const Eigen::RowVectorXd d1 = basis_row(U, p, t, 1), d2 = basis_row(U, p, t, 2);
    const double xt = d1.dot(a), xtt = d2.dot(a);
    if (!(std::abs(xt) > 0)) fail(nm, ": ", field, " is given but the curve's abscissa does not advance at that end");
    // x' y'' - y' x'' = k |x'|^3 (1 + s^2)^1.5, y' = d1 . y
    add(xt * d2 - xtt * d1, k * std::abs(xt) * xt * xt * std::pow(1.0 + s * s, 1.5), field);
  };
  add_curvature(r.curvB, r.slopeB, 0.0, "CAB", "alphaB / slopeB");
  add_curvature(r.curvE, r.slopeE, 1.0, "CAE", "alphaE / slopeE");
  const bool want_area = given(r.area, "Area"), want_xc = given(r.xC, "xC");
  if (want_area || want_xc) {
    if (std::isnan(r.area_from) || r.area_from == std::numeric_limits<double>::infinity())
      fail(nm, ": area_from is ", r.area_from, "; expected a number or -inf");
    const double t0 = invert_abscissa(U, p, a, r.area_from);
    Eigen::RowVectorXd ar = Eigen::RowVectorXd::Zero(n), mr = Eigen::RowVectorXd::Zero(n);
    const auto& g = detail::gauss_rule(2 * p);
    std::vector<double> br{t0};
    for (int i = p + 1; i < n; ++i)
      if (U[i] > t0) br.push_back(U[i]);
    br.push_back(1.0);
    for (std::size_t k = 0; k + 1 < br.size(); ++k) {
      const double h = 0.5 * (br[k + 1] - br[k]), m = 0.5 * (br[k + 1] + br[k]);
      if (!(h > 0)) continue;
      for (std::size_t q = 0; q < g.x.size(); ++q) {
        const double t = m + h * g.x[q];
        const Eigen::RowVectorXd N = basis_row(U, p, t), dN = basis_row(U, p, t, 1);
        const double x = N.dot(a), dx = dN.dot(a);
        ar += g.w[q] * h * dx * N;
        mr += g.w[q] * h * x * dx * N;
      }
    }
    if (want_area) add(ar, r.area, "Area");
    if (want_xc) add(mr - r.xC * ar, 0.0, "xC");
  }
  for (std::size_t k = 0; k < r.points.size(); ++k) {
    const Eigen::Vector2d& q = r.points[k];
    if (!std::isfinite(q[0]) || !std::isfinite(q[1])) fail(nm, ": points[", k, "] is (", q[0], ", ", q[1], "); expected finite values");
    if (q[0] < a[0] || q[0] > a[n - 1])
      fail(nm, ": points[", k, "] x = ", q[0], " is outside the curve (", a[0], " to ", a[n - 1], ")");
    add(basis_row(U, p, invert_abscissa(U, p, a, q[0])), q[1], "points[" + std::to_string(k) + "]");
  }
  for (std::size_t k = 0; k < r.param_points.size(); ++k) {
    const Eigen::Vector2d& q = r.param_points[k];
    if (!(q[0] >= 0 && q[0] <= 1) || !std::isfinite(q[1])) fail(nm, ": param_points[", k, "] is (", q[0], ", ", q[1], "); expected t in [0, 1] and a finite y");
    add(basis_row(U, p, q[0]), q[1], "param_points[" + std::to_string(k) + "]");
  }
  for (std::size_t k = 0; k < r.fixed.size(); ++k) {
    const auto [i, v] = r.fixed[k];
    if (i < 0 || i >= n || !std::isfinite(v)) fail(nm, ": fixed[", k, "] is (", i, ", ", v, "); expected an index 0..", n - 1, " and a finite y");
    Eigen::RowVectorXd e = Eigen::RowVectorXd::Zero(n);
    e[i] = 1;
    add(e, v, "fixed[" + std::to_string(i) + "]");
  }
  const int m = static_cast<int>(rows.size());
  if (m > n) fail(nm, ": ", m, " conditions need at least ", m, " control points; the curve has ", n);

  // Fairness: E2 of the y ordinates (x(t) is fixed): Gram matrix of N''.
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(n, n);
  {
    const auto& g = detail::gauss_rule(p);
    for (int s = p; s < n; ++s) {
      const double h = 0.5 * (U[s + 1] - U[s]), mid = 0.5 * (U[s + 1] + U[s]);
      if (!(h > 0)) continue;
      for (std::size_t q = 0; q < g.x.size(); ++q) {
        const Eigen::RowVectorXd d2 = basis_row(U, p, mid + h * g.x[q], 2);
        G += g.w[q] * h * d2.transpose() * d2;
      }
    }
  }
  // Inequalities g . y <= h: bounds on the interior ordinates 1..n-2 and, from abscissa
  // concave_from on, a concave control polygon (non-increasing slopes) -- which makes the
  // curve concave there (no inflection). Solved by a primal active-set method on the KKT system.
  const bool lower_on = !std::isnan(r.y_lower), upper_on = !std::isnan(r.y_upper);
  if (lower_on) detail::require_finite(r.y_lower, nm + ": y_lower");
  if (upper_on) detail::require_finite(r.y_upper, nm + ": y_upper");
  std::vector<Eigen::RowVectorXd> gin;
  std::vector<double> hin;
  std::vector<std::string> gname;
  auto is_fixed = [&](int i) { return std::any_of(r.fixed.begin(), r.fixed.end(), [&](const auto& f) { return f.first == i; }); };
  for (int i = 1; i < n - 1; ++i) {
    if (is_fixed(i)) continue;
    Eigen::RowVectorXd e = Eigen::RowVectorXd::Zero(n);
    if (upper_on) {
      e[i] = 1;
      gin.push_back(e), hin.push_back(r.y_upper), gname.push_back("y <= " + fmt(r.y_upper));
    }
    if (lower_on) {
      e[i] = -1;
      gin.push_back(e), hin.push_back(-r.y_lower), gname.push_back("y >= " + fmt(r.y_lower));
    }
  }
  if (!std::isnan(r.concave_from)) {
    for (int i = 1; i < n - 1; ++i) {
      const double h0 = a[i] - a[i - 1], h1 = a[i + 1] - a[i];
      if (a[i - 1] < r.concave_from || !(h0 > 0) || !(h1 > 0)) continue;
      Eigen::RowVectorXd g = Eigen::RowVectorXd::Zero(n);
      g[i + 1] = 1 / h1, g[i] = -1 / h1 - 1 / h0, g[i - 1] = 1 / h0;
      gin.push_back(g), hin.push_back(0.0), gname.push_back("concave below x = " + fmt(r.concave_from));
    }
  }
  const int ni = static_cast<int>(gin.size());
  std::vector<int> active;
  Eigen::VectorXd y;
  const double yscale = std::max({1.0, upper_on ? std::abs(r.y_upper) : 0.0, lower_on ? std::abs(r.y_lower) : 0.0});
  auto gscale = [&](int j) { return yscale * gin[j].cwiseAbs().sum(); };
  for (int iter = 0; iter <= 4 * (n + ni); ++iter) {
    const int ma = static_cast<int>(active.size());
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n + m + ma, n + m + ma);
    K.topLeftCorner(n, n) = 2.0 * G;
    Eigen::VectorXd b = Eigen::VectorXd::Zero(n + m + ma);
    for (int i = 0; i < m; ++i) {
      K.block(n + i, 0, 1, n) = rows[i];
      K.block(0, n + i, n, 1) = rows[i].transpose();
      b[n + i] = rhs[i];
    }
    for (int k = 0; k < ma; ++k) {
      K.block(n + m + k, 0, 1, n) = gin[active[k]];
      K.block(0, n + m + k, n, 1) = gin[active[k]].transpose();
      b[n + m + k] = hin[active[k]];
    }
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(K);
    const Eigen::VectorXd sol = lu.solve(b);
    y = sol.head(n);
    // Most violated inactive inequality (relative to its scale).
    int worst = -1;
    double worst_v = 1e-12;
    for (int j = 0; j < ni; ++j) {
      if (std::find(active.begin(), active.end(), j) != active.end()) continue;
      const double v = (gin[j].dot(y) - hin[j]) / gscale(j);
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
  // Conflicting conditions show as a residual the solve cannot remove.
  double scale = 1e-300;
  for (int i = 0; i < m; ++i) scale = std::max(scale, std::abs(rhs[i]) + rows[i].cwiseAbs().sum() * y.cwiseAbs().maxCoeff());
  std::vector<std::string> bad;
  for (int i = 0; i < m; ++i)
    if (!std::isfinite(rows[i].dot(y)) || std::abs(rows[i].dot(y) - rhs[i]) > kFeasibleTol * scale) bad.push_back(names[i]);
  // The active-set loop may stop with an inequality still violated when the conditions need it.
  for (int j = 0; j < ni && bad.empty(); ++j)
    if ((gin[j].dot(y) - hin[j]) / gscale(j) > 1e-9) bad.push_back(gname[j]);
  if (!bad.empty()) {
    std::string list;
    for (const auto& s : names) list += (list.empty() ? "" : ", ") + s;
    if (!std::isnan(r.concave_from)) list += ", a concave shape below " + fmt(r.concave_from);
    if (upper_on || lower_on) list += std::string(", and ") + (upper_on ? "y <= " + fmt(r.y_upper) : "") +
                                 (upper_on && lower_on ? " / " : "") + (lower_on ? "y >= " + fmt(r.y_lower) : "");
    throw InfeasibleFormParameters(nm + ": the conditions " + list + " contradict each other on a curve with " +
                                   std::to_string(n) + " control points (not met: " + bad.front() + ")");
  }
  Eigen::MatrixXd P(n, 2);
  P.col(0) = a;
  P.col(1) = y;
  return NurbsCurve(p, U, P);
}

}  // namespace fairlines
