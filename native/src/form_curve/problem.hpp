// Internal: the form-parameter curve problem (variables, constraints, objective,
// barrier) shared by the solver and the diagnosis. Not part of the public API.
#pragma once

#include <Eigen/Core>

#include <string>
#include <vector>

#include "fairlines/form_curve.hpp"

namespace fairlines::form_curve_impl {

/// Gauss-Legendre nodes / weights on [-1, 1] (Newton iteration on P_n).
void gauss_legendre(int n, Eigen::VectorXd& nodes, Eigen::VectorXd& weights);

/// Basis data of a clamped uniform B-spline on [0,1] at the quadrature points of every
/// knot span, plus the end derivative rows.
struct SplineTables {
  int n = 0, p = 0, nq = 0;    // control points, degree, quadrature points in total
  Eigen::VectorXd knots;
  Eigen::VectorXd w;           // nq quadrature weights (in t)
  std::vector<int> first;      // nq: index of the first non-zero basis function
  Eigen::MatrixXd N[4];        // (p+1) x nq: derivative d of the non-zero basis functions
  Eigen::MatrixXd end_rows[2]; // 3 x n: derivatives 0..2 of all basis functions at t=0 / t=1
  Eigen::MatrixXd K[3];        // n x n Gram matrices int N^(k) N^(k)T, k = 1..3
  // Area and moments: their integrands y x', x y x', y^2 x' are polynomials of degree
  // <= 3p - 1 on every knot span, so the smallest Gauss rule exact for them,
  // ceil(3p / 2) points per span, gives the same values as any higher order. The
  // general rule above (>= 8 points per span) is kept for the arc length.
  int per_span_area = 0, nqa = 0;
  Eigen::VectorXd wa;          // nqa quadrature weights (in t); point q lies on span q / per_span_area
  Eigen::MatrixXd Na[2];       // (p+1) x nqa: values and first derivatives of the non-zero basis functions
  SplineTables(int n_control, int degree);
};

enum class ConKind { Linear, Curvature, Area, MomentXC, MomentYC, Point };

struct Constraint {
  ConKind kind;
  std::string name;         // form parameter name ("points[3].y" for points)
  Eigen::VectorXd row;      // Linear: c = row . z - target
  double target = 0;        // current (continuation) target
  double requested = 0;     // requested value
  double start = 0;         // value at the start curve
  double scale = 1;         // residual scale for tolerances
  int end = 0;              // Curvature: 0 start, 1 end
  int point = -1, coord = 0;  // Point constraints
};

/// Linear inequalities G z - h > 0 as they are gathered: rows of G, entries of h, and names.
struct InequalityRows {
  std::vector<Eigen::VectorXd> rows;
  std::vector<double> rhs;
  std::vector<std::string>& names;
  void add(Eigen::VectorXd row, double hh, std::string name);
};

struct Problem {
  const FormCurveRequest& req;
  SplineTables tab;
  int n, p, dim, npts, nv, nctrl;
  double Ls = 1;                       // length scale
  std::vector<Constraint> cons;        // equality constraints
  Eigen::MatrixXd G;                   // linear inequalities G z - h > 0
  Eigen::VectorXd h;
  std::vector<std::string> ineq_names;
  Eigen::MatrixXd Kf;                  // combined quadratic fairness matrix (n x n)
  bool need_area = false;

  explicit Problem(const FormCurveRequest& r);

  int var(int coord, int i) const { return coord * n + i; }
  int tvar(int j) const { return nctrl + j; }
  bool has(const std::string& name) const { return req.params.count(name) > 0; }
  double param(const std::string& name) const { return req.params.at(name); }
  /// The requested 3-D tangent at end e (0 start, 1 end); empty when none.
  const Eigen::VectorXd& end_tangent(int e) const;

  // Steps of the constructor: the length scale Ls, the equality constraints (linear end
  // conditions, then end curvatures, area and centroid, then interpolated points), and the
  // inequality rows (monotone control polygon, y >= 0, end tangent sense, point parameters).
  double length_scale() const;
  void add_end_conditions();
  void add_curvature_and_integral_conditions();
  void add_point_conditions();
  void add_monotone_rows(InequalityRows& ineq) const;
  void add_end_sense_rows(InequalityRows& ineq) const;

  /// Constraints, Jacobian and sum lambda_i Hess c_i (HL only if lambda non-empty).
  void constraints(const Eigen::VectorXd& z, Eigen::VectorXd& c, Eigen::MatrixXd* J,
                   const Eigen::VectorXd* lambda, Eigen::MatrixXd* HL) const;
  /// Area A and first moments My = int x y dx, Mx = int y^2/2 dx of the curve, with the
  /// Jacobian rows of the area-type constraints and their Hessian terms (weighted by lambda).
  struct AreaIntegrals {
    double A = 0, My = 0, Mx = 0;
  };
  AreaIntegrals area_integrals(const Eigen::VectorXd& z, Eigen::MatrixXd* J, const Eigen::VectorXd* lambda,
                               Eigen::MatrixXd* HL) const;
  /// End curvature constraint i: value, Jacobian row, Hessian term.
  void curvature_constraint(int i, const Eigen::VectorXd& z, Eigen::VectorXd& c, Eigen::MatrixXd* J,
                            const Eigen::VectorXd* lambda, Eigen::MatrixXd* HL) const;
  /// Point constraint i (a coordinate at a free parameter): value, Jacobian row, Hessian term.
  void point_constraint(int i, const Eigen::VectorXd& z, Eigen::VectorXd& c, Eigen::MatrixXd* J,
                        const Eigen::VectorXd* lambda, Eigen::MatrixXd* HL) const;
  /// Objective, gradient and Hessian (g, H optional): the fairness energy, the length term and
  /// the penalties of the approximated points, each added by one step below to g, H and to the
  /// sum f it returns (f passed by value: a local sum the compiler keeps in a register).
  double objective(const Eigen::VectorXd& z, Eigen::VectorXd* g, Eigen::MatrixXd* H) const;
  double add_fairness(const Eigen::VectorXd& z, double f, Eigen::VectorXd* g, Eigen::MatrixXd* H) const;
  double add_length(const Eigen::VectorXd& z, double f, Eigen::VectorXd* g, Eigen::MatrixXd* H) const;
  double add_point_penalties(const Eigen::VectorXd& z, double f, Eigen::VectorXd* g, Eigen::MatrixXd* H) const;
  /// Fairness measures of control points z.
  FairnessMeasures measures(const Eigen::VectorXd& z) const;
  /// Curve value and derivatives up to 2 at parameter t: (3 x dim), plus the local
  /// basis derivative table (3 x (p+1)) and first index.
  void point_derivs(const Eigen::VectorXd& z, double t, Eigen::MatrixXd& C, Eigen::MatrixXd& ders,
                    int& first) const;
  /// Scaled constraint residual max |c_i| / scale_i.
  double scaled_violation(const Eigen::VectorXd& c) const;
};

/// Area, x-moment int x y dx and y-moment int y^2/2 dx of control points z (first two coords).
void area_moments(const SplineTables& tab, const Eigen::VectorXd& z, double& A, double& My, double& Mx);

}  // namespace fairlines::form_curve_impl
