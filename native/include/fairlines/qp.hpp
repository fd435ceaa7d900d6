// Small dense convex quadratic programs (the fairest-curve problems of the hull designer):
//
//   minimise   1/2 x' H x + g' x
//   subject to E x = e          (m_e equalities)
//              A x <= b         (m_i inequalities)
//
// Solved by the dual active-set method of Goldfarb & Idnani (Math. Programming 27, 1983): start
// from the minimum subject to the equalities, add the most violated inequality, step in the
// primal and dual variables, drop a constraint whose multiplier would turn negative. It needs
// no feasible starting point, ends in finitely many steps and proves infeasibility when no
// step can restore a violated constraint. Linear systems use a Cholesky factor of H and of the
// active set's Schur complement (no explicit inverse). A warm start (the active set of a
// similar problem, e.g. the neighbouring section) is solved as an equality problem first and
// thinned until its multipliers are >= 0, which is a valid dual-feasible start.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace fairlines {

struct QuadraticProgram {
  Eigen::MatrixXd H;  ///< (n, n) symmetric, positive definite on the null space of E
  Eigen::VectorXd g;  ///< (n)
  Eigen::MatrixXd E;  ///< (m_e, n) equality rows (may have zero rows)
  Eigen::VectorXd e;  ///< (m_e)
  Eigen::MatrixXd A;  ///< (m_i, n) inequality rows, A x <= b (may have zero rows)
  Eigen::VectorXd b;  ///< (m_i)
};

struct QpOptions {
  /// A constraint counts as met when its residual is within this fraction of the problem's
  /// scale (largest |x|, |b|, |e|, 1); rows are normalised to unit length first.
  double feasibility_tol = 1e-10;
  /// H is regularised by this fraction of its largest diagonal entry (keeps the Cholesky
  /// factor defined when H is only semidefinite on directions no constraint fixes).
  double regularisation = 1e-13;
  /// Active-set changes before giving up (ConvergenceError); 0: 6 (n + m_i) + 20.
  int max_iterations = 0;
};

enum class QpStatus {
  Optimal,           ///< x is the minimiser; every constraint met
  Infeasible,        ///< no x meets the constraints: `conflict` lists the ones in contradiction
  IterationLimit,    ///< QpOptions::max_iterations reached (should not happen on sane input)
};

struct QpSolution {
  QpStatus status = QpStatus::Optimal;
  Eigen::VectorXd x;           ///< (n) minimiser (last iterate when not Optimal)
  Eigen::VectorXd y_eq;        ///< (m_e) multipliers of the equalities: H x + g + E' y_eq + A' y_in = 0
  Eigen::VectorXd y_in;        ///< (m_i) multipliers of the inequalities, >= 0, zero when inactive
  std::vector<int> active;     ///< inequalities active at the solution (indices into A)
  /// When Infeasible: the constraints found in contradiction -- equality indices as they are,
  /// inequality indices offset by m_e (index m_e + i is row i of A).
  std::vector<int> conflict;
  int iterations = 0;          ///< active-set changes made
};

/// Solve a convex QP (see the file comment). `warm_active`: inequality indices believed to be
/// active (e.g. from a similar problem); any subset is valid. Throws InvalidInput on
/// inconsistent sizes or non-finite entries. Infeasibility is a status, not an exception, so
/// that callers can name the form parameters in conflict.
QpSolution solve_qp(const QuadraticProgram& qp, const std::vector<int>& warm_active = {}, const QpOptions& options = {});

}  // namespace fairlines
