// Structured grids against exact geometry: distributions against the spacings asked for,
// arc length on a circle, grids on a cylinder, grid control that must not move the surface.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "fairlines/errors.hpp"
#include "fairlines/grids.hpp"
#include "fairlines/skinning.hpp"
#include "helpers.hpp"

using namespace fairlines;

namespace {

constexpr double kSpacingTol = 0.01;  ///< end spacings within 1 % of the request
constexpr double kRadius = 3.0;       ///< circle / cylinder radius (m)
constexpr double kHeight = 5.0;       ///< cylinder height (m)

Eigen::VectorXd spacings(const Eigen::VectorXd& x) { return x.tail(x.size() - 1) - x.head(x.size() - 1); }

double max_neighbour_ratio(const Eigen::VectorXd& x) {
  const Eigen::VectorXd d = spacings(x);
  double r = 1.0;
  for (Eigen::Index k = 1; k < d.size(); ++k) r = std::max({r, d[k] / d[k - 1], d[k - 1] / d[k]});
  return r;
}

/// Exact quarter circle of radius kRadius in the plane z = 0 (rational quadratic).
NurbsCurve quarter_circle() {
  Eigen::VectorXd k(6);
  k << 0, 0, 0, 1, 1, 1;
  Eigen::MatrixXd P(3, 3);
  P << kRadius, 0, 0, kRadius, kRadius, 0, 0, kRadius, 0;
  return NurbsCurve(2, k, P, Eigen::Vector3d(1.0, std::sqrt(0.5), 1.0));
}

/// Quarter cylinder: u around the circle, v straight up to kHeight.
NurbsSurface quarter_cylinder() {
  Eigen::VectorXd ku(6), kv(4);
  ku << 0, 0, 0, 1, 1, 1;
  kv << 0, 0, 1, 1;
  Eigen::MatrixXd P(6, 3);
  Eigen::VectorXd w(6);
  const double c[3][2] = {{kRadius, 0}, {kRadius, kRadius}, {0, kRadius}};
  const double wu[3] = {1.0, std::sqrt(0.5), 1.0};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 2; ++j) {
      P.row(i * 2 + j) << c[i][0], c[i][1], kHeight * j;
      w[i * 2 + j] = wu[i];
    }
  return NurbsSurface(2, 1, ku, kv, 3, 2, P, w);
}

/// Arc length along the circle from (R, 0) to the point p.
double arc_on_circle(const Eigen::RowVectorXd& p) { return kRadius * std::atan2(p[1], p[0]); }

}  // namespace

TEST(Grids, OneSidedDistributionsHitTheirEndSpacing) {
  const double length = 2.0, first = 0.004;
  for (Spacing kind : {Spacing::Sinh, Spacing::Tanh}) {
    const Eigen::VectorXd a = distribute({kind, 41, first, 0.0}, length);
    EXPECT_NEAR(a[1] - a[0], first, kSpacingTol * first);
    const Eigen::VectorXd b = distribute({kind, 41, 0.0, first}, length);
    EXPECT_NEAR(b[40] - b[39], first, kSpacingTol * first);
    EXPECT_DOUBLE_EQ(b[40], length);
    EXPECT_GT(spacings(b).minCoeff(), 0.0);
  }
}

TEST(Grids, TwoSidedTanhHitsBothEndSpacings) {
  for (auto [first, last] : {std::pair{0.001, 0.05}, std::pair{0.02, 0.002}, std::pair{0.01, 0.01}}) {
    const Eigen::VectorXd x = distribute({Spacing::TanhTwoSided, 51, first, last}, 1.5);
    EXPECT_NEAR(x[1] - x[0], first, kSpacingTol * first);
    EXPECT_NEAR(x[50] - x[49], last, kSpacingTol * last);
    EXPECT_GT(spacings(x).minCoeff(), 0.0);
  }
}

TEST(Grids, GeometricGrowthKeepsItsStretchingLimit) {
  const double max_ratio = 1.1, first = 0.001;
  const Eigen::VectorXd x = distribute({Spacing::Geometric, 0, first, 0.0, max_ratio}, 1.0);
  EXPECT_NEAR(x[1] - x[0], first, kSpacingTol * first);
  EXPECT_LE(max_neighbour_ratio(x), max_ratio * (1 + 1e-9));
  // One point fewer would need a larger ratio: the fewest points were chosen.
  EXPECT_THROW(distribute({Spacing::Geometric, static_cast<int>(x.size()) - 1, first, 0.0, max_ratio}, 1.0),
               InfeasibleFormParameters);
}

TEST(Grids, ClusteredSpacingNotBelowUniformIsInfeasible) {
  EXPECT_THROW(distribute({Spacing::Sinh, 11, 0.2, 0.0}, 1.0), InfeasibleFormParameters);
  EXPECT_THROW(distribute({Spacing::Sinh, 11, 0.01, 0.01}, 1.0), InvalidInput);
}

TEST(Grids, ArcLengthParametersLandAtTheExactArcOnACircle) {
  const NurbsCurve c = quarter_circle();
  const double total = 0.5 * std::numbers::pi * kRadius;
  const Eigen::VectorXd s = Eigen::VectorXd::LinSpaced(37, 0.0, total);
  const Eigen::MatrixXd p = c.evaluate(parameters_at_arc_length(c, s));
  for (Eigen::Index k = 0; k < s.size(); ++k) EXPECT_NEAR(arc_on_circle(p.row(k)), s[k], 1e-10 * total);
}

TEST(Grids, SkinningEqualArcPointsShareTheArcLengthOnACircle) {
  const double total = 0.5 * std::numbers::pi * kRadius;
  const NurbsCurve c = quarter_circle();
  EXPECT_NEAR(arc_length(c), total, 1e-12 * total);
  const Eigen::MatrixXd p = equal_arc_length_points(c, 19, 0.0);
  for (Eigen::Index k = 0; k < p.rows(); ++k) EXPECT_NEAR(arc_on_circle(p.row(k)), total * k / 18.0, 1e-7 * total);
}

TEST(Grids, EqualArcPointsOnAUniformSpeedLineAreEquallySpaced) {
  // Constant speed: the Hermite guess is exact and Newton's correction is round-off only.
  Eigen::VectorXd k(7);
  k << 0, 0, 0, 0.5, 1, 1, 1;
  Eigen::MatrixXd P(4, 3);
  P << 0, 0, 0, 1, 0, 0, 3, 0, 0, 4, 0, 0;  // uniform speed: spans of equal length in t
  const NurbsCurve c(2, k, P);
  for (Eigen::Index m : {7, 24, 101}) {
    const Eigen::MatrixXd p = equal_arc_length_points(c, static_cast<int>(m), 0.0);
    const Eigen::VectorXd d = spacings(p.col(0));
    EXPECT_LT((d.array() - 4.0 / (m - 1)).abs().maxCoeff(), 1e-12);
    const Eigen::MatrixXd q = c.evaluate(parameters_at_arc_length(c, Eigen::VectorXd::LinSpaced(m, 0.0, 4.0)));
    EXPECT_LT((q.col(0) - Eigen::VectorXd::LinSpaced(m, 0.0, 4.0)).cwiseAbs().maxCoeff(), 1e-12);
  }
}

TEST(Grids, SurfaceGridOnACylinderHasTheAskedSpacingsInArcLength) {
  const Distribution du{Spacing::TanhTwoSided, 31, 0.02, 0.1}, dv{Spacing::Geometric, 25, 0.05, 0.0, 1.3};
  const StructuredGrid g = surface_grid(quarter_cylinder(), du, dv);
  ASSERT_EQ(g.ni, 31);
  ASSERT_EQ(g.nj, 25);
  const Eigen::VectorXd radius = g.points.leftCols(2).rowwise().norm();
  EXPECT_LT((radius.array() - kRadius).abs().maxCoeff(), 1e-12 * kRadius);
  for (int j : {0, g.nj - 1}) {  // the two circular boundaries
    Eigen::VectorXd s(g.ni);
    for (int i = 0; i < g.ni; ++i) s[i] = arc_on_circle(g.points.row(i * g.nj + j));
    EXPECT_NEAR(s[1] - s[0], du.first, kSpacingTol * du.first);
    EXPECT_NEAR(s[g.ni - 1] - s[g.ni - 2], du.last, kSpacingTol * du.last);
  }
  Eigen::VectorXd z(g.nj);
  for (int j = 0; j < g.nj; ++j) z[j] = g.points(j, 2);
  EXPECT_NEAR(z[1] - z[0], dv.first, kSpacingTol * dv.first);
  EXPECT_LE(max_neighbour_ratio(z), dv.max_ratio * (1 + 1e-9));
}

TEST(Grids, KnotInsertionMovesNoSurfacePoint) {
  std::mt19937 rng(14);
  for (bool rational : {false, true}) {
    const NurbsSurface s = test::random_surface(7, 6, 3, 2, rational, rng);
    const NurbsSurface t = cluster_by_knots(s, Direction::U, 0.37, 0.01, 6);
    EXPECT_EQ(t.knots_u().size(), s.knots_u().size() + 6);
    EXPECT_LT(test::surface_distance(s, t), 1e-12 * 10.0);
  }
}

TEST(Grids, WeightReparameterisationMovesNoSurfacePoint) {
  std::mt19937 rng(15);
  const double ratio = 4.0, r = std::sqrt(ratio);
  for (bool rational : {false, true}) {
    const NurbsSurface s = test::random_surface(7, 6, 3, 3, rational, rng);
    const NurbsSurface t = cluster_by_weights(s, Direction::V, ratio);
    EXPECT_LT((t.control_points() - s.control_points()).norm(), 1e-12);
    const Eigen::VectorXd sigma = Eigen::VectorXd::LinSpaced(41, 0.0, 1.0);
    Eigen::VectorXd tv(sigma.size());  // the Moebius map on [0, 1]
    for (Eigen::Index k = 0; k < sigma.size(); ++k) tv[k] = sigma[k] / (sigma[k] + r * (1.0 - sigma[k]));
    const Eigen::VectorXd u = Eigen::VectorXd::LinSpaced(41, 0.0, 1.0);
    EXPECT_LT((t.evaluate_grid(u, sigma) - s.evaluate_grid(u, tv)).rowwise().norm().maxCoeff(), 1e-11);
  }
}

TEST(Grids, WeightReparameterisationClustersAUniformGridByTheRatio) {
  const double ratio = 5.0;
  const NurbsSurface plane = quarter_cylinder();  // v is straight with uniform speed
  const NurbsSurface t = cluster_by_weights(plane, Direction::V, ratio);
  const Eigen::VectorXd v = Eigen::VectorXd::LinSpaced(2001, 0.0, 1.0);
  const Eigen::MatrixXd p = t.evaluate_grid(Eigen::VectorXd::Constant(1, 0.3), v);
  const Eigen::VectorXd d = spacings(p.col(2));
  EXPECT_NEAR(d[d.size() - 1] / d[0], ratio, kSpacingTol * ratio);
}

TEST(Grids, QualityOfAUniformPlanarGridIsExact) {
  const int ni = 5, nj = 4;
  Eigen::MatrixXd pts(ni * nj, 3);
  for (int i = 0; i < ni; ++i)
    for (int j = 0; j < nj; ++j) pts.row(i * nj + j) << 0.5 * i, 2.0 * j, 0.0;
  const GridQuality q = grid_quality(pts, ni, nj);
  EXPECT_NEAR(q.max_stretching, 1.0, 1e-12);
  EXPECT_NEAR(q.max_orthogonality_deg, 0.0, 1e-9);
  EXPECT_NEAR(q.max_aspect_ratio, 4.0, 1e-12);
  EXPECT_NEAR(q.first_min, 0.5, 1e-12);
  EXPECT_NEAR(q.first_min_j, 2.0, 1e-12);
  EXPECT_EQ(q.degenerate_cells, 0);
}
