// Dual active-set QP (Goldfarb & Idnani 1983): see fairlines/qp.hpp.
//
// Equalities are eliminated first (null-space method: x = x_p + Z y with E x_p = e and E Z = 0,
// from a column-pivoted QR of E'), so the dual active-set iteration runs on the reduced problem
// in y with inequalities only; a nearly singular H on directions the equalities fix then does
// no harm.
//
// Notation: C the active constraint rows (unit normals), d their right-hand sides, lambda their
// multipliers with H x + g + C' lambda = 0; Hi v means a solve with the Cholesky factor of H;
// W = Hi C' (one column per active constraint), S = C Hi C' (the Schur complement). Adding a
// violated row a moves x along z = -(Hi a - W S^-1 C Hi a), which keeps C x = d and lowers a'x,
// while the active multipliers change by -t r, r = S^-1 C Hi a.
#include "fairlines/qp.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Cholesky>
#include <Eigen/QR>

#include "fairlines/errors.hpp"
#include "nurbs/checks.hpp"

namespace fairlines {

namespace {

using detail::fail;

/// Below this fraction of its own H-norm a new row's projected part counts as dependent on
/// the active rows.
constexpr double kDependentTol = 1e-11;
/// Multiplier directions smaller than this (relative) do not limit a step.
constexpr double kRatioTol = 1e-14;
/// Proximal passes that remove the regularisation's bias (see solve_refined).
constexpr int kRefinements = 3;

struct Row {
  Eigen::VectorXd c;  // unit normal
  double d = 0;       // right-hand side after normalisation
  bool equality = false;
};

class ActiveSetSolver {
 public:
  ActiveSetSolver(const QuadraticProgram& qp, const QpOptions& opt) : qp_(qp), opt_(opt), n_(static_cast<int>(qp.H.rows())), g_(qp.g) {
    const Eigen::Index me = qp.E.rows(), mi = qp.A.rows();
    rows_.reserve(me + mi);
    for (Eigen::Index i = 0; i < me; ++i) rows_.push_back(normalised(qp.E.row(i), qp.e[i], true));
    for (Eigen::Index i = 0; i < mi; ++i) rows_.push_back(normalised(qp.A.row(i), qp.b[i], false));
    m_eq_ = static_cast<int>(me);
    double dmax = 0.0;
    for (int i = 0; i < n_; ++i) dmax = std::max(dmax, std::abs(qp.H(i, i)));
    Eigen::MatrixXd Hr = qp.H;
    delta_ = opt.regularisation * std::max(dmax, 1e-300);
    Hr.diagonal().array() += delta_;
    llt_.compute(Hr);
    if (llt_.info() != Eigen::Success) fail("qp: H is not positive definite; expected a convex objective");
    hinv_.assign(rows_.size(), Eigen::VectorXd());
    scale_ = 1.0;
    for (const Row& r : rows_) scale_ = std::max(scale_, std::abs(r.d));
    lambda_.resize(0);
  }

  /// Proximal refinement: the regularised problem is solved again with its linear term moved
  /// by delta x (min q(x) + delta/2 |x - x_prev|^2), which removes the bias toward x = 0 the
  /// regularisation adds (the bias shrinks by delta / (delta + smallest curvature) per pass).
  QpSolution solve_refined(const std::vector<int>& warm) {
    QpSolution s = solve(warm);
    for (int pass = 0; pass < kRefinements && s.status == QpStatus::Optimal && delta_ > 0; ++pass) {
      g_ = qp_.g - delta_ * s.x;
      const Eigen::VectorXd prev = s.x;
      const int its = s.iterations;
      s = solve(s.active);
      s.iterations += its;
      if ((s.x - prev).cwiseAbs().maxCoeff() <= 1e-15 * std::max(1.0, prev.cwiseAbs().maxCoeff())) break;
    }
    g_ = qp_.g;
    return s;
  }

 private:
  QpSolution solve(const std::vector<int>& warm) {
    QpSolution out;
    active_.clear();
    conflict_rows_.clear();
    lambda_.resize(0);
    x_ = -llt_.solve(g_);
    // Equalities first (never dropped), then the warm inequalities.
    for (int i = 0; i < m_eq_; ++i) try_add(i);
    for (int w : warm)
      if (w >= 0 && w < static_cast<int>(rows_.size()) - m_eq_ && !is_active(m_eq_ + w)) try_add(m_eq_ + w);
    solve_equality_problem();
    for (int i = 0; i < m_eq_; ++i)
      if (!is_active(i) && !equality_met(i)) return infeasible(out, i);
    thin_warm_start();
    const int limit = opt_.max_iterations > 0 ? opt_.max_iterations : 6 * (n_ + static_cast<int>(rows_.size()) - m_eq_) + 20;
    for (iterations_ = 0; iterations_ < limit;) {
      const int p = most_violated();
      if (p < 0) return finish(out, QpStatus::Optimal);
      if (!add_violated(p)) return infeasible(out, p);
    }
    return finish(out, QpStatus::IterationLimit);
  }

  Row normalised(const Eigen::RowVectorXd& c, double d, bool eq) const {
    if (c.size() != n_) fail("qp: a constraint row has ", c.size(), " entries; expected ", n_);
    Row r;
    const double s = c.norm();
    r.equality = eq;
    if (s > 0) {
      r.c = c.transpose() / s;
      r.d = d / s;
    } else {
      r.c = Eigen::VectorXd::Zero(n_);
      r.d = d;
    }
    return r;
  }

  const Eigen::VectorXd& hinv(int k) {
    if (hinv_[k].size() == 0) hinv_[k] = llt_.solve(rows_[k].c);
    return hinv_[k];
  }
  bool is_active(int k) const { return std::find(active_.begin(), active_.end(), k) != active_.end(); }
  double tol() const { return opt_.feasibility_tol * std::max(scale_, x_.cwiseAbs().maxCoeff()); }
  double residual(int k) const { return rows_[k].c.dot(x_) - rows_[k].d; }
  bool equality_met(int k) const { return std::abs(residual(k)) <= tol(); }

  /// Rebuild W and the factor of S for the current active set.
  void refactor() {
    const int k = static_cast<int>(active_.size());
    W_.resize(n_, k);
    C_.resize(k, n_);
    for (int j = 0; j < k; ++j) {
      W_.col(j) = hinv(active_[j]);
      C_.row(j) = rows_[active_[j]].c.transpose();
    }
    if (k > 0) schur_.compute(C_ * W_);
  }

  /// Part of Hi c not explained by the active rows, relative to c' Hi c: ~0 when dependent.
  double independence(int k) {
    const Eigen::VectorXd& w = hinv(k);
    const double full = rows_[k].c.dot(w);
    if (active_.empty()) return full > 0 ? 1.0 : 0.0;
    const Eigen::VectorXd r = schur_.solve(C_ * w);
    return (full - (C_ * w).dot(r)) / std::max(full, 1e-300);
  }

  /// Adds row k to the active set when independent of it (no step taken).
  bool try_add(int k) {
    if (rows_[k].c.squaredNorm() == 0.0) return false;
    if (independence(k) <= kDependentTol) return false;
    active_.push_back(k);
    lambda_.conservativeResize(static_cast<Eigen::Index>(active_.size()));
    lambda_[lambda_.size() - 1] = 0.0;
    refactor();
    return true;
  }

  void drop(int j) {
    active_.erase(active_.begin() + j);
    const Eigen::Index k = lambda_.size();
    for (Eigen::Index i = j; i + 1 < k; ++i) lambda_[i] = lambda_[i + 1];
    lambda_.conservativeResize(k - 1);
    refactor();
  }

  /// x and lambda of min q subject to the active rows as equalities.
  void solve_equality_problem() {
    const Eigen::VectorXd x0 = -llt_.solve(g_);
    if (active_.empty()) {
      x_ = x0;
      return;
    }
    Eigen::VectorXd d(active_.size());
    for (std::size_t j = 0; j < active_.size(); ++j) d[j] = rows_[active_[j]].d;
    lambda_ = schur_.solve(C_ * x0 - d);
    x_ = x0 - W_ * lambda_;
  }

  /// Drops warm-start inequalities with negative multipliers until the start is dual feasible.
  void thin_warm_start() {
    for (;;) {
      int worst = -1;
      double most = 0.0;
      for (std::size_t j = 0; j < active_.size(); ++j)
        if (!rows_[active_[j]].equality && lambda_[j] < most) most = lambda_[j], worst = static_cast<int>(j);
      if (worst < 0) return;
      drop(worst);
      solve_equality_problem();
    }
  }

  int most_violated() const {
    int p = -1;
    double worst = tol();
    for (int k = m_eq_; k < static_cast<int>(rows_.size()); ++k) {
      if (rows_[k].c.squaredNorm() == 0.0) continue;
      const double v = residual(k);
      if (v > worst && !is_active(k)) worst = v, p = k;
    }
    return p;
  }

  /// One Goldfarb-Idnani major step: brings row p into the active set. False: infeasible.
  bool add_violated(int p) {
    double lambda_p = 0.0;
    for (;;) {
      ++iterations_;
      const Eigen::VectorXd& w = hinv(p);
      Eigen::VectorXd r, z = -w;
      if (!active_.empty()) {
        r = schur_.solve(C_ * w);
        z += W_ * r;
      }
      const double az = rows_[p].c.dot(z), full = rows_[p].c.dot(w);
      double t1 = std::numeric_limits<double>::infinity();
      int jdrop = -1;
      for (std::size_t j = 0; j < active_.size(); ++j) {
        if (rows_[active_[j]].equality || !(r[j] > kRatioTol * r.cwiseAbs().maxCoeff())) continue;
        const double t = lambda_[j] / r[j];
        if (t < t1) t1 = t, jdrop = static_cast<int>(j);
      }
      if (-az <= kDependentTol * full) {
        if (jdrop < 0) {
          conflict_rows_ = active_;
          return false;
        }
        if (!active_.empty()) lambda_ -= t1 * r;
        lambda_p += t1;
        drop(jdrop);
        continue;
      }
      const double t2 = residual(p) / -az;
      const double t = std::min(t1, t2);
      x_ += t * z;
      if (!active_.empty()) lambda_ -= t * r;
      lambda_p += t;
      if (t2 <= t1) {
        active_.push_back(p);
        lambda_.conservativeResize(static_cast<Eigen::Index>(active_.size()));
        lambda_[lambda_.size() - 1] = lambda_p;
        refactor();
        return true;
      }
      drop(jdrop);
    }
  }

  QpSolution& finish(QpSolution& out, QpStatus status) {
    const int me = m_eq_, mi = static_cast<int>(rows_.size()) - m_eq_;
    out.status = status;
    out.x = x_;
    out.y_eq = Eigen::VectorXd::Zero(me);
    out.y_in = Eigen::VectorXd::Zero(mi);
    for (std::size_t j = 0; j < active_.size(); ++j) {
      const int k = active_[j];
      const double s = k < me ? qp_.E.row(k).norm() : qp_.A.row(k - me).norm();
      const double y = s > 0 ? lambda_[j] / s : 0.0;  // multipliers of the caller's unscaled rows
      if (k < me) out.y_eq[k] = y;
      else out.y_in[k - me] = y, out.active.push_back(k - me);
    }
    std::sort(out.active.begin(), out.active.end());
    out.iterations = iterations_;
    return out;
  }

  QpSolution infeasible(QpSolution& out, int culprit) {
    finish(out, QpStatus::Infeasible);
    out.conflict = conflict_rows_;
    out.conflict.push_back(culprit);
    std::sort(out.conflict.begin(), out.conflict.end());
    out.conflict.erase(std::unique(out.conflict.begin(), out.conflict.end()), out.conflict.end());
    return out;
  }

  const QuadraticProgram& qp_;
  const QpOptions& opt_;
  int n_;
  Eigen::VectorXd g_;  // linear term in use (moved by the proximal refinement)
  double delta_ = 0.0;
  int m_eq_ = 0;
  std::vector<Row> rows_;
  std::vector<Eigen::VectorXd> hinv_;
  Eigen::LLT<Eigen::MatrixXd> llt_;
  Eigen::LLT<Eigen::MatrixXd> schur_;
  Eigen::MatrixXd W_, C_;
  Eigen::VectorXd x_, lambda_;
  std::vector<int> active_, conflict_rows_;
  double scale_ = 1.0;
  int iterations_ = 0;
};

void check_sizes(const QuadraticProgram& qp) {
  const Eigen::Index n = qp.H.rows();
  if (n < 1 || qp.H.cols() != n) fail("qp: H is ", qp.H.rows(), " x ", qp.H.cols(), "; expected a square matrix with n >= 1");
  if (qp.g.size() != n) fail("qp: g has ", qp.g.size(), " entries; expected ", n);
  if (qp.E.rows() > 0 && qp.E.cols() != n) fail("qp: E has ", qp.E.cols(), " columns; expected ", n);
  if (qp.E.rows() != qp.e.size()) fail("qp: E has ", qp.E.rows(), " rows but e has ", qp.e.size(), " entries");
  if (qp.A.rows() > 0 && qp.A.cols() != n) fail("qp: A has ", qp.A.cols(), " columns; expected ", n);
  if (qp.A.rows() != qp.b.size()) fail("qp: A has ", qp.A.rows(), " rows but b has ", qp.b.size(), " entries");
  detail::require_finite(qp.H, "qp: H");
  detail::require_finite(qp.g, "qp: g");
  detail::require_finite(qp.E, "qp: E");
  detail::require_finite(qp.e, "qp: e");
  detail::require_finite(qp.A, "qp: A");
  detail::require_finite(qp.b, "qp: b");
}

}  // namespace

/// Below this fraction of the largest diagonal entry of R an equality row counts as dependent on
/// the others (column-pivoted QR of E').
constexpr double kRankTol = 1e-12;

namespace {

/// The equalities E x = e, rows normalised (En, en) and factored by column-pivoted QR of En':
/// rank r, Q, and the least-norm solution xp. x = xp + Z w, Z = Q.rightCols(n - r), meets them
/// for every w.
struct EqualitySpace {
  Eigen::MatrixXd En;
  Eigen::VectorXd en;
  Eigen::Index r = 0;
  Eigen::MatrixXd Q;
  Eigen::VectorXd xp;
};

EqualitySpace equality_space(const QuadraticProgram& qp) {
  const Eigen::Index me = qp.E.rows();
  EqualitySpace eq;
  Eigen::VectorXd s = qp.E.rowwise().norm();
  for (Eigen::Index i = 0; i < me; ++i) s[i] = s[i] > 0 ? 1.0 / s[i] : 0.0;
  eq.En = s.asDiagonal() * qp.E;
  eq.en = s.asDiagonal() * qp.e;
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(eq.En.transpose());
  qr.setThreshold(kRankTol);
  eq.r = qr.rank();
  eq.Q = qr.householderQ();
  const Eigen::MatrixXd R = qr.matrixR().topLeftCorner(eq.r, eq.r).template triangularView<Eigen::Upper>();
  const Eigen::VectorXd ep = qr.colsPermutation().transpose() * eq.en;
  const Eigen::VectorXd zr = R.transpose().template triangularView<Eigen::Lower>().solve(ep.head(eq.r));
  eq.xp = eq.Q.leftCols(eq.r) * zr;
  return eq;
}

/// Infeasible: the equalities contradict themselves (extra < 0) or inequality row `extra` (its
/// index among all rows, equalities first). x = xp, zero multipliers.
QpSolution conflict_with_equalities(const QuadraticProgram& qp, const Eigen::VectorXd& xp, int extra) {
  QpSolution out;
  out.status = QpStatus::Infeasible;
  out.x = xp;
  out.y_eq = Eigen::VectorXd::Zero(qp.E.rows());
  out.y_in = Eigen::VectorXd::Zero(qp.A.rows());
  if (extra >= 0) out.conflict.push_back(extra);
  for (Eigen::Index j = 0; j < qp.E.rows(); ++j) out.conflict.push_back(static_cast<int>(j));
  std::sort(out.conflict.begin(), out.conflict.end());
  return out;
}

/// The equalities fix x = xp: the inequalities are met or not (those not met are the conflict).
QpSolution at_fixed_point(const QuadraticProgram& qp, const Eigen::VectorXd& xp, double scale, const QpOptions& options) {
  QpSolution out;
  out.status = QpStatus::Optimal;
  out.x = xp;
  out.y_in = Eigen::VectorXd::Zero(qp.A.rows());
  for (Eigen::Index i = 0; i < qp.A.rows(); ++i)
    if (qp.A.row(i).dot(xp) - qp.b[i] > options.feasibility_tol * scale * std::max(1.0, qp.A.row(i).norm())) {
      out.status = QpStatus::Infeasible;
      out.conflict.push_back(static_cast<int>(i));
    }
  return out;
}

/// A row of the reduced inequalities that the equalities already fix (its reduced part
/// vanishes) is met, and made a zero row, or contradicts them: returns the first such row, or -1.
int drop_fixed_rows(const QuadraticProgram& qp, QuadraticProgram& red, double scale, const QpOptions& options) {
  for (Eigen::Index i = 0; i < red.A.rows(); ++i)
    if (red.A.row(i).norm() <= kRankTol * qp.A.row(i).norm()) {
      red.A.row(i).setZero();
      if (red.b[i] < -options.feasibility_tol * scale * qp.A.row(i).norm()) return static_cast<int>(i);
      red.b[i] = std::max(red.b[i], 0.0);
    }
  return -1;
}

}  // namespace

QpSolution solve_qp(const QuadraticProgram& qp, const std::vector<int>& warm_active, const QpOptions& options) {
  check_sizes(qp);
  if (!(options.feasibility_tol > 0) || !(options.regularisation >= 0))
    fail("qp: options feasibility_tol ", options.feasibility_tol, " / regularisation ", options.regularisation,
         "; expected > 0 / >= 0");
  const Eigen::Index n = qp.H.rows(), me = qp.E.rows();
  if (me == 0) {
    ActiveSetSolver solver(qp, options);
    return solver.solve_refined(warm_active);
  }
  // Null space of the (row-normalised) equalities.
  const EqualitySpace eq = equality_space(qp);
  const double scale = std::max({1.0, eq.en.cwiseAbs().maxCoeff(), eq.xp.cwiseAbs().maxCoeff()});
  const Eigen::VectorXd eres = eq.En * eq.xp - eq.en;
  for (Eigen::Index i = 0; i < me; ++i)
    if (std::abs(eres[i]) > options.feasibility_tol * scale) return conflict_with_equalities(qp, eq.xp, -1);
  QpSolution out;
  if (eq.r == n) {
    out = at_fixed_point(qp, eq.xp, scale, options);
  } else {
    const Eigen::MatrixXd Z = eq.Q.rightCols(n - eq.r);
    QuadraticProgram red{Z.transpose() * qp.H * Z, Z.transpose() * (qp.H * eq.xp + qp.g), Eigen::MatrixXd(0, n - eq.r),
                         Eigen::VectorXd(0), qp.A * Z, qp.b - qp.A * eq.xp};
    const int contradicted = drop_fixed_rows(qp, red, scale, options);
    if (contradicted >= 0) return conflict_with_equalities(qp, eq.xp, static_cast<int>(me) + contradicted);
    ActiveSetSolver solver(red, options);
    out = solver.solve_refined(warm_active);
    out.x = (eq.xp + Z * out.x).eval();
  }
  // Equality multipliers from stationarity, E' y_eq = -(H x + g + A' y_in), by least squares.
  const Eigen::VectorXd resid = -(qp.H * out.x + qp.g + qp.A.transpose() * out.y_in);
  out.y_eq = qp.E.transpose().colPivHouseholderQr().solve(resid);
  for (int& k : out.conflict) k += static_cast<int>(me);
  if (out.status == QpStatus::Infeasible)
    for (Eigen::Index j = 0; j < me; ++j) out.conflict.push_back(static_cast<int>(j));
  std::sort(out.conflict.begin(), out.conflict.end());
  return out;
}

}  // namespace fairlines
