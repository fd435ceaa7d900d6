// Fair skinning and hydrostatics: exact box hydrostatics, the E2-least
// interpolant is the natural spline (second derivative zero at free ends), parallel ends.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "fairlines/errors.hpp"
#include "fairlines/hydrostatics.hpp"
#include "fairlines/skinning.hpp"
#include "helpers.hpp"

namespace fairlines {
namespace {

NurbsSurface box(double L, double B, double D) {
  Eigen::MatrixXd P(6, 3);
  P << 0, B / 2, D, L, B / 2, D, 0, B / 2, 0, L, B / 2, 0, 0, 0, 0, L, 0, 0;
  Eigen::VectorXd ku(5), kv(4);
  ku << 0, 0, 0.5, 1, 1;
  kv << 0, 0, 1, 1;
  return NurbsSurface(1, 1, ku, kv, 3, 2, P);
}

TEST(Hydrostatics, BoxIsExact) {
  // A curved-free degree-1 surface: every Gauss rule is exact here, so this checks the
  // divergence-theorem bookkeeping and the draft clipping.
  const double L = 12, B = 3, D = 2, d = 0.8;
  const Hydrostatics h = hydrostatics(box(L, B, D), d);
  EXPECT_NEAR(h.volume, L * B * d, 1e-12 * L * B * d);
  EXPECT_NEAR(h.waterplane_area, L * B, 1e-12 * L * B);
  EXPECT_NEAR(h.wetted_surface, L * (2 * d + B), 1e-12 * L * B);
  EXPECT_NEAR(h.vcb, d / 2, 1e-12);
  EXPECT_NEAR(h.lcb, L / 2, 1e-12);
  EXPECT_NEAR(h.cb, 1.0, 1e-12);
  EXPECT_NEAR(h.cm, 1.0, 1e-12);
  EXPECT_NEAR(h.sac_area[3], B * d, 1e-12);
  EXPECT_THROW(hydrostatics(box(L, B, D), std::nan("")), InvalidInput);
}

NurbsCurve line_section(double x, double y0, double z0, double y1, double z1) {
  Eigen::MatrixXd P(2, 3);
  P << x, y0, z0, x, y1, z1;
  Eigen::VectorXd k(4);
  k << 0, 0, 1, 1;
  return NurbsCurve(1, k, P);
}

TEST(FairSkin, FreeEndsAreNaturalAndParallelEndsAreFlat) {
  // V-shaped sections whose breadth follows a non-polynomial law along x.
  std::vector<NurbsCurve> secs;
  for (int d = 0; d < 9; ++d) {
    const double x = 10.0 * d, b = 1.0 + std::sin(0.3 * d);
    secs.push_back(line_section(x, b, 4.0, 0.0, 0.0));
  }
  SkinOptions o;
  o.n_control = 4;
  const SkinResult r = fair_skin(secs, o);
  EXPECT_LT(r.longitudinal_max, 1e-10);
  for (double u : {0.2, 0.5, 0.9}) {
    const Eigen::MatrixXd D0 = r.surface.derivatives(u, 0.0, 2), D1 = r.surface.derivatives(u, 1.0, 2);
    // Row k*(order+1)+l: S_vv is row 2.
    EXPECT_NEAR(D0(2, 1), 0.0, 1e-9);
    EXPECT_NEAR(D1(2, 1), 0.0, 1e-9);
  }
  o.start = SkinEnd::Parallel;
  o.end = SkinEnd::Parallel;
  const SkinResult p = fair_skin(secs, o);
  for (double u : {0.2, 0.5, 0.9}) {
    EXPECT_NEAR(p.surface.derivatives(u, 0.0, 1)(1, 1), 0.0, 1e-9);
    EXPECT_NEAR(p.surface.derivatives(u, 1.0, 1)(1, 1), 0.0, 1e-9);
  }
  // Station parameterisation: x(u, v) = 80 v exactly.
  EXPECT_NEAR(p.surface.evaluate(0.37, 0.61)[0], 80 * 0.61, 1e-10);
  // E2 grows when the ends are constrained.
  EXPECT_GT(p.row_e2.sum(), r.row_e2.sum());
}

TEST(FairSkin, BadInputNamesTheProblem) {
  std::vector<NurbsCurve> one{line_section(0, 1, 1, 0, 0)};
  EXPECT_THROW(fair_skin(one), InvalidInput);
  std::vector<NurbsCurve> two{line_section(0, 1, 1, 0, 0), line_section(1, 1, 1, 0, 0)};
  SkinOptions o;
  o.c1_sections = {1};
  try {
    fair_skin(two, o);
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("c1_sections"), std::string::npos);
  }
}

}  // namespace
}  // namespace fairlines
