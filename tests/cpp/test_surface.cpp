#include <cmath>
#include <numbers>
#include <random>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "fairlines/conics.hpp"
#include "fairlines/errors.hpp"
#include "fairlines/surface.hpp"
#include "fairlines/volume.hpp"
#include "helpers.hpp"

using namespace fairlines;

TEST(Surface, GridAndScatteredEvaluationAgreeWithDerivativeRoutine) {
  std::mt19937 rng(6);
  for (auto [pu, pv] : {std::pair{3, 3}, std::pair{2, 3}, std::pair{1, 1}, std::pair{4, 2}, std::pair{5, 5}}) {
    for (bool rational : {false, true}) {
      const NurbsSurface s = test::random_surface(9, 8, pu, pv, rational, rng);
      const Eigen::VectorXd u = Eigen::VectorXd::LinSpaced(13, 0.0, 1.0), v = Eigen::VectorXd::LinSpaced(11, 0.0, 1.0);
      const Eigen::MatrixXd G = s.evaluate_grid(u, v);
      for (int a = 0; a < 13; ++a)
        for (int b = 0; b < 11; ++b) {
          const Eigen::Vector3d ref = s.derivatives(u[a], v[b], 0).row(0).transpose();
          EXPECT_LT((G.row(a * 11 + b).transpose() - ref).norm(), 1e-12);
          EXPECT_LT((s.evaluate(u[a], v[b]) - ref).norm(), 1e-12);
        }
    }
  }
}

// The batch scattered path has fixed-degree kernels for degrees 1..3 in each direction:
// check every pair against the general derivative routine, including parameters exactly on
// (repeated) interior knots, at the domain ends, outside the domain (clamped) and odd counts.
TEST(Surface, ScatteredBatchMatchesGeneralRoutineOnKnotsAndEnds) {
  std::mt19937 rng(26);
  std::uniform_real_distribution<double> T(0.0, 1.0);
  for (int pu = 1; pu <= 4; ++pu)
    for (int pv = 1; pv <= 3; ++pv)
      for (bool rational : {false, true}) {
        NurbsSurface s0 = test::random_surface(9, 7, pu, pv, rational, rng);
        // Double an interior knot (an empty span) where the degree allows it.
        Eigen::VectorXd ku = s0.knots_u(), kv = s0.knots_v();
        if (pu >= 2) ku[pu + 2] = ku[pu + 1];
        if (pv >= 2) kv[pv + 2] = kv[pv + 1];
        const NurbsSurface s(pu, pv, ku, kv, 9, 7, s0.control_points(), rational ? s0.weights() : Eigen::VectorXd());
        std::vector<double> us, vs;
        for (int k = 0; k < 301; ++k) {
          us.push_back(T(rng));
          vs.push_back(T(rng));
        }
        for (Eigen::Index k = 0; k < ku.size(); ++k) {
          us.push_back(ku[k]);
          vs.push_back(kv[std::min<Eigen::Index>(k, kv.size() - 1)]);
        }
        for (double t : {-0.25, 0.0, 1.0, 1.25, std::nextafter(1.0, 0.0)}) {
          us.push_back(t);
          vs.push_back(1.0 - t);
        }
        const Eigen::VectorXd u = Eigen::Map<Eigen::VectorXd>(us.data(), us.size());
        const Eigen::VectorXd v = Eigen::Map<Eigen::VectorXd>(vs.data(), vs.size());
        const Eigen::MatrixXd S = s.evaluate(u, v);
        for (Eigen::Index k = 0; k < u.size(); ++k) {
          const Eigen::Vector3d ref = s.derivatives(u[k], v[k], 0).row(0).transpose();
          EXPECT_LT((S.row(k).transpose() - ref).norm(), 1e-12 * (1.0 + ref.norm()))
              << "degrees (" << pu << ", " << pv << ") rational " << rational << " at (" << u[k] << ", " << v[k] << ")";
        }
      }
}

TEST(Surface, BatchFirstDerivativesAgreeWithGeneralRoutine) {
  std::mt19937 rng(16);
  for (auto [pu, pv] : {std::pair{3, 3}, std::pair{2, 3}, std::pair{1, 2}, std::pair{4, 5}, std::pair{8, 2}}) {
    for (bool rational : {false, true}) {
      const NurbsSurface s = test::random_surface(10, 9, pu, pv, rational, rng);
      std::uniform_real_distribution<double> U(0.0, 1.0);
      std::vector<double> u(50), v(50), out(9 * 50);
      for (int k = 0; k < 50; ++k) u[k] = U(rng), v[k] = U(rng);
      u[0] = 0.0, v[1] = 1.0;  // domain ends
      s.evaluate_first_derivatives_into(u.data(), v.data(), 50, out.data());
      for (int k = 0; k < 50; ++k) {
        const Eigen::MatrixXd D = s.derivatives(u[k], v[k], 1);
        const double scale = 1.0 + D.cwiseAbs().maxCoeff();
        for (int c = 0; c < 3; ++c) {
          EXPECT_NEAR(out[9 * k + c], D(0, c), 1e-12 * scale);
          EXPECT_NEAR(out[9 * k + 3 + c], D(2, c), 1e-11 * scale) << pu << pv << rational;
          EXPECT_NEAR(out[9 * k + 6 + c], D(1, c), 1e-11 * scale) << pu << pv << rational;
        }
      }
    }
  }
}

TEST(Surface, DerivativesMatchFiniteDifferences) {
  std::mt19937 rng(7);
  const NurbsSurface s = test::random_surface(7, 6, 3, 2, true, rng);
  const double h = 1e-6;
  for (auto [u, v] : {std::pair{0.3, 0.4}, std::pair{0.71, 0.18}}) {
    const Eigen::MatrixXd D = s.derivatives(u, v, 2);  // row k*3 + l
    const Eigen::Vector3d Su = (s.evaluate(u + h, v) - s.evaluate(u - h, v)) / (2 * h);
    const Eigen::Vector3d Sv = (s.evaluate(u, v + h) - s.evaluate(u, v - h)) / (2 * h);
    EXPECT_LT((D.row(3).transpose() - Su).norm(), 1e-5 * (1 + Su.norm()));
    EXPECT_LT((D.row(1).transpose() - Sv).norm(), 1e-5 * (1 + Sv.norm()));
    const Eigen::MatrixXd Dp = s.derivatives(u, v + h, 1), Dm = s.derivatives(u, v - h, 1);
    const Eigen::Vector3d Suv = (Dp.row(2) - Dm.row(2)).transpose() / (2 * h);
    EXPECT_LT((D.row(4).transpose() - Suv).norm(), 1e-4 * (1 + Suv.norm()));
  }
}

TEST(Surface, KnotInsertionAndDegreeElevationLeaveShapeUnchanged) {
  std::mt19937 rng(8);
  for (bool rational : {false, true}) {
    const NurbsSurface s = test::random_surface(8, 7, 3, 3, rational, rng);
    EXPECT_LT(test::surface_distance(s, s.insert_knot(Direction::U, 0.37, 2)), 1e-12);
    EXPECT_LT(test::surface_distance(s, s.insert_knot(Direction::V, 0.61, 1)), 1e-12);
    const NurbsSurface e = s.elevate_degree(Direction::V, 1).elevate_degree(Direction::U, 2);
    EXPECT_EQ(e.degree_u(), 5);
    EXPECT_EQ(e.degree_v(), 4);
    EXPECT_LT(test::surface_distance(s, e), 1e-12);
  }
}

TEST(Surface, SphereIsExactWithConstantCurvature) {
  const double r = 1.7;
  const Eigen::Vector3d c(0.5, -1.0, 2.0);
  const NurbsSurface s = sphere(c, r);
  const Eigen::VectorXd u = Eigen::VectorXd::LinSpaced(100, 0.0, 1.0), v = Eigen::VectorXd::LinSpaced(100, 0.0, 1.0);
  const Eigen::MatrixXd G = s.evaluate_grid(u, v);
  EXPECT_LT(((G.rowwise() - c.transpose()).rowwise().norm().array() - r).abs().maxCoeff(), 1e-12);
  const Eigen::VectorXd uu = Eigen::VectorXd::LinSpaced(50, 0.01, 0.99), vv = Eigen::VectorXd::LinSpaced(50, 0.05, 0.95);
  const auto [K, H] = s.curvature(uu, vv);
  EXPECT_LT((K.array() - 1.0 / (r * r)).abs().maxCoeff(), 1e-9);
  EXPECT_LT((H.array().abs() - 1.0 / r).abs().maxCoeff(), 1e-9);
  // Normals are radial, also at the poles (degenerate parameterization).
  Eigen::VectorXd pu(3), pv(3);
  pu << 0.3, 0.3, 0.7;
  pv << 0.0, 1.0, 0.4;
  const Eigen::MatrixXd N = s.normal(pu, pv);
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d radial = (s.evaluate(pu[k], pv[k]) - c).normalized();
    EXPECT_GT(std::abs(N.row(k).dot(radial)), 1.0 - 1e-12) << k;
    // Orientation is continuous into the poles: same side as a nearby interior normal.
    Eigen::VectorXd iu(1), iv(1);
    iu << pu[k];
    iv << std::clamp(pv[k], 0.01, 0.99);
    EXPECT_GT(N.row(k).dot(s.normal(iu, iv).row(0)), 0.9) << k;
  }
}

TEST(Surface, CylinderIsExact) {
  const NurbsSurface s = cylinder(Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 0, 1), 0.8, 3.0);
  const Eigen::VectorXd u = Eigen::VectorXd::LinSpaced(60, 0.0, 1.0), v = Eigen::VectorXd::LinSpaced(7, 0.0, 1.0);
  const Eigen::MatrixXd G = s.evaluate_grid(u, v);
  for (Eigen::Index i = 0; i < G.rows(); ++i) EXPECT_NEAR(std::hypot(G(i, 0) - 1.0, G(i, 1)), 0.8, 1e-12);
  const auto [K, H] = s.curvature(Eigen::VectorXd::LinSpaced(10, 0.05, 0.95), Eigen::VectorXd::LinSpaced(10, 0.1, 0.9));
  EXPECT_LT(K.cwiseAbs().maxCoeff(), 1e-10);
  EXPECT_LT((H.array().abs() - 0.5 / 0.8).abs().maxCoeff(), 1e-10);
}

TEST(Surface, ClosestPointInsideAndAtBoundaries) {
  const NurbsSurface s = sphere(Eigen::Vector3d::Zero(), 2.0);
  std::mt19937 rng(9);
  std::normal_distribution<double> g;
  for (int k = 0; k < 20; ++k) {
    const Eigen::Vector3d d = Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized();
    const auto [u, v, q] = s.closest_point(5.0 * d);
    EXPECT_LT((q - 2.0 * d).norm(), 1e-8) << k;
  }
  // A flat bilinear patch: points beyond an edge project onto that edge.
  Eigen::MatrixXd P(4, 3);
  P << 0, 0, 0, 0, 1, 0, 1, 0, 0, 1, 1, 0;
  Eigen::VectorXd K(4);
  K << 0, 0, 1, 1;
  const NurbsSurface flat(1, 1, K, K, 2, 2, P);
  const auto [u, v, q] = flat.closest_point(Eigen::Vector3d(1.5, 0.4, 2.0));
  EXPECT_NEAR(u, 1.0, 1e-14);
  EXPECT_NEAR(v, 0.4, 1e-12);
  EXPECT_LT((q - Eigen::Vector3d(1.0, 0.4, 0.0)).norm(), 1e-12);
}

TEST(Surface, BatchClosestPointsAreTheSphereFootsAndEachPointsSearch) {
  const NurbsSurface s = sphere(Eigen::Vector3d(0.5, -1.0, 2.0), 2.0);
  std::mt19937 rng(11);
  std::normal_distribution<double> g;
  Eigen::MatrixXd pts(40, 3), dirs(40, 3);
  for (Eigen::Index k = 0; k < pts.rows(); ++k) {
    dirs.row(k) = Eigen::RowVector3d(g(rng), g(rng), g(rng)).normalized();
    pts.row(k) = Eigen::RowVector3d(0.5, -1.0, 2.0) + (0.3 + 0.2 * k) * dirs.row(k);  // inside and outside
  }
  const auto [u, v, q] = s.closest_points(pts);
  for (Eigen::Index k = 0; k < pts.rows(); ++k) {
    EXPECT_LT((q.row(k) - (Eigen::RowVector3d(0.5, -1.0, 2.0) + 2.0 * dirs.row(k))).norm(), 1e-8) << k;
    const auto [uk, vk, qk] = s.closest_point(pts.row(k).transpose());
    EXPECT_EQ(u[k], uk) << k;  // the batch shares only what depends on the surface
    EXPECT_EQ(v[k], vk) << k;
  }
  EXPECT_THROW(s.closest_points(Eigen::MatrixXd::Zero(3, 2)), InvalidInput);
}

TEST(Surface, BadInputThrowsInvalidInput) {
  Eigen::MatrixXd P = Eigen::MatrixXd::Zero(4, 3);
  Eigen::VectorXd K(4);
  K << 0, 0, 1, 1;
  EXPECT_NO_THROW(NurbsSurface(1, 1, K, K, 2, 2, P));
  EXPECT_THROW(NurbsSurface(1, 1, K, K, 2, 3, P), InvalidInput);
  EXPECT_THROW(NurbsSurface(2, 1, K, K, 2, 2, P), InvalidInput);
  EXPECT_THROW(NurbsSurface(1, 1, K, K, 2, 2, P, Eigen::Vector4d(1, 1, 1, 0)), InvalidInput);
  Eigen::VectorXd D = K;
  D[1] = 0.5;
  D[2] = 0.2;
  EXPECT_THROW(NurbsSurface(1, 1, D, K, 2, 2, P), InvalidInput);
  EXPECT_THROW(parse_direction("w"), InvalidInput);
}

TEST(Volume, TrilinearLatticeReproducesAffineMap) {
  // A degree-1 lattice whose control points are an affine image of the parameter cube
  // reproduces that map exactly everywhere (linear precision).
  Eigen::Matrix3d A;
  A << 2, 0.3, 0, -0.1, 1.5, 0.2, 0, 0.4, 3;
  const Eigen::Vector3d b(1, 2, 3);
  const Eigen::VectorXd K = clamped_uniform_knots(3, 1);
  Eigen::MatrixXd P(27, 3);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) P.row((i * 3 + j) * 3 + k) = (A * Eigen::Vector3d(i / 2.0, j / 2.0, k / 2.0) + b).transpose();
  const NurbsVolume vol({1, 1, 1}, {K, K, K}, {3, 3, 3}, P);
  Eigen::VectorXd s(3), t(3), r(3);
  s << 0.1, 0.5, 0.9;
  t << 0.7, 0.2, 0.0;
  r << 0.3, 1.0, 0.6;
  const Eigen::MatrixXd out = vol.evaluate(s, t, r);
  for (int k = 0; k < 3; ++k) EXPECT_LT((out.row(k).transpose() - (A * Eigen::Vector3d(s[k], t[k], r[k]) + b)).norm(), 1e-14);
}
