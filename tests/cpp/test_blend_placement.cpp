// Blend boundaries around a seam, judged in the hull's parameter space: the boundary holds
// every seam point at least the clearance from it (a seam on a half ellipse, so the distance
// to an ellipse about the same centre is exact to check along rays).
#include <cmath>

#include <gtest/gtest.h>

#include "fairlines/blend_placement.hpp"
#include "fairlines/errors.hpp"

using namespace fairlines;

namespace {

NurbsSurface unit_patch() {  // bilinear over u, v in [0, 1]: the placement reads only the domain and knots
  Eigen::VectorXd k(4);
  k << 0, 0, 1, 1;
  Eigen::MatrixXd P(4, 3);
  P << 0, 0, 0, 0, 0, 1, 1, 0, 0, 1, 0, 1;
  return NurbsSurface(1, 1, k, k, 2, 2, P);
}

/// A seam on the half ellipse about the stem point (1, vc) with semi-axes a (u) and b (v).
void stem_seam(double vc, double a, double b, int n, Eigen::MatrixXd& uv, Eigen::MatrixXd& uv_b) {
  uv.resize(n, 2);
  uv_b.resize(n, 2);
  for (int i = 0; i < n; ++i) {
    const double phi = M_PI * i / (n - 1);
    uv.row(i) << 1.0 - a * std::sin(phi), vc - b * std::cos(phi);
    uv_b.row(i) << 0.1 + 0.2 * i / (n - 1), double(i) / (n - 1);
  }
}

/// The seam on the half ellipse of semi-axes 0.2 (u) and 0.15 (v) about (1, 0.5).
struct BlendPlacement : ::testing::Test {
  BlendPlacement() { stem_seam(0.5, 0.2, 0.15, 41, uv, uv_b); }
  Eigen::MatrixXd uv, uv_b;
  BlendPlacementOptions o;
};

}  // namespace

TEST_F(BlendPlacement, HalfEllipseAboutTheStemHoldsTheSeamWithItsClearance) {
  const BlendSpec spec = blend_boundaries_around_seam(unit_patch(), uv, uv_b, o);
  ASSERT_EQ(spec.hull_uv.rows(), o.points);
  EXPECT_NEAR(spec.hull_uv(0, 0), 1.0, 1e-15);
  EXPECT_NEAR(spec.hull_uv(o.points - 1, 0), 1.0, 1e-15);
  // every boundary point lies on the ellipse of semi-axes (0.2 + cu, 0.15 + cv) about (1, 0.5)
  for (int i = 0; i < o.points; ++i) {
    const double du = (1.0 - spec.hull_uv(i, 0)) / (0.2 + o.clearance_u);
    const double dv = (spec.hull_uv(i, 1) - 0.5) / (0.15 + o.clearance_v);
    EXPECT_NEAR(std::hypot(du, dv), 1.0, 1e-12) << i;
  }
  EXPECT_NEAR(spec.bulb_u, 0.3 + o.bulb_clearance, 1e-15);
  EXPECT_DOUBLE_EQ(spec.tension, o.tension);
}

TEST_F(BlendPlacement, ABoundaryReachingTheDeckIsNoBlendFits) {
  o.clearance_v = 0.5;
  EXPECT_THROW(blend_boundaries_around_seam(unit_patch(), uv, uv_b, o), NoBlendFits);
}

TEST_F(BlendPlacement, BadShapesAndOptionsAreInvalidInput) {
  o.points = 2;
  EXPECT_THROW(blend_boundaries_around_seam(unit_patch(), uv, uv_b, o), InvalidInput);
  o = {};
  o.clearance_u = std::nan("");
  EXPECT_THROW(blend_boundaries_around_seam(unit_patch(), uv, uv_b, o), InvalidInput);
  EXPECT_THROW(blend_boundaries_around_seam(unit_patch(), uv, uv_b.topRows(3), {}), InvalidInput);
  uv(3, 1) = std::nan("");
  EXPECT_THROW(blend_boundaries_around_seam(unit_patch(), uv, uv_b, {}), InvalidInput);
}
