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

TEST(Hydrostatics, ClipsTheGirthLinesOfABargeWhoseRowsClimbTheWholeDepth) {
  // A degree-1 barge whose keel rises to the deck over e at both ends: its keel's and bilge's
  // rows (v lines) span the whole depth, more than its end sections (u lines) do. The waterline
  // runs along the bilge's row over the midbody, so only clipping the u lines is exact. At
  // d = D/2 the waterline ends on the columns x = e/2 and L - e/2: exact at any Gauss count.
  const double L = 60, B = 12, D = 8, e = 10, d = D / 2;
  const double xs[6] = {0, e / 2, e, L - e, L - e / 2, L}, zk[6] = {D, d, 0, 0, d, D};
  Eigen::MatrixXd P(18, 3);
  for (int j = 0; j < 6; ++j) {
    P.row(j) << xs[j], B / 2, D;
    P.row(6 + j) << xs[j], B / 2, zk[j];
    P.row(12 + j) << xs[j], 0, zk[j];
  }
  Eigen::VectorXd ku(5), kv(8);
  ku << 0, 0, 0.5, 1, 1;
  kv << 0, 0, 0.1, 0.2, 0.8, 0.9, 1, 1;
  const NurbsSurface barge(1, 1, ku, kv, 3, 6, P);
  for (int gauss : {2, 4, 8}) {
    HydrostaticsOptions o;
    o.gauss = gauss;
    const Hydrostatics h = hydrostatics(barge, d, o);
    EXPECT_NEAR(h.volume, B * (d * (L - 2 * e) + d * e / 2), 1e-12 * L * B * D) << gauss;
    EXPECT_NEAR(h.waterplane_area, (L - e) * B, 1e-12 * L * B) << gauss;
    EXPECT_NEAR(h.lcb, L / 2, 1e-12 * L) << gauss;
  }
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

// fair_skin(sections, o) throws InvalidInput whose message names `needle`.
void expect_skin_refused(const std::vector<NurbsCurve>& sections, const SkinOptions& o, const std::string& needle) {
  try {
    fair_skin(sections, o);
    FAIL() << "expected InvalidInput naming " << needle;
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

TEST(FairSkin, BadInputNamesTheProblem) {
  std::vector<NurbsCurve> one{line_section(0, 1, 1, 0, 0)};
  EXPECT_THROW(fair_skin(one), InvalidInput);
  std::vector<NurbsCurve> two{line_section(0, 1, 1, 0, 0), line_section(1, 1, 1, 0, 0)};
  SkinOptions o;
  o.c1_sections = {1};
  expect_skin_refused(two, o, "c1_sections");
}

// A C0 section: a breadth that grows linearly to x = 20 and stays constant forward of it is met
// exactly on both sides (straight aft, constant forward), and a not-a-knot start next to it is
// refused naming the end condition.
TEST(FairSkin, C0SectionKeepsAKnuckleExactly) {
  std::vector<NurbsCurve> secs;
  for (int d = 0; d <= 8; ++d) {
    const double x = 5.0 * d, w = 0.5 + 0.5 * std::min(1.0, x / 20.0);
    secs.push_back(line_section(x, w, 1, 0, 0));
  }
  SkinOptions o;
  o.c0_sections = {4};
  const SkinResult r = fair_skin(secs, o);
  for (double v : {0.05, 0.3, 0.45, 0.55, 0.8, 0.97}) {
    const double x = 40.0 * v, w = 0.5 + 0.5 * std::min(1.0, x / 20.0);
    EXPECT_NEAR(r.surface.evaluate(0.0, v)[1], w, 1e-10) << v;
  }
  o.start = SkinEnd::NotAKnot;
  o.c0_sections = {1};
  expect_skin_refused(secs, o, "not_a_knot");
}

// A bottom row on the centre plane at x 20 and 22.5 m leaving it as 0.05 (x - x0)^2 either side:
// its least-E2 interpolant dips 2.9 cm across the plane; kept off it, every sampled point of
// the skin has y >= 0 and the top row is untouched.
TEST(FairSkin, YNonnegativeKeepsTheSkinOffTheCentrePlane) {
  std::vector<NurbsCurve> secs;
  for (int d = 0; d <= 16; ++d) {
    const double x = 2.5 * d;
    const double y = x > 22.5 ? 0.05 * (x - 22.5) * (x - 22.5) : x < 20.0 ? 0.05 * (x - 20.0) * (x - 20.0) : 0.0;
    secs.push_back(line_section(x, 5.0, 1.0, y, 0.0));
  }
  SkinOptions o;
  o.degree_u = 1;
  o.params = SkinParams::Station;
  const SkinResult free = fair_skin(secs, o);
  o.y_nonnegative = true;
  const SkinResult kept = fair_skin(secs, o);
  double free_min = 0, kept_min = 0;
  for (int j = 0; j <= 800; ++j) {
    free_min = std::min(free_min, free.surface.evaluate(1.0, j / 800.0)[1]);
    kept_min = std::min(kept_min, kept.surface.evaluate(1.0, j / 800.0)[1]);
  }
  EXPECT_LT(free_min, -0.02);
  EXPECT_GE(kept_min, 0.0);
  EXPECT_EQ(kept.centre_plane_columns, 1);
  EXPECT_GT(kept.centre_plane_miss, 0.0);
  EXPECT_LE(kept.centre_plane_miss, kCentrePlaneMaxMiss * 40.0);
  for (int j = 0; j <= 20; ++j) EXPECT_EQ(kept.surface.evaluate(0.0, j / 20.0)[1], free.surface.evaluate(0.0, j / 20.0)[1]);
}

// Waterplane moments, metacentres and trim on a box barge, whose values are closed-form:
// I_T = L B^3 / 12, I_L = B L^3 / 12, KMt = B^2 / 12T + T / 2, and under a trim t (linear
// draft) LCB = L/2 - t L / (12 T).
constexpr double kL = 100.0, kB = 20.0, kD = 10.0;

TEST(Waterplane, BoxBargeMomentsAndMetacentres) {
  for (double T : {1.0, 5.0, 10.0}) {
    const Hydrostatics h = hydrostatics(box(kL, kB, kD), T);
    EXPECT_NEAR(h.inertia_t, kL * kB * kB * kB / 12, 1e-12 * kL * kB * kB * kB);
    EXPECT_NEAR(h.inertia_l, kB * kL * kL * kL / 12, 1e-12 * kB * kL * kL * kL);
    EXPECT_NEAR(h.kmt, kB * kB / (12 * T) + T / 2, 1e-12 * h.kmt);
    EXPECT_NEAR(h.tpc, 1.025 * kL * kB / 100, 1e-12 * h.tpc);
  }
}

TEST(Waterplane, TrimByTheSternIsALinearDraft) {
  HydrostaticsOptions o;
  o.trim = 1.0;
  o.trim_length = kL;
  const Hydrostatics h = hydrostatics(box(kL, kB, kD), 5.0, o);
  EXPECT_NEAR(h.volume, kL * kB * 5.0, 1e-9);
  EXPECT_NEAR(h.lcb, kL / 2 - o.trim * kL / (12 * 5.0), 1e-10);
}

TEST(Waterplane, WaterplaneAboveTheTopIsRefused) {
  EXPECT_THROW(hydrostatics(box(kL, kB, kD), kD + 0.5), InvalidInput);
  HydrostaticsOptions o;
  o.trim = 2.0;  // the AP end would go under
  o.trim_length = kL;
  EXPECT_THROW(hydrostatics(box(kL, kB, kD), kD - 0.5, o), InvalidInput);
  o.trim_length = 0;
  EXPECT_THROW(hydrostatics(box(kL, kB, kD), 5.0, o), InvalidInput);
}

}  // namespace
}  // namespace fairlines

namespace fairlines {
namespace {

/// q cubic sections on one knot vector (6 control points): the same shape for the first four
/// stations (a parallel body), then shrinking quadratically in y. Rows 0..3 lie on one vertical
/// segment at fractions 0, 1/3, 2/3, 1 (a zone): row 0 fixed at the deck, row 3 rising.
std::vector<NurbsCurve> body_sections(int q) {
  std::vector<NurbsCurve> secs;
  const Eigen::VectorXd U = (Eigen::VectorXd(10) << 0, 0, 0, 0, 1.0 / 3, 2.0 / 3, 1, 1, 1, 1).finished();
  for (int d = 0; d < q; ++d) {
    const double t = std::max(0, d - 3), shrink = 1.0 - 0.01 * t * t, zf = 8.0 - 0.3 * t;
    Eigen::MatrixXd P(6, 3);
    P << 0, 5, 10, 0, 5, 10 - (10 - zf) / 3, 0, 5, 10 - 2 * (10 - zf) / 3, 0, 5, zf, 0, 4 * shrink, 2, 0, 0, 0;
    P.col(0).setConstant(10.0 * d);
    secs.emplace_back(3, U, P);
  }
  return secs;
}

TEST(FairSkin, SectionsOnOneKnotVectorAreUsedExactlyAndRunsAreHeld) {
  const int q = 12;
  const std::vector<NurbsCurve> secs = body_sections(q);
  SkinOptions o;
  o.e2 = 0.0;
  o.e3 = 1.0;
  o.straight_groups = {{0, 3}};
  const SkinResult r = fair_skin(secs, o);
  EXPECT_EQ(r.section_fit_max, 0.0);
  EXPECT_GT(r.held_columns, 0);
  const NurbsSurface& s = r.surface;
  EXPECT_TRUE(s.knots_u() == secs[0].knots());
  // Every station's iso-curve is its section, control point for control point.
  for (int d = 0; d < q; ++d) {
    const NurbsCurve iso = s.iso_curve(Direction::V, r.section_params[d]);
    EXPECT_LT((iso.control_points() - secs[d].control_points()).cwiseAbs().maxCoeff(), 1e-10) << d;
  }
  // The parallel body (stations 0..3) is exactly the first section, between the stations too.
  const Eigen::VectorXd us = Eigen::VectorXd::LinSpaced(41, 0.0, 1.0);
  const Eigen::MatrixXd first = secs[0].evaluate(us);
  for (double v : {0.03, 0.11, 0.2, 0.27}) {
    const Eigen::MatrixXd p = s.evaluate(us, Eigen::VectorXd::Constant(41, v));
    EXPECT_LT((p.rightCols(2) - first.rightCols(2)).cwiseAbs().maxCoeff(), 1e-13) << v;
  }
  // An extra knot in the interval after the run's last station.
  const Eigen::VectorXd& kv = s.knots_v();
  const double v3 = r.section_params[3], v4 = r.section_params[4];
  EXPECT_TRUE(((kv.array() > v3) && (kv.array() < v4)).any());
  // The zone stays straight between the stations: rows 1, 2 on the segment of rows 0 and 3.
  for (double v : {0.31, 0.47, 0.66, 0.93}) {
    const NurbsCurve iso = s.iso_curve(Direction::V, v);
    const Eigen::RowVector3d a = iso.control_points().row(0), b = iso.control_points().row(3);
    for (int i : {1, 2}) {
      const Eigen::RowVector3d p = iso.control_points().row(i);
      const double frac = i / 3.0;
      EXPECT_LT((p - (a + frac * (b - a))).norm(), 1e-12) << v;
    }
  }
  // Without holding the runs the interpolant rings over the parallel body.
  o.hold_runs = false;
  const SkinResult free = fair_skin(secs, o);
  const Eigen::MatrixXd p = free.surface.evaluate(us, Eigen::VectorXd::Constant(41, 0.2));
  EXPECT_GT((p.rightCols(2) - first.rightCols(2)).cwiseAbs().maxCoeff(), 1e-5);
  // A group whose rows are not at fixed fractions is refused.
  o.straight_groups = {{2, 5}};
  EXPECT_THROW(fair_skin(secs, o), InvalidInput);
}

}  // namespace
}  // namespace fairlines
