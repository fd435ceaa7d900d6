// Gauss-Legendre quadrature rules on [-1, 1] (internal; shared by form-parameter curves,
// skinning, hydrostatics and the hull builder). An n-point rule integrates polynomials of degree 2n - 1 exactly.
#pragma once

#include <cmath>
#include <numbers>
#include <vector>

namespace fairlines::detail {

struct GaussRule {
  std::vector<double> x, w;
};

/// n-point Gauss-Legendre rule (n >= 1): nodes by Newton iteration on P_n from the
/// Chebyshev-like start cos(pi (i + 3/4) / (n + 1/2)), weights 2 / ((1 - x^2) P_n'(x)^2).
inline GaussRule gauss_legendre(int n) {
  GaussRule r;
  r.x.resize(n);
  r.w.resize(n);
  for (int i = 0; i < n; ++i) {
    double x = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
    double dp = 1.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      if (n == 1) p0 = 1.0, p1 = x;
      dp = n * (x * p1 - p0) / (x * x - 1.0);
      const double dx = p1 / dp;
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    {
      double p0 = 1.0, p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (x * p1 - p0) / (x * x - 1.0);
    }
    r.x[i] = -x;
    r.w[i] = 2.0 / ((1.0 - x * x) * dp * dp);
  }
  return r;
}

/// Cached rules for n <= 32.
inline const GaussRule& gauss_rule(int n) {
  static const std::vector<GaussRule> rules = [] {
    std::vector<GaussRule> v(33);
    for (int k = 1; k <= 32; ++k) v[k] = gauss_legendre(k);
    return v;
  }();
  return rules[n < 1 ? 1 : (n > 32 ? 32 : n)];
}

}  // namespace fairlines::detail
