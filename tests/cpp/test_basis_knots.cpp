#include <random>

#include <gtest/gtest.h>

#include "fairlines/basis.hpp"
#include "fairlines/errors.hpp"
#include "fairlines/knots.hpp"
#include "helpers.hpp"

using namespace fairlines;

TEST(Basis, PartitionOfUnityAndNonNegativity) {
  std::mt19937 rng(1);
  for (int p = 1; p <= 5; ++p) {
    const int n = p + 7;
    const Eigen::VectorXd U = test::random_clamped_knots(n, p, rng);
    std::vector<double> N(p + 1);
    for (int k = 0; k <= 1000; ++k) {
      const double t = k / 1000.0;
      const int span = find_span(p, U, t);
      ASSERT_GE(span, p);
      ASSERT_LE(span, n - 1);
      basis_functions(span, t, p, U, N.data());
      double sum = 0.0;
      for (double x : N) {
        EXPECT_GE(x, -1e-15);
        sum += x;
      }
      EXPECT_NEAR(sum, 1.0, 1e-14) << "p=" << p << " t=" << t;
    }
  }
}

TEST(Basis, DerivativesMatchFiniteDifferences) {
  std::mt19937 rng(2);
  const int p = 4, n = 11;
  const Eigen::VectorXd U = test::random_clamped_knots(n, p, rng);
  Eigen::MatrixXd d(3, p + 1), dp(3, p + 1), dm(3, p + 1);
  for (double t : {0.13, 0.37, 0.61, 0.89}) {
    const int span = find_span(p, U, t);
    const double h = 1e-6;
    if (find_span(p, U, t + h) != span || find_span(p, U, t - h) != span) continue;
    basis_derivatives(span, t, p, 2, U, d);
    basis_derivatives(span, t + h, p, 2, U, dp);
    basis_derivatives(span, t - h, p, 2, U, dm);
    for (int j = 0; j <= p; ++j) {
      EXPECT_NEAR(d(1, j), (dp(0, j) - dm(0, j)) / (2 * h), 1e-5 * (1 + std::abs(d(1, j))));
      EXPECT_NEAR(d(2, j), (dp(1, j) - dm(1, j)) / (2 * h), 1e-4 * (1 + std::abs(d(2, j))));
    }
    // Derivatives of a partition of unity sum to zero.
    EXPECT_NEAR(d.row(1).sum(), 0.0, 1e-10);
    EXPECT_NEAR(d.row(2).sum(), 0.0, 1e-8);
  }
}

TEST(Knots, ValidationNamesTheProblem) {
  Eigen::VectorXd U(8);
  U << 0, 0, 0, 0, 1, 1, 1, 1;
  EXPECT_NO_THROW(validate_knots(U, 3, 4));
  EXPECT_THROW(validate_knots(U, 3, 5), InvalidInput);  // wrong count
  Eigen::VectorXd D = U;
  D[4] = 0.5;
  D[3] = 0.7;  // decreasing
  try {
    validate_knots(D, 3, 4);
    FAIL() << "decreasing knots accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("decrease at index"), std::string::npos) << e.what();
  }
  Eigen::VectorXd N = U;
  N[2] = std::nan("");
  EXPECT_THROW(validate_knots(N, 3, 4), InvalidInput);
  EXPECT_THROW(validate_knots(U, 0, 4), InvalidInput);
}

TEST(Knots, ClampedUnclampedAveragedHartleyJudd) {
  const Eigen::VectorXd c = clamped_uniform_knots(7, 3);
  ASSERT_EQ(c.size(), 11);
  EXPECT_DOUBLE_EQ(c[3], 0.0);
  EXPECT_DOUBLE_EQ(c[4], 0.25);
  EXPECT_DOUBLE_EQ(c[7], 1.0);
  const Eigen::VectorXd u = unclamped_uniform_knots(7, 3);
  EXPECT_DOUBLE_EQ(u[3], 0.0);
  EXPECT_DOUBLE_EQ(u[7], 1.0);
  EXPECT_NEAR(u[1] - u[0], 0.25, 1e-15);

  // Averaging for interpolation (P&T eq. 9.8): interior knot j = mean of p parameters.
  Eigen::VectorXd prm(6);
  prm << 0.0, 0.1, 0.3, 0.6, 0.8, 1.0;
  const Eigen::VectorXd a = averaged_knots(prm, 3, 6);
  EXPECT_NEAR(a[4], (0.1 + 0.3 + 0.6) / 3, 1e-15);
  EXPECT_NEAR(a[5], (0.3 + 0.6 + 0.8) / 3, 1e-15);
  // Approximation rule: every knot span holds at least one parameter.
  const Eigen::VectorXd many = Eigen::VectorXd::LinSpaced(50, 0.0, 1.0);
  const Eigen::VectorXd b = averaged_knots(many, 3, 12);
  for (int i = 3; i < 12; ++i) {
    int count = 0;
    for (int k = 0; k < 50; ++k) count += (many[k] >= b[i] && many[k] < b[i + 1]);
    EXPECT_GE(count, 1) << "span " << i;
  }
  // Hartley-Judd on equally spaced collinear points gives uniform knots.
  Eigen::MatrixXd line(8, 2);
  for (int i = 0; i < 8; ++i) line.row(i) << i, 2.0 * i;
  const Eigen::VectorXd hj = hartley_judd_knots(line, 3, 8);
  const Eigen::VectorXd uni = clamped_uniform_knots(8, 3);
  EXPECT_LT((hj - uni).cwiseAbs().maxCoeff(), 1e-14);
}

TEST(Knots, Parameterizations) {
  Eigen::MatrixXd P(3, 2);
  P << 0, 0, 1, 0, 1, 3;  // chords 1 and 3
  const Eigen::VectorXd ch = parameterize(P, Parameterization::ChordLength);
  EXPECT_NEAR(ch[1], 0.25, 1e-15);
  const Eigen::VectorXd ce = parameterize(P, Parameterization::Centripetal);
  EXPECT_NEAR(ce[1], 1.0 / (1.0 + std::sqrt(3.0)), 1e-15);
  const Eigen::VectorXd un = parameterize(P, Parameterization::Uniform);
  EXPECT_NEAR(un[1], 0.5, 1e-15);
  Eigen::MatrixXd dup(3, 2);
  dup << 0, 0, 0, 0, 1, 1;
  EXPECT_THROW(parameterize(dup, Parameterization::ChordLength), InvalidInput);
  EXPECT_THROW(parse_parameterization("arc"), InvalidInput);
  EXPECT_THROW(parse_knot_method("magic"), InvalidInput);
}
