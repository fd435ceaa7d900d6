// Bare-hull sections on one shared knot vector (fairlines/sections.hpp): exact flats, the form
// parameters met (checked by independent dense quadrature on the evaluated curve), smooth
// dependence on the parameters where a flat ends, and infeasible data named.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "fairlines/errors.hpp"
#include "fairlines/sections.hpp"

namespace fairlines {
namespace {

constexpr double kHalfB = 16.125;

SectionSpec midship() {
  SectionSpec s;
  s.x = 122.4;
  s.z_deck = 19;
  s.y_deck = kHalfB;
  s.draft = 11;
  s.y_dwl = kHalfB;
  s.z_keel = 0;
  s.z_fos = 3.6;
  s.y_fob = 12.5;
  s.alpha_bottom = -90;
  s.half_area = 0.985 * kHalfB * 11;  // Cm 0.985
  return s;
}

SectionSpec bow() {
  SectionSpec s;
  s.x = 215;
  s.z_deck = 19;
  s.y_deck = 13.0;
  s.draft = 11;
  s.y_dwl = 6.5;
  s.z_keel = 0.5;
  s.half_area = 45.0;
  s.alpha_deck = -20;
  s.alpha_bottom = -60;
  return s;
}

/// Area below z = T between the curve and the centre line, and its first moment in z, by the
/// trapezoidal rule on 40001 points of the evaluated curve (independent of the engine's Green
/// quadrature).
std::pair<double, double> area_below(const NurbsCurve& c, double T) {
  const Eigen::MatrixXd P = c.evaluate(Eigen::VectorXd::LinSpaced(40001, 0.0, 1.0));
  double a = 0, m = 0;
  for (Eigen::Index i = 0; i + 1 < P.rows(); ++i) {
    double z0 = P(i, 2), z1 = P(i + 1, 2), y0 = P(i, 1), y1 = P(i + 1, 1);
    if (z0 > T && z1 > T) continue;
    if (z0 > T) y0 += (y1 - y0) * (z0 - T) / (z0 - z1), z0 = T;
    if (z1 > T) y1 += (y0 - y1) * (z1 - T) / (z1 - z0), z1 = T;
    a += 0.5 * (z0 - z1) * (y0 + y1);
    m += 0.5 * (z0 - z1) * (y0 * z0 + y1 * z1);
  }
  return {a, m};
}

TEST(Sections, ShareOneKnotVector) {
  const Eigen::VectorXd U = section_knot_vector(16);
  EXPECT_EQ(U.size(), 26);
  const NurbsCurve a = design_section(midship(), kHalfB), b = design_section(bow(), kHalfB);
  EXPECT_EQ(a.n_control(), 22);
  EXPECT_EQ(b.n_control(), 22);
  EXPECT_TRUE(a.knots() == U && b.knots() == U);
  EXPECT_EQ(section_straight_groups(16), (std::vector<std::pair<int, int>>{{0, 3}, {18, 21}}));
  EXPECT_THROW(section_knot_vector(7), InvalidInput);
}

TEST(Sections, MidshipFlatsAreExactAndTheAreaIsMet) {
  const SectionSpec s = midship();
  const NurbsCurve c = design_section(s, kHalfB);
  const Eigen::MatrixXd P = c.evaluate(Eigen::VectorXd::LinSpaced(20001, 0.0, 1.0));
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    EXPECT_NEAR(P(i, 0), s.x, 1e-12 * s.x);
    // Sums of B-spline basis functions times equal ordinates: exact to the last bit or two.
    if (P(i, 2) >= s.z_fos) EXPECT_NEAR(P(i, 1), kHalfB, 1e-14 * kHalfB) << P(i, 2);  // flat of side
    if (P(i, 1) <= s.y_fob) EXPECT_NEAR(P(i, 2), 0.0, 1e-14) << P(i, 1);              // flat of bottom
    EXPECT_LE(P(i, 1), kHalfB * (1 + 1e-15));
    EXPECT_GE(P(i, 1), -1e-15);
  }
  EXPECT_NEAR(area_below(c, s.draft).first, s.half_area, 1e-3);
  // Ends: deck point and keel point on the centre line.
  EXPECT_EQ(P(0, 1), kHalfB);
  EXPECT_EQ(P(0, 2), 19.0);
  EXPECT_EQ(P(P.rows() - 1, 1), 0.0);
  EXPECT_EQ(P(P.rows() - 1, 2), 0.0);
}

TEST(Sections, BowSectionMeetsDwlAnglesAndArea) {
  const SectionSpec s = bow();
  const NurbsCurve c = design_section(s, kHalfB);
  // The DWL point lies on the curve.
  const Eigen::MatrixXd P = c.evaluate(Eigen::VectorXd::LinSpaced(200001, 0.0, 1.0));
  double best = 1e9;
  for (Eigen::Index i = 0; i < P.rows(); ++i) best = std::min(best, std::hypot(P(i, 1) - s.y_dwl, P(i, 2) - s.draft));
  EXPECT_LT(best, 1e-4);
  EXPECT_NEAR(area_below(c, s.draft).first, s.half_area, 1e-3);
  // End tangents: along the deck and bottom angles (the section is wide: no fade).
  const Eigen::MatrixXd D0 = c.derivatives(0.0, 1), D1 = c.derivatives(1.0, 1);
  const double deg = std::numbers::pi / 180;
  EXPECT_NEAR(std::atan2(D0(1, 1), -D0(1, 2)) / deg, s.alpha_deck, 1e-9);
  EXPECT_NEAR(std::atan2(D1(1, 1), -D1(1, 2)) / deg, s.alpha_bottom, 1e-9);
}

TEST(Sections, CentroidHeightIsMetWhenAsked) {
  SectionSpec s = bow();
  const auto [a0, m0] = area_below(design_section(s, kHalfB), s.draft);
  s.z_centroid = m0 / a0 - 0.3;  // lower than the fairest curve's own
  const NurbsCurve c = design_section(s, kHalfB);
  const auto [a, m] = area_below(c, s.draft);
  EXPECT_NEAR(a, s.half_area, 1e-3);
  EXPECT_NEAR(m / a, s.z_centroid, 1e-4);
}

TEST(Sections, NothingJumpsWhereAFlatEnds) {
  // The flat of side shrinks to nothing and goes on "above the deck" (the fos curve's straight
  // continuation); the flat of bottom likewise through y_fob = 0. The control points must move
  // continuously: the largest step over a small parameter step stays proportional to it.
  auto max_step = [](const NurbsCurve& a, const NurbsCurve& b) {
    return (a.control_points() - b.control_points()).cwiseAbs().maxCoeff();
  };
  SectionSpec s = midship();
  s.half_area = 120;
  s.y_dwl = 12.0;
  s.y_fob = 10.0;
  s.z_fos = 17.0;
  double worst = 0;
  const double h = 1e-3;
  NurbsCurve prev = design_section(s, kHalfB);
  for (double zf = 17.0 + h; zf <= 21.0; zf += h) {
    s.z_fos = zf;
    const NurbsCurve c = design_section(s, kHalfB);
    worst = std::max(worst, max_step(prev, c) / h);
    prev = c;
  }
  EXPECT_LT(worst, 20.0);  // a jump of 1 cm would show as 10 / h = 1e4
  s = midship();
  s.half_area = 120;
  s.z_fos = 11.0;
  s.y_fob = 1.0;
  worst = 0;
  prev = design_section(s, kHalfB);
  for (double yf = 1.0 - h; yf >= -1.0; yf -= h) {
    s.y_fob = yf;
    const NurbsCurve c = design_section(s, kHalfB);
    worst = std::max(worst, max_step(prev, c) / h);
    prev = c;
  }
  EXPECT_LT(worst, 20.0);
}

TEST(Sections, DepartureFromTheFlatFollowsTheGivenRate) {
  // The flat of side ends at the DWL: with a departure rate K the section loses K d^3 of
  // breadth at depth d below the flat's end.
  SectionSpec s = midship();
  s.z_fos = s.draft;
  s.half_area = 150;
  s.flat_departure = 2e-3;
  const NurbsCurve c = design_section(s, kHalfB);
  const Eigen::MatrixXd P = c.evaluate(Eigen::VectorXd::LinSpaced(400001, 0.0, 1.0));
  double z_end = 0;  // lowest point still on the flat
  for (Eigen::Index i = 0; i < P.rows() && P(i, 1) >= kHalfB * (1 - 1e-14); ++i) z_end = P(i, 2);
  for (double d : {0.05, 0.1}) {
    Eigen::Index i = 0;
    while (P(i, 2) > z_end - d) ++i;
    const double k = (kHalfB - P(i, 1)) / std::pow(z_end - P(i, 2), 3);
    EXPECT_NEAR(k, s.flat_departure, 0.15 * s.flat_departure) << d;
  }
}

TEST(Sections, FlatsAreStraightWhateverTheAngleCurvesSay) {
  // Under a flat of side the zone is vertical and under a flat of bottom horizontal: the deck
  // and bottom angles apply where there is no flat.
  SectionSpec s = midship();
  const NurbsCurve a = design_section(s, kHalfB);
  s.alpha_deck = -10;
  s.alpha_bottom = -80;
  const NurbsCurve b = design_section(s, kHalfB);
  EXPECT_EQ((a.control_points() - b.control_points()).cwiseAbs().maxCoeff(), 0.0);
}

TEST(Sections, StemIsTheCentreLine) {
  SectionSpec s = bow();
  s.y_deck = s.y_dwl = 0;
  s.half_area = 0;
  s.z_keel = 4;
  const NurbsCurve c = design_section(s, kHalfB);
  EXPECT_EQ(c.control_points().col(1).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(c.control_points()(0, 2), 19.0);
  EXPECT_EQ(c.control_points()(c.n_control() - 1, 2), 4.0);
}

TEST(Sections, ContradictionsAreNamed) {
  auto message = [](const SectionSpec& s) -> std::string {
    try {
      design_section(s, kHalfB);
    } catch (const InfeasibleFormParameters& e) {
      return e.what();
    }
    return "";
  };
  // A section that would bulge past B/2 is kept inside: control points pinned to B/2, the
  // area still met.
  SectionSpec s = bow();
  s.y_deck = kHalfB;
  s.alpha_deck = 0;
  s.y_dwl = 15.0;
  s.half_area = 40;
  const NurbsCurve held = design_section(s, kHalfB);
  EXPECT_LE(held.control_points().col(1).maxCoeff(), kHalfB * (1 + 1e-12));
  EXPECT_GE(held.control_points().col(1).minCoeff(), -1e-12);
  EXPECT_NEAR(area_below(held, s.draft).first, s.half_area, 1e-3);
  // Almost the whole box B/2 x (T - keel) below the DWL: no section fits (it would have to
  // leave 0 <= y <= B/2 or fold back); the station is named.
  s = bow();
  s.half_area = 0.999 * kHalfB * (s.draft - s.z_keel);
  EXPECT_NE(message(s).find("section at x = 215 m"), std::string::npos) << message(s);
  s = midship();
  s.y_dwl = 15;  // the DWL leaves B/2 while the flat side still reaches below it
  EXPECT_NE(message(s).find("DWL half-breadth"), std::string::npos) << message(s);
  s = midship();
  s.half_area = std::nan("");
  EXPECT_THROW(design_section(s, kHalfB), InvalidInput);
  s = midship();
  s.degree = 2;
  EXPECT_THROW(design_section(s, kHalfB), InvalidInput);
}

}  // namespace
}  // namespace fairlines
