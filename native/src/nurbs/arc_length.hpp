// Arc length along a curve (internal; shared by structured grids and skinning): a table of
// the cumulative length and its inversion t(s).
//
// Notation: t the curve parameter on [t0, t1]; v(t) > 0 the speed integrated (|C'(t)|, or a
// weighted speed such as |C'| (1 + w |k|)); s(t) = integral of v from t0. The table holds s
// at the ends of `pieces` equal pieces of every non-empty knot span (Gauss-Legendre on each
// piece) and the one-sided speeds just inside each piece's ends (the speed may jump at a knot
// of full multiplicity), so that t(s) is first guessed by cubic Hermite interpolation with
// dt/ds = 1/v at the ends, then corrected by Newton on s(t) - target inside the piece.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "nurbs/gauss.hpp"

namespace fairlines::detail {

struct ArcTable {
  std::vector<double> t, s;               ///< piece ends and the cumulative length there
  std::vector<double> speed_a, speed_b;   ///< speed just inside the start / end of piece k
};

/// Integral of `speed` over [a, b] by the n-point Gauss-Legendre rule.
template <class Speed>
double arc_piece(Speed&& speed, double a, double b, int n) {
  const GaussRule& g = gauss_rule(n);
  const double h = 0.5 * (b - a), m = 0.5 * (a + b);
  double sum = 0.0;
  for (std::size_t k = 0; k < g.x.size(); ++k) sum += g.w[k] * speed(m + h * g.x[k]);
  return sum * h;
}

/// Table on [t0, t1] with `pieces` equal pieces per non-empty knot span of `knots`, each
/// integrated by a `gauss`-point rule.
template <class Speed>
ArcTable arc_table(Speed&& speed, const Eigen::VectorXd& knots, double t0, double t1, int pieces, int gauss) {
  ArcTable tab;
  tab.t.push_back(t0);
  tab.s.push_back(0.0);
  for (Eigen::Index i = 0; i + 1 < knots.size(); ++i) {
    const double a = std::max(knots[i], t0), b = std::min(knots[i + 1], t1);
    if (!(b > a)) continue;
    for (int k = 0; k < pieces; ++k) {
      const double ta = a + (b - a) * k / pieces, tb = a + (b - a) * (k + 1) / pieces;
      const double eps = 1e-9 * (tb - ta);  // one-sided: inside the piece
      tab.t.push_back(tb);
      tab.s.push_back(tab.s.back() + arc_piece(speed, ta, tb, gauss));
      tab.speed_a.push_back(speed(ta + eps));
      tab.speed_b.push_back(speed(tb - eps));
    }
  }
  return tab;
}

/// Parameter where s(t) = target: Hermite guess on the table's piece (linear where the speed
/// vanishes), then at most `newton` Newton steps, s(t) integrated from the piece's start by a
/// `gauss`-point rule, kept inside the piece by bisection (the last step is clamped to the
/// bracket instead, and skipped where the speed vanishes); stops when |s(t) - target| <= tol.
/// The result stays in the piece, so t(s) is monotone.
template <class Speed>
double invert_arc(Speed&& speed, const ArcTable& tab, double target, int newton, int gauss, double tol) {
  const auto it = std::upper_bound(tab.s.begin(), tab.s.end(), target);
  const std::size_t k = it == tab.s.begin() ? 0 : static_cast<std::size_t>(it - tab.s.begin()) - 1;
  if (k + 1 >= tab.s.size()) return tab.t.back();
  const double t0 = tab.t[k], t1 = tab.t[k + 1], s0 = tab.s[k], ds = tab.s[k + 1] - s0;
  if (!(ds > 0)) return t0;
  const double x = (target - s0) / ds, dt = t1 - t0;
  double m0 = dt, m1 = dt;  // d t / d x at the ends (linear fallback)
  if (tab.speed_a[k] > 1e-12 * ds / dt && tab.speed_b[k] > 1e-12 * ds / dt) {
    m0 = ds / tab.speed_a[k];
    m1 = ds / tab.speed_b[k];
  }
  const double x2 = x * x, x3 = x2 * x;
  double t = (2 * x3 - 3 * x2 + 1) * t0 + (x3 - 2 * x2 + x) * m0 + (-2 * x3 + 3 * x2) * t1 + (x3 - x2) * m1;
  t = std::clamp(t, t0, t1);
  double lo = t0, hi = t1;
  for (int step = 0; step < newton; ++step) {
    const double f = (t > t0 ? arc_piece(speed, t0, t, gauss) : 0.0) - (target - s0);
    if (std::abs(f) <= tol) break;
    (f > 0 ? hi : lo) = t;
    const double v = speed(t);
    if (step + 1 == newton) {  // last step: no bisection, which could undo a good guess
      if (v > 0) t = std::clamp(t - f / v, lo, hi);
      break;
    }
    double nt = v > 0 ? t - f / v : 0.5 * (lo + hi);
    if (!(nt > lo && nt < hi)) nt = 0.5 * (lo + hi);
    t = nt;
  }
  return t;
}

}  // namespace fairlines::detail
