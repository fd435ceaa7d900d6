// Internal: SQP / barrier / continuation solver of the form-parameter curve problem.
#pragma once

#include <cstdlib>
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

struct Solver {
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
  bool debug = std::getenv("FAIRLINES_FC_DEBUG") != nullptr;

  explicit Solver(Problem& problem);
  Eigen::VectorXd start_curve(std::mt19937* rng) const;
  Eigen::VectorXd fair_linear_start(const Eigen::VectorXd& zc) const;
  Eigen::VectorXd project_linear(const Eigen::VectorXd& z) const;
  bool interior(const Eigen::VectorXd& z) const;
  void set_starts(const Eigen::VectorXd& z);
  void set_targets(double tau);
  bool newton(Eigen::VectorXd& z, Eigen::VectorXd& lam, double mu, double tol_c, double tol_g, int maxit);
  double merit(const Eigen::VectorXd& z, double mu, double nu, Eigen::VectorXd& c) const;
  /// The merit from already computed objective f, constraints c and slacks s = G z - h > 0.
  double merit_of(double f, const Eigen::VectorXd& c, const Eigen::VectorXd& s, double mu, double nu) const;
  double restore_tol = 1e-3;
  bool restore(Eigen::VectorXd& z, int maxit);
  RunOutcome run(const Eigen::VectorXd& z0, bool continuation);
};

/// Input validation (InvalidInput) and closed-form necessary conditions
/// (InfeasibleFormParameters); defined in diagnose.cpp.
void validate_request(const FormCurveRequest& req);
/// Builds the InfeasibleFormParameters message after the solver failed from every start.
std::string failure_report(Solver& solver, const RunOutcome& best);

}  // namespace fairlines::form_curve_impl
