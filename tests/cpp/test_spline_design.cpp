// Fairest spline functions (fairlines/spline_design.hpp) against exact truths: straight lines,
// flat parts, integrals by dense independent quadrature, bounds and signs at dense samples.
#include <cmath>

#include <gtest/gtest.h>

#include "fairlines/errors.hpp"
#include "fairlines/spline_design.hpp"

namespace fairlines {
namespace {

double f(const NurbsCurve& c, double x, int d = 0) { return c.derivatives(x, d)(d, 0); }

/// Simpson's rule on 20 000 intervals: independent of the designer's Gauss rows.
template <typename F>
double simpson(F&& g, double a, double b) {
  const int m = 20000;
  const double h = (b - a) / m;
  double s = g(a) + g(b);
  for (int i = 1; i < m; ++i) s += (i % 2 ? 4.0 : 2.0) * g(a + i * h);
  return s * h / 3.0;
}

SplineDesignRequest base(double x0, double x1, int spans, std::vector<double> breaks = {}) {
  SplineDesignRequest r;
  r.name = "test";
  r.knots = spline_function_knots(x0, x1, breaks, spans);
  return r;
}

TEST(SplineDesign, EndValuesAloneGiveTheStraightLine) {
  SplineDesignRequest r = base(2.0, 12.0, 9);
  r.conditions = {{2.0, 0, 1.0, "yB"}, {12.0, 0, 6.0, "yE"}};
  const NurbsCurve c = design_spline_function(r);
  for (double x = 2.0; x <= 12.0; x += 0.37) EXPECT_NEAR(f(c, x), 1.0 + 0.5 * (x - 2.0), 1e-10);
}

TEST(SplineDesign, FlatPartIsExactAndLeftWithG2) {
  SplineDesignRequest r = base(0.0, 100.0, 14, {30.0, 60.0});
  r.flats = {{30.0, 60.0, 16.0, "parallel part"}};
  r.conditions = {{0.0, 0, 5.0, "yB"}, {100.0, 0, 0.0, "yE"}};
  const NurbsCurve c = design_spline_function(r);
  for (double x = 30.0; x <= 60.0; x += 1.5) EXPECT_NEAR(f(c, x), 16.0, 1e-12);
  for (double x : {30.0, 60.0}) {
    EXPECT_NEAR(f(c, x, 1), 0.0, 1e-12);
    EXPECT_NEAR(f(c, x, 2), 0.0, 1e-12);
  }
  EXPECT_NEAR(f(c, 0.0), 5.0, 1e-12);
  EXPECT_NEAR(f(c, 100.0), 0.0, 1e-12);
}

TEST(SplineDesign, WeightedAreaAndCentroidMet) {
  // A weight w(x) = 1 + x / 50 given as a linear spline function.
  Eigen::MatrixXd wc(2, 1);
  wc << 1.0, 3.0;
  Eigen::VectorXd wk(4);
  wk << 0.0, 0.0, 100.0, 100.0;
  const NurbsCurve w(1, wk, wc);
  SplineDesignRequest r = base(0.0, 100.0, 12);
  r.conditions = {{0.0, 0, 0.0, "yB"}, {100.0, 0, 0.0, "yE"}};
  SplineIntegral area{0.0, 100.0, 0, {w}, 900.0, std::nan(""), "volume"};
  SplineIntegral cen{0.0, 100.0, 0, {w}, 0.0, 55.0, "lcb"};
  r.integrals = {area, cen};
  const NurbsCurve c = design_spline_function(r);
  auto ww = [](double x) { return 1.0 + x / 50.0; };
  const double A = simpson([&](double x) { return f(c, x) * ww(x); }, 0.0, 100.0);
  const double M = simpson([&](double x) { return x * f(c, x) * ww(x); }, 0.0, 100.0);
  EXPECT_NEAR(A, 900.0, 1e-7);
  EXPECT_NEAR(M / A, 55.0, 1e-8);
}

TEST(SplineDesign, BoundsAndConcavityHoldEverywhere) {
  SplineDesignRequest r = base(0.0, 10.0, 10);
  r.conditions = {{0.0, 0, 0.0, "yB"}, {10.0, 0, 0.0, "yE"}};
  r.integrals = {{0.0, 10.0, 0, {}, 70.0, std::nan(""), "Area"}};  // more than a fair bump below 8 holds
  r.bounds = {{0.0, 10.0, 0.0, 8.0, "0 <= y <= 8"}};
  r.shapes = {{0.0, 10.0, 2, -1, "concave"}};
  const NurbsCurve c = design_spline_function(r);
  for (double x = 0.0; x <= 10.0; x += 0.01) {
    EXPECT_LE(f(c, x), 8.0 + 1e-9);
    EXPECT_GE(f(c, x), -1e-9);
    EXPECT_LE(f(c, x, 2), 1e-8);
  }
  EXPECT_NEAR(simpson([&](double x) { return f(c, x); }, 0.0, 10.0), 70.0, 1e-7);
}

TEST(SplineDesign, ContradictionNamesTheConditions) {
  SplineDesignRequest r = base(0.0, 10.0, 8);
  r.conditions = {{0.0, 0, 0.0, "yB"}, {10.0, 0, 0.0, "yE"}};
  r.integrals = {{0.0, 10.0, 0, {}, 90.0, std::nan(""), "Area"}};
  r.bounds = {{0.0, 10.0, 0.0, 8.0, "y <= B/2"}};
  try {
    design_spline_function(r);
    FAIL() << "expected InfeasibleFormParameters";
  } catch (const InfeasibleFormParameters& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("Area"), std::string::npos) << msg;
    EXPECT_NE(msg.find("y <= B/2"), std::string::npos) << msg;
  }
}

TEST(SplineDesign, BadInputThrows) {
  SplineDesignRequest r = base(0.0, 10.0, 8);
  r.conditions = {{11.0, 0, 0.0, "yE"}};
  EXPECT_THROW(design_spline_function(r), InvalidInput);
  r.conditions = {{5.0, 4, 0.0, "y''''"}};
  EXPECT_THROW(design_spline_function(r), InvalidInput);
  r.conditions.clear();
  r.knots[1] = 0.5;  // not clamped
  EXPECT_THROW(design_spline_function(r), InvalidInput);
}

}  // namespace
}  // namespace fairlines
