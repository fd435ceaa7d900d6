// Linear form-parameter curves (the basic curves): parameters met exactly (checked by
// independent dense trapezoidal quadrature), conflicts reported, bounds respected. Sections:
// test_sections.cpp.
#include <cmath>

#include <gtest/gtest.h>

#include "fairlines/errors.hpp"
#include "fairlines/hull.hpp"

namespace fairlines {
namespace {

/// Area and first moment of y dx along a 2-D curve by the trapezoidal rule on 20001 points.
std::pair<double, double> trapezoid_area(const NurbsCurve& c) {
  const Eigen::MatrixXd P = c.evaluate(Eigen::VectorXd::LinSpaced(20001, 0.0, 1.0));
  double a = 0, m = 0;
  for (Eigen::Index i = 0; i + 1 < P.rows(); ++i) {
    const double dx = P(i + 1, 0) - P(i, 0);
    a += 0.5 * dx * (P(i, 1) + P(i + 1, 1));
    m += 0.5 * dx * (P(i, 0) * P(i, 1) + P(i + 1, 0) * P(i + 1, 1));
  }
  return {a, m};
}

TEST(LinearFormCurve, MeetsEndsAnglesAreaAndCentroid) {
  LinearFormRequest r;
  r.abscissae = Eigen::VectorXd::LinSpaced(8, 0.0, 1.0);
  r.yB = 1.0;
  r.yE = 0.2;
  r.slopeB = std::tan(-5.0 * M_PI / 180);
  r.slopeE = std::tan(-60.0 * M_PI / 180);
  r.area = 0.62;
  r.xC = 0.43;
  const NurbsCurve c = design_linear_form_curve(r);
  const Eigen::MatrixXd D0 = c.derivatives(0.0, 1), D1 = c.derivatives(1.0, 1);
  EXPECT_NEAR(D0(0, 1), 1.0, 1e-12);
  EXPECT_NEAR(D1(0, 1), 0.2, 1e-12);
  EXPECT_NEAR(D0(1, 1) / D0(1, 0), r.slopeB, 1e-10);
  EXPECT_NEAR(D1(1, 1) / D1(1, 0), r.slopeE, 1e-10);
  const auto [a, m] = trapezoid_area(c);
  EXPECT_NEAR(a, 0.62, 1e-7);
  EXPECT_NEAR(m / a, 0.43, 1e-7);
}

TEST(LinearFormCurve, ContradictionsAreInfeasibleAndBoundsHold) {
  LinearFormRequest r;
  r.name = "test curve";
  r.abscissae = Eigen::VectorXd::LinSpaced(6, 0.0, 1.0);
  r.yB = 0.0;
  r.yE = 0.0;
  r.points.emplace_back(0.5, 1.0);
  r.points.emplace_back(0.5, 2.0);  // the same x twice with different y
  try {
    design_linear_form_curve(r);
    FAIL() << "expected InfeasibleFormParameters";
  } catch (const InfeasibleFormParameters& e) {
    EXPECT_NE(std::string(e.what()).find("test curve"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("points[1]"), std::string::npos);
  }
  // A large area under an upper bound: the curve flattens against the bound instead of
  // overshooting it.
  LinearFormRequest b;
  b.abscissae = Eigen::VectorXd::LinSpaced(12, 0.0, 1.0);
  b.yB = 1.0;
  b.yE = 0.0;
  b.slopeB = 0.0;
  b.area = 0.8;
  b.y_upper = 1.0;
  b.y_lower = 0.0;
  const NurbsCurve c = design_linear_form_curve(b);
  EXPECT_LE(c.control_points().col(1).maxCoeff(), 1.0 + 1e-12);
  EXPECT_NEAR(trapezoid_area(c).first, 0.8, 1e-7);
  b.area = 1.2;  // more than the unit box allows
  EXPECT_THROW(design_linear_form_curve(b), InfeasibleFormParameters);
}

}  // namespace
}  // namespace fairlines
