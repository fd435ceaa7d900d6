// design_form_curve: validation, closed-form checks, continuation runs, multistart,
// and the result / diagnosis.
#include <cmath>
#include <numbers>
#include <random>

#include "fairlines/errors.hpp"
#include "fairlines/limits.hpp"
#include "problem.hpp"
#include "solver.hpp"

namespace fairlines {

using form_curve_impl::Problem;
using form_curve_impl::RunOutcome;
using form_curve_impl::Solver;

namespace {

Eigen::VectorXd flatten(const Eigen::MatrixXd& cps) {
  Eigen::VectorXd z(cps.size());
  for (int c = 0; c < cps.cols(); ++c) z.segment(c * cps.rows(), cps.rows()) = cps.col(c);
  return z;
}

std::map<std::string, double> params_of(const form_curve_impl::SplineTables& tab, const Eigen::VectorXd& z,
                                        int dim) {
  const int n = tab.n;
  std::map<std::string, double> out;
  const char* pos[2][3] = {{"xB", "yB", "zB"}, {"xE", "yE", "zE"}};
  for (int e = 0; e < 2; ++e)
    for (int c = 0; c < dim; ++c) out[pos[e][c]] = z[c * n + (e == 0 ? 0 : n - 1)];
  const char* an[2] = {"alphaB", "alphaE"};
  const char* cn[2] = {"CAB", "CAE"};
  for (int e = 0; e < 2; ++e) {
    const Eigen::MatrixXd& R = tab.end_rows[e];
    const double x1 = R.row(1).dot(z.segment(0, n)), y1 = R.row(1).dot(z.segment(n, n));
    const double x2 = R.row(2).dot(z.segment(0, n)), y2 = R.row(2).dot(z.segment(n, n));
    out[an[e]] = std::atan2(y1, x1) * 180.0 / std::numbers::pi;
    out[cn[e]] = (x1 * y2 - y1 * x2) / std::pow(x1 * x1 + y1 * y1, 1.5);
  }
  double A, My, Mx;
  form_curve_impl::area_moments(tab, z, A, My, Mx);
  out["Area"] = A;
  out["xC"] = My / A;
  out["yC"] = Mx / A;
  return out;
}

double angle_diff(double a, double b) {
  double d = std::fmod(a - b, 360.0);
  if (d > 180) d -= 360;
  if (d <= -180) d += 360;
  return d;
}

}  // namespace

namespace {

// A curve handed to form_parameters_of / fairness_of: finite (n x 2) or (n x 3), degree in
// [2, 15], degree + 1 <= n <= the form-curve control point limit.
void check_measured_curve(const char* who, int degree, const Eigen::MatrixXd& control_points) {
  const Eigen::Index n = control_points.rows();
  if (control_points.cols() < 2 || control_points.cols() > 3 || n < degree + 1 || degree < 2 || degree > 15 ||
      n > limits::kMaxFormCurveControlPoints || !control_points.allFinite())
    throw InvalidInput(std::string(who) + ": control_points must be finite (n x 2) or (n x 3) with degree + 1 <= n <= " +
                       std::to_string(limits::kMaxFormCurveControlPoints) + " and 2 <= degree <= 15; got " +
                       std::to_string(n) + " x " + std::to_string(control_points.cols()) + ", degree " +
                       std::to_string(degree));
}

}  // namespace

std::map<std::string, double> form_parameters_of(int degree, const Eigen::MatrixXd& control_points) {
  check_measured_curve("form_parameters_of", degree, control_points);
  form_curve_impl::SplineTables tab(static_cast<int>(control_points.rows()), degree);
  return params_of(tab, flatten(control_points), static_cast<int>(control_points.cols()));
}

FairnessMeasures fairness_of(int degree, const Eigen::MatrixXd& control_points) {
  FormCurveRequest req;
  req.dim = static_cast<int>(control_points.cols());
  req.degree = degree;
  check_measured_curve("fairness_of", degree, control_points);
  req.n_control = static_cast<int>(control_points.rows());
  req.bounds.monotone_axis = -1;
  req.bounds.y_nonnegative = false;
  Problem pb(req);
  return pb.measures(flatten(control_points));
}

namespace {

// The deterministic start curves: the user's control points projected onto the linear form
// parameters, or the fairest curve meeting only those (when inside the bounds) and the straight one.
std::vector<Eigen::VectorXd> deterministic_starts(Solver& solver, const Problem& pb, const FormCurveRequest& req) {
  std::vector<Eigen::VectorXd> starts;
  if (req.initial_control_points.size() > 0) {
    Eigen::VectorXd z0 = solver.start_curve(nullptr);
    z0.head(pb.nctrl) = flatten(req.initial_control_points);
    z0 = solver.project_linear(z0);
    if (!solver.interior(z0))
      throw InvalidInput("initial_control_points (after projection onto the linear form parameters) violate the bounds");
    starts.push_back(z0);
    return starts;
  }
  const Eigen::VectorXd zc = solver.start_curve(nullptr);
  const Eigen::VectorXd zf = solver.fair_linear_start(zc);
  if (solver.interior(zf)) starts.push_back(zf);
  starts.push_back(zc);
  return starts;
}

struct Runs {
  RunOutcome best, furthest;  // the fairest feasible run; the infeasible run that got furthest
  bool have = false;
  int steps = 0, iterations = 0;
};

// Runs from the deterministic starts, then 1 + multistart random ones (kFallbackRestarts more
// when none has succeeded); a deterministic start after the first is tried only while none has.
Runs run_starts(Solver& solver, const std::vector<Eigen::VectorXd>& starts, const FormCurveRequest& req) {
  constexpr int kFallbackRestarts = 6;
  std::mt19937 rng(req.options.seed);
  Runs r;
  r.furthest.tau = -1;
  const int wanted = 1 + req.options.multistart;
  const int n_det = static_cast<int>(starts.size());
  for (int attempt = 0; attempt < wanted + kFallbackRestarts; ++attempt) {
    if (attempt >= wanted && r.have) break;
    if (attempt >= 1 && attempt < n_det && r.have) continue;
    Eigen::VectorXd z0;
    if (attempt < n_det) {
      z0 = starts[attempt];
    } else {
      bool ok = false;
      for (int k = 0; k < 20 && !ok; ++k) {
        z0 = solver.project_linear(solver.start_curve(&rng));
        ok = solver.interior(z0);
      }
      if (!ok) continue;
    }
    if (!solver.interior(z0)) continue;
    RunOutcome out = solver.run(z0, req.options.continuation);  // the iteration budget applies per start
    r.iterations += solver.iterations();
    r.steps += out.steps;
    if (out.feasible && (!r.have || out.objective < r.best.objective)) {
      r.best = out;
      r.have = true;
    }
    if (!out.feasible && out.tau > r.furthest.tau) r.furthest = out;
  }
  return r;
}

// No run met the request: ConvergenceError when the furthest reached the values, else
// InfeasibleFormParameters with the report of the furthest run.
[[noreturn]] void fail_runs(Solver& solver, Problem& pb, RunOutcome furthest, const Eigen::VectorXd& first_start) {
  if (furthest.tau < 0) {
    furthest.z = first_start;
    furthest.tau = 0;
  }
  if (furthest.tau >= 1)
    throw ConvergenceError("form-parameter solver reached the requested values but not the tolerance (violation " +
                           std::to_string(furthest.violation) + ")");
  // restore the continuation origin of the furthest run for the report
  for (size_t i = 0; i < pb.cons.size() && i < furthest.starts.size(); ++i) pb.cons[i].start = furthest.starts[i];
  throw InfeasibleFormParameters(form_curve_impl::failure_report(solver, furthest));
}

FormCurveResult result_of(Problem& pb, const FormCurveRequest& req, const Runs& r) {
  const RunOutcome& best = r.best;
  FormCurveResult res;
  res.degree = pb.p;
  res.knots = pb.tab.knots;
  res.control_points.resize(pb.n, pb.dim);
  for (int c = 0; c < pb.dim; ++c) res.control_points.col(c) = best.z.segment(c * pb.n, pb.n);
  const auto all = params_of(pb.tab, best.z, pb.dim);
  for (const auto& [k, v] : req.params) {
    res.achieved[k] = all.at(k);
    res.residuals[k] = (k == "alphaB" || k == "alphaE") ? angle_diff(all.at(k), v) : all.at(k) - v;
  }
  res.point_parameters = best.z.tail(pb.npts);
  res.point_residuals.resize(pb.npts);
  Eigen::MatrixXd C, ders;
  for (int j = 0; j < pb.npts; ++j) {
    int f = 0;
    pb.point_derivs(best.z, best.z[pb.tvar(j)], C, ders, f);
    res.point_residuals[j] = (C.row(0).transpose() - req.points[j].position).norm();
  }
  res.fairness = pb.measures(best.z);
  res.objective = best.objective;
  res.iterations = r.iterations;
  res.continuation_steps = r.steps;
  res.converged = best.converged;
  return res;
}

}  // namespace

FormCurveResult design_form_curve(const FormCurveRequest& request) {
  form_curve_impl::validate_request(request);
  check_form_parameters_feasible(request);
  FormCurveRequest req = request;
  Problem pb(req);
  Solver solver(pb, req.options.max_iterations);
  const std::vector<Eigen::VectorXd> starts = deterministic_starts(solver, pb, req);
  const Runs runs = run_starts(solver, starts, req);
  if (!runs.have) fail_runs(solver, pb, runs.furthest, starts.front());
  return result_of(pb, req, runs);
}

namespace form_curve_detail {

Derivatives evaluate_problem(const FormCurveRequest& request, const Eigen::VectorXd& z,
                             const Eigen::VectorXd& lambda) {
  form_curve_impl::validate_request(request);
  Problem pb(request);
  if (z.size() != pb.nv) throw InvalidInput("evaluate_problem: z has the wrong length");
  Derivatives d;
  pb.constraints(z, d.c, &d.J, lambda.size() == static_cast<long>(pb.cons.size()) ? &lambda : nullptr, &d.HL);
  if (lambda.size() != static_cast<long>(pb.cons.size())) d.HL = Eigen::MatrixXd::Zero(pb.nv, pb.nv);
  d.f = pb.objective(z, &d.g, &d.H);
  for (const auto& k : pb.cons) d.names.push_back(k.name);
  return d;
}

}  // namespace form_curve_detail
}  // namespace fairlines
