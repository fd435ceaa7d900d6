#include "fairlines/knots.hpp"

#include <cmath>

#include "checks.hpp"

namespace fairlines {

using detail::fail;

Parameterization parse_parameterization(const std::string& name) {
  if (name == "uniform") return Parameterization::Uniform;
  if (name == "chord" || name == "chord_length") return Parameterization::ChordLength;
  if (name == "centripetal") return Parameterization::Centripetal;
  fail("parameterization is '", name, "'; expected 'chord', 'centripetal' or 'uniform'");
}

KnotMethod parse_knot_method(const std::string& name) {
  if (name == "average" || name == "averaging") return KnotMethod::Average;
  if (name == "hartley_judd") return KnotMethod::HartleyJudd;
  fail("knots is '", name, "'; expected 'average' or 'hartley_judd'");
}

std::string parameterization_name(Parameterization method) {
  switch (method) {
    case Parameterization::Uniform: return "uniform";
    case Parameterization::Centripetal: return "centripetal";
    default: return "chord";
  }
}

std::string knot_method_name(KnotMethod method) {
  return method == KnotMethod::HartleyJudd ? "hartley_judd" : "average";
}

void validate_knots(const Eigen::VectorXd& U, int p, int n, const std::string& what) {
  detail::require_degree(p);
  if (n < p + 1) fail("control point count is ", n, "; a degree-", p, " B-spline needs at least ", p + 1);
  const Eigen::Index expected = static_cast<Eigen::Index>(n) + p + 1;
  if (U.size() != expected)
    fail(what, " has ", U.size(), " values; expected ", expected, " (control points ", n,
         " + degree ", p, " + 1)");
  detail::require_finite(U, what);
  for (Eigen::Index i = 1; i < U.size(); ++i)
    if (U[i] < U[i - 1])
      fail(what, " decrease at index ", i, " (", U[i - 1], " > ", U[i], "); expected non-decreasing values");
  if (!(U[n] > U[p]))
    fail(what, " give an empty domain [", U[p], ", ", U[n], "]; expected knots[degree] < knots[n_control]");
  // Interior knots of multiplicity above the degree would disconnect the curve.
  for (Eigen::Index i = p + 1; i < n;) {
    Eigen::Index j = i;
    while (j + 1 < U.size() && U[j + 1] == U[i]) ++j;
    const Eigen::Index mult = j - i + 1;
    if (U[i] > U[p] && U[i] < U[n] && mult > p)
      fail(what, " value ", U[i], " has multiplicity ", mult, " inside the domain; expected at most the degree ", p);
    i = j + 1;
  }
}

namespace {

/// The arguments of a uniform knot vector: n control points of degree p over [t0, t1].
void require_uniform_knot_request(int n, int p, double t0, double t1) {
  detail::require_degree(p);
  if (n < p + 1) fail("control point count is ", n, "; a degree-", p, " B-spline needs at least ", p + 1);
  if (n > limits::kMaxControlPoints)
    fail("control point count is ", n, "; the limit is ", limits::kMaxControlPoints, " per direction");
  detail::require_finite(t0, "t0");
  detail::require_finite(t1, "t1");
  if (!(t1 > t0)) fail("knot range [", t0, ", ", t1, "] is empty; expected t0 < t1");
}

}  // namespace

Eigen::VectorXd clamped_uniform_knots(int n, int p, double t0, double t1) {
  require_uniform_knot_request(n, p, t0, t1);
  Eigen::VectorXd U(n + p + 1);
  const int segments = n - p;
  for (int i = 0; i <= p; ++i) {
    U[i] = t0;
    U[n + i] = t1;
  }
  for (int i = 1; i < segments; ++i) U[p + i] = t0 + (t1 - t0) * i / segments;
  return U;
}

Eigen::VectorXd unclamped_uniform_knots(int n, int p, double t0, double t1) {
  require_uniform_knot_request(n, p, t0, t1);
  Eigen::VectorXd U(n + p + 1);
  const double h = (t1 - t0) / (n - p);
  for (int i = 0; i < n + p + 1; ++i) U[i] = t0 + (i - p) * h;
  return U;
}

Eigen::VectorXd parameterize(const Eigen::MatrixXd& P, Parameterization method) {
  const Eigen::Index m = P.rows();
  if (m < 2) fail("points has ", m, " rows; expected at least 2");
  detail::require_finite(P, "points");
  Eigen::VectorXd u(m);
  u[0] = 0.0;
  for (Eigen::Index i = 1; i < m; ++i) {
    double d = 1.0;
    if (method != Parameterization::Uniform) {
      d = (P.row(i) - P.row(i - 1)).norm();
      if (d == 0.0) fail("points ", i - 1, " and ", i, " coincide; chord and centripetal parameterization need distinct consecutive points");
      if (method == Parameterization::Centripetal) d = std::sqrt(d);
    }
    u[i] = u[i - 1] + d;
  }
  u /= u[m - 1];
  u[m - 1] = 1.0;
  return u;
}

Eigen::VectorXd averaged_knots(const Eigen::VectorXd& u, int p, int n) {
  const Eigen::Index m = u.size();
  detail::require_degree(p);
  if (n < p + 1) fail("n_control is ", n, "; expected at least degree + 1 = ", p + 1);
  if (n > m) fail("n_control is ", n, "; expected at most the number of points ", m);
  Eigen::VectorXd U(n + p + 1);
  for (int i = 0; i <= p; ++i) {
    U[i] = 0.0;
    U[n + i] = 1.0;
  }
  if (n == m) {
    for (int j = 1; j < n - p; ++j) U[j + p] = u.segment(j, p).sum() / p;
  } else {
    // P&T eq. 9.69: every interior knot lies between data parameters, so each span holds data.
    const double d = static_cast<double>(m) / (n - p);
    for (int j = 1; j < n - p; ++j) {
      const int i = static_cast<int>(j * d);
      const double alpha = j * d - i;
      U[p + j] = (1.0 - alpha) * u[i - 1] + alpha * u[i];
    }
  }
  return U;
}

Eigen::VectorXd hartley_judd_knots(const Eigen::MatrixXd& P, int p, int n, Parameterization metric) {
  const Eigen::Index m = P.rows();
  detail::require_degree(p);
  if (n < p + 1) fail("n_control is ", n, "; expected at least degree + 1 = ", p + 1);
  if (n > m) fail("n_control is ", n, "; expected at most the number of points ", m);
  // Chord lengths of the data polygon, resampled to n - 1 chords of n virtual points
  // when approximating (n < m): the virtual points are equally spaced in data index.
  const Eigen::VectorXd cum = [&] {
    Eigen::VectorXd c(m);
    c[0] = 0.0;
    for (Eigen::Index i = 1; i < m; ++i) {
      const double d = (P.row(i) - P.row(i - 1)).norm();
      c[i] = c[i - 1] + (metric == Parameterization::Uniform ? 1.0 : metric == Parameterization::Centripetal ? std::sqrt(d) : d);
    }
    return c;
  }();
  if (!(cum[m - 1] > 0.0)) fail("points all coincide; Hartley-Judd knots need a polygon of positive length");
  auto cum_at = [&](double x) {  // cumulative length at fractional data index x
    const Eigen::Index i = std::min<Eigen::Index>(static_cast<Eigen::Index>(x), m - 2);
    const double a = x - static_cast<double>(i);
    return (1.0 - a) * cum[i] + a * cum[i + 1];
  };
  Eigen::VectorXd d(n - 1);
  for (int j = 0; j < n - 1; ++j) {
    const double x0 = static_cast<double>(j) * (m - 1) / (n - 1);
    const double x1 = static_cast<double>(j + 1) * (m - 1) / (n - 1);
    d[j] = cum_at(x1) - cum_at(x0);
  }
  // Spacing of knot interval i (i = p+1 .. n) is the sum of p consecutive chords.
  Eigen::VectorXd s(n - p);
  for (int i = 0; i < n - p; ++i) s[i] = d.segment(i, p).sum();
  if (!(s.sum() > 0.0)) fail("points give zero-length chords; Hartley-Judd knots need distinct points");
  Eigen::VectorXd U(n + p + 1);
  for (int i = 0; i <= p; ++i) {
    U[i] = 0.0;
    U[n + i] = 1.0;
  }
  double acc = 0.0;
  const double total = s.sum();
  for (int i = 1; i < n - p; ++i) {
    acc += s[i - 1];
    U[p + i] = acc / total;
  }
  return U;
}

Eigen::VectorXd greville_abscissae(const Eigen::VectorXd& U, int p) {
  const Eigen::Index n = U.size() - p - 1;
  Eigen::VectorXd g(n);
  for (Eigen::Index i = 0; i < n; ++i) g[i] = U.segment(i + 1, p).sum() / p;
  return g;
}

}  // namespace fairlines
