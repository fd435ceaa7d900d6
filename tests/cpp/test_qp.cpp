// Dense convex QP (fairlines/qp.hpp) against independent truths: the KKT conditions, and the
// minimum over every active set of small problems (brute force).
#include <random>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "fairlines/errors.hpp"
#include "fairlines/qp.hpp"

namespace fairlines {
namespace {

QuadraticProgram random_qp(int n, int me, int mi, std::mt19937& rng) {
  std::normal_distribution<double> N(0.0, 1.0);
  QuadraticProgram qp;
  Eigen::MatrixXd M = Eigen::MatrixXd::NullaryExpr(n, n, [&] { return N(rng); });
  qp.H = M * M.transpose() + 0.1 * Eigen::MatrixXd::Identity(n, n);
  qp.g = Eigen::VectorXd::NullaryExpr(n, [&] { return N(rng); });
  qp.E = Eigen::MatrixXd::NullaryExpr(me, n, [&] { return N(rng); });
  qp.e = Eigen::VectorXd::NullaryExpr(me, [&] { return N(rng); });
  qp.A = Eigen::MatrixXd::NullaryExpr(mi, n, [&] { return N(rng); });
  // A point x0 meets every inequality with slack, so the problem is feasible.
  const Eigen::VectorXd x0 = Eigen::VectorXd::NullaryExpr(n, [&] { return N(rng); });
  qp.b = qp.A * x0 + Eigen::VectorXd::NullaryExpr(mi, [&] { return std::abs(N(rng)); });
  if (me > 0) qp.e = qp.E * x0;
  return qp;
}

void expect_kkt(const QuadraticProgram& qp, const QpSolution& s, double tol) {
  ASSERT_EQ(s.status, QpStatus::Optimal);
  const Eigen::VectorXd grad = qp.H * s.x + qp.g + qp.E.transpose() * s.y_eq + qp.A.transpose() * s.y_in;
  EXPECT_LT(grad.cwiseAbs().maxCoeff(), tol) << "stationarity";
  if (qp.E.rows()) EXPECT_LT((qp.E * s.x - qp.e).cwiseAbs().maxCoeff(), tol) << "equalities";
  for (Eigen::Index i = 0; i < qp.A.rows(); ++i) {
    const double slack = qp.b[i] - qp.A.row(i).dot(s.x);
    EXPECT_GT(slack, -tol) << "inequality " << i;
    EXPECT_GE(s.y_in[i], -tol) << "multiplier sign " << i;
    EXPECT_LT(std::abs(slack * s.y_in[i]), tol) << "complementarity " << i;
  }
}

TEST(Qp, RandomProblemsMeetKkt) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 300; ++trial) {
    const int n = 2 + trial % 12, me = trial % 3, mi = trial % 25;
    const QuadraticProgram qp = random_qp(n, std::min(me, n - 1), mi, rng);
    expect_kkt(qp, solve_qp(qp), 1e-8);
  }
}

// Brute force: every subset of inequalities taken as equalities; the feasible candidate of
// least objective is the minimiser (strictly convex, so unique).
TEST(Qp, SmallProblemsMatchBruteForce) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 3, mi = 6;
    const QuadraticProgram qp = random_qp(n, trial % 2, mi, rng);
    double best = std::numeric_limits<double>::infinity();
    Eigen::VectorXd best_x;
    for (int mask = 0; mask < (1 << mi); ++mask) {
      std::vector<int> rows;
      for (int i = 0; i < mi; ++i)
        if (mask & (1 << i)) rows.push_back(i);
      const int k = static_cast<int>(rows.size()) + static_cast<int>(qp.E.rows());
      if (k > n) continue;
      Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n + k, n + k);
      Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n + k);
      K.topLeftCorner(n, n) = qp.H;
      rhs.head(n) = -qp.g;
      int r = n;
      for (Eigen::Index i = 0; i < qp.E.rows(); ++i, ++r) {
        K.block(r, 0, 1, n) = qp.E.row(i);
        K.block(0, r, n, 1) = qp.E.row(i).transpose();
        rhs[r] = qp.e[i];
      }
      for (int i : rows) {
        K.block(r, 0, 1, n) = qp.A.row(i);
        K.block(0, r, n, 1) = qp.A.row(i).transpose();
        rhs[r++] = qp.b[i];
      }
      Eigen::FullPivLU<Eigen::MatrixXd> lu(K);
      if (lu.rank() < n + k) continue;
      const Eigen::VectorXd x = lu.solve(rhs).head(n);
      if (((qp.A * x - qp.b).array() > 1e-9).any()) continue;
      const double f = 0.5 * x.dot(qp.H * x) + qp.g.dot(x);
      if (f < best) best = f, best_x = x;
    }
    const QpSolution s = solve_qp(qp);
    ASSERT_EQ(s.status, QpStatus::Optimal);
    EXPECT_LT((s.x - best_x).cwiseAbs().maxCoeff(), 1e-8) << "trial " << trial;
  }
}

TEST(Qp, AnyWarmStartGivesTheSameSolution) {
  std::mt19937 rng(7);
  std::bernoulli_distribution coin(0.4);
  for (int trial = 0; trial < 100; ++trial) {
    const QuadraticProgram qp = random_qp(8, 2, 20, rng);
    const QpSolution cold = solve_qp(qp);
    std::vector<int> warm;
    for (int i = 0; i < 20; ++i)
      if (coin(rng)) warm.push_back(i);
    const QpSolution hot = solve_qp(qp, warm);
    ASSERT_EQ(hot.status, QpStatus::Optimal);
    EXPECT_LT((hot.x - cold.x).cwiseAbs().maxCoeff(), 1e-9);
    const QpSolution same = solve_qp(qp, cold.active);
    EXPECT_LE(same.iterations, 1) << "warm start from the optimal active set";
  }
}

TEST(Qp, InfeasibleInequalitiesNamed) {
  // x0 + x1 <= 1, x0 >= 1, x1 >= 1 (written -x <= -1): contradictory; x2 free.
  QuadraticProgram qp;
  qp.H = Eigen::MatrixXd::Identity(3, 3);
  qp.g = Eigen::VectorXd::Zero(3);
  qp.E.resize(0, 3);
  qp.e.resize(0);
  qp.A.resize(4, 3);
  qp.A << 1, 1, 0, -1, 0, 0, 0, -1, 0, 0, 0, 1;
  qp.b.resize(4);
  qp.b << 1, -1, -1, 5;
  const QpSolution s = solve_qp(qp);
  EXPECT_EQ(s.status, QpStatus::Infeasible);
  std::vector<int> expected{0, 1, 2};  // inequality rows (no equalities, so no offset)
  EXPECT_EQ(s.conflict, expected);
}

TEST(Qp, ContradictoryEqualitiesAreInfeasible) {
  QuadraticProgram qp;
  qp.H = Eigen::MatrixXd::Identity(2, 2);
  qp.g = Eigen::VectorXd::Zero(2);
  qp.E.resize(2, 2);
  qp.E << 1, 1, 2, 2;
  qp.e.resize(2);
  qp.e << 1, 3;
  qp.A.resize(0, 2);
  qp.b.resize(0);
  EXPECT_EQ(solve_qp(qp).status, QpStatus::Infeasible);
  qp.e << 1, 2;  // consistent duplicates are fine
  const QpSolution s = solve_qp(qp);
  ASSERT_EQ(s.status, QpStatus::Optimal);
  EXPECT_NEAR(s.x[0], 0.5, 1e-12);
  EXPECT_NEAR(s.x[1], 0.5, 1e-12);
}

TEST(Qp, BadSizesThrow) {
  QuadraticProgram qp;
  qp.H = Eigen::MatrixXd::Identity(2, 2);
  qp.g = Eigen::VectorXd::Zero(3);
  EXPECT_THROW(solve_qp(qp), InvalidInput);
  qp.g = Eigen::VectorXd::Zero(2);
  qp.H(0, 0) = std::nan("");
  EXPECT_THROW(solve_qp(qp), InvalidInput);
}

}  // namespace
}  // namespace fairlines

namespace fairlines {
namespace {

TEST(Qp, DuplicateAndDependentRowsAreHandled) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 50; ++trial) {
    QuadraticProgram qp = random_qp(6, 1, 8, rng);
    // Each inequality twice, plus one that repeats the equality (as an upper bound).
    Eigen::MatrixXd A(17, 6);
    Eigen::VectorXd b(17);
    A << qp.A, 2.0 * qp.A, qp.E.row(0);
    b << qp.b, 2.0 * qp.b, qp.e[0];
    qp.A = A;
    qp.b = b;
    expect_kkt(qp, solve_qp(qp), 1e-8);
  }
}

}  // namespace
}  // namespace fairlines

namespace fairlines {
namespace {

TEST(Qp, EqualitiesThatFixEverythingStillCheckTheInequalities) {
  QuadraticProgram qp;
  qp.H = Eigen::MatrixXd::Identity(2, 2);
  qp.g = Eigen::VectorXd::Zero(2);
  qp.E = Eigen::MatrixXd::Identity(2, 2);
  qp.e = Eigen::Vector2d(1.0, 2.0);
  qp.A = Eigen::RowVector2d(1.0, 1.0);
  qp.b = Eigen::VectorXd::Constant(1, 2.5);
  const QpSolution s = solve_qp(qp);
  EXPECT_EQ(s.status, QpStatus::Infeasible);
  std::vector<int> expected{0, 1, 2};
  EXPECT_EQ(s.conflict, expected);
  qp.b[0] = 3.0;
  EXPECT_EQ(solve_qp(qp).status, QpStatus::Optimal);
}

}  // namespace
}  // namespace fairlines
