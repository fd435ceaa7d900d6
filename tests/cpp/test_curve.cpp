#include <cmath>
#include <numbers>
#include <random>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "fairlines/conics.hpp"
#include "fairlines/curve.hpp"
#include "fairlines/errors.hpp"
#include "helpers.hpp"

using namespace fairlines;

TEST(Curve, DerivativesMatchFiniteDifferences) {
  std::mt19937 rng(3);
  for (bool rational : {false, true}) {
    const NurbsCurve c = test::random_curve(9, 3, 3, rational, rng);
    for (double t : {0.11, 0.42, 0.77}) {
      const Eigen::MatrixXd D = c.derivatives(t, 2);
      const double h = 1e-6;
      const Eigen::MatrixXd Dp = c.derivatives(t + h, 1), Dm = c.derivatives(t - h, 1);
      EXPECT_LT((D.row(1) - (Dp.row(0) - Dm.row(0)) / (2 * h)).norm(), 1e-5 * (1 + D.row(1).norm()));
      EXPECT_LT((D.row(2) - (Dp.row(1) - Dm.row(1)) / (2 * h)).norm(), 1e-4 * (1 + D.row(2).norm()));
    }
  }
}

TEST(Curve, KnotInsertionAndRefinementLeaveShapeUnchanged) {
  std::mt19937 rng(4);
  for (bool rational : {false, true}) {
    const NurbsCurve c = test::random_curve(10, 3, 3, rational, rng);
    const NurbsCurve c1 = c.insert_knot(0.3141, 2);
    EXPECT_EQ(c1.n_control(), c.n_control() + 2);
    EXPECT_LT(test::curve_distance(c, c1), 1e-12);
    Eigen::VectorXd X(5);
    X << 0.05, 0.2, 0.2, 0.5, 0.93;
    const NurbsCurve c2 = c.refine_knots(X);
    EXPECT_EQ(c2.n_control(), c.n_control() + 5);
    EXPECT_LT(test::curve_distance(c, c2), 1e-12);
  }
}

TEST(Curve, DegreeElevationLeavesShapeUnchanged) {
  std::mt19937 rng(5);
  for (bool rational : {false, true}) {
    const NurbsCurve c = test::random_curve(8, 3, 2, rational, rng);
    const NurbsCurve e = c.elevate_degree(2);
    EXPECT_EQ(e.degree(), 5);
    EXPECT_LT(test::curve_distance(c, e), 1e-12);
  }
  // An unclamped curve is clamped to its domain first.
  Eigen::MatrixXd P(6, 2);
  P << 0, 0, 1, 2, 2, -1, 3, 1, 4, 0, 5, 2;
  const NurbsCurve u(3, unclamped_uniform_knots(6, 3), P);
  EXPECT_LT(test::curve_distance(u, u.elevate_degree(1)), 1e-12);
}

TEST(Curve, CircleIsExact) {
  const NurbsCurve c = circle(Eigen::Vector3d(1, 2, 3), 2.5, Eigen::Vector3d(1, 1, 1));
  const Eigen::MatrixXd pts = c.evaluate(Eigen::VectorXd::LinSpaced(10000, 0.0, 1.0));
  const Eigen::Vector3d n = Eigen::Vector3d(1, 1, 1).normalized();
  for (Eigen::Index i = 0; i < pts.rows(); ++i) {
    const Eigen::Vector3d d = pts.row(i).transpose() - Eigen::Vector3d(1, 2, 3);
    EXPECT_NEAR(d.norm(), 2.5, 1e-12);
    EXPECT_NEAR(d.dot(n), 0.0, 1e-12);
  }
  // Curvature of a circle is 1/r everywhere; torsion of a plane curve is 0.
  const Eigen::VectorXd t = Eigen::VectorXd::LinSpaced(101, 0.0, 1.0);
  EXPECT_LT((c.curvature(t).array() - 1.0 / 2.5).abs().maxCoeff(), 1e-12);
  EXPECT_LT(c.torsion(t).cwiseAbs().maxCoeff(), 1e-10);
}

TEST(Curve, ArcsAndEllipse) {
  for (double deg : {30.0, 90.0, 135.0, 200.0, 300.0}) {
    const double a1 = deg * std::numbers::pi / 180.0;
    const NurbsCurve a = arc(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), 3.0, 0.0, a1);
    const Eigen::MatrixXd pts = a.evaluate(Eigen::VectorXd::LinSpaced(1000, 0.0, 1.0));
    EXPECT_LT((pts.rowwise().norm().array() - 3.0).abs().maxCoeff(), 1e-12);
    EXPECT_LT((pts.row(999).transpose() - Eigen::Vector3d(3 * std::cos(a1), 3 * std::sin(a1), 0)).norm(), 1e-12);
  }
  const NurbsCurve e = ellipse(Eigen::Vector3d::Zero(), Eigen::Vector3d(4, 0, 0), Eigen::Vector3d(0, 1.5, 0));
  const Eigen::MatrixXd pts = e.evaluate(Eigen::VectorXd::LinSpaced(1000, 0.0, 1.0));
  for (Eigen::Index i = 0; i < pts.rows(); ++i)
    EXPECT_NEAR(std::pow(pts(i, 0) / 4.0, 2) + std::pow(pts(i, 1) / 1.5, 2), 1.0, 1e-12);
}

TEST(Curve, ClosestPoint) {
  const NurbsCurve c = circle(Eigen::Vector3d::Zero(), 2.0, Eigen::Vector3d::UnitZ());
  // Closest point to a circle from an outside point lies on the ray from the centre.
  for (double ang : {0.1, 1.0, 2.5, 4.0, 6.0}) {
    const Eigen::VectorXd q = Eigen::Vector3d(5 * std::cos(ang), 5 * std::sin(ang), 1.0);
    const auto [tc, pc] = c.closest_point(q);
    EXPECT_LT((pc - Eigen::Vector3d(2 * std::cos(ang), 2 * std::sin(ang), 0)).norm(), 1e-9) << ang;
  }
  // Beyond the end of an open curve the closest point is the end point.
  Eigen::MatrixXd L(2, 2);
  L << 0, 0, 1, 0;
  Eigen::VectorXd K(4);
  K << 0, 0, 1, 1;
  const NurbsCurve seg(1, K, L);
  const auto [te, pe] = seg.closest_point(Eigen::Vector2d(3, 1));
  EXPECT_DOUBLE_EQ(te, 1.0);
  EXPECT_LT((pe - Eigen::Vector2d(1, 0)).norm(), 1e-15);
}

TEST(Curve, BadInputThrowsInvalidInput) {
  Eigen::MatrixXd P(4, 2);
  P << 0, 0, 1, 1, 2, 0, 3, 1;
  Eigen::VectorXd U(8);
  U << 0, 0, 0, 0, 1, 1, 1, 1;
  EXPECT_NO_THROW(NurbsCurve(3, U, P));
  EXPECT_THROW(NurbsCurve(4, U, P), InvalidInput);                 // degree / count mismatch
  EXPECT_THROW(NurbsCurve(3, U.head(7), P), InvalidInput);         // wrong knot count
  EXPECT_THROW(NurbsCurve(3, U, P, Eigen::Vector4d(1, 1, 0, 1)), InvalidInput);   // weight 0
  EXPECT_THROW(NurbsCurve(3, U, P, Eigen::Vector4d(1, 1, -2, 1)), InvalidInput);  // negative
  Eigen::MatrixXd Pn = P;
  Pn(2, 1) = std::numeric_limits<double>::infinity();
  EXPECT_THROW(NurbsCurve(3, U, Pn), InvalidInput);
  EXPECT_THROW(NurbsCurve(3, U, Eigen::MatrixXd(0, 2)), InvalidInput);
  const NurbsCurve c(3, U, P);
  EXPECT_THROW(c.insert_knot(0.5, 4), InvalidInput);  // multiplicity above degree
  EXPECT_THROW(c.insert_knot(1.5), InvalidInput);     // outside the domain
  EXPECT_THROW(c.elevate_degree(0), InvalidInput);
}
