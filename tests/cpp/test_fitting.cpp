#include <cmath>
#include <numbers>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "fairlines/errors.hpp"
#include "fairlines/fitting.hpp"

using namespace fairlines;

namespace {

// Quarter of a super-ellipse-like smooth curve (analytic, no special structure).
Eigen::MatrixXd sample_curve(int m) {
  Eigen::MatrixXd P(m, 2);
  for (int i = 0; i < m; ++i) {
    const double s = 0.5 * std::numbers::pi * i / (m - 1);
    P.row(i) << 3.0 * std::cos(s) + 0.2 * std::sin(3 * s), 1.5 * std::sin(s);
  }
  return P;
}

double true_error(const NurbsCurve& c) {
  // Distance from dense exact samples to the curve (closest points).
  const Eigen::MatrixXd dense = sample_curve(400);
  double e = 0.0;
  for (int i = 0; i < 400; ++i) e = std::max(e, (c.closest_point(dense.row(i).transpose()).second - dense.row(i).transpose()).norm());
  return e;
}

}  // namespace

TEST(Fitting, InterpolationPassesThroughEveryPoint) {
  for (auto kn : {KnotMethod::Average, KnotMethod::HartleyJudd})
    for (auto pm : {Parameterization::ChordLength, Parameterization::Centripetal, Parameterization::Uniform}) {
      FitOptions o;
      o.parameterization = pm;
      o.knot_method = kn;
      const CurveFit f = fit_curve(sample_curve(25), o);
      EXPECT_LT(f.max_deviation, 1e-12);
      EXPECT_LE(f.rms_deviation, f.max_deviation);
      EXPECT_EQ(f.curve.n_control(), 25);
    }
}

TEST(Fitting, InterpolationConvergesAtFourthOrder) {
  FitOptions o;
  double prev = 0.0;
  for (int m : {9, 17, 33, 65}) {
    const double e = true_error(fit_curve(sample_curve(m), o).curve);
    if (prev > 0.0) EXPECT_GT(prev / e, 10.0) << "m=" << m << " error " << e << " previous " << prev;
    prev = e;
  }
}

TEST(Fitting, LeastSquaresConvergesAndKeepsEnds) {
  const Eigen::MatrixXd P = sample_curve(401);
  double prev = 0.0;
  for (int n : {8, 16, 32}) {
    FitOptions o;
    o.n_control = n;
    const CurveFit f = fit_curve(P, o);
    EXPECT_LT((f.curve.control_points().row(0) - P.row(0)).norm(), 1e-15);
    EXPECT_LT((f.curve.control_points().row(n - 1) - P.row(400)).norm(), 1e-15);
    if (prev > 0.0) EXPECT_GT(prev / f.max_deviation, 8.0) << "n=" << n;
    prev = f.max_deviation;
  }
}

TEST(Fitting, SurfaceFromGrid) {
  // z = sin(x) cos(y) on a non-uniform grid: interpolation exact at nodes, LSQ converges.
  const int R = 21, C = 17;
  Eigen::MatrixXd G(R * C, 3);
  for (int r = 0; r < R; ++r)
    for (int c = 0; c < C; ++c) {
      const double x = 2.0 * std::pow(r / (R - 1.0), 1.3), y = 1.5 * c / (C - 1.0);
      G.row(r * C + c) << x, y, std::sin(x) * std::cos(y);
    }
  FitOptions o;
  const SurfaceFit f = fit_surface(G, R, C, o, o);
  EXPECT_LT(f.max_deviation, 1e-12);
  FitOptions a = o, b = o;
  a.n_control = 8;
  b.n_control = 7;
  const SurfaceFit g = fit_surface(G, R, C, a, b);
  EXPECT_LT(g.max_deviation, 2e-3);
  EXPECT_GT(g.max_deviation, 0.0);
}

TEST(Fitting, BadInput) {
  FitOptions o;
  EXPECT_THROW(fit_curve(sample_curve(3), o), InvalidInput);  // fewer points than degree + 1
  o.n_control = 50;
  EXPECT_THROW(fit_curve(sample_curve(10), o), InvalidInput);  // more control points than data
  Eigen::MatrixXd P = sample_curve(10);
  P(4, 0) = std::nan("");
  EXPECT_THROW(fit_curve(P, FitOptions{}), InvalidInput);
}
