// Fairest spline functions (fairlines/spline_design.hpp) against exact truths: straight lines,
// flat parts, integrals by dense independent quadrature, bounds and signs at dense samples; the
// integrals of products of spline functions against the Beta function and dense Simpson sums.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "fairlines/errors.hpp"
#include "fairlines/spline_design.hpp"
#include "helpers.hpp"

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

/// Round-off of the exact integrals below (values of order 0.01 .. 200, a few dozen Gauss terms).
constexpr double kRoundOff = 1e-15;
/// Dense Simpson (2 000 intervals per smooth piece) against the exact integral: its error
/// h^4 max|g''''| / 180 is far below 1e-12 for these unit-range random splines; 1e-10 relative
/// lies well above it and far below what a lost Gauss point or a missed knot costs (1e-4 or more).
constexpr double kSimpsonTolerance = 1e-10;

/// A spline function of x on [x0, x1] from its Bernstein (single-span) coefficients.
NurbsCurve bezier(double x0, double x1, const std::vector<double>& coefficients) {
  const int p = static_cast<int>(coefficients.size()) - 1;
  Eigen::VectorXd k(2 * (p + 1));
  k << Eigen::VectorXd::Constant(p + 1, x0), Eigen::VectorXd::Constant(p + 1, x1);
  return NurbsCurve(p, k, Eigen::Map<const Eigen::VectorXd>(coefficients.data(), p + 1));
}

/// Simpson's rule on 2 000 intervals of every piece between `breaks` (sorted): the integrand is
/// smooth on each piece, so this converges as h^4 without the Gauss rules' help.
template <typename F>
double piecewise_simpson(F&& g, const std::vector<double>& breaks) {
  double s = 0.0;
  for (std::size_t i = 0; i + 1 < breaks.size(); ++i) {
    const int m = 2000;
    const double a = breaks[i], h = (breaks[i + 1] - a) / m;
    double t = g(a) + g(breaks[i + 1]);
    for (int j = 1; j < m; ++j) t += (j % 2 ? 4.0 : 2.0) * g(a + j * h);
    s += t * h / 3.0;
  }
  return s;
}

TEST(SplineProductIntegral, BetaIntegralsOfRefinedMonomials) {
  // x and (1 - x)^2 on [0, 1], given with interior knots so that the rule works piece by piece:
  // int_0^1 x^(power + 1) (1 - x)^2 dx = B(power + 2, 3) = 2 (power + 1)! / (power + 4)!.
  Eigen::VectorXd extra(3);
  extra << 0.25, 0.5, 0.8;
  const NurbsCurve x = bezier(0.0, 1.0, {0.0, 1.0}).refine_knots(extra);
  Eigen::VectorXd other(2);
  other << 0.1, 0.65;
  const NurbsCurve one_minus_sq = bezier(0.0, 1.0, {1.0, 0.0, 0.0}).refine_knots(other);
  for (int power = 0; power <= 4; ++power) {
    double beta = 2.0;
    for (int k = power + 2; k <= power + 4; ++k) beta /= k;  // 2 (power + 1)! / (power + 4)!
    EXPECT_NEAR(spline_product_integral({x, one_minus_sq}, 0.0, 1.0, power), beta, kRoundOff) << "power " << power;
  }
  // No factors: int_2^5 x^3 dx; one factor over part of its domain: int_0^0.5 x dx.
  EXPECT_NEAR(spline_product_integral({}, 2.0, 5.0, 3), (625.0 - 16.0) / 4.0, 200 * kRoundOff);
  EXPECT_NEAR(spline_product_integral({x}, 0.0, 0.5, 0), 0.125, kRoundOff);
  EXPECT_EQ(spline_product_integral({x}, 0.3, 0.3, 1), 0.0);
}

TEST(SplineProductIntegral, RandomSplineProductsMatchDenseSimpson) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 6; ++trial) {
    std::vector<NurbsCurve> factors;
    std::vector<double> breaks{0.0, 1.0};
    for (int k = 0; k < 3; ++k) {
      factors.push_back(test::random_curve(7 + k, 2 + (trial + k) % 3, 1, false, rng));
      const Eigen::VectorXd& K = factors.back().knots();
      breaks.insert(breaks.end(), K.data(), K.data() + K.size());
    }
    std::sort(breaks.begin(), breaks.end());
    breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
    const int power = trial % 2;
    auto g = [&](double t) {
      double v = std::pow(t, power);
      for (const NurbsCurve& c : factors) v *= c.evaluate(t)[0];
      return v;
    };
    const double truth = piecewise_simpson(g, breaks);
    EXPECT_NEAR(spline_product_integral(factors, 0.0, 1.0, power), truth, kSimpsonTolerance * (1.0 + std::abs(truth))) << "trial " << trial;
  }
}

TEST(SplineProductIntegral, MeasuresTheDesignedIntegral) {
  // A designed curve's weighted area and centroid conditions, read back through the product
  // integral (weight: a quadratic bump and a linear ramp, both over part of the range).
  const std::vector<NurbsCurve> weights{bezier(0.0, 60.0, {1.0, 4.0, 1.0}), bezier(0.0, 60.0, {0.5, 2.0})};
  SplineDesignRequest r = base(0.0, 60.0, 10, {20.0});
  r.conditions = {{0.0, 0, 1.0, "yB"}, {60.0, 0, 0.0, "yE"}};
  r.integrals = {{0.0, 60.0, 0, weights, 2500.0, std::nan(""), "volume"}, {0.0, 60.0, 0, weights, 0.0, 27.0, "lcb"}};
  const NurbsCurve c = design_spline_function(r);
  std::vector<NurbsCurve> product = weights;
  product.push_back(c);
  const double area = spline_product_integral(product, 0.0, 60.0, 0);
  // The QP meets its equality rows to round-off of the 2 500 (1e-9 leaves room for the solver).
  EXPECT_NEAR(area, 2500.0, 1e-9);
  EXPECT_NEAR(spline_product_integral(product, 0.0, 60.0, 1) / area, 27.0, 1e-10);
}

TEST(SplineProductIntegral, RefusesWhatItCannotIntegrateExactly) {
  const NurbsCurve x = bezier(0.0, 1.0, {0.0, 1.0});
  EXPECT_THROW(spline_product_integral({x}, 0.6, 0.4, 0), InvalidInput);       // from > to
  EXPECT_THROW(spline_product_integral({x}, 0.0, 1.1, 0), InvalidInput);       // beyond the domain
  EXPECT_NO_THROW(spline_product_integral({x}, -1e-12, 1.0 + 1e-12, 0));       // within kDomainTolerance
  EXPECT_THROW(spline_product_integral({x}, 0.0, 1.0, -1), InvalidInput);      // negative power
  EXPECT_THROW(spline_product_integral({x}, 0.0, 1.0, kMaxProductDegree), InvalidInput);  // degree 64
  Eigen::VectorXd k(4);
  k << 0.0, 0.0, 1.0, 1.0;
  Eigen::MatrixXd P(2, 1);
  P << 0.0, 1.0;
  Eigen::VectorXd wts(2);
  wts << 1.0, 2.0;
  EXPECT_THROW(spline_product_integral({NurbsCurve(1, k, P, wts)}, 0.0, 1.0, 0), InvalidInput);  // rational
  EXPECT_THROW(spline_product_integral({NurbsCurve(1, k, Eigen::MatrixXd::Ones(2, 2))}, 0.0, 1.0, 0), InvalidInput);  // 2-D
}

}  // namespace
}  // namespace fairlines
