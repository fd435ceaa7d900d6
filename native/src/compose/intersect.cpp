// Surface-surface intersection (subdivision + marching), see fairlines/intersect.hpp.
#include "fairlines/intersect.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include "fairlines/errors.hpp"
#include "nurbs/checks.hpp"
#include "nurbs/knot_refinement.hpp"

namespace fairlines {

namespace {

struct Box {
  Eigen::Vector3d lo, hi;
  Eigen::Vector2d ulo, uhi;  // parameter rectangle (u range in x, v range in y)
};

struct Deriv {
  Eigen::Vector3d s, su, sv;
};

/// Point and first partials at (u, v) clamped to the domain, without heap allocation (the
/// seed search and the marching call this tens of thousands of times).
Deriv deriv(const NurbsSurface& f, double u, double v) {
  if (!std::isfinite(u) || !std::isfinite(v)) f.derivatives(u, v, 1);  // throws InvalidInput naming it
  const auto [u0, u1] = f.domain_u();
  const auto [v0, v1] = f.domain_v();
  u = std::clamp(u, u0, u1);
  v = std::clamp(v, v0, v1);
  double d[9];
  f.evaluate_first_derivatives_into(&u, &v, 1, d);
  return {Eigen::Vector3d(d[0], d[1], d[2]), Eigen::Vector3d(d[3], d[4], d[5]), Eigen::Vector3d(d[6], d[7], d[8])};
}

bool clamped(const Eigen::VectorXd& k, int p) {
  const Eigen::Index n = k.size();
  for (int i = 1; i <= p; ++i)
    if (k[i] != k[0] || k[n - 1 - i] != k[n - 1]) return false;
  return true;
}

/// Knots to insert so every breakpoint (existing interior knots and `extra` uniform ones) has
/// multiplicity p: afterwards span i of the distinct breakpoints owns control rows i*p..i*p+p.
Eigen::VectorXd bezier_insertions(const Eigen::VectorXd& k, int p, int extra, std::vector<double>& breaks) {
  const double a = k[0], b = k[k.size() - 1];
  std::vector<double> interior;
  for (Eigen::Index i = p + 1; i < k.size() - p - 1; ++i) interior.push_back(k[i]);
  std::vector<double> targets = interior;
  for (int e = 1; e < extra; ++e) targets.push_back(a + (b - a) * e / extra);
  std::sort(targets.begin(), targets.end());
  // merge near-equal targets onto the existing knot
  std::vector<double> uniq;
  const double eps = 1e-12 * (b - a);
  for (double t : targets)
    if (uniq.empty() || t - uniq.back() > eps) uniq.push_back(t);
  std::vector<double> ins;
  breaks.assign(1, a);
  for (double t : uniq) {
    int mult = 0;
    double snapped = t;
    for (double q : interior)
      if (std::abs(q - t) <= eps) {
        ++mult;
        snapped = q;
      }
    for (int r = mult; r < p; ++r) ins.push_back(snapped);
    breaks.push_back(snapped);
  }
  breaks.push_back(b);
  Eigen::VectorXd out(static_cast<Eigen::Index>(ins.size()));
  for (size_t i = 0; i < ins.size(); ++i) out[static_cast<Eigen::Index>(i)] = ins[i];
  return out;
}

/// The Bezier patches' control points of `s` refined by the knots iu (along u) and iv (along
/// v), one u strip at a time (the whole refined net is megabytes; a strip, kilobytes). The
/// values are those of s.refine_knots(U, iu).refine_knots(V, iv).control_points(), bit for
/// bit: each line a non-rational 4-D curve of the homogeneous net with a weight of its own
/// (1, refined with it and divided out), and a surface again between the two steps.
class RefinedNet {
 public:
  RefinedNet(const NurbsSurface& s, const Eigen::VectorXd& iu, const Eigen::VectorXd& iv)
      : s_(s), iv_(iv), nv_(s.nv()), P_(s.control_points()), pw_(s.homogeneous()) {
    if (!iu.size()) return;
    detail::RowMatrix A(s.nu(), nv_ * kW);  // lines of u: row i, line j
    for (int i = 0; i < s.nu(); ++i)
      for (int j = 0; j < nv_; ++j) {
        for (int c = 0; c < 4; ++c) A(i, j * kW + c) = pw_(i * nv_ + j, c);
        A(i, j * kW + 4) = 1.0;
      }
    A = detail::refine_rows(s.degree_u(), s.knots_u(), iu, A).first;
    P_.resize(A.rows() * nv_, 3);
    pw_.resize(A.rows() * nv_, 4);
    for (Eigen::Index i = 0; i < A.rows(); ++i)
      for (int j = 0; j < nv_; ++j) {
        double q[4];
        for (int c = 0; c < 4; ++c) q[c] = A(i, j * kW + c) / A(i, j * kW + 4);
        for (int c = 0; c < 3; ++c) P_(i * nv_ + j, c) = q[c] / q[3], pw_(i * nv_ + j, c) = P_(i * nv_ + j, c) * q[3];
        pw_(i * nv_ + j, 3) = q[3];
      }
  }

  /// Control points of rows first .. first + count - 1 of the refined net: strip(r, j) a
  /// point (count x nv_out, 3 columns per row).
  Eigen::MatrixXd strip(int first, int count, int& nv_out) const {
    if (!iv_.size()) {
      nv_out = nv_;
      Eigen::MatrixXd out(count, 3 * nv_);
      for (int r = 0; r < count; ++r)
        for (int j = 0; j < nv_; ++j) out.block(r, 3 * j, 1, 3) = P_.row((first + r) * nv_ + j);
      return out;
    }
    detail::RowMatrix B(nv_, count * kW);  // lines of v: row j, line r
    for (int r = 0; r < count; ++r)
      for (int j = 0; j < nv_; ++j) {
        for (int c = 0; c < 4; ++c) B(j, r * kW + c) = pw_((first + r) * nv_ + j, c);
        B(j, r * kW + 4) = 1.0;
      }
    B = detail::refine_rows(s_.degree_v(), s_.knots_v(), iv_, B).first;
    nv_out = static_cast<int>(B.rows());
    Eigen::MatrixXd out(count, 3 * nv_out);
    for (int r = 0; r < count; ++r)
      for (int j = 0; j < nv_out; ++j) {
        double q[4];
        for (int c = 0; c < 4; ++c) q[c] = B(j, r * kW + c) / B(j, r * kW + 4);
        for (int c = 0; c < 3; ++c) out(r, 3 * j + c) = q[c] / q[3];
      }
    return out;
  }

 private:
  static constexpr int kW = 5;  // x w, y w, z w, w and the line curve's own weight
  const NurbsSurface& s_;
  const Eigen::VectorXd& iv_;
  int nv_;
  Eigen::MatrixXd P_, pw_;  // the net after the u step, rows i nv + j
};

std::vector<Box> patch_boxes(const NurbsSurface& s0, int extra) {
  const int pu = s0.degree_u(), pv = s0.degree_v();
  if (!clamped(s0.knots_u(), pu) || !clamped(s0.knots_v(), pv))
    throw InvalidInput("intersect_surfaces: surface knot vectors must be clamped (end knots repeated degree + 1 times)");
  std::vector<double> bu, bv;
  const Eigen::VectorXd iu = bezier_insertions(s0.knots_u(), pu, extra, bu);
  const Eigen::VectorXd iv = bezier_insertions(s0.knots_v(), pv, extra, bv);
  const RefinedNet net(s0, iu, iv);
  std::vector<Box> boxes;
  for (size_t i = 0; i + 1 < bu.size(); ++i) {
    int nv = 0;
    const Eigen::MatrixXd P = net.strip(static_cast<int>(i) * pu, pu + 1, nv);
    for (size_t j = 0; j + 1 < bv.size(); ++j) {
      Box bx;
      bx.lo.setConstant(1e300);
      bx.hi.setConstant(-1e300);
      for (int r = 0; r <= pu; ++r)
        for (int c = 0; c <= pv; ++c) {
          const Eigen::Vector3d q = P.block(r, 3 * (static_cast<int>(j) * pv + c), 1, 3).transpose();
          bx.lo = bx.lo.cwiseMin(q);
          bx.hi = bx.hi.cwiseMax(q);
        }
      bx.ulo = {bu[i], bv[j]};
      bx.uhi = {bu[i + 1], bv[j + 1]};
      boxes.push_back(bx);
    }
  }
  return boxes;
}

bool boxes_overlap(const Box& p, const Box& q, double slack) {
  return !((p.lo.array() > q.hi.array() + slack).any() || (q.lo.array() > p.hi.array() + slack).any());
}

/// The box holding every box of `boxes` (3-D extent only).
Box enclosing_box(const std::vector<Box>& boxes) {
  Box all{boxes[0].lo, boxes[0].hi, {}, {}};
  for (const auto& x : boxes) {
    all.lo = all.lo.cwiseMin(x.lo);
    all.hi = all.hi.cwiseMax(x.hi);
  }
  return all;
}

struct Domain {
  double u0, u1, v0, v1;
  explicit Domain(const NurbsSurface& s) {
    std::tie(u0, u1) = s.domain_u();
    std::tie(v0, v1) = s.domain_v();
  }
  bool inside(double u, double v, double slack = 0.0) const {
    return u >= u0 - slack && u <= u1 + slack && v >= v0 - slack && v <= v1 + slack;
  }
  void clamp(double& u, double& v) const {
    u = std::clamp(u, u0, u1);
    v = std::clamp(v, v0, v1);
  }
};

/// Which parameter of x (0..3) leaves its domain the most, and the boundary value; -1 if none.
int exiting(const Domain& da, const Domain& db, const Eigen::Vector4d& x, double& value) {
  const double lo[4] = {da.u0, da.v0, db.u0, db.v0};
  const double hi[4] = {da.u1, da.v1, db.u1, db.v1};
  int worst = -1;
  double excess = 0.0;
  for (int k = 0; k < 4; ++k) {
    const double span = hi[k] - lo[k];
    const double e = std::max(lo[k] - x[k], x[k] - hi[k]) / span;
    if (e > excess) {
      excess = e;
      worst = k;
      value = x[k] < lo[k] ? lo[k] : hi[k];
    }
  }
  return worst;
}

/// Newton with parameter `fixed` held at `value`: 3 equations S_a = S_b in 3 unknowns.
bool solve_on_boundary(const NurbsSurface& a, const NurbsSurface& b, const Domain& da, const Domain& db,
                       Eigen::Vector4d& x, int fixed, double value, double tol) {
  x[fixed] = value;
  for (int it = 0; it < 40; ++it) {
    da.clamp(x[0], x[1]);
    db.clamp(x[2], x[3]);
    const Deriv A = deriv(a, x[0], x[1]), B = deriv(b, x[2], x[3]);
    const Eigen::Vector3d r = A.s - B.s;
    if (r.norm() < tol) return true;
    Eigen::Matrix<double, 3, 4> J;
    J << A.su, A.sv, -B.su, -B.sv;
    Eigen::Matrix3d K;
    int c = 0;
    for (int k = 0; k < 4; ++k)
      if (k != fixed) K.col(c++) = J.col(k);
    const Eigen::Vector3d d = K.colPivHouseholderQr().solve(-r);
    if (!d.allFinite()) return false;
    c = 0;
    for (int k = 0; k < 4; ++k)
      if (k != fixed) x[k] += d[c++];
  }
  da.clamp(x[0], x[1]);
  db.clamp(x[2], x[3]);
  return (deriv(a, x[0], x[1]).s - deriv(b, x[2], x[3]).s).norm() < tol * 10.0;
}

IntersectionPoint make_point(const NurbsSurface& a, const NurbsSurface& b, const Eigen::Vector4d& x, double& gap) {
  const Eigen::Vector3d pa = a.evaluate(x[0], x[1]), pb = b.evaluate(x[2], x[3]);
  gap = std::max(gap, (pa - pb).norm());
  return {0.5 * (pa + pb), {x[0], x[1]}, {x[2], x[3]}};
}

/// The two surfaces of an intersection with their domains and the options.
struct SurfacePair {
  const NurbsSurface& a;
  const NurbsSurface& b;
  const Domain& da;
  const Domain& db;
  const IntersectOptions& o;
};

/// The unit direction n_a x n_b of the intersection at A (on a), B (on b). Throws
/// ConvergenceError where the normals are parallel: the surfaces touch instead of crossing.
Eigen::Vector3d crossing_direction(const Deriv& A, const Deriv& B) {
  const Eigen::Vector3d t = A.su.cross(A.sv).normalized().cross(B.su.cross(B.sv).normalized());
  if (t.norm() < 1e-9) {
    std::ostringstream os;
    os << "intersect_surfaces: tangential contact at (" << A.s.transpose()
       << "); the surfaces touch instead of crossing";
    throw ConvergenceError(os.str());
  }
  return t.normalized();
}

enum class Corrected { Converged, LeftDomain, Failed };

/// Newton from the predicted xn on S_a = S_b and (S_a - A.s) . t = h: the point at distance h
/// along t from the last one.
Corrected correct(const SurfacePair& sp, const Deriv& A, const Eigen::Vector3d& t, double h, Eigen::Vector4d& xn) {
  for (int it = 0; it < 30; ++it) {
    double bv;
    if (exiting(sp.da, sp.db, xn, bv) >= 0) return Corrected::LeftDomain;
    const Deriv An = deriv(sp.a, xn[0], xn[1]), Bn = deriv(sp.b, xn[2], xn[3]);
    Eigen::Vector4d F;
    F.head<3>() = An.s - Bn.s;
    F[3] = (An.s - A.s).dot(t) - h;
    if (F.head<3>().norm() < sp.o.tolerance && std::abs(F[3]) < 1e-3 * h) return Corrected::Converged;
    Eigen::Matrix4d J;
    J.block<3, 1>(0, 0) = An.su;
    J.block<3, 1>(0, 1) = An.sv;
    J.block<3, 1>(0, 2) = -Bn.su;
    J.block<3, 1>(0, 3) = -Bn.sv;
    J(3, 0) = An.su.dot(t);
    J(3, 1) = An.sv.dot(t);
    J(3, 2) = 0.0;
    J(3, 3) = 0.0;
    const Eigen::Vector4d d = J.partialPivLu().solve(-F);
    if (!d.allFinite()) return Corrected::Failed;
    xn += d;
  }
  return Corrected::Failed;
}

/// Whether the intersection's direction at xn turns from t by more than max_turn_deg.
bool turns_too_far(const SurfacePair& sp, const Eigen::Vector4d& xn, const Eigen::Vector3d& t) {
  const double turn_max = sp.o.max_turn_deg * M_PI / 180.0;
  const Deriv An = deriv(sp.a, xn[0], xn[1]), Bn = deriv(sp.b, xn[2], xn[3]);
  const Eigen::Vector3d tn = An.su.cross(An.sv).normalized().cross(Bn.su.cross(Bn.sv).normalized());
  const double turn = tn.norm() > 1e-12 ? std::acos(std::min(1.0, std::abs(tn.normalized().dot(t)))) : M_PI;
  return turn > turn_max;
}

enum class Step { Accepted, EndedOnBoundary };

/// One step from x (A, B: the surfaces there) along t: predictor (parameter steps moving each
/// surface by h t), corrector, refused when the direction turns too far, h halved until a step
/// is accepted (xn). A corrector that leaves a domain ends the branch on that boundary (appended
/// to out) when the boundary point lies within 2 h of A.
Step take_step(const SurfacePair& sp, const Deriv& A, const Deriv& B, const Eigen::Vector4d& x,
               const Eigen::Vector3d& t, double h_min, double& h, Eigen::Vector4d& xn,
               std::vector<IntersectionPoint>& out, double& gap) {
  for (;; h *= 0.5) {
    if (h < h_min) {
      std::ostringstream os;
      os << "intersect_surfaces: marching step collapsed near (" << A.s.transpose() << ")";
      throw ConvergenceError(os.str());
    }
    Eigen::Matrix<double, 3, 2> Ja, Jb;
    Ja << A.su, A.sv;
    Jb << B.su, B.sv;
    const Eigen::Vector2d ga = Ja.colPivHouseholderQr().solve(h * t);
    const Eigen::Vector2d gb = Jb.colPivHouseholderQr().solve(h * t);
    xn << x[0] + ga[0], x[1] + ga[1], x[2] + gb[0], x[3] + gb[1];
    const Corrected c = correct(sp, A, t, h, xn);
    if (c == Corrected::Converged && !turns_too_far(sp, xn, t)) return Step::Accepted;
    if (c == Corrected::LeftDomain) {
      // land on that boundary from the current point
      double bval = 0.0;
      const int ex = exiting(sp.da, sp.db, xn, bval);
      Eigen::Vector4d xb = x;
      if (solve_on_boundary(sp.a, sp.b, sp.da, sp.db, xb, ex, bval, sp.o.tolerance) &&
          (sp.a.evaluate(xb[0], xb[1]) - A.s).norm() < 2.0 * h) {
        out.push_back(make_point(sp.a, sp.b, xb, gap));
        return Step::EndedOnBoundary;
      }
    }
  }
}

/// The branch's last point on the boundary parameter ex = bval that the accepted step to xn
/// crossed: solved from xn, else from the last inside point x.
Eigen::Vector4d land_on_boundary(const SurfacePair& sp, const Eigen::Vector4d& x, const Eigen::Vector4d& xn, int ex,
                                 double bval) {
  Eigen::Vector4d xb = xn;
  if (!solve_on_boundary(sp.a, sp.b, sp.da, sp.db, xb, ex, bval, sp.o.tolerance)) {
    xb = x;
    if (!solve_on_boundary(sp.a, sp.b, sp.da, sp.db, xb, ex, bval, sp.o.tolerance))
      throw ConvergenceError("intersect_surfaces: could not land a branch on a domain boundary");
  }
  return xb;
}

/// Marches from x in direction sign * (n_a x n_b); appends points (excluding the start).
/// Returns true if the branch closed on `start_point`.
bool march(const SurfacePair& sp, Eigen::Vector4d x, double sign, double h0, std::vector<IntersectionPoint>& out,
           double& gap, const Eigen::Vector3d& start_point) {
  double h = h0;
  const double h_min = h0 * 1e-4;
  Eigen::Vector3d t_prev = Eigen::Vector3d::Zero();
  int steps = 0;
  while (static_cast<int>(out.size()) < sp.o.max_points) {
    const Deriv A = deriv(sp.a, x[0], x[1]), B = deriv(sp.b, x[2], x[3]);
    Eigen::Vector3d t = sign * crossing_direction(A, B);
    if (steps > 0 && t.dot(t_prev) < 0.0) t = -t;  // keep heading
    Eigen::Vector4d xn;
    if (take_step(sp, A, B, x, t, h_min, h, xn, out, gap) == Step::EndedOnBoundary) return false;
    double bval = 0.0;
    const int ex = exiting(sp.da, sp.db, xn, bval);
    if (ex >= 0) {
      out.push_back(make_point(sp.a, sp.b, land_on_boundary(sp, x, xn, ex, bval), gap));
      return false;
    }
    x = xn;
    out.push_back(make_point(sp.a, sp.b, x, gap));
    t_prev = t;
    ++steps;
    if (steps > 3 && (out.back().point - start_point).norm() < 0.75 * h) return true;
    if (h < h0) h = std::min(h0, h * 1.5);
  }
  throw ConvergenceError("intersect_surfaces: branch exceeded max_points");
}

}  // namespace

double refine_intersection(const NurbsSurface& a, const NurbsSurface& b, Eigen::Vector4d& x, double tolerance,
                           int max_iterations) {
  const Domain da(a), db(b);
  double r_norm = 1e300;
  for (int it = 0; it < max_iterations; ++it) {
    da.clamp(x[0], x[1]);
    db.clamp(x[2], x[3]);
    const Deriv A = deriv(a, x[0], x[1]), B = deriv(b, x[2], x[3]);
    const Eigen::Vector3d r = A.s - B.s;
    r_norm = r.norm();
    if (r_norm < tolerance) return r_norm;
    Eigen::Matrix<double, 3, 4> J;
    J << A.su, A.sv, -B.su, -B.sv;
    const Eigen::Vector4d d = J.completeOrthogonalDecomposition().solve(-r);
    if (!d.allFinite()) break;
    x += d;
  }
  da.clamp(x[0], x[1]);
  db.clamp(x[2], x[3]);
  return (a.evaluate(x[0], x[1]) - b.evaluate(x[2], x[3])).norm();
}

std::vector<IntersectionCurve> intersect_surfaces(const NurbsSurface& a, const NurbsSurface& b,
                                                  const IntersectOptions& o) {
  if (o.subdivisions < 1) detail::fail("subdivisions is ", o.subdivisions, "; expected an integer >= 1");
  if (!(o.tolerance > 0.0) || o.tolerance > 1e-6)
    detail::fail("tolerance is ", o.tolerance, "; expected a value in (0, 1e-6] metres");
  if (o.step < 0.0 || !std::isfinite(o.step)) detail::fail("step is ", o.step, "; expected >= 0 metres");
  if (o.max_points < 10) detail::fail("max_points is ", o.max_points, "; expected >= 10");
  const std::vector<Box> ba = patch_boxes(a, o.subdivisions), bb = patch_boxes(b, o.subdivisions);
  auto diag = [](const std::vector<Box>& bs) {
    const Box all = enclosing_box(bs);
    return (all.hi - all.lo).norm();
  };
  const double h0 = o.step > 0.0 ? o.step : std::min(diag(ba), diag(bb)) / 150.0;
  const double slack = 1e-9 * std::max(diag(ba), diag(bb));
  const Domain da(a), db(b);
  const SurfacePair pair{a, b, da, db, o};
  // seeds: Newton from the centres of every overlapping patch pair
  std::vector<Eigen::Vector4d> seeds;
  const Box all_b = enclosing_box(bb);
  for (const auto& p : ba) {
    // a patch clear of b's whole box overlaps none of its patches: skip the inner loop
    if (!boxes_overlap(p, all_b, slack)) continue;
    for (const auto& q : bb) {
      if (!boxes_overlap(p, q, slack)) continue;
      Eigen::Vector4d x;
      x << 0.5 * (p.ulo + p.uhi), 0.5 * (q.ulo + q.uhi);
      if (refine_intersection(a, b, x, o.tolerance) < o.tolerance) seeds.push_back(x);
    }
  }
  std::vector<IntersectionCurve> curves;
  for (const auto& s : seeds) {
    const Eigen::Vector3d ps = a.evaluate(s[0], s[1]);
    bool covered = false;
    for (const auto& c : curves) {
      for (const auto& q : c.points)
        if ((q.point - ps).norm() < 2.0 * h0) {
          covered = true;
          break;
        }
      if (covered) break;
    }
    if (covered) continue;
    IntersectionCurve c;
    double gap = 0.0;
    std::vector<IntersectionPoint> fwd, bwd;
    const IntersectionPoint p0 = make_point(a, b, s, gap);
    const bool closed = march(pair, s, 1.0, h0, fwd, gap, p0.point);
    if (!closed) march(pair, s, -1.0, h0, bwd, gap, p0.point);
    c.points.assign(bwd.rbegin(), bwd.rend());
    c.points.push_back(p0);
    c.points.insert(c.points.end(), fwd.begin(), fwd.end());
    if (closed) c.points.pop_back();  // last point duplicates the start region
    c.closed = closed;
    c.max_gap = gap;
    curves.push_back(std::move(c));
  }
  return curves;
}

}  // namespace fairlines
