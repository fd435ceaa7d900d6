// Point distributions along a line of given length (Thompson, Warsi & Mastin 1985, ch. 8;
// Vinokur 1983 for the two-sided tanh).
//
// Notation: N points, xi = k / (N - 1), h = 1 / (N - 1); x(xi) in [0, 1] the normalised
// position; d0, d1 the first and last spacings divided by the length. Every stretching
// parameter is solved so that the DISCRETE end spacings x(h) - x(0) and x(1) - x(1 - h) are
// met, not the end slopes (the slope form misses them by several per cent at strong stretching).
#include <cmath>
#include <functional>
#include <numbers>

#include <Eigen/Dense>

#include "fairlines/errors.hpp"
#include "fairlines/grids.hpp"
#include "nurbs/checks.hpp"

namespace fairlines {

namespace {

constexpr double kSolveTol = 1e-13;      ///< relative tolerance of the stretching-parameter solves
constexpr int kBisections = 200;         ///< bisection steps (each halves the bracket)
constexpr int kMaxGeometricPoints = 100000;
constexpr int kNewtonIterations = 60;

[[noreturn]] void infeasible(const std::string& msg) { throw InfeasibleFormParameters(msg); }

/// Root of a function decreasing in b on (lo, hi) by bisection on log b.
double bisect_decreasing(const std::function<double(double)>& f, double target, double lo, double hi) {
  for (int it = 0; it < kBisections && hi - lo > kSolveTol * hi; ++it) {
    const double mid = std::sqrt(lo * hi);
    (f(mid) > target ? lo : hi) = mid;
  }
  return std::sqrt(lo * hi);
}

/// sinh(b x) / sinh(b) without overflow.
double sinh_ratio(double b, double x) {
  return std::exp(b * (x - 1.0)) * (-std::expm1(-2.0 * b * x)) / (-std::expm1(-2.0 * b));
}

/// One-sided stretching clustered at xi = 0 with first spacing d0 (< h).
Eigen::VectorXd one_sided(Spacing kind, int n, double d0) {
  const double h = 1.0 / (n - 1);
  auto x = [kind](double b, double xi) {
    return kind == Spacing::Sinh ? sinh_ratio(b, xi) : 1.0 + std::tanh(b * (xi - 1.0)) / std::tanh(b);
  };
  // x(h) falls from h (b -> 0) to 0 (b -> infinity); x(h) ~ exp(-b (1 - h)) for large b.
  const double hi = std::min(700.0, (-std::log(d0) + 10.0) / (1.0 - h));
  const double b = bisect_decreasing([&](double bb) { return x(bb, h); }, d0, 1e-8, hi);
  Eigen::VectorXd r(n);
  for (int k = 0; k < n; ++k) r[k] = x(b, k * h);
  r[0] = 0.0;
  r[n - 1] = 1.0;
  return r;
}

/// Vinokur's two-sided map with shape c (c > 0: tanh, c < 0: tan, c = 0: linear) and A.
double vinokur(double c, double a, double xi) {
  double u = xi;
  if (c > 1e-8) u = 0.5 * (1.0 + std::tanh(c * (xi - 0.5)) / std::tanh(0.5 * c));
  else if (c < -1e-8) u = 0.5 * (1.0 + std::tan(-c * (xi - 0.5)) / std::tan(-0.5 * c));
  return u / (a + (1.0 - a) * u);
}

/// Start from the slope form: A = sqrt(d1 / d0), sinh(c) / c = h / sqrt(d0 d1), then Newton
/// on (log A, c) for the discrete spacings.
Eigen::VectorXd two_sided(int n, double d0, double d1) {
  const double h = 1.0 / (n - 1);
  const double bb = h / std::sqrt(d0 * d1);
  double c = 0.0;
  if (bb > 1.0 + 1e-12) c = bisect_decreasing([](double x) { return -std::sinh(x) / x; }, -bb, 1e-8, 700.0);
  else if (bb < 1.0 - 1e-12)  // sin(c) / c = bb, 0 < c < pi
    c = -bisect_decreasing([](double x) { return std::sin(x) / x; }, bb, 1e-8, std::numbers::pi * (1 - 1e-12));
  Eigen::Vector2d p(0.5 * std::log(d1 / d0), c);
  auto residual = [&](const Eigen::Vector2d& q) {
    const double a = std::exp(q[0]);
    return Eigen::Vector2d(std::log(vinokur(q[1], a, h) / d0), std::log((1.0 - vinokur(q[1], a, 1.0 - h)) / d1));
  };
  const double c_max = std::numbers::pi * (1.0 - 1e-9);
  for (int it = 0; it < kNewtonIterations; ++it) {
    const Eigen::Vector2d f = residual(p);
    if (!f.allFinite()) infeasible("the two-sided tanh cannot meet these end spacings");
    if (f.norm() < 1e-12) break;
    Eigen::Matrix2d jac;
    for (int k = 0; k < 2; ++k) {
      Eigen::Vector2d q = p;
      const double step = 1e-7 * std::max(1.0, std::abs(p[k]));
      q[k] += step;
      jac.col(k) = (residual(q) - f) / step;
    }
    Eigen::Vector2d dp = jac.partialPivLu().solve(-f);
    double t = 1.0;  // damped: keep c inside the tan branch's domain
    while (p[1] + t * dp[1] < -c_max && t > 1e-6) t *= 0.5;
    p += t * dp;
    if (it == kNewtonIterations - 1 && residual(p).norm() > 1e-9)
      throw ConvergenceError("two-sided tanh distribution: end spacings not met after Newton iterations");
  }
  Eigen::VectorXd r(n);
  for (int k = 0; k < n; ++k) r[k] = vinokur(p[1], std::exp(p[0]), k * h);
  r[0] = 0.0;
  r[n - 1] = 1.0;
  for (int k = 1; k < n; ++k)
    if (!(r[k] > r[k - 1])) infeasible("the two-sided tanh with these end spacings folds back; use more points");
  return r;
}

/// Sum of r^k, k < m, divided into 1: the ratio whose geometric spacings from d0 fill [0, 1].
double geometric_ratio(int intervals, double d0) {
  auto total = [&](double r) { return std::abs(r - 1.0) < 1e-12 ? d0 * intervals : d0 * std::expm1(intervals * std::log(r)) / (r - 1.0); };
  double lo = 1e-6, hi = 1e6;
  for (int it = 0; it < kBisections && hi - lo > kSolveTol * hi; ++it) {
    const double mid = std::sqrt(lo * hi);
    (total(mid) < 1.0 ? lo : hi) = mid;
  }
  return std::sqrt(lo * hi);
}

Eigen::VectorXd geometric(int n, double d0, double max_ratio) {
  if (!(d0 < 1.0)) infeasible("the first spacing is not shorter than the line");
  double r = 0.0;
  if (n == 0) {  // fewest points whose ratio stays within max_ratio
    for (n = 2; n <= kMaxGeometricPoints; ++n) {
      r = geometric_ratio(n - 1, d0);
      if (r <= max_ratio) break;
    }
    if (n > kMaxGeometricPoints) infeasible("geometric growth needs more than 100000 points");
  } else {
    r = geometric_ratio(n - 1, d0);
  }
  if (std::max(r, 1.0 / r) > max_ratio * (1.0 + 1e-12)) {
    std::ostringstream os;
    os << "geometric growth from a first spacing of " << d0 << " x length with " << n << " points needs a ratio of " << r
       << "; max_ratio is " << max_ratio << ": use more points (or points = 0 to choose them)";
    infeasible(os.str());
  }
  Eigen::VectorXd x(n);
  x[0] = 0.0;
  double ds = d0;
  for (int k = 1; k < n; ++k, ds *= r) x[k] = x[k - 1] + ds;
  x /= x[n - 1];  // round-off only: the ratio was solved for the sum
  return x;
}

void check(const Distribution& d, double length) {
  detail::require_positive(length, "length");
  if (d.points < (d.kind == Spacing::Geometric ? 0 : 2) || d.points == 1)
    detail::fail("points is ", d.points, "; expected >= 2", d.kind == Spacing::Geometric ? " (or 0: chosen)" : "");
  if (d.points > kMaxGeometricPoints) detail::fail("points is ", d.points, "; expected at most ", kMaxGeometricPoints);
  if (!(d.first >= 0.0) || !std::isfinite(d.first)) detail::fail("first is ", d.first, " m; expected a spacing >= 0");
  if (!(d.last >= 0.0) || !std::isfinite(d.last)) detail::fail("last is ", d.last, " m; expected a spacing >= 0");
  const bool one = d.kind == Spacing::Sinh || d.kind == Spacing::Tanh;
  if (one && (d.first > 0.0) == (d.last > 0.0))
    detail::fail("a one-sided distribution takes exactly one of first (", d.first, " m) and last (", d.last,
                 " m) > 0: the end to cluster at");
  if (d.kind == Spacing::TanhTwoSided && !(d.first > 0.0 && d.last > 0.0))
    detail::fail("first is ", d.first, " m and last is ", d.last, " m; the two-sided tanh needs both > 0");
  if (d.kind == Spacing::Geometric) {
    if (!(d.first > 0.0)) detail::fail("first is ", d.first, " m; geometric growth needs a first spacing > 0");
    if (!(d.max_ratio > 1.0) || !std::isfinite(d.max_ratio))
      detail::fail("max_ratio is ", d.max_ratio, "; expected a finite value > 1");
  }
}

}  // namespace

Eigen::VectorXd distribute(const Distribution& d, double length) {
  check(d, length);
  const int n = d.points;
  const double d0 = d.first / length, d1 = d.last / length;
  Eigen::VectorXd x;
  switch (d.kind) {
    case Spacing::Uniform:
      x = Eigen::VectorXd::LinSpaced(n, 0.0, 1.0);
      break;
    case Spacing::Sinh:
    case Spacing::Tanh: {
      const double dd = d0 > 0.0 ? d0 : d1;
      if (!(dd < 1.0 / (n - 1))) {
        std::ostringstream os;
        os << "the clustered spacing " << dd * length << " m is not below the uniform spacing " << length / (n - 1)
           << " m of " << n << " points on " << length << " m; use Uniform or fewer points";
        infeasible(os.str());
      }
      x = one_sided(d.kind, n, dd);
      if (d0 == 0.0) x = (1.0 - x.reverse().array()).matrix().eval();  // eval: reverse() aliases x
      break;
    }
    case Spacing::TanhTwoSided:
      if (!(d0 + d1 < 1.0)) infeasible("first + last spacing is not shorter than the line");
      x = two_sided(n, d0, d1);
      break;
    case Spacing::Geometric:
      x = geometric(n, d0, d.max_ratio);
      break;
  }
  x *= length;
  x[x.size() - 1] = length;
  return x;
}

}  // namespace fairlines
