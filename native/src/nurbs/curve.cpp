#include "fairlines/curve.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

#include "checks.hpp"
#include "knot_refinement.hpp"
#include "fairlines/basis.hpp"
#include "fairlines/knots.hpp"
#include "homogeneous.hpp"

namespace fairlines {

using detail::fail;

namespace {

/// Least of f on [a, b] by golden-section search (f unimodal there), in `steps` steps.
template <typename F>
double golden_minimum(F f, double a, double b, int steps) {
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double x1 = b - g * (b - a), x2 = a + g * (b - a), f1 = f(x1), f2 = f(x2);
  for (int it = 0; it < steps && b - a > 0.0; ++it) {
    if (f1 <= f2) b = x2, x2 = x1, f2 = f1, x1 = b - g * (b - a), f1 = f(x1);
    else a = x1, x1 = x2, f1 = f2, x2 = a + g * (b - a), f2 = f(x2);
  }
  return f1 <= f2 ? x1 : x2;
}

double binomial(int n, int k) {
  double r = 1.0;
  for (int i = 1; i <= k; ++i) r = r * (n - k + i) / i;
  return r;
}

// Sorted (knot, multiplicity) pairs of a knot vector.
std::vector<std::pair<double, int>> knot_multiplicities(const Eigen::VectorXd& U) {
  std::vector<std::pair<double, int>> out;
  for (Eigen::Index i = 0; i < U.size(); ++i) {
    if (!out.empty() && out.back().first == U[i])
      ++out.back().second;
    else
      out.emplace_back(U[i], 1);
  }
  return out;
}

}  // namespace

NurbsCurve::NurbsCurve(int degree, Eigen::VectorXd knots, Eigen::MatrixXd control_points,
                       Eigen::VectorXd weights)
    : degree_(degree), knots_(std::move(knots)), points_(std::move(control_points)), weights_(std::move(weights)) {
  detail::require_degree(degree_);
  if (points_.rows() == 0 || points_.cols() == 0)
    fail("control_points is empty (", points_.rows(), " x ", points_.cols(), "); expected an n x dim array");
  detail::require_finite(points_, "control_points");
  validate_knots(knots_, degree_, static_cast<int>(points_.rows()));
  weights_ = detail::weights_or_ones(std::move(weights_), points_.rows());
  refresh();
}

void NurbsCurve::refresh() {
  rational_ = (weights_.array() != 1.0).any();
  detail::pack_homogeneous(points_, weights_, pw_);
}

std::pair<double, double> NurbsCurve::domain() const {
  return {knots_[degree_], knots_[n_control()]};
}

Eigen::VectorXd NurbsCurve::evaluate(double t) const {
  Eigen::VectorXd one(1);
  one[0] = t;
  return evaluate(one).row(0).transpose();
}

Eigen::MatrixXd NurbsCurve::evaluate(const Eigen::VectorXd& t) const {
  detail::require_finite(t, "t");
  const int p = degree_, d = dim(), nk = static_cast<int>(knots_.size());
  const auto [a, b] = domain();
  Eigen::MatrixXd out(t.size(), d);
  std::vector<double> N(p + 1);
  std::vector<double> acc(d + 1);
  for (Eigen::Index k = 0; k < t.size(); ++k) {
    const double tk = std::clamp(t[k], a, b);
    const int span = find_span(p, knots_.data(), nk, tk);
    basis_functions(span, tk, p, knots_.data(), N.data());
    std::fill(acc.begin(), acc.end(), 0.0);
    for (int j = 0; j <= p; ++j) {
      const double* P = &pw_[static_cast<size_t>(span - p + j) * (d + 1)];
      for (int c = 0; c <= d; ++c) acc[c] += N[j] * P[c];
    }
    for (int c = 0; c < d; ++c) out(k, c) = acc[c] / acc[d];
  }
  return out;
}

Eigen::MatrixXd NurbsCurve::derivatives(double t, int order) const {
  detail::require_order(order);
  detail::require_finite(t, "t");
  const int p = degree_, d = dim();
  const auto [a, b] = domain();
  const double tc = std::clamp(t, a, b);
  const int span = find_span(p, knots_, tc);
  Eigen::MatrixXd nders(order + 1, p + 1);
  basis_derivatives(span, tc, p, order, knots_, nders);
  // Homogeneous derivatives, then the quotient rule (P&T A4.2).
  Eigen::MatrixXd hw = Eigen::MatrixXd::Zero(order + 1, d + 1);
  for (int k = 0; k <= order; ++k)
    for (int j = 0; j <= p; ++j) {
      const double* P = &pw_[static_cast<size_t>(span - p + j) * (d + 1)];
      for (int c = 0; c <= d; ++c) hw(k, c) += nders(k, j) * P[c];
    }
  Eigen::MatrixXd ck(order + 1, d);
  for (int k = 0; k <= order; ++k) {
    Eigen::RowVectorXd v = hw.row(k).head(d);
    for (int i = 1; i <= k; ++i) v -= binomial(k, i) * hw(i, d) * ck.row(k - i);
    ck.row(k) = v / hw(0, d);
  }
  return ck;
}

Eigen::MatrixXd NurbsCurve::derivatives(const Eigen::VectorXd& t, int order) const {
  detail::require_order(order);
  detail::require_result_size(static_cast<double>(t.size()) * (order + 1) * dim(), "derivatives");
  Eigen::MatrixXd out(t.size() * (order + 1), dim());
  for (Eigen::Index k = 0; k < t.size(); ++k) out.middleRows(k * (order + 1), order + 1) = derivatives(t[k], order);
  return out;
}

Eigen::VectorXd NurbsCurve::curvature(const Eigen::VectorXd& t) const {
  if (dim() < 2) fail("curvature needs a curve of dimension 2 or 3; this one has dimension ", dim());
  Eigen::VectorXd k(t.size());
  for (Eigen::Index i = 0; i < t.size(); ++i) {
    const Eigen::MatrixXd D = derivatives(t[i], 2);
    const double speed = D.row(1).norm();
    if (!(speed > 0.0)) fail("curvature is undefined at t = ", t[i], ": the curve has zero speed there");
    if (dim() == 2) {
      k[i] = (D(1, 0) * D(2, 1) - D(1, 1) * D(2, 0)) / (speed * speed * speed);
    } else {
      Eigen::Vector3d d1 = Eigen::Vector3d::Zero(), d2 = Eigen::Vector3d::Zero();
      d1.head(std::min(3, dim())) = D.row(1).head(std::min(3, dim())).transpose();
      d2.head(std::min(3, dim())) = D.row(2).head(std::min(3, dim())).transpose();
      k[i] = d1.cross(d2).norm() / (speed * speed * speed);
    }
  }
  return k;
}

Eigen::VectorXd NurbsCurve::torsion(const Eigen::VectorXd& t) const {
  if (dim() != 3) fail("torsion needs a 3-D curve; this one has dimension ", dim());
  Eigen::VectorXd tau(t.size());
  for (Eigen::Index i = 0; i < t.size(); ++i) {
    const Eigen::MatrixXd D = derivatives(t[i], 3);
    const Eigen::Vector3d d1 = D.row(1).transpose(), d2 = D.row(2).transpose(), d3 = D.row(3).transpose();
    const Eigen::Vector3d c = d1.cross(d2);
    const double c2 = c.squaredNorm();
    // Below this relative size the curve is locally straight and torsion is undefined.
    constexpr double kStraight = 1e-24;
    tau[i] = (c2 > kStraight * std::pow(d1.squaredNorm(), 3)) ? c.dot(d3) / c2 : 0.0;
  }
  return tau;
}

// Newton steps from each start; the search stays within the start's knot span.
constexpr int kClosestNewtonSteps = 50;
// Golden-section steps on the bracket of the nearest sample in each span.
constexpr int kClosestGoldenSteps = 80;
// Relative distance^2 difference below which two answers are the same point up to round-off.
constexpr double kClosestTieRelative = 1e-12;

std::pair<double, Eigen::VectorXd> NurbsCurve::closest_point(const Eigen::VectorXd& p) const {
  if (p.size() != dim()) fail("point has ", p.size(), " coordinates; expected ", dim());
  detail::require_finite(p, "point");
  // Every non-empty knot span is searched from its samples' local minima, and the search stays in the
  // span: across a knot the curve may turn (a C0 corner of a degree-1 or repeated-knot curve),
  // and a rational curve's samples may bunch so that another span's samples all lie nearer.
  const int per_span = 4 * (degree_ + 1);
  const double scale = std::max(1.0, (points_.colwise().maxCoeff() - points_.colwise().minCoeff()).norm());
  auto dist2 = [&](double t) { return (evaluate(t) - p).squaredNorm(); };
  // Newton on the distance's slope from `t`, kept within [lo, hi].
  auto newton = [&](double t, double lo, double hi) {
    for (int it = 0; it < kClosestNewtonSteps; ++it) {
      const Eigen::MatrixXd D = derivatives(t, 2);
      const Eigen::VectorXd r = D.row(0).transpose() - p;
      const double f = D.row(1).dot(r);
      const double df = D.row(2).dot(r) + D.row(1).squaredNorm();
      if (!(df > 0.0)) break;  // negative curvature of the distance: keep the start
      const double tn = std::clamp(t - f / df, lo, hi);
      const double step = std::abs(tn - t) * D.row(1).norm();
      t = tn;
      // Converged when the step moves the point by less than this relative tolerance.
      if (step < 1e-15 * scale) break;
    }
    return t;
  };
  double best_t = domain().first, best_d = dist2(best_t);
  for (int i = degree_; i < n_control(); ++i) {
    const double lo = knots_[i], hi = knots_[i + 1];
    if (hi <= lo) continue;
    const Eigen::VectorXd tv = Eigen::VectorXd::LinSpaced(per_span + 1, lo, hi);
    const Eigen::MatrixXd pts = evaluate(tv);
    const Eigen::VectorXd pts_d2 = (pts.rowwise() - p.transpose()).rowwise().squaredNorm();
    // Every sample nearer than its neighbours starts a search: a span may hold two local minima
    // of nearly the same distance, and the nearest sample may lie in the worse one's basin (a
    // rational quintic: 4.413 m found against 4.407 m).
    for (Eigen::Index k = 0; k <= per_span; ++k) {
      if ((k > 0 && pts_d2[k] > pts_d2[k - 1]) || (k < per_span && pts_d2[k] > pts_d2[k + 1])) continue;
      // Newton from the sample may stall, oscillate or stop on the span's end where it was
      // clamped: Newton also polishes the golden-section minimum of the samples' bracket around
      // it, and the nearer of the two answers is kept.
      const double tg = golden_minimum(dist2, tv[std::max<Eigen::Index>(k - 1, 0)],
                                       tv[std::min<Eigen::Index>(k + 1, per_span)], kClosestGoldenSteps);
      for (const double start : {tv[k], tg}) {
        const double t = newton(start, lo, hi);
        const double d = dist2(t);
        if (d < best_d) best_d = d, best_t = t;
      }
      // Where Newton wandered off from both starts, the bracket's own minimum (to within the
      // golden search's resolution) is kept; a mere round-off difference does not replace Newton's.
      const double dg = dist2(tg);
      if (dg < best_d * (1.0 - kClosestTieRelative)) best_d = dg, best_t = tg;
    }
  }
  return {best_t, evaluate(best_t)};
}

Eigen::MatrixXd NurbsCurve::homogeneous() const {
  const int d = dim();
  Eigen::MatrixXd pw(n_control(), d + 1);
  for (int i = 0; i < n_control(); ++i)
    for (int c = 0; c <= d; ++c) pw(i, c) = pw_[static_cast<size_t>(i) * (d + 1) + c];
  return pw;
}

NurbsCurve NurbsCurve::from_homogeneous(int degree, Eigen::VectorXd knots, const Eigen::MatrixXd& pw) {
  const Eigen::Index d = pw.cols() - 1;
  Eigen::VectorXd w = pw.col(d);
  for (Eigen::Index i = 0; i < w.size(); ++i)
    if (!(w[i] > 0.0)) fail("homogeneous weight ", i, " is ", w[i], "; expected > 0");
  Eigen::MatrixXd P = pw.leftCols(d).array().colwise() / w.array();
  return NurbsCurve(degree, std::move(knots), std::move(P), std::move(w));
}

NurbsCurve NurbsCurve::insert_knot(double t, int times) const {
  detail::require_times(times);
  detail::require_finite(t, "t");
  const auto [a, b] = domain();
  if (t < a || t > b) fail("knot t = ", t, " lies outside the domain [", a, ", ", b, "]");
  int mult = 0;
  for (Eigen::Index i = 0; i < knots_.size(); ++i) mult += (knots_[i] == t);
  // times is compared with the room left (not mult + times) so a huge count cannot overflow.
  if (times > degree_ + ((t == a || t == b) ? 1 : 0) - mult)
    fail("inserting knot ", t, " ", times, " time(s) raises its multiplicity from ", mult, " to ",
         static_cast<long long>(mult) + times,
         "; expected at most the degree ", degree_);
  Eigen::VectorXd X = Eigen::VectorXd::Constant(times, t);
  return refine_knots(X);
}

NurbsCurve NurbsCurve::refine_knots(const Eigen::VectorXd& X_in) const {
  if (X_in.size() == 0) return *this;
  detail::require_finite(X_in, "new_knots");
  Eigen::VectorXd X = X_in;
  std::sort(X.data(), X.data() + X.size());
  const auto [a0, b0] = domain();
  if (X[0] < a0 || X[X.size() - 1] > b0)
    fail("new_knots span [", X[0], ", ", X[X.size() - 1], "] outside the domain [", a0, ", ", b0, "]");
  auto [Qw, Ubar] = detail::refine_rows(degree_, knots_, X, homogeneous());
  return from_homogeneous(degree_, std::move(Ubar), Qw);
}

NurbsCurve NurbsCurve::split_range(double a, double b) const {
  detail::require_finite(a, "a");
  detail::require_finite(b, "b");
  const auto [lo, hi] = domain();
  if (!(a >= lo && b <= hi && a < b)) fail("range [", a, ", ", b, "] is not inside the domain [", lo, ", ", hi, "] or is empty");
  const int p = degree_;
  auto mult_of = [](const Eigen::VectorXd& U, double x) {
    int m = 0;
    for (Eigen::Index i = 0; i < U.size(); ++i) m += (U[i] == x);
    return m;
  };
  std::vector<double> ins;
  for (int k = mult_of(knots_, a); k < p; ++k) ins.push_back(a);
  for (int k = mult_of(knots_, b); k < p; ++k) ins.push_back(b);
  const NurbsCurve c = ins.empty() ? *this : refine_knots(Eigen::Map<Eigen::VectorXd>(ins.data(), static_cast<Eigen::Index>(ins.size())));
  const Eigen::VectorXd& U = c.knots_;
  int r = 0;
  while (r + 1 < U.size() && U[r + 1] <= a) ++r;  // last index with U[r] == a
  int s = 0;
  while (U[s] < b) ++s;                            // first index with U[s] == b
  const int first = r - p, last = s - 1;
  Eigen::VectorXd K(last - first + 1 + p + 1);
  for (int i = 0; i <= p; ++i) {
    K[i] = a;
    K[K.size() - 1 - i] = b;
  }
  for (int i = r + 1; i < s; ++i) K[p + 1 + (i - r - 1)] = U[i];
  const Eigen::MatrixXd pw = c.homogeneous().middleRows(first, last - first + 1);
  return from_homogeneous(p, K, pw);
}

NurbsCurve NurbsCurve::elevate_degree(int times) const {
  detail::require_times(times);
  if (times > limits::kMaxDegree - degree_)
    fail("times is ", times, ": degree ", degree_, " + ", times, " exceeds the degree limit ", limits::kMaxDegree,
         "; expected times <= ", limits::kMaxDegree - degree_);
  // Work on the clamped representation of the domain so both ends are interpolatory.
  const auto [a, b] = domain();
  const NurbsCurve c = split_range(a, b);
  const int p = c.degree_ + times;
  std::vector<double> K;
  for (const auto& [value, mult] : knot_multiplicities(c.knots_))
    for (int k = 0; k < mult + times; ++k) K.push_back(value);
  Eigen::VectorXd U = Eigen::Map<Eigen::VectorXd>(K.data(), static_cast<Eigen::Index>(K.size()));
  const int n = static_cast<int>(U.size()) - p - 1;
  // The old homogeneous curve lies in the new spline space; collocation at the Greville
  // abscissae (Schoenberg-Whitney holds) recovers its coefficients exactly.
  const Eigen::VectorXd g = greville_abscissae(U, p);
  const Eigen::MatrixXd Pw = c.homogeneous();
  const NurbsCurve hom(c.degree_, c.knots_, Pw);  // polynomial curve in R^{d+1}
  const Eigen::MatrixXd rhs = hom.evaluate(g);
  // The collocation matrix is banded (p + 1 entries a row): a sparse factorization keeps
  // the work and memory linear in the number of control points.
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<size_t>(n) * (p + 1));
  std::vector<double> N(p + 1);
  for (int i = 0; i < n; ++i) {
    const int span = find_span(p, U, g[i]);
    basis_functions(span, g[i], p, U, N.data());
    for (int j = 0; j <= p; ++j)
      if (N[j] != 0.0) entries.emplace_back(i, span - p + j, N[j]);
  }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(entries.begin(), entries.end());
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(A);
  if (lu.info() != Eigen::Success) fail("degree elevation: the collocation matrix is singular");
  const Eigen::MatrixXd Qw = lu.solve(rhs);
  return from_homogeneous(p, U, Qw);
}

void NurbsCurve::set_control_point(int i, const Eigen::VectorXd& p) {
  if (i < 0 || i >= n_control()) fail("control point index ", i, " is out of range [0, ", n_control() - 1, "]");
  if (p.size() != dim()) fail("control point has ", p.size(), " coordinates; expected ", dim());
  detail::require_finite(p, "control point");
  points_.row(i) = p.transpose();
  refresh();
}

void NurbsCurve::set_weight(int i, double w) {
  if (i < 0 || i >= n_control()) fail("weight index ", i, " is out of range [0, ", n_control() - 1, "]");
  if (!(w > 0.0) || !std::isfinite(w)) fail("weight is ", w, "; expected a finite value > 0");
  weights_[i] = w;
  refresh();
}

}  // namespace fairlines
