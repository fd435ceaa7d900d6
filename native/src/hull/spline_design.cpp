// Fairest spline functions meeting form parameters: see fairlines/spline_design.hpp.
//
// Notation: U the clamped knot vector (x in metres), p the degree, n the control points (the
// unknown coefficients); N a row of basis functions at one x, D the map from f's coefficients
// to those of f^(k); the QP minimises x' H x / 2 + g' x subject to E x = e and A x <= b.
#include "fairlines/spline_design.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include "fairlines/basis.hpp"
#include "fairlines/errors.hpp"
#include "fairlines/qp.hpp"
#include "nurbs/checks.hpp"
#include "nurbs/gauss.hpp"
#include "nurbs/gram.hpp"

namespace fairlines {

namespace {

using detail::fail;

/// Rows of a QP under construction, each with the name of the condition it encodes.
struct RowSet {
  std::vector<Eigen::RowVectorXd> rows;
  std::vector<double> rhs;
  std::vector<std::string> names;
  void add(Eigen::RowVectorXd r, double b, std::string name) {
    rows.push_back(std::move(r));
    rhs.push_back(b);
    names.push_back(std::move(name));
  }
  Eigen::MatrixXd matrix(int n) const {
    Eigen::MatrixXd M(static_cast<Eigen::Index>(rows.size()), n);
    for (std::size_t i = 0; i < rows.size(); ++i) M.row(static_cast<Eigen::Index>(i)) = rows[i];
    return M;
  }
  Eigen::VectorXd vector() const { return Eigen::Map<const Eigen::VectorXd>(rhs.data(), static_cast<Eigen::Index>(rhs.size())); }
};

/// Matrix D (n - k, n) mapping the coefficients of f to those of f^(k) (P&T eq. 3.8 applied k
/// times); row i of it belongs to the basis function of degree p - k on knots U[i + k ..].
Eigen::MatrixXd derivative_coefficients(const Eigen::VectorXd& U, int p, int k) {
  const int n = static_cast<int>(U.size()) - p - 1;
  Eigen::MatrixXd D = Eigen::MatrixXd::Identity(n, n);
  for (int d = 1; d <= k; ++d) {
    const int m = n - d, q = p - d + 1;  // from degree q to q - 1
    Eigen::MatrixXd step = Eigen::MatrixXd::Zero(m, m + 1);
    for (int i = 0; i < m; ++i) {
      const double h = U[i + d + q] - U[i + d];
      if (h > 0) step(i, i) = -q / h, step(i, i + 1) = q / h;
    }
    D = (step * D).eval();
  }
  return D;
}

/// Indices i in [0, count) whose support [U[i + shift], U[i + shift + order]] meets (from, to).
std::vector<int> touching(const Eigen::VectorXd& U, int count, int shift, int order, double from, double to) {
  std::vector<int> out;
  for (int i = 0; i < count; ++i)
    if (U[i + shift] < to && U[i + shift + order] > from) out.push_back(i);
  return out;
}

double eval_factors(const std::vector<NurbsCurve>& f, double x) {
  double w = 1.0;
  for (const NurbsCurve& c : f) w *= c.evaluate(x)[0];
  return w;
}

/// Visits the Gauss-Legendre nodes x and weights w of int_{from}^{to} for an integrand that is a
/// polynomial of degree <= `degree` between the values of `knot_vectors`: the knots inside
/// (from, to) split the range into pieces, each with degree / 2 + 1 points (exact to degree
/// 2 (degree / 2 + 1) - 1 >= degree), pieces from `from` upward.
template <class Visit>
void piecewise_gauss(double from, double to, const std::vector<const Eigen::VectorXd*>& knot_vectors, int degree,
                     Visit&& visit) {
  std::set<double> br{from, to};
  for (const Eigen::VectorXd* K : knot_vectors)
    for (Eigen::Index i = 0; i < K->size(); ++i)
      if ((*K)[i] > from && (*K)[i] < to) br.insert((*K)[i]);
  const auto& g = detail::gauss_rule(degree / 2 + 1);
  for (auto it = br.begin(); std::next(it) != br.end(); ++it) {
    const double a = *it, b = *std::next(it), h = 0.5 * (b - a), m = 0.5 * (a + b);
    for (std::size_t q = 0; q < g.x.size(); ++q) visit(m + h * g.x[q], g.w[q] * h);
  }
}

/// Row of int_{from}^{to} x^power N(x) w(x) dx, exact for the polynomial integrand.
Eigen::RowVectorXd integral_row(const Eigen::VectorXd& U, int p, const SplineIntegral& in, int power) {
  std::vector<const Eigen::VectorXd*> knots{&U};
  int deg = p + power;
  for (const NurbsCurve& c : in.factors) knots.push_back(&c.knots()), deg += c.degree();
  Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(U.size() - p - 1);
  piecewise_gauss(in.from, in.to, knots, deg, [&](double x, double w) {
    row += w * std::pow(x, power) * eval_factors(in.factors, x) * basis_row(U, p, x);
  });
  return row;
}

void check_request(const SplineDesignRequest& r) {
  const std::string& nm = r.name;
  if (r.degree < 2 || r.degree > 5) fail(nm, ": degree is ", r.degree, "; expected 2 to 5");
  const int p = r.degree;
  const Eigen::VectorXd& U = r.knots;
  if (U.size() < 2 * (p + 1)) fail(nm, ": ", U.size(), " knots; expected at least ", 2 * (p + 1), " (degree + 1 control points)");
  detail::require_finite(U, nm + ": knots");
  for (Eigen::Index i = 0; i + 1 < U.size(); ++i)
    if (U[i + 1] < U[i]) fail(nm, ": knots decrease at index ", i + 1, "; expected non-decreasing values");
  for (int i = 1; i <= p; ++i)
    if (U[i] != U[0] || U[U.size() - 1 - i] != U[U.size() - 1]) fail(nm, ": knots are not clamped; expected ", p + 1, " equal end knots");
  if (!(U[U.size() - 1] > U[0])) fail(nm, ": the knots span no range (", U[0], " to ", U[U.size() - 1], ")");
  if (!(r.e2 >= 0) || !(r.e3 >= 0) || !std::isfinite(r.e2 + r.e3)) fail(nm, ": e2 / e3 are ", r.e2, " / ", r.e3, "; expected finite weights >= 0");
  const double x0 = U[0], x1 = U[U.size() - 1], tol = 1e-9 * (x1 - x0);
  auto inside = [&](double x, const std::string& what) {
    if (!std::isfinite(x) || x < x0 - tol || x > x1 + tol) fail(nm, ": ", what, " x = ", x, "; expected ", x0, " <= x <= ", x1);
  };
  auto range = [&](double a, double b, const std::string& what) {
    inside(a, what), inside(b, what);
    if (!(b >= a)) fail(nm, ": ", what, " runs from ", a, " to ", b, "; expected from <= to");
  };
  for (const auto& c : r.conditions) {
    inside(c.x, c.name);
    if (c.derivative < 0 || c.derivative > std::min(3, p)) fail(nm, ": ", c.name, " asks derivative ", c.derivative, "; expected 0 to ", std::min(3, p));
    if (c.combination.size() > static_cast<std::size_t>(std::min(3, p) + 1))
      fail(nm, ": ", c.name, " combines ", c.combination.size(), " derivatives; expected at most ", std::min(3, p) + 1);
    for (double v : c.combination) detail::require_finite(v, nm + ": " + c.name + " combination");
    detail::require_finite(c.value, nm + ": " + c.name);
  }
  for (const auto& c : r.integrals) {
    range(c.from, c.to, c.name);
    if (c.power < 0 || c.power > 1) fail(nm, ": ", c.name, " power is ", c.power, "; expected 0 or 1");
    int degree = p + 1;  // the centroid's first moment
    for (const NurbsCurve& f : c.factors) {
      if (f.dim() != 1) fail(nm, ": ", c.name, " has a weight factor of dimension ", f.dim(), "; expected a function (dimension 1)");
      degree += f.degree();
    }
    if (degree > kMaxProductDegree) fail(nm, ": ", c.name, "'s integrand has degree ", degree, "; expected at most ", kMaxProductDegree);
  }
  for (const auto& c : r.flats) range(c.from, c.to, c.name), detail::require_finite(c.value, nm + ": " + c.name);
  for (const auto& c : r.bounds) range(c.from, c.to, c.name);
  for (const auto& c : r.shapes) {
    range(c.from, c.to, c.name);
    if (c.derivative < 1 || c.derivative > std::min(2, p - 1)) fail(nm, ": ", c.name, " constrains derivative ", c.derivative, "; expected 1 or 2");
    if (c.sign != 1 && c.sign != -1) fail(nm, ": ", c.name, " sign is ", c.sign, "; expected +1 or -1");
    if (!(c.margin >= 0) || !std::isfinite(c.margin)) fail(nm, ": ", c.name, " margin is ", c.margin, "; expected a finite value >= 0");
  }
  for (const auto& c : r.linear) range(c.from, c.to, c.name);
  for (const auto& f : r.fit) {
    inside(f.x, "fit point");
    if (!std::isfinite(f.y) || !(f.weight >= 0) || !std::isfinite(f.weight)) fail(nm, ": fit point (", f.x, ", ", f.y, ") weight ", f.weight, "; expected finite values, weight >= 0");
  }
}

/// The clamped knots of the request's spline function and what they span.
struct SplineSpace {
  const Eigen::VectorXd& U;
  int p, n;       ///< degree, control points
  double x0, x1;  ///< its range (metres)
  explicit SplineSpace(const SplineDesignRequest& r)
      : U(r.knots), p(r.degree), n(static_cast<int>(r.knots.size()) - r.degree - 1), x0(U[0]), x1(U[n + p]) {}
  Eigen::RowVectorXd unit(int i) const {
    Eigen::RowVectorXd e = Eigen::RowVectorXd::Zero(n);
    e[i] = 1.0;
    return e;
  }
};

/// H and g of the objective: e2 int (f - reference)''^2 + e3 h^2 int (f - reference)'''^2, the
/// fit points' squared distances and the linear terms, h the mean knot span.
QuadraticProgram objective(const SplineDesignRequest& r, const SplineSpace& s) {
  const double h = (s.x1 - s.x0) / std::max(1, s.n - s.p);
  QuadraticProgram qp;
  qp.H = 2.0 * r.e2 * detail::derivative_gram(s.U, s.p, 2);
  if (r.e3 > 0) qp.H += 2.0 * r.e3 * h * h * detail::derivative_gram(s.U, s.p, 3);
  qp.g = Eigen::VectorXd::Zero(s.n);
  if (r.reference.size() > 0) {  // the fairness terms only: H holds nothing else yet
    if (r.reference.size() != s.n) fail(r.name, ": reference has ", r.reference.size(), " coefficients; expected ", s.n, " (one per control point)");
    detail::require_finite(r.reference, r.name + ": reference");
    qp.g -= qp.H * r.reference;
  }
  for (const auto& f : r.fit) {
    const Eigen::RowVectorXd N = basis_row(s.U, s.p, std::clamp(f.x, s.x0, s.x1));
    qp.H += 2.0 * f.weight * N.transpose() * N;
    qp.g -= 2.0 * f.weight * f.y * N.transpose();
  }
  for (const auto& c : r.linear) qp.g += c.value * integral_row(s.U, s.p, c, c.power).transpose();
  return qp;
}

/// Equality rows: values and derivative combinations at points, integrals and centroids, and
/// the coefficients of the flat parts.
RowSet equality_rows(const SplineDesignRequest& r, const SplineSpace& s) {
  RowSet eq;
  for (const auto& c : r.conditions) {
    const double x = std::clamp(c.x, s.x0, s.x1);
    if (c.combination.empty()) {
      eq.add(basis_row(s.U, s.p, x, c.derivative), c.value, c.name);
      continue;
    }
    Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(s.n);
    for (std::size_t k = 0; k < c.combination.size(); ++k) row += c.combination[k] * basis_row(s.U, s.p, x, static_cast<int>(k));
    eq.add(row, c.value, c.name);
  }
  for (const auto& c : r.integrals) {
    if (std::isnan(c.centroid)) eq.add(integral_row(s.U, s.p, c, c.power), c.value, c.name);
    else eq.add(integral_row(s.U, s.p, c, 1) - c.centroid * integral_row(s.U, s.p, c, 0), 0.0, c.name);
  }
  for (const auto& c : r.flats)
    for (int i : touching(s.U, s.n, 0, s.p + 1, c.from, c.to)) eq.add(s.unit(i), c.value, c.name);
  return eq;
}

/// Inequality rows A x <= b: bounds on a value or on the coefficients over a range, and the
/// signs of the coefficients of f' or f''.
RowSet inequality_rows(const SplineDesignRequest& r, const SplineSpace& s) {
  RowSet in;
  for (const auto& c : r.bounds) {
    if (c.from == c.to) {  // a bound on the value at one point
      const Eigen::RowVectorXd N = basis_row(s.U, s.p, std::clamp(c.from, s.x0, s.x1));
      if (!std::isnan(c.upper)) in.add(N, c.upper, c.name);
      if (!std::isnan(c.lower)) in.add(-N, -c.lower, c.name);
      continue;
    }
    for (int i : touching(s.U, s.n, 0, s.p + 1, c.from, c.to)) {
      const Eigen::RowVectorXd e = s.unit(i);
      if (!std::isnan(c.upper)) in.add(e, c.upper, c.name);
      if (!std::isnan(c.lower)) in.add(-e, -c.lower, c.name);
    }
  }
  for (const auto& c : r.shapes) {
    const Eigen::MatrixXd D = derivative_coefficients(s.U, s.p, c.derivative);
    for (int i : touching(s.U, s.n - c.derivative, c.derivative, s.p + 1 - c.derivative, c.from, c.to))
      in.add(-c.sign * D.row(i), -c.margin, c.name);
  }
  return in;
}

/// InfeasibleFormParameters naming the conditions of the rows the QP found in conflict.
[[noreturn]] void throw_conflict(const std::string& name, const QpSolution& s, const RowSet& eq, const RowSet& in) {
  const auto n_eq = static_cast<int>(eq.rows.size());
  std::set<std::string> names;
  for (int k : s.conflict) names.insert(k < n_eq ? eq.names[k] : in.names[k - n_eq]);
  std::string list;
  for (const auto& nm : names) list += (list.empty() ? "" : ", ") + nm;
  throw InfeasibleFormParameters(name + ": the conditions " + list + " contradict each other");
}

}  // namespace

NurbsCurve design_spline_function(const SplineDesignRequest& r) {
  check_request(r);
  const SplineSpace space(r);
  QuadraticProgram qp = objective(r, space);
  const RowSet eq = equality_rows(r, space), in = inequality_rows(r, space);
  qp.E = eq.matrix(space.n);
  qp.e = eq.vector();
  qp.A = in.matrix(space.n);
  qp.b = in.vector();
  const QpSolution s = solve_qp(qp);
  if (s.status != QpStatus::Optimal) throw_conflict(r.name, s, eq, in);
  return NurbsCurve(space.p, space.U, s.x);
}

double spline_product_integral(const std::vector<NurbsCurve>& factors, double from, double to, int power) {
  const char* nm = "spline_product_integral";
  if (!std::isfinite(from) || !std::isfinite(to) || !(from <= to)) fail(nm, ": range ", from, " to ", to, "; expected finite from <= to");
  if (power < 0 || power > kMaxProductDegree) fail(nm, ": power is ", power, "; expected 0 to ", kMaxProductDegree);
  std::vector<const Eigen::VectorXd*> knots;
  int degree = power;
  for (std::size_t i = 0; i < factors.size(); ++i) {
    const NurbsCurve& f = factors[i];
    if (f.dim() != 1) fail(nm, ": factor ", i, " has dimension ", f.dim(), "; expected a function (dimension 1)");
    // A rational factor makes the integrand no polynomial: the Gauss rule would not be exact.
    if (f.is_rational()) fail(nm, ": factor ", i, " is rational; expected a non-rational spline function");
    const auto [x0, x1] = f.domain();
    const double tol = kDomainTolerance * std::max(1.0, std::abs(x0) + std::abs(x1));
    if (from < x0 - tol || to > x1 + tol) fail(nm, ": range ", from, " to ", to, " leaves factor ", i, "'s domain ", x0, " to ", x1);
    knots.push_back(&f.knots());
    degree += f.degree();
  }
  if (degree > kMaxProductDegree) fail(nm, ": the integrand has degree ", degree, "; expected at most ", kMaxProductDegree);
  double sum = 0.0;
  piecewise_gauss(from, to, knots, degree, [&](double x, double w) { sum += w * std::pow(x, power) * eval_factors(factors, x); });
  return sum;
}

Eigen::VectorXd spline_function_knots(double x0, double x1, const std::vector<double>& breaks, int spans, int degree,
                                      int min_piece_spans) {
  if (!(x1 > x0) || !std::isfinite(x0) || !std::isfinite(x1)) fail("spline knots: range ", x0, " to ", x1, "; expected finite x0 < x1");
  if (degree < 1) fail("spline knots: degree is ", degree, "; expected >= 1");
  if (min_piece_spans < 1 || spans > 100000) fail("spline knots: spans ", spans, " / min_piece_spans ", min_piece_spans, "; expected 1 .. 100000 / >= 1");
  std::vector<double> pts{x0};
  const double tol = 1e-9 * (x1 - x0);
  std::vector<double> b = breaks;
  std::sort(b.begin(), b.end());
  for (double x : b)
    if (x > pts.back() + tol && x < x1 - tol) pts.push_back(x);
  pts.push_back(x1);
  const int pieces = static_cast<int>(pts.size()) - 1;
  if (spans < pieces) spans = pieces;
  std::vector<double> knots(degree + 1, x0);
  for (int k = 0; k < pieces; ++k) {
    const double a = pts[k], c = pts[k + 1];
    const int m = std::max(min_piece_spans, static_cast<int>(std::lround(spans * (c - a) / (x1 - x0))));
    for (int j = 1; j <= m; ++j) knots.push_back(j == m ? c : a + (c - a) * j / m);
  }
  knots.pop_back();
  for (int i = 0; i <= degree; ++i) knots.push_back(x1);
  return Eigen::Map<Eigen::VectorXd>(knots.data(), static_cast<Eigen::Index>(knots.size()));
}

}  // namespace fairlines
