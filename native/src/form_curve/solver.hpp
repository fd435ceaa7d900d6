// Internal: SQP / barrier / continuation solver of the form-parameter curve problem.
#pragma once

#include <random>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "problem.hpp"

namespace fairlines::form_curve_impl {

struct RunOutcome {
  Eigen::VectorXd z, lam;
  std::vector<double> starts;  // start values of the constraints (continuation origin)
  double tau = 0;          // continuation parameter reached (1 = requested values)
  double violation = 1e300;
  double objective = 0;
  int steps = 0;           // accepted continuation steps
  bool feasible = false;   // constraints met to tolerance, bounds strictly satisfied
  bool converged = false;  // and KKT conditions met
};

/// The barrier model at an iterate: objective f, gradient g, Hessian H; constraints c,
/// Jacobian J, constraint Hessian HL; slacks s = G z - h > 0; barrier gradient gt, Hessian Ht.
struct NewtonModel {
  double f = 0;
  Eigen::VectorXd g, c, s, gt;
  Eigen::MatrixXd H, J, HL, Ht;
};

/// The solver of one problem: state (linear system, kept inequalities, duals, iteration
/// count) is private; design_form_curve asks it for start curves and runs it from each.
class Solver {
 public:
  /// `iteration_budget`: Newton and restoration iterations allowed per run (per start).
  Solver(Problem& problem, int iteration_budget);
  Eigen::VectorXd start_curve(std::mt19937* rng) const;
  Eigen::VectorXd fair_linear_start(const Eigen::VectorXd& zc) const;
  Eigen::VectorXd project_linear(const Eigen::VectorXd& z) const;
  bool interior(const Eigen::VectorXd& z) const;
  /// One solve from z0 (the iteration count starts again at 0).
  RunOutcome run(const Eigen::VectorXd& z0, bool continuation);
  /// Iterations the last run took.
  int iterations() const { return total_iterations; }

 private:
  friend std::string failure_report(Solver& solver, const RunOutcome& best);

  Problem& pb;
  int m = 0;
  Eigen::MatrixXd L;            // linear equalities L z = b
  Eigen::VectorXd b;
  std::vector<int> lin_index;   // their indices in pb.cons
  Eigen::MatrixXd G;            // kept inequalities G z - h > 0
  Eigen::VectorXd h;
  std::vector<std::string> ineq_names;
  int total_iterations = 0;
  int max_total = 400;
  double last_violation = 0, last_stationarity = 0;
  Eigen::MatrixXd soc_Y, soc_R;
  Eigen::VectorXd vdual;        // dual estimates of the inequalities
  double restore_tol = 1e-3;

  void set_starts(const Eigen::VectorXd& z);
  void set_targets(double tau);
  bool newton(Eigen::VectorXd& z, Eigen::VectorXd& lam, double mu, double tol_c, double tol_g, int maxit);
  // Steps of newton():
  bool model_at(const Eigen::VectorXd& z, const Eigen::VectorXd& lam, double mu, NewtonModel& md);
  /// KKT step d and multipliers: null-space (QR of J^T, inertia-corrected), or without
  /// constraints an inertia-corrected Newton step, or for dependent gradients a regularised
  /// KKT solve (regular = false). False when no finite step exists.
  bool kkt_step(const NewtonModel& md, Eigen::VectorXd& d, Eigen::VectorXd& lam_new, bool& regular);
  /// False when J^T is rank deficient; d empty when the reduced Hessian cannot be corrected.
  bool null_space_step(const NewtonModel& md, Eigen::VectorXd& d, Eigen::VectorXd& lam_new);
  bool regularised_step(const NewtonModel& md, Eigen::VectorXd& d, Eigen::VectorXd& lam_new) const;
  /// Backtracking on the l1 merit with fraction-to-boundary and second-order corrections;
  /// moves z and returns true when a step is accepted (alpha its length).
  bool line_search(Eigen::VectorXd& z, const Eigen::VectorXd& d, const NewtonModel& md, double mu, double nu,
                   bool regular, double& alpha);
  void dual_step(const NewtonModel& md, const Eigen::VectorXd& d, double mu);
  double merit(const Eigen::VectorXd& z, double mu, double nu, Eigen::VectorXd& c) const;
  /// The merit from already computed objective f, constraints c and slacks s = G z - h > 0.
  double merit_of(double f, const Eigen::VectorXd& c, const Eigen::VectorXd& s, double mu, double nu) const;
  bool restore(Eigen::VectorXd& z, int maxit);
  // Steps of restore(): the merit 1/2 |S c|^2 - mu sum log(G z - h) (inf outside), its
  // Gauss-Newton model (A, g) from the scaled Jacobian Js, the damped step with the rows of
  // nearly crossed inequalities held, and the step fraction that keeps G z - h > 0.
  double restoration_merit(const Eigen::VectorXd& z, const Eigen::VectorXd& sinv, double mu, Eigen::VectorXd& c) const;
  void restoration_model(const Eigen::MatrixXd& Js, const Eigen::VectorXd& sc, const Eigen::VectorXd& s, double mu,
                         Eigen::MatrixXd& A, Eigen::VectorXd& g) const;
  Eigen::VectorXd restoration_step(const Eigen::MatrixXd& A, const Eigen::VectorXd& g, const Eigen::VectorXd& s,
                                   double lm, double diag) const;
  double fraction_to_boundary(const Eigen::VectorXd& d, const Eigen::VectorXd& s) const;
  // Steps of run(): the requested values at once (restoration, then Newton); else continuation
  // from the start values (returns the fraction tau of the way reached); then the barrier
  // weight driven down, a final Newton solve and the outcome's measures.
  bool direct_solve(RunOutcome& out, double mu0);
  double continue_to_targets(RunOutcome& out, double mu0, bool continuation);
  void polish(RunOutcome& out, double mu0, double mu_min);
};

/// Input validation (InvalidInput) and closed-form necessary conditions
/// (InfeasibleFormParameters); defined in diagnose.cpp.
void validate_request(const FormCurveRequest& req);
/// Builds the InfeasibleFormParameters message after the solver failed from every start.
std::string failure_report(Solver& solver, const RunOutcome& best);

}  // namespace fairlines::form_curve_impl
