// Form-parameter curve problem: basis tables, constraints with analytic Jacobian and
// Hessians, fairness objective with gradient and Hessian.
//
// Notation:
//   n, p, dim    control points, degree and coordinates (2: x, y; 3: x, y, z) of the clamped
//                uniform B-spline C(t), t in [0, 1]
//   z            the variables: the control coordinates one coordinate after the other
//                (var(c, i) = c n + i), then one curve parameter t_j per point (tvar(j))
//   nv, nctrl    number of variables, and of control coordinates among them (dim n)
//   B, E         start (t = 0) and end (t = 1) in the parameter names: xB, yE, alphaB, CAE ...
//   Ls           length scale of the request (m): the residual scale of each constraint
//   c, J, HL     constraint values c_i(z) = value - target, their Jacobian, and
//                sum_i lambda_i Hess c_i
//   G, h         linear inequalities G z - h > 0: monotone control polygon, y >= 0, end tangent
//                sense, 0 < t_j < 1
//   Kf           fairness matrix e1 K1 + e2 K2 + e3 K3 (Kk: Gram matrix of the k-th derivatives)
//   A, My, Mx    area int y x' dt, moments int x y x' dt and int y^2/2 x' dt
//   N0, N1       the p + 1 non-zero basis values and first derivatives at a Gauss point
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <tuple>
#include <vector>

#include <Eigen/Geometry>

#include "fairlines/basis.hpp"
#include "fairlines/knots.hpp"
#include "nurbs/gauss.hpp"
#include "problem.hpp"

namespace fairlines::form_curve_impl {

void gauss_legendre(int n, Eigen::VectorXd& nodes, Eigen::VectorXd& weights) {
  const detail::GaussRule& g = detail::gauss_rule(n);
  nodes = Eigen::Map<const Eigen::VectorXd>(g.x.data(), n);
  weights = Eigen::Map<const Eigen::VectorXd>(g.w.data(), n);
}

SplineTables::SplineTables(int n_control, int degree) : n(n_control), p(degree) {
  knots = clamped_uniform_knots(n, p, 0.0, 1.0);
  const int per_span = std::max(8, (3 * p + 1) / 2 + 1);
  Eigen::VectorXd gx, gw;
  gauss_legendre(per_span, gx, gw);
  const int spans = n - p;
  nq = spans * per_span;
  w.resize(nq);
  first.resize(nq);
  for (auto& m : N) m.resize(p + 1, nq);
  Eigen::MatrixXd ders(4, p + 1);
  int q = 0;
  for (int s = 0; s < spans; ++s) {
    const double a = knots[p + s], b = knots[p + s + 1];
    for (int k = 0; k < per_span; ++k, ++q) {
      const double t = 0.5 * (a + b) + 0.5 * (b - a) * gx[k];
      w[q] = 0.5 * (b - a) * gw[k];
      const int span = p + s;
      basis_derivatives(span, t, p, 3, knots, ders);
      first[q] = span - p;
      for (int d = 0; d < 4; ++d) N[d].col(q) = ders.row(d).transpose();
    }
  }
  per_span_area = (3 * p + 1) / 2;  // 2 * per_span_area - 1 >= 3p - 1
  gauss_legendre(per_span_area, gx, gw);
  nqa = spans * per_span_area;
  wa.resize(nqa);
  for (auto& m : Na) m.resize(p + 1, nqa);
  q = 0;
  for (int s = 0; s < spans; ++s) {
    const double a = knots[p + s], b = knots[p + s + 1];
    for (int k = 0; k < per_span_area; ++k, ++q) {
      const double t = 0.5 * (a + b) + 0.5 * (b - a) * gx[k];
      wa[q] = 0.5 * (b - a) * gw[k];
      basis_derivatives(p + s, t, p, 1, knots, ders.topRows(2));
      for (int d = 0; d < 2; ++d) Na[d].col(q) = ders.row(d).transpose();
    }
  }
  for (int e = 0; e < 2; ++e) {
    end_rows[e] = Eigen::MatrixXd::Zero(3, n);
    const double t = e == 0 ? 0.0 : 1.0;
    const int span = find_span(p, knots, t);
    basis_derivatives(span, t, p, 2, knots, ders.topRows(3));
    for (int d = 0; d < 3; ++d)
      for (int k = 0; k <= p; ++k) end_rows[e](d, span - p + k) = ders(d, k);
  }
  for (int d = 1; d <= 3; ++d) {
    K[d - 1] = Eigen::MatrixXd::Zero(n, n);
    for (int qq = 0; qq < nq; ++qq) {
      const int f = first[qq];
      for (int i = 0; i <= p; ++i)
        for (int j = 0; j <= p; ++j) K[d - 1](f + i, f + j) += w[qq] * N[d](i, qq) * N[d](j, qq);
    }
  }
}

void area_moments(const SplineTables& tab, const Eigen::VectorXd& z, double& A, double& My, double& Mx) {
  A = My = Mx = 0;
  const int n = tab.n, pp = tab.p + 1;
  for (int q = 0; q < tab.nqa; ++q) {
    const int f = q / tab.per_span_area;
    const double* N0 = tab.Na[0].col(q).data();
    const double* N1 = tab.Na[1].col(q).data();
    double x = 0, y = 0, xp = 0;
    for (int k = 0; k < pp; ++k) {
      x += N0[k] * z[f + k];
      y += N0[k] * z[n + f + k];
      xp += N1[k] * z[f + k];
    }
    const double wq = tab.wa[q];
    A += wq * y * xp;
    My += wq * x * y * xp;
    Mx += wq * 0.5 * y * y * xp;
  }
}

namespace {
constexpr double kDeg = std::numbers::pi / 180.0;

/// Names of the end conditions: position [end][coordinate], angle, 3-D tangent, curvature.
constexpr const char* kEndPosition[2][3] = {{"xB", "yB", "zB"}, {"xE", "yE", "zE"}};
constexpr const char* kEndAngle[2] = {"alphaB", "alphaE"};
constexpr const char* kEndTangent[2] = {"tangent_start", "tangent_end"};
constexpr const char* kEndCurvature[2] = {"CAB", "CAE"};

Eigen::VectorXd unit_row(int nv, int k) {
  Eigen::VectorXd r = Eigen::VectorXd::Zero(nv);
  r[k] = 1;
  return r;
}

/// The point name in messages: "points[j]".
std::string point_name(int j) { return "points[" + std::to_string(j) + "]"; }
}  // namespace

void InequalityRows::add(Eigen::VectorXd row, double hh, std::string name) {
  rows.push_back(std::move(row));
  rhs.push_back(hh);
  names.push_back(std::move(name));
}

Problem::Problem(const FormCurveRequest& r)
    : req(r), tab(r.n_control, r.degree), n(r.n_control), p(r.degree), dim(r.dim),
      npts(static_cast<int>(r.points.size())) {
  nctrl = dim * n;
  nv = nctrl + npts;
  Ls = length_scale();
  add_end_conditions();
  add_curvature_and_integral_conditions();
  need_area = has("Area") || has("xC") || has("yC");
  add_point_conditions();
  InequalityRows ineq{{}, {}, ineq_names};
  add_monotone_rows(ineq);
  if (req.bounds.y_nonnegative)
    for (int i = 0; i < n; ++i) ineq.add(unit_row(nv, var(1, i)), 0, "y >= 0 (control point " + std::to_string(i) + ")");
  add_end_sense_rows(ineq);
  for (int j = 0; j < npts; ++j) {
    ineq.add(unit_row(nv, tvar(j)), 0, point_name(j) + " parameter > 0");
    ineq.add(-unit_row(nv, tvar(j)), -1, point_name(j) + " parameter < 1");
  }
  G.resize(static_cast<int>(ineq.rows.size()), nv);
  h.resize(static_cast<int>(ineq.rows.size()));
  for (size_t i = 0; i < ineq.rows.size(); ++i) {
    G.row(static_cast<int>(i)) = ineq.rows[i].transpose();
    h[static_cast<int>(i)] = ineq.rhs[i];
  }
  const auto& fw = req.fairness;
  Kf = fw.e1 * tab.K[0] + fw.e2 * tab.K[1] + fw.e3 * tab.K[2];
}

const Eigen::VectorXd& Problem::end_tangent(int e) const { return e == 0 ? req.tangent_start : req.tangent_end; }

double Problem::length_scale() const {
  double ext = 0;
  for (int c = 0; c < dim; ++c) {
    double lo = 1e300, hi = -1e300;
    for (const auto& end : kEndPosition)
      if (has(end[c])) lo = std::min(lo, param(end[c])), hi = std::max(hi, param(end[c]));
    for (const auto& pt : req.points) lo = std::min(lo, pt.position[c]), hi = std::max(hi, pt.position[c]);
    if (hi >= lo) ext = std::max(ext, hi - lo);
  }
  if (has("Area")) ext = std::max(ext, std::sqrt(std::abs(param("Area"))));
  return ext > 1e-12 ? ext : 1.0;
}

void Problem::add_end_conditions() {
  for (int e = 0; e < 2; ++e)
    for (int c = 0; c < dim; ++c)
      if (has(kEndPosition[e][c])) {
        Constraint k{ConKind::Linear, kEndPosition[e][c], unit_row(nv, var(c, e == 0 ? 0 : n - 1))};
        k.target = k.requested = k.start = param(kEndPosition[e][c]);
        k.scale = Ls;
        cons.push_back(k);
      }
  // the end tangent (x', y') is normal to (-sin a, cos a)
  for (int e = 0; e < 2; ++e)
    if (has(kEndAngle[e])) {
      const double a = param(kEndAngle[e]) * kDeg;
      const Eigen::RowVectorXd d1 = tab.end_rows[e].row(1);
      Constraint k{ConKind::Linear, kEndAngle[e], Eigen::VectorXd::Zero(nv)};
      k.row.segment(var(0, 0), n) = -std::sin(a) * d1.transpose();
      k.row.segment(var(1, 0), n) = std::cos(a) * d1.transpose();
      k.scale = Ls * d1.norm();
      cons.push_back(k);
    }
  // a 3-D end tangent along d: C' normal to two directions e1, e2 across d
  for (int e = 0; e < 2 && dim == 3; ++e)
    if (end_tangent(e).size() == 3) {
      const Eigen::Vector3d d = end_tangent(e).normalized();
      Eigen::Vector3d e1 = std::abs(d.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
      e1 = (e1 - e1.dot(d) * d).normalized();
      const Eigen::Vector3d e2 = d.cross(e1);
      const Eigen::RowVectorXd d1 = tab.end_rows[e].row(1);
      for (const Eigen::Vector3d& ev : {e1, e2}) {
        Constraint k{ConKind::Linear, kEndTangent[e], Eigen::VectorXd::Zero(nv)};
        for (int c = 0; c < 3; ++c) k.row.segment(var(c, 0), n) = ev[c] * d1.transpose();
        k.scale = Ls * d1.norm();
        cons.push_back(k);
      }
    }
}

void Problem::add_curvature_and_integral_conditions() {
  for (int e = 0; e < 2; ++e)
    if (has(kEndCurvature[e])) {
      Constraint k{ConKind::Curvature, kEndCurvature[e], {}};
      k.requested = k.target = param(kEndCurvature[e]);
      k.end = e;
      k.scale = 1.0 / Ls;
      cons.push_back(k);
    }
  // the area (m^2) and its moments (m^3): the centroid conditions are My - xC A = 0, Mx - yC A = 0
  const std::tuple<ConKind, const char*, double> integrals[] = {
      {ConKind::Area, "Area", Ls * Ls}, {ConKind::MomentXC, "xC", Ls * Ls * Ls}, {ConKind::MomentYC, "yC", Ls * Ls * Ls}};
  for (const auto& [kind, name, scale] : integrals)
    if (has(name)) {
      Constraint k{kind, name, {}};
      k.requested = k.target = param(name);
      k.scale = scale;
      cons.push_back(k);
    }
}

void Problem::add_point_conditions() {
  const char* cn = "xyz";
  for (int j = 0; j < npts; ++j) {
    if (!std::isinf(req.points[j].weight)) continue;
    for (int c = 0; c < dim; ++c) {
      Constraint k{ConKind::Point, point_name(j) + "." + cn[c], {}};
      k.requested = k.target = req.points[j].position[c];
      k.point = j;
      k.coord = c;
      k.scale = Ls;
      cons.push_back(k);
    }
  }
}

void Problem::add_monotone_rows(InequalityRows& ineq) const {
  const int ax = req.bounds.monotone_axis;
  if (ax < 0) return;
  // increasing or decreasing: from the end values, else from the first and last point
  double sgn = 1;
  const char* bn = kEndPosition[0][ax];
  const char* en = kEndPosition[1][ax];
  if (has(bn) && has(en)) sgn = param(en) >= param(bn) ? 1 : -1;
  else if (npts >= 2) sgn = req.points.back().position[ax] >= req.points.front().position[ax] ? 1 : -1;
  for (int i = 0; i + 1 < n; ++i) {
    Eigen::VectorXd row = Eigen::VectorXd::Zero(nv);
    row[var(ax, i + 1)] = sgn;
    row[var(ax, i)] = -sgn;
    ineq.add(row, 0, std::string(ax == 0 ? "x" : "y") + "-monotone (control points " + std::to_string(i) + "," +
                         std::to_string(i + 1) + ")");
  }
}

void Problem::add_end_sense_rows(InequalityRows& ineq) const {
  double chord = 0;
  for (int c = 0; c < dim; ++c) {
    const char* bn = kEndPosition[0][c];
    const char* en = kEndPosition[1][c];
    if (has(bn) && has(en)) chord += (param(en) - param(bn)) * (param(en) - param(bn));
  }
  chord = std::sqrt(chord);
  const double hmin = req.bounds.min_end_speed * chord;
  for (int e = 0; e < 2; ++e) {
    const Eigen::RowVectorXd d1 = tab.end_rows[e].row(1);
    if (has(kEndAngle[e])) {
      const double a = param(kEndAngle[e]) * kDeg;
      Eigen::VectorXd row = Eigen::VectorXd::Zero(nv);
      row.segment(var(0, 0), n) = std::cos(a) * d1.transpose();
      row.segment(var(1, 0), n) = std::sin(a) * d1.transpose();
      ineq.add(row, hmin, std::string(kEndAngle[e]) + " (tangent sense, end speed >= min_end_speed * chord)");
    }
    if (dim == 3 && end_tangent(e).size() == 3) {
      const Eigen::Vector3d d = end_tangent(e).normalized();
      Eigen::VectorXd row = Eigen::VectorXd::Zero(nv);
      for (int c = 0; c < 3; ++c) row.segment(var(c, 0), n) = d[c] * d1.transpose();
      ineq.add(row, hmin, std::string(kEndTangent[e]) + " (tangent sense, end speed >= min_end_speed * chord)");
    }
  }
}

void Problem::point_derivs(const Eigen::VectorXd& z, double t, Eigen::MatrixXd& C, Eigen::MatrixXd& ders,
                           int& f) const {
  const double tc = std::clamp(t, 0.0, 1.0);
  const int span = find_span(p, tab.knots, tc);
  ders.resize(3, p + 1);
  basis_derivatives(span, tc, p, 2, tab.knots, ders);
  f = span - p;
  C = Eigen::MatrixXd::Zero(3, dim);
  for (int c = 0; c < dim; ++c)
    for (int k = 0; k <= p; ++k) C.col(c) += ders.col(k) * z[var(c, f + k)];
}

namespace {

/// One Gauss point of the area integrals: weight w, the curve's x, y and x' there, and the p + 1
/// non-zero basis values N0 and derivatives N1.
struct AreaPoint {
  double w, x, y, xp;
  const double* N0;
  const double* N1;
};

/// Adds a Gauss point's terms to the gradients of A = int y x', My = int x y x' and
/// Mx = int y^2/2 x' with respect to the span's x control points (gA, gMy, gMx at f) and y
/// control points (at n + f). Plain loops over raw pointers: with a run-time degree, Eigen's
/// dynamic-size expressions on these (p+1)-vectors cost a call and often an allocation each.
inline void add_area_gradients(const AreaPoint& q, int pp, int n, int f, double* gA, double* gMy, double* gMx) {
  double* gAx = gA + f;
  double* gAy = gA + n + f;
  double* gMyx = gMy + f;
  double* gMyy = gMy + n + f;
  double* gMxx = gMx + f;
  double* gMxy = gMx + n + f;
  const double w = q.w, x = q.x, y = q.y, xp = q.xp;
  const double a1 = w * y, a0 = w * xp, b0 = w * y * xp, b1 = w * x * y, b2 = w * x * xp, c1 = w * 0.5 * y * y;
  for (int k = 0; k < pp; ++k) {
    gAx[k] += a1 * q.N1[k];
    gAy[k] += a0 * q.N0[k];
    gMyx[k] += b0 * q.N0[k] + b1 * q.N1[k];
    gMyy[k] += b2 * q.N0[k];
    gMxx[k] += c1 * q.N1[k];
    gMxy[k] += b0 * q.N0[k];
  }
}

/// The multipliers of A, My and Mx in the constraints' lambda-weighted Hessian.
struct AreaMultipliers {
  double A = 0, My = 0, Mx = 0;
};

/// The Hessian of lA A + lMy My + lMx Mx on one knot span in (p+1) x (p+1) blocks: x-x, y-y, and
/// rows x, columns y.
struct SpanHessian {
  Eigen::MatrixXd xx, yy, xy;
};

/// Adds a Gauss point's terms to the span's Hessian blocks (column-major; u a p + 1 scratch).
inline void add_area_hessian(const AreaPoint& q, int pp, const AreaMultipliers& l, double* u, SpanHessian& hs) {
  const double* N0 = q.N0;
  const double* N1 = q.N1;
  const double a = q.w * l.My * q.y, b = q.w * l.Mx * q.xp;
  const double al = q.w * (l.A + l.My * q.x + l.Mx * q.y), be = q.w * l.My * q.xp;
  for (int i = 0; i < pp; ++i) u[i] = al * N1[i] + be * N0[i];
  for (int k = 0; k < pp; ++k) {  // column k
    double* cxx = hs.xx.col(k).data();
    double* cyy = hs.yy.col(k).data();
    double* cxy = hs.xy.col(k).data();
    const double aN1 = a * N1[k], aN0 = a * N0[k], bN0 = b * N0[k], n0 = N0[k];
    for (int i = 0; i < pp; ++i) {
      cxx[i] += aN1 * N0[i] + aN0 * N1[i];
      cyy[i] += bN0 * N0[i];
      cxy[i] += u[i] * n0;
    }
  }
}

/// Indices of the Area, xC and yC constraints (-1: not requested).
struct AreaRows {
  int area = -1, xc = -1, yc = -1;
};

AreaRows area_rows(const std::vector<Constraint>& cons) {
  AreaRows r;
  for (int i = 0; i < static_cast<int>(cons.size()); ++i) {
    if (cons[i].kind == ConKind::Area) r.area = i;
    if (cons[i].kind == ConKind::MomentXC) r.xc = i;
    if (cons[i].kind == ConKind::MomentYC) r.yc = i;
  }
  return r;
}

/// The multipliers of A, My and Mx: the centroid conditions My - xC A and Mx - yC A weigh A too.
AreaMultipliers area_multipliers(const AreaRows& r, const Eigen::VectorXd& lambda, double xc, double yc) {
  AreaMultipliers l;
  if (r.area >= 0) l.A += lambda[r.area];
  if (r.xc >= 0) l.A -= xc * lambda[r.xc], l.My = lambda[r.xc];
  if (r.yc >= 0) l.A -= yc * lambda[r.yc], l.Mx = lambda[r.yc];
  return l;
}

}  // namespace

Problem::AreaIntegrals Problem::area_integrals(const Eigen::VectorXd& z, Eigen::MatrixXd* J,
                                               const Eigen::VectorXd* lambda, Eigen::MatrixXd* HL) const {
  if (!need_area) return {};
  const bool hess = HL && lambda;
  double A = 0, My = 0, Mx = 0;
  const AreaRows rows = area_rows(cons);
  const double xc = rows.xc >= 0 ? cons[rows.xc].target : 0, yc = rows.yc >= 0 ? cons[rows.yc].target : 0;
  const AreaMultipliers l = hess ? area_multipliers(rows, *lambda, xc, yc) : AreaMultipliers{};
  Eigen::VectorXd gA, gMy, gMx;
  if (J) gA = gMy = gMx = Eigen::VectorXd::Zero(nv);
  // The Hessian is accumulated per span in blocks and scattered once per span.
  const int pp = p + 1;
  SpanHessian hs;
  if (hess) hs.xx.resize(pp, pp), hs.yy.resize(pp, pp), hs.xy.resize(pp, pp);
  double u[16];  // scratch of add_area_hessian: on the stack for p + 1 <= 16, else on the heap
  std::vector<double> ubuf;
  double* uu = u;
  if (pp > 16) ubuf.resize(pp), uu = ubuf.data();
  const double* zd = z.data();
  for (int q0 = 0; q0 < tab.nqa; q0 += tab.per_span_area) {
    const int f = q0 / tab.per_span_area;
    const double* zx = zd + f;
    const double* zy = zd + n + f;
    if (hess) hs.xx.setZero(), hs.yy.setZero(), hs.xy.setZero();
    for (int q = q0; q < q0 + tab.per_span_area; ++q) {
      AreaPoint pt{tab.wa[q], 0, 0, 0, tab.Na[0].col(q).data(), tab.Na[1].col(q).data()};
      for (int k = 0; k < pp; ++k) {
        pt.x += pt.N0[k] * zx[k];
        pt.y += pt.N0[k] * zy[k];
        pt.xp += pt.N1[k] * zx[k];
      }
      A += pt.w * pt.y * pt.xp;
      My += pt.w * pt.x * pt.y * pt.xp;
      Mx += pt.w * 0.5 * pt.y * pt.y * pt.xp;
      if (J) add_area_gradients(pt, pp, n, f, gA.data(), gMy.data(), gMx.data());
      if (hess) add_area_hessian(pt, pp, l, uu, hs);
    }
    if (hess) {
      Eigen::MatrixXd& H = *HL;
      H.block(f, f, pp, pp) += hs.xx;
      H.block(n + f, n + f, pp, pp) += hs.yy;
      H.block(f, n + f, pp, pp) += hs.xy;
      H.block(n + f, f, pp, pp) += hs.xy.transpose();
    }
  }
  if (J) {
    if (rows.area >= 0) J->row(rows.area) = gA.transpose();
    if (rows.xc >= 0) J->row(rows.xc) = (gMy - xc * gA).transpose();
    if (rows.yc >= 0) J->row(rows.yc) = (gMx - yc * gA).transpose();
  }
  return {A, My, Mx};
}

void Problem::curvature_constraint(int i, const Eigen::VectorXd& z, Eigen::VectorXd& c, Eigen::MatrixXd* J,
                                   const Eigen::VectorXd* lambda, Eigen::MatrixXd* HL) const {
  const Constraint& k = cons[i];
  const bool hess = HL && lambda;
  const Eigen::MatrixXd& R = tab.end_rows[k.end];
  const Eigen::Vector4d d(R.row(1).dot(z.segment(0, n)), R.row(1).dot(z.segment(n, n)),
                          R.row(2).dot(z.segment(0, n)), R.row(2).dot(z.segment(n, n)));
  const double u = d[0] * d[3] - d[1] * d[2];
  const double s = d[0] * d[0] + d[1] * d[1];
  const double s15 = s * std::sqrt(s);
  c[i] = u / s15 - k.target;
  if (!J && !hess) return;
  const Eigen::Vector4d du(d[3], -d[2], -d[1], d[0]);
  const Eigen::Vector4d ds(2 * d[0], 2 * d[1], 0, 0);
  const Eigen::Vector4d dk = du / s15 - 1.5 * u / (s15 * s) * ds;
  if (J) {
    J->row(i).segment(0, n) = dk[0] * R.row(1) + dk[2] * R.row(2);
    J->row(i).segment(n, n) = dk[1] * R.row(1) + dk[3] * R.row(2);
  }
  if (hess) {
    Eigen::Matrix4d d2u = Eigen::Matrix4d::Zero();
    d2u(0, 3) = d2u(3, 0) = 1;
    d2u(1, 2) = d2u(2, 1) = -1;
    Eigen::Matrix4d d2s = Eigen::Matrix4d::Zero();
    d2s(0, 0) = d2s(1, 1) = 2;
    const Eigen::Matrix4d Hk = d2u / s15 - 1.5 / (s15 * s) * (du * ds.transpose() + ds * du.transpose()) +
                               3.75 * u / (s15 * s * s) * ds * ds.transpose() - 1.5 * u / (s15 * s) * d2s;
    // d = (x1, y1, x2, y2) depends only on the p+1 control points next to the end:
    // d_x = B zx, d_y = B zy with B = end rows 1, 2 restricted to them
    const int pp = p + 1, r0 = k.end == 0 ? 0 : n - pp;
    Eigen::MatrixXd B(2, pp);
    B.row(0) = R.row(1).segment(r0, pp);
    B.row(1) = R.row(2).segment(r0, pp);
    const double l = (*lambda)[i];
    for (int a = 0; a < 2; ++a)
      for (int bb = 0; bb < 2; ++bb) {
        Eigen::Matrix2d Hab;  // Hk restricted to (coord a) x (coord bb): d indices a, a+2
        Hab << Hk(a, bb), Hk(a, bb + 2), Hk(a + 2, bb), Hk(a + 2, bb + 2);
        HL->block(a * n + r0, bb * n + r0, pp, pp).noalias() += l * (B.transpose() * Hab * B);
      }
  }
}

void Problem::point_constraint(int i, const Eigen::VectorXd& z, Eigen::VectorXd& c, Eigen::MatrixXd* J,
                               const Eigen::VectorXd* lambda, Eigen::MatrixXd* HL) const {
  const Constraint& k = cons[i];
  const bool hess = HL && lambda;
  Eigen::MatrixXd C, ders;
  const int tv = tvar(k.point);
  int f = 0;
  point_derivs(z, z[tv], C, ders, f);
  c[i] = C(0, k.coord) - k.target;
  if (J) {
    for (int j = 0; j <= p; ++j) (*J)(i, var(k.coord, f + j)) = ders(0, j);
    (*J)(i, tv) = C(1, k.coord);
  }
  if (hess) {
    const double l = (*lambda)[i];
    for (int j = 0; j <= p; ++j) {
      (*HL)(var(k.coord, f + j), tv) += l * ders(1, j);
      (*HL)(tv, var(k.coord, f + j)) += l * ders(1, j);
    }
    (*HL)(tv, tv) += l * C(2, k.coord);
  }
}

void Problem::constraints(const Eigen::VectorXd& z, Eigen::VectorXd& c, Eigen::MatrixXd* J,
                          const Eigen::VectorXd* lambda, Eigen::MatrixXd* HL) const {
  const int m = static_cast<int>(cons.size());
  c.resize(m);
  if (J) J->setZero(m, nv);
  if (HL && lambda) HL->setZero(nv, nv);
  const auto [A, My, Mx] = area_integrals(z, J, lambda, HL);
  for (int i = 0; i < m; ++i) {
    const Constraint& k = cons[i];
    switch (k.kind) {
      case ConKind::Linear:
        c[i] = k.row.dot(z) - k.target;
        if (J) J->row(i) = k.row.transpose();
        break;
      case ConKind::Area: c[i] = A - k.target; break;
      case ConKind::MomentXC: c[i] = My - k.target * A; break;
      case ConKind::MomentYC: c[i] = Mx - k.target * A; break;
      case ConKind::Curvature: curvature_constraint(i, z, c, J, lambda, HL); break;
      case ConKind::Point: point_constraint(i, z, c, J, lambda, HL); break;
    }
  }
}

double Problem::objective(const Eigen::VectorXd& z, Eigen::VectorXd* g, Eigen::MatrixXd* H) const {
  double f = 0;
  if (g) g->setZero(nv);
  if (H) H->setZero(nv, nv);
  f = add_fairness(z, f, g, H);
  if (req.fairness.length > 0) f = add_length(z, f, g, H);
  return add_point_penalties(z, f, g, H);
}

double Problem::add_fairness(const Eigen::VectorXd& z, double f, Eigen::VectorXd* g, Eigen::MatrixXd* H) const {
  // X^T Kf X per coordinate: its Hessian 2 Kf is constant (knots never change). Plain loops:
  // this runs in every merit evaluation of the line search, where an Eigen temporary for Kf X
  // would be a heap allocation each time.
  for (int c = 0; c < dim; ++c) {
    const double* X = z.data() + c * n;
    for (int j = 0; j < n; ++j) {
      const double* Kj = Kf.col(j).data();
      double kx = 0;
      for (int i = 0; i < n; ++i) kx += Kj[i] * X[i];  // (Kf X)_j, Kf symmetric
      f += X[j] * kx;
      if (g) (*g)[c * n + j] = 2 * kx;
    }
    if (H) H->block(c * n, c * n, n, n) = 2 * Kf;
  }
  return f;
}

double Problem::add_length(const Eigen::VectorXd& z, double f, Eigen::VectorXd* g, Eigen::MatrixXd* H) const {
  // length weight * int |C'| dt by the Gauss rule of the tables
  const double sw = req.fairness.length;
  Eigen::VectorXd v(dim);
  for (int q = 0; q < tab.nq; ++q) {
    const int fi = tab.first[q];
    const auto N1 = tab.N[1].col(q);
    for (int c = 0; c < dim; ++c) v[c] = N1.dot(z.segment(c * n + fi, p + 1));
    const double len = std::max(v.norm(), 1e-300);
    const double w = sw * tab.w[q];
    f += w * len;
    if (g)
      for (int c = 0; c < dim; ++c) g->segment(c * n + fi, p + 1) += w * v[c] / len * N1;
    if (H) {
      const Eigen::MatrixXd Hv = (Eigen::MatrixXd::Identity(dim, dim) - v * v.transpose() / (len * len)) / len;
      const Eigen::MatrixXd NN = N1 * N1.transpose();
      for (int a = 0; a < dim; ++a)
        for (int b = 0; b < dim; ++b) H->block(a * n + fi, b * n + fi, p + 1, p + 1) += w * Hv(a, b) * NN;
    }
  }
  return f;
}

double Problem::add_point_penalties(const Eigen::VectorXd& z, double f, Eigen::VectorXd* g, Eigen::MatrixXd* H) const {
  // weight * |C(t_j) - P_j|^2 of every approximated point, t_j a variable
  Eigen::MatrixXd C, ders;
  for (int j = 0; j < npts; ++j) {
    const double wt = req.points[j].weight;
    if (std::isinf(wt)) continue;
    const int tv = tvar(j);
    int fi = 0;
    point_derivs(z, z[tv], C, ders, fi);
    for (int c = 0; c < dim; ++c) {
      const double r = C(0, c) - req.points[j].position[c];
      f += wt * r * r;
      if (g) {
        for (int k = 0; k <= p; ++k) (*g)[var(c, fi + k)] += 2 * wt * r * ders(0, k);
        (*g)[tv] += 2 * wt * r * C(1, c);
      }
      if (H) {
        // grad r: entries ders(0,k) at control vars, C(1,c) at t
        for (int a = 0; a <= p; ++a) {
          for (int b = 0; b <= p; ++b) (*H)(var(c, fi + a), var(c, fi + b)) += 2 * wt * ders(0, a) * ders(0, b);
          const double cross = 2 * wt * (ders(0, a) * C(1, c) + r * ders(1, a));
          (*H)(var(c, fi + a), tv) += cross;
          (*H)(tv, var(c, fi + a)) += cross;
        }
        (*H)(tv, tv) += 2 * wt * (C(1, c) * C(1, c) + r * C(2, c));
      }
    }
  }
  return f;
}

FairnessMeasures Problem::measures(const Eigen::VectorXd& z) const {
  FairnessMeasures m;
  double* E[3] = {&m.E1, &m.E2, &m.E3};
  for (int k = 0; k < 3; ++k)
    for (int c = 0; c < dim; ++c) {
      const auto X = z.segment(c * n, n);
      *E[k] += X.dot(tab.K[k] * X);
    }
  Eigen::VectorXd v(dim);
  for (int q = 0; q < tab.nq; ++q) {
    const int fi = tab.first[q];
    for (int c = 0; c < dim; ++c) v[c] = tab.N[1].col(q).dot(z.segment(c * n + fi, p + 1));
    m.length += tab.w[q] * v.norm();
  }
  return m;
}

double Problem::scaled_violation(const Eigen::VectorXd& c) const {
  double v = 0;
  for (int i = 0; i < c.size(); ++i) v = std::max(v, std::abs(c[i]) / cons[i].scale);
  return v;
}

}  // namespace fairlines::form_curve_impl
