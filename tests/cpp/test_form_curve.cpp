// Form-parameter curve solver: exactness against dense quadrature of the evaluated
// curve, analytic derivatives against finite differences, infeasibility and bad input.
#include <cmath>
#include <numbers>
#include <random>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "fairlines/curve.hpp"
#include "fairlines/errors.hpp"
#include "fairlines/form_curve.hpp"
#include "fairlines/knots.hpp"

namespace fairlines {
namespace {

FormCurveRequest table3() {
  FormCurveRequest r;
  r.params = {{"xB", 0.0},    {"yB", 0.569026}, {"xE", 1.0},   {"yE", 0.0},       {"alphaB", -31.0}, {"alphaE", -58.0},
              {"CAB", -1.5},  {"CAE", -4.41},   {"Area", 0.1925}, {"xC", 0.28489}, {"yC", 0.16952}};
  return r;
}

FormCurveRequest table2() {
  FormCurveRequest r;
  r.params = {{"xB", 0.0},   {"yB", 0.998204}, {"xE", 1.0},      {"yE", 0.33031}, {"alphaB", -5.0}, {"alphaE", -85.0},
              {"CAB", -0.5}, {"CAE", -1.5},    {"Area", 0.8103}, {"xC", 0.4330},  {"yC", 0.42195}};
  return r;
}

/// Every form parameter from the evaluated NurbsCurve: composite Simpson in t.
std::map<std::string, double> dense_parameters(const NurbsCurve& c, int m = 20000) {
  double A = 0, My = 0, Mx = 0;
  const double h = 1.0 / m;
  for (int i = 0; i <= m; ++i) {
    const double t = i * h;
    const Eigen::MatrixXd d = c.derivatives(t, 1);
    const double w = (i == 0 || i == m) ? 1 : (i % 2 ? 4 : 2);
    const double x = d(0, 0), y = d(0, 1), xp = d(1, 0);
    A += w * y * xp;
    My += w * x * y * xp;
    Mx += w * 0.5 * y * y * xp;
  }
  A *= h / 3;
  My *= h / 3;
  Mx *= h / 3;
  std::map<std::string, double> out{{"Area", A}, {"xC", My / A}, {"yC", Mx / A}};
  const char* end[2] = {"B", "E"};
  for (int e = 0; e < 2; ++e) {
    const Eigen::MatrixXd d = c.derivatives(e == 0 ? 0.0 : 1.0, 2);
    out[std::string("x") + end[e]] = d(0, 0);
    out[std::string("y") + end[e]] = d(0, 1);
    out[std::string("alpha") + end[e]] = std::atan2(d(1, 1), d(1, 0)) * 180 / std::numbers::pi;
    out[std::string("CA") + end[e]] =
        (d(1, 0) * d(2, 1) - d(1, 1) * d(2, 0)) / std::pow(d(1, 0) * d(1, 0) + d(1, 1) * d(1, 1), 1.5);
  }
  return out;
}

TEST(FormCurve, Table3MetExactlyAndCheckedByDenseQuadrature) {
  const FormCurveRequest req = table3();
  const FormCurveResult res = design_form_curve(req);
  EXPECT_TRUE(res.converged);
  for (const auto& [k, v] : res.residuals) EXPECT_LE(std::abs(v), 1e-9) << k;
  const NurbsCurve curve(res.degree, res.knots, res.control_points);
  const auto dense = dense_parameters(curve);
  for (const auto& [k, v] : req.params) EXPECT_NEAR(dense.at(k), v, 1e-8) << k;
  // section: x monotone and y >= 0 on the control polygon
  for (int i = 0; i + 1 < res.control_points.rows(); ++i)
    EXPECT_GE(res.control_points(i + 1, 0) - res.control_points(i, 0), 0.0);
  EXPECT_GE(res.control_points.col(1).minCoeff(), 0.0);
}

TEST(FormCurve, Table2InfeasibleWithoutFoldingNamesConflict) {
  try {
    design_form_curve(table2());
    FAIL() << "expected InfeasibleFormParameters";
  } catch (const InfeasibleFormParameters& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("yC"), std::string::npos);
    EXPECT_NE(msg.find("Area"), std::string::npos);
    EXPECT_NE(msg.find("0.42697"), std::string::npos);
  }
}

TEST(FormCurve, Table2WithoutYcIsFairAndExact) {
  FormCurveRequest req = table2();
  req.params.erase("yC");
  const FormCurveResult res = design_form_curve(req);
  for (const auto& [k, v] : res.residuals) EXPECT_LE(std::abs(v), 1e-9) << k;
  const NurbsCurve curve(res.degree, res.knots, res.control_points);
  for (int i = 0; i <= 2000; ++i) EXPECT_GE(curve.derivatives(i / 2000.0, 1)(1, 0), -1e-12);
}

TEST(FormCurve, SpaceCurveAndMoreControlPoints) {
  FormCurveRequest req;
  req.dim = 3;
  req.n_control = 12;
  req.params = {{"xB", 0}, {"yB", 0}, {"zB", 0}, {"xE", 1}, {"yE", 2}, {"zE", 1}};
  req.tangent_start = Eigen::Vector3d(1, 0, 0);
  req.tangent_end = Eigen::Vector3d(0, 0, 1);
  req.bounds.monotone_axis = -1;
  req.bounds.y_nonnegative = false;
  const FormCurveResult res = design_form_curve(req);
  const NurbsCurve curve(res.degree, res.knots, res.control_points);
  const Eigen::Vector3d d0 = curve.derivatives(0.0, 1).row(1).transpose();
  const Eigen::Vector3d d1 = curve.derivatives(1.0, 1).row(1).transpose();
  EXPECT_LE(d0.normalized().cross(Eigen::Vector3d(1, 0, 0)).norm(), 1e-9);
  EXPECT_GT(d0.x(), 0);
  EXPECT_LE(d1.normalized().cross(Eigen::Vector3d(0, 0, 1)).norm(), 1e-9);
  EXPECT_GT(d1.z(), 0);
  EXPECT_NEAR(res.control_points(11, 1), 2.0, 1e-12);
}

TEST(FormCurve, AnalyticDerivativesMatchFiniteDifferences) {
  FormCurveRequest req = table3();
  req.fairness.e1 = 0.2;
  req.fairness.length = 0.7;
  FormPoint p;
  p.position = Eigen::Vector2d(0.5, 0.2);
  req.points.push_back(p);
  p.position = Eigen::Vector2d(0.3, 0.4);
  p.weight = 20;
  req.points.push_back(p);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(0.2, 0.8), N(-1, 1);
  const int n = req.n_control, nv = 2 * n + 2;
  Eigen::VectorXd z(nv);
  for (int i = 0; i < n; ++i) z[i] = double(i) / (n - 1) + 0.02 * N(rng), z[n + i] = U(rng);
  z[2 * n] = 0.45;
  z[2 * n + 1] = 0.35;
  const auto d0 = form_curve_detail::evaluate_problem(req, z, Eigen::VectorXd());
  Eigen::VectorXd lam(d0.c.size());
  for (int i = 0; i < lam.size(); ++i) lam[i] = N(rng);
  const auto d = form_curve_detail::evaluate_problem(req, z, lam);
  const double h = 1e-6;
  for (int i = 0; i < nv; ++i) {
    Eigen::VectorXd zp = z, zm = z;
    zp[i] += h;
    zm[i] -= h;
    const auto dp = form_curve_detail::evaluate_problem(req, zp, lam);
    const auto dm = form_curve_detail::evaluate_problem(req, zm, lam);
    const Eigen::VectorXd Jfd = (dp.c - dm.c) / (2 * h);
    const Eigen::VectorXd HLfd = (dp.J.transpose() * lam - dm.J.transpose() * lam) / (2 * h);
    const Eigen::VectorXd Hfd = (dp.g - dm.g) / (2 * h);
    for (int r = 0; r < d.c.size(); ++r) EXPECT_NEAR(d.J(r, i), Jfd[r], 1e-6 * (1 + std::abs(Jfd[r]))) << r << "," << i;
    for (int r = 0; r < nv; ++r) {
      EXPECT_NEAR(d.HL(r, i), HLfd[r], 1e-5 * (1 + std::abs(HLfd[r]))) << r << "," << i;
      EXPECT_NEAR(d.H(r, i), Hfd[r], 1e-4 * (1 + std::abs(Hfd[r]))) << r << "," << i;
    }
    EXPECT_NEAR(d.g[i], (dp.f - dm.f) / (2 * h), 1e-6 * (1 + std::abs(d.g[i])));
  }
}

TEST(FormCurve, InfeasibleRequestsThrowTyped) {
  FormCurveRequest r = table3();
  r.params["xC"] = 1.5;  // centroid outside the end points' x range
  EXPECT_THROW(design_form_curve(r), InfeasibleFormParameters);
  r = table3();
  r.params["Area"] = -0.2;
  EXPECT_THROW(design_form_curve(r), InfeasibleFormParameters);
  r = table3();
  r.params["alphaB"] = 135;
  EXPECT_THROW(design_form_curve(r), InfeasibleFormParameters);
}

TEST(FormCurve, BadInputThrowsInvalidInput) {
  FormCurveRequest r = table3();
  r.params["Area"] = std::nan("");
  EXPECT_THROW(design_form_curve(r), InvalidInput);
  r = table3();
  r.params["Volume"] = 1;
  EXPECT_THROW(design_form_curve(r), InvalidInput);
  r = table3();
  r.n_control = 5;  // 11 conditions on 10 coordinates
  EXPECT_THROW(design_form_curve(r), InvalidInput);
  r = table3();
  r.fairness.e2 = -1;
  EXPECT_THROW(design_form_curve(r), InvalidInput);
  r = table3();
  r.dim = 4;
  EXPECT_THROW(design_form_curve(r), InvalidInput);
}

}  // namespace
}  // namespace fairlines
