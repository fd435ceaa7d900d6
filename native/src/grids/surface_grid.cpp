// Arc length along curves, algebraic surface grids and grid control that keeps the surface.
//
// Notation: [u0, u1] x [v0, v1] the surface's domain; a_i, b_i the u-parameters of the i-th
// point on the boundaries v = v0 and v = v1, c_j, d_j the v-parameters on u = u0 and u = u1,
// all normalised to [0, 1] (primes dropped). Grid line i joins (a_i, 0) to (b_i, 1), line j
// joins (0, c_j) to (1, d_j); their crossing (U, V) solves U = a + V (b - a), V = c + U (d - c)
// (parametric transfinite interpolation, Thompson, Warsi & Mastin 1985, sec. 8.6).
#include <algorithm>
#include <cmath>

#include "fairlines/errors.hpp"
#include "fairlines/grids.hpp"
#include "nurbs/checks.hpp"
#include "nurbs/arc_length.hpp"

namespace fairlines {

namespace {

constexpr int kGaussPoints = 8;       ///< Gauss-Legendre points per piece of a knot span
constexpr int kPiecesPerSpan = 16;    ///< pieces per knot span of the arc-length table
constexpr double kDegenerate = 1e-9;  ///< a boundary shorter than this x the surface size is a pole
constexpr double kArcTol = 1e-12;     ///< arc-length inversion tolerance, relative to the curve's length
constexpr int kNewtonSteps = 50;      ///< most Newton (or bisection) steps of the inversion

double speed(const NurbsCurve& c, double t) { return c.derivatives(t, 1).row(1).norm(); }

detail::ArcTable arc_table(const NurbsCurve& c) {
  const auto [t0, t1] = c.domain();
  return detail::arc_table([&](double t) { return speed(c, t); }, c.knots(), t0, t1, kPiecesPerSpan, kGaussPoints);
}

double extent(const NurbsSurface& s) {
  const Eigen::MatrixXd& P = s.control_points();
  return (P.colwise().maxCoeff() - P.colwise().minCoeff()).norm();
}

/// parameters_at_arc_length() on a table built already.
Eigen::VectorXd parameters_on_table(const NurbsCurve& curve, const detail::ArcTable& a, const Eigen::VectorXd& s) {
  const double total = a.s.back(), tol = kArcTol * std::max(total, 1e-300);
  Eigen::VectorXd t(s.size());
  for (Eigen::Index k = 0; k < s.size(); ++k) {
    if (s[k] < -tol || s[k] > total + tol)
      detail::fail("s[", k, "] is ", s[k], " m; expected within [0, ", total, "] (the arc length)");
    if (k > 0 && s[k] < s[k - 1]) detail::fail("s[", k, "] is ", s[k], " m; expected increasing arc lengths");
    t[k] = detail::invert_arc([&](double x) { return speed(curve, x); }, a, s[k], kNewtonSteps, kGaussPoints, tol);
  }
  return t;
}

/// Parameters (normalised to [0, 1] over [lo, hi]) of `d` along a boundary curve, or empty
/// for a pole.
Eigen::VectorXd boundary(const NurbsCurve& c, const Distribution& d, double size) {
  const detail::ArcTable a = arc_table(c);
  const double len = a.s.back();
  if (len < kDegenerate * size) return {};
  const auto [t0, t1] = c.domain();
  return ((parameters_on_table(c, a, distribute(d, len)).array() - t0) / (t1 - t0)).matrix();
}

}  // namespace

Eigen::VectorXd parameters_at_arc_length(const NurbsCurve& curve, const Eigen::VectorXd& s) {
  detail::require_finite(s, "s");
  return parameters_on_table(curve, arc_table(curve), s);
}

StructuredGrid parameter_grid(const NurbsSurface& surface, const Eigen::VectorXd& us, const Eigen::VectorXd& vs) {
  const auto [u0, u1] = surface.domain_u();
  const auto [v0, v1] = surface.domain_v();
  auto check = [](const Eigen::VectorXd& p, double lo, double hi, const char* name) {
    detail::require_finite(p, name);
    if (p.size() < 2) detail::fail(name, " has ", p.size(), " values; expected >= 2");
    for (Eigen::Index k = 0; k < p.size(); ++k) {
      if (p[k] < lo || p[k] > hi) detail::fail(name, "[", k, "] is ", p[k], "; expected within [", lo, ", ", hi, "]");
      if (k > 0 && !(p[k] > p[k - 1])) detail::fail(name, "[", k, "] is ", p[k], "; expected increasing values");
    }
  };
  check(us, u0, u1, "us");
  check(vs, v0, v1, "vs");
  detail::require_result_size(3.0 * us.size() * vs.size(), "the grid");
  StructuredGrid r;
  r.ni = static_cast<int>(us.size());
  r.nj = static_cast<int>(vs.size());
  r.points = surface.evaluate_grid(us, vs);
  r.params.resize(r.ni * r.nj, 2);
  for (int i = 0; i < r.ni; ++i)
    for (int j = 0; j < r.nj; ++j) r.params.row(i * r.nj + j) << us[i], vs[j];
  return r;
}

StructuredGrid surface_grid(const NurbsSurface& surface, const Distribution& du, const Distribution& dv) {
  const auto [u0, u1] = surface.domain_u();
  const auto [v0, v1] = surface.domain_v();
  const double size = extent(surface);
  Eigen::VectorXd a = boundary(surface.iso_curve(Direction::V, v0), du, size);
  Eigen::VectorXd b = boundary(surface.iso_curve(Direction::V, v1), du, size);
  Eigen::VectorXd c = boundary(surface.iso_curve(Direction::U, u0), dv, size);
  Eigen::VectorXd d = boundary(surface.iso_curve(Direction::U, u1), dv, size);
  if (a.size() == 0) a = b;
  if (b.size() == 0) b = a;
  if (c.size() == 0) c = d;
  if (d.size() == 0) d = c;
  if (a.size() == 0 || c.size() == 0) detail::fail("the surface has two opposite degenerate boundaries; no grid");
  if (a.size() != b.size() || c.size() != d.size())  // Geometric with points = 0 on boundaries of unequal length
    detail::fail("the boundaries got ", a.size(), " and ", b.size(), " (u), ", c.size(), " and ", d.size(),
                 " (v) points; give Geometric a fixed number of points on a surface");
  StructuredGrid r;
  r.ni = static_cast<int>(a.size());
  r.nj = static_cast<int>(c.size());
  detail::require_result_size(3.0 * r.ni * r.nj, "the grid");
  Eigen::VectorXd pu(r.ni * r.nj), pv(r.ni * r.nj);
  for (int i = 0; i < r.ni; ++i)
    for (int j = 0; j < r.nj; ++j) {
      const double ba = b[i] - a[i], dc = d[j] - c[j];
      const double U = (a[i] + c[j] * ba) / (1.0 - dc * ba), V = c[j] + U * dc;
      pu[i * r.nj + j] = std::clamp(u0 + (u1 - u0) * U, u0, u1);
      pv[i * r.nj + j] = std::clamp(v0 + (v1 - v0) * V, v0, v1);
    }
  r.points = surface.evaluate(pu, pv);
  r.params.resize(r.ni * r.nj, 2);
  r.params.col(0) = pu;
  r.params.col(1) = pv;
  return r;
}

Eigen::VectorXd knot_line_parameters(const NurbsSurface& surface, Direction dir, int per_span) {
  if (per_span < 1 || per_span > 10000) detail::fail("per_span is ", per_span, "; expected 1 .. 10000");
  const Eigen::VectorXd& k = dir == Direction::U ? surface.knots_u() : surface.knots_v();
  const auto [lo, hi] = dir == Direction::U ? surface.domain_u() : surface.domain_v();
  std::vector<double> t{lo};
  for (Eigen::Index i = 0; i < k.size(); ++i)
    if (k[i] > t.back() && k[i] <= hi) {
      const double a = t.back();
      for (int p = 1; p <= per_span; ++p) t.push_back(a + (k[i] - a) * p / per_span);
    }
  return Eigen::Map<Eigen::VectorXd>(t.data(), static_cast<Eigen::Index>(t.size()));
}

NurbsSurface cluster_by_knots(const NurbsSurface& surface, Direction dir, double at, double spacing, int count,
                              double growth) {
  const auto [lo, hi] = dir == Direction::U ? surface.domain_u() : surface.domain_v();
  detail::require_finite(at, "at");
  if (at < lo || at > hi) detail::fail("at is ", at, "; expected within the domain [", lo, ", ", hi, "]");
  detail::require_positive(spacing, "spacing");
  if (!(growth >= 1.0) || !std::isfinite(growth)) detail::fail("growth is ", growth, "; expected a finite value >= 1");
  if (count < 1 || count > 1000) detail::fail("count is ", count, "; expected 1 .. 1000");
  const Eigen::VectorXd& k = dir == Direction::U ? surface.knots_u() : surface.knots_v();
  const double gap = 1e-9 * (hi - lo);  // closer to an existing knot than this: skipped
  std::vector<double> add;
  auto take = [&](double x) {
    if (x <= lo + gap || x >= hi - gap || static_cast<int>(add.size()) >= count) return;
    for (Eigen::Index i = 0; i < k.size(); ++i)
      if (std::abs(k[i] - x) < gap) return;
    add.push_back(x);
  };
  take(at);
  double off = 0.0, step = spacing;
  for (int it = 0; static_cast<int>(add.size()) < count && it < 4 * count + 8; ++it, step *= growth) {
    off += step;
    take(at - off);
    take(at + off);
  }
  std::sort(add.begin(), add.end());
  if (add.empty()) return surface;
  return surface.refine_knots(dir, Eigen::Map<Eigen::VectorXd>(add.data(), static_cast<Eigen::Index>(add.size())));
}

NurbsSurface cluster_by_weights(const NurbsSurface& surface, Direction dir, double ratio) {
  if (!(ratio >= 1e-3 && ratio <= 1e3)) detail::fail("ratio is ", ratio, "; expected within [0.001, 1000]");
  const double r = std::sqrt(ratio);
  const bool in_u = dir == Direction::U;
  const int p = in_u ? surface.degree_u() : surface.degree_v();
  const auto [lo, hi] = in_u ? surface.domain_u() : surface.domain_v();
  Eigen::VectorXd k = in_u ? surface.knots_u() : surface.knots_v();
  Eigen::VectorXd sigma(k.size());  // new knots, normalised: sigma = r t / (1 - t + r t)
  for (Eigen::Index i = 0; i < k.size(); ++i) {
    const double t = (k[i] - lo) / (hi - lo), den = 1.0 - t + r * t;  // t outside [0, 1]: unclamped ends
    if (!(den > 0.0)) detail::fail("ratio is ", ratio, "; too strong for this surface's unclamped knots");
    sigma[i] = r * t / den;
    k[i] = lo + (hi - lo) * sigma[i];
  }
  Eigen::MatrixXd pw = surface.homogeneous();
  const int n = in_u ? surface.nu() : surface.nv(), nv = surface.nv();
  for (int i = 0; i < n; ++i) {
    double lambda = 1.0;
    for (int q = 1; q <= p; ++q) lambda *= r + (1.0 - r) * sigma[i + q];
    if (in_u) pw.middleRows(static_cast<Eigen::Index>(i) * nv, nv) *= lambda;
    else
      for (int a = 0; a < surface.nu(); ++a) pw.row(static_cast<Eigen::Index>(a) * nv + i) *= lambda;
  }
  return NurbsSurface::from_homogeneous(surface.degree_u(), surface.degree_v(), in_u ? k : surface.knots_u(),
                                        in_u ? surface.knots_v() : k, surface.nu(), surface.nv(), pw);
}

}  // namespace fairlines
