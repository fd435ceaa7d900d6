// Shared helpers for the GoogleTest suite: reproducible random NURBS and invariant checks.
#pragma once

#include <random>

#include <Eigen/Core>
#include <gtest/gtest.h>

#include "fairlines/curve.hpp"
#include "fairlines/knots.hpp"
#include "fairlines/surface.hpp"

namespace fairlines::test {

/// Random non-decreasing clamped knot vector with distinct interior knots on [0, 1].
inline Eigen::VectorXd random_clamped_knots(int n, int p, std::mt19937& rng) {
  std::uniform_real_distribution<double> U(0.05, 0.95);
  Eigen::VectorXd k = clamped_uniform_knots(n, p);
  std::vector<double> interior(n - p - 1);
  for (auto& x : interior) x = U(rng);
  std::sort(interior.begin(), interior.end());
  for (int i = 0; i < n - p - 1; ++i) k[p + 1 + i] = interior[i];
  return k;
}

inline NurbsCurve random_curve(int n, int p, int dim, bool rational, std::mt19937& rng) {
  std::uniform_real_distribution<double> X(-5.0, 5.0), W(0.3, 3.0);
  Eigen::MatrixXd P(n, dim);
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < dim; ++c) P(i, c) = X(rng);
  Eigen::VectorXd w;
  if (rational) {
    w.resize(n);
    for (int i = 0; i < n; ++i) w[i] = W(rng);
  }
  return NurbsCurve(p, random_clamped_knots(n, p, rng), P, w);
}

inline NurbsSurface random_surface(int nu, int nv, int pu, int pv, bool rational, std::mt19937& rng) {
  std::uniform_real_distribution<double> X(-5.0, 5.0), W(0.3, 3.0);
  Eigen::MatrixXd P(nu * nv, 3);
  for (int i = 0; i < nu * nv; ++i)
    for (int c = 0; c < 3; ++c) P(i, c) = X(rng);
  Eigen::VectorXd w;
  if (rational) {
    w.resize(nu * nv);
    for (int i = 0; i < nu * nv; ++i) w[i] = W(rng);
  }
  return NurbsSurface(pu, pv, random_clamped_knots(nu, pu, rng), random_clamped_knots(nv, pv, rng), nu, nv, P, w);
}

/// Largest distance between two curves sampled at the same `samples` parameters.
inline double curve_distance(const NurbsCurve& a, const NurbsCurve& b, int samples = 2001) {
  const auto [t0, t1] = a.domain();
  const Eigen::VectorXd t = Eigen::VectorXd::LinSpaced(samples, t0, t1);
  return (a.evaluate(t) - b.evaluate(t)).rowwise().norm().maxCoeff();
}

inline double surface_distance(const NurbsSurface& a, const NurbsSurface& b, int samples = 101) {
  const auto [u0, u1] = a.domain_u();
  const auto [v0, v1] = a.domain_v();
  const Eigen::VectorXd u = Eigen::VectorXd::LinSpaced(samples, u0, u1), v = Eigen::VectorXd::LinSpaced(samples, v0, v1);
  return (a.evaluate_grid(u, v) - b.evaluate_grid(u, v)).rowwise().norm().maxCoeff();
}

}  // namespace fairlines::test
