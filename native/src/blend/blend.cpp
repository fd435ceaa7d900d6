// Blending surface by fair skinning of Hermite sections (quintic G2 or cubic G1), see
// fairlines/blend.hpp.
//
// Notation: a, b the two surfaces; P_a, P_b boundary points of a section; n_a, n_b the unit
// normals there; d_a, d_b unit cross-boundary directions in the tangent planes, each toward the
// other surface; v = tension |P_b - P_a| the section's speed at both ends; kappa_a, kappa_b the
// surfaces' normal curvatures in d_a, d_b. A quintic section's Bezier points Q0 .. Q5:
//   Q0 = P_a, Q1 = Q0 + v/5 d_a, Q2 = 2 Q1 - Q0 + kappa_a v^2 n_a / 20   (S_t = 5 (Q1 - Q0),
//   Q5 = P_b, Q4 = Q5 + v/5 d_b, Q3 = 2 Q4 - Q5 + kappa_b v^2 n_b / 20    S_tt = 20 (Q2 - 2 Q1 + Q0))
// so S_tt . n = kappa |S_t|^2 at both ends: the section's normal curvature is the surface's, and
// a surface tangent to another along a curve with equal normal curvature across it is G2 there
// (Pegna & Wolter's linkage-curve theorem).
#include "fairlines/blend.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <tuple>
#include <vector>

#include <Eigen/Geometry>

#include <Eigen/LU>

#include "fairlines/basis.hpp"
#include "fairlines/errors.hpp"
#include "fairlines/fitting.hpp"
#include "fairlines/knots.hpp"
#include "common/soft_cap.hpp"
#include "nurbs/checks.hpp"

namespace fairlines {

namespace {

/// Parameter points of a (k, 2) polyline at n equal fractions of its 3-D arc length.
Eigen::MatrixXd resample(const NurbsSurface& s, const Eigen::MatrixXd& uv, int n, const char* what) {
  if (uv.cols() != 2 || uv.rows() < 2) detail::fail(what, " has shape (", uv.rows(), ", ", uv.cols(), "); expected (k, 2) with k >= 2");
  detail::require_finite(uv, what);
  const auto [u0, u1] = s.domain_u();
  const auto [v0, v1] = s.domain_v();
  const double eu = 1e-9 * (u1 - u0), ev = 1e-9 * (v1 - v0);
  for (Eigen::Index i = 0; i < uv.rows(); ++i)
    if (uv(i, 0) < u0 - eu || uv(i, 0) > u1 + eu || uv(i, 1) < v0 - ev || uv(i, 1) > v1 + ev)
      detail::fail(what, "[", i, "] = (", uv(i, 0), ", ", uv(i, 1), ") lies outside the surface domain [", u0, ", ", u1,
                   "] x [", v0, ", ", v1, "]");
  // the points are interpolated by a cubic in parameter space (a polyline would put kinks,
  // which no C1 blend can follow, into the boundary), densely sampled -> 3-D arc length
  constexpr int kPerSegment = 16;
  const Eigen::Index m = (uv.rows() - 1) * kPerSegment + 1;
  Eigen::MatrixXd dense(m, 2);
  FitOptions fo;
  fo.degree = static_cast<int>(std::min<Eigen::Index>(3, uv.rows() - 1));
  const CurveFit cf = fit_curve(uv, fo);
  const double t0 = cf.curve.knots()[0], t1 = cf.curve.knots()[cf.curve.knots().size() - 1];
  for (Eigen::Index i = 0; i < m; ++i) dense.row(i) = cf.curve.evaluate(t0 + (t1 - t0) * i / (m - 1)).transpose();
  for (Eigen::Index i = 0; i < m; ++i) {
    dense(i, 0) = std::clamp(dense(i, 0), u0, u1);
    dense(i, 1) = std::clamp(dense(i, 1), v0, v1);
  }
  const Eigen::MatrixXd P = s.evaluate(Eigen::VectorXd(dense.col(0)), Eigen::VectorXd(dense.col(1)));
  std::vector<double> arc(m, 0.0);
  for (Eigen::Index i = 1; i < m; ++i) arc[i] = arc[i - 1] + (P.row(i) - P.row(i - 1)).norm();
  if (!(arc[m - 1] > 0.0)) detail::fail(what, " has zero length on the surface; expected a curve");
  Eigen::MatrixXd out(n, 2);
  Eigen::Index q = 0;
  for (int j = 0; j < n; ++j) {
    const double target = arc[m - 1] * j / (n - 1);
    while (q + 2 < m && arc[q + 1] < target) ++q;
    const double w = std::clamp((target - arc[q]) / std::max(1e-300, arc[q + 1] - arc[q]), 0.0, 1.0);
    out.row(j) = dense.row(q) + w * (dense.row(q + 1) - dense.row(q));
  }
  return out;
}

/// A boundary point with its unit normal and the surface's first and second partial derivatives.
struct Frame {
  Eigen::Vector3d p, n, su, sv, suu, suv, svv;
};

Frame frame(const NurbsSurface& s, double u, double v) {
  const Eigen::MatrixXd d = s.derivatives(u, v, 2);  // row k * 3 + l: d^(k+l) / du^k dv^l
  Eigen::VectorXd uu(1), vv(1);
  uu[0] = u;
  vv[0] = v;
  return {d.row(0).transpose(), s.normal(uu, vv).row(0).transpose(), d.row(3).transpose(), d.row(1).transpose(),
          d.row(6).transpose(), d.row(4).transpose(), d.row(2).transpose()};
}

/// The surface's normal curvature at f in the unit tangent direction t (1/m, signed along f.n):
/// t = alpha S_u + beta S_v (least squares over the tangent plane), kappa = n . (alpha^2 S_uu +
/// 2 alpha beta S_uv + beta^2 S_vv) / |alpha S_u + beta S_v|^2, the second fundamental form over the first.
double normal_curvature(const Frame& f, const Eigen::Vector3d& t) {
  Eigen::Matrix2d g;
  g << f.su.dot(f.su), f.su.dot(f.sv), f.su.dot(f.sv), f.sv.dot(f.sv);
  const Eigen::Vector2d ab = g.ldlt().solve(Eigen::Vector2d(f.su.dot(t), f.sv.dot(t)));
  const Eigen::Vector3d c1 = ab[0] * f.su + ab[1] * f.sv;
  const double speed2 = c1.squaredNorm();
  if (!ab.allFinite() || !(speed2 > 0.0)) return 0.0;
  return f.n.dot(ab[0] * ab[0] * f.suu + 2.0 * ab[0] * ab[1] * f.suv + ab[1] * ab[1] * f.svv) / speed2;
}

/// Newton foot point of p on s from (u, v): (S - p) . S_u = (S - p) . S_v = 0, clamped to
/// the domain. Returns false when it does not settle (the caller then searches globally).
bool project(const NurbsSurface& s, const Eigen::Vector3d& p, double& u, double& v, Eigen::Vector3d& q) {
  const auto [u0, u1] = s.domain_u();
  const auto [v0, v1] = s.domain_v();
  for (int it = 0; it < 30; ++it) {
    const Eigen::MatrixXd d = s.derivatives(u, v, 2);  // row k * 3 + l
    const Eigen::Vector3d S = d.row(0).transpose(), Sv = d.row(1).transpose(), Svv = d.row(2).transpose();
    const Eigen::Vector3d Su = d.row(3).transpose(), Suv = d.row(4).transpose(), Suu = d.row(6).transpose();
    const Eigen::Vector3d r = S - p;
    const Eigen::Vector2d f(r.dot(Su), r.dot(Sv));
    Eigen::Matrix2d J;
    J << Su.dot(Su) + r.dot(Suu), Su.dot(Sv) + r.dot(Suv), Su.dot(Sv) + r.dot(Suv), Sv.dot(Sv) + r.dot(Svv);
    const Eigen::Vector2d step = J.colPivHouseholderQr().solve(-f);
    if (!step.allFinite()) return false;
    const double nu = std::clamp(u + step[0], u0, u1), nv = std::clamp(v + step[1], v0, v1);
    const bool done = std::abs(nu - u) < 1e-13 * (u1 - u0) && std::abs(nv - v) < 1e-13 * (v1 - v0);
    u = nu;
    v = nv;
    if (done || it == 29) {
      q = s.evaluate(u, v);
      // at a clamped boundary the gradient condition need not vanish; accept a settled foot
      return done;
    }
  }
  return false;
}


/// The largest |n_y| of a surface's unit normal at a centre-plane point for the surface to count
/// as smooth across the centre plane (its mirror image meets it within about 6 degrees).
constexpr double kSmoothAcrossPlane = 0.1;

/// Per row (Q0 .. Q3 or Q5) and end (start, end): the unit tangent the row must arrive with at
/// a centre-plane end, or zero where it keeps its own. Where the surface the row lies on (or
/// next to) is smooth across the centre plane, the row runs along e_y projected onto that
/// surface's tangent plane, so the blend stays tangent to the surface and joins its mirror
/// image smoothly.
using EndTangents = std::vector<std::array<Eigen::Vector3d, 2>>;

Eigen::Vector3d across_plane(const Eigen::Vector3d& n) {
  if (std::abs(n.y()) > kSmoothAcrossPlane) return Eigen::Vector3d::Zero();
  return (Eigen::Vector3d::UnitY() - n.y() * n).normalized();
}

/// Control points (n + ends, 3 m) of the m section rows (n, 3 m together) interpolated at
/// parameters par with the end tangents given (P&T 9.2.2: interpolation with end derivatives,
/// each derivative taking a repeated parameter in the knot averaging; its length is the end
/// chord's speed). A row with a zero tangent keeps the end derivative of the plain interpolant.
Eigen::MatrixXd rows_with_end_tangents(const Eigen::MatrixXd& all, const Eigen::VectorXd& par, int p,
                                       const EndTangents& t, bool at_start, bool at_end, Eigen::VectorXd& knots) {
  const Eigen::Index n = all.rows();
  const NurbsCurve plain = fit_curve_with(all, par, averaged_knots(par, p, static_cast<int>(n)), p).curve;
  const Eigen::Index N = n + at_start + at_end;
  Eigen::VectorXd ext(N);
  ext << Eigen::VectorXd::Constant(at_start ? 1 : 0, par[0]), par, Eigen::VectorXd::Constant(at_end ? 1 : 0, par[n - 1]);
  knots = averaged_knots(ext, p, static_cast<int>(N));
  Eigen::MatrixXd A(N, N), rhs(N, all.cols());
  for (Eigen::Index k = 0; k < n; ++k) {
    A.row(k) = basis_row(knots, p, par[k]);
    rhs.row(k) = all.row(k);
  }
  Eigen::Index r = n;
  for (const int e : {0, 1}) {
    if (!(e == 0 ? at_start : at_end)) continue;
    const double te = e == 0 ? par[0] : par[n - 1];
    const Eigen::Index a = e == 0 ? 0 : n - 2, b = e == 0 ? 1 : n - 1;  // the end chord
    A.row(r) = basis_row(knots, p, te, 1);
    rhs.row(r) = plain.derivatives(te, 1).row(1);
    for (int q = 0; q < static_cast<int>(t.size()); ++q) {
      if (t[q][e].isZero()) continue;
      const Eigen::Vector3d chord = (all.block<1, 3>(b, 3 * q) - all.block<1, 3>(a, 3 * q)).transpose();
      const double sign = chord.dot(t[q][e]) >= 0.0 ? 1.0 : -1.0;
      rhs.block<1, 3>(r, 3 * q) = (sign * chord.norm() / (par[b] - par[a]) * t[q][e]).transpose();
    }
    ++r;
  }
  Eigen::PartialPivLU<Eigen::MatrixXd> lu(A);
  const Eigen::MatrixXd c = lu.solve(rhs);
  if (!c.allFinite()) detail::fail("the blend's rows with centre-plane end tangents have no interpolant");
  return c;
}

}  // namespace

BoundaryContinuity measure_boundary_continuity(const NurbsSurface& blend, bool at_v1, const NurbsSurface& s,
                                               int samples) {
  if (samples < 2) detail::fail("samples is ", samples, "; expected >= 2");
  const auto [u0, u1] = blend.domain_u();
  const auto [v0, v1] = blend.domain_v();
  BoundaryContinuity c;
  double pu = 0.0, pv = 0.0;
  for (int k = 0; k < samples; ++k) {
    const double u = u0 + (u1 - u0) * k / (samples - 1);
    const double v = at_v1 ? v1 : v0;
    const Eigen::MatrixXd d = blend.derivatives(u, v, 1);
    const Eigen::Vector3d p = d.row(0).transpose();
    const Eigen::Vector3d bu = d.row(2).transpose(), bv = d.row(1).transpose();
    const Eigen::Vector3d nb = bu.cross(bv).normalized();
    // projection: global search at the first point, then Newton continued from the last
    double su, sv;
    Eigen::Vector3d q;
    if (k == 0 || !project(s, p, pu, pv, q)) {
      std::tie(su, sv, q) = s.closest_point(p);
    } else {
      su = pu;
      sv = pv;
    }
    pu = su;
    pv = sv;
    Eigen::VectorXd uu(1), vv(1);
    uu[0] = su;
    vv[0] = sv;
    const Eigen::Vector3d ns = s.normal(uu, vv).row(0).transpose();
    const double cosang = std::min(1.0, std::abs(nb.dot(ns)));
    c.max_angle_deg = std::max(c.max_angle_deg, std::acos(cosang) * 180.0 / M_PI);
    c.max_gap = std::max(c.max_gap, (q - p).norm());
  }
  return c;
}

namespace {

/// The rows of section control points of the Hermite sections, (n, 3) each: Q0 on a, ..., the
/// last on b (4 rows for cubic sections, 6 for quintic).
using SectionRows = std::vector<Eigen::MatrixXd>;

/// Orients the unit directions d (one per sample) alike along the boundary: toward the other
/// surface where `toward` (d . gap / |gap|, before orienting) says so most clearly, then by
/// continuity from there. Per sample by the gap alone, d flips where the gap runs nearly across
/// it (a blend from the bulb's top up to a hull boundary straight above: d along x, gap along
/// z), and the rows between cross over into a fold.
void orient_by_continuity(std::vector<Eigen::Vector3d>& d, const std::vector<double>& toward) {
  const int n = static_cast<int>(d.size());
  int k = 0;
  for (int j = 1; j < n; ++j)
    if (std::abs(toward[j]) > std::abs(toward[k])) k = j;
  if (toward[k] < 0.0) d[k] = -d[k];
  for (int j = k + 1; j < n; ++j)
    if (d[j].dot(d[j - 1]) < 0.0) d[j] = -d[j];
  for (int j = k - 1; j >= 0; --j)
    if (d[j].dot(d[j + 1]) < 0.0) d[j] = -d[j];
}

/// Where a tangent row point would come nearer the centre plane than this share of its
/// boundary point's height, keep_off_plane starts turning it (see there).
constexpr double kRowAbovePlane = 0.15;

/// Below this |e . d| (e = n x e_y, d the direction to lift) keep_off_plane turns d less and
/// shortens the handle instead: where d heads straight for the centre plane either way round
/// lifts it alike, and the side it turned to flipped between neighbouring samples, pleating the
/// whole blend. A narrower fade turns the rows faster than d turns along the boundary (at 0.15
/// one of bench_design_options' bulbed blends still folded by 115 deg; none by over 60 at 0.3).
constexpr double kTurnFade = 0.3;

/// A tangent row's direction and speed factor (<= 1) from keep_off_plane.
struct LiftedRow {
  Eigen::Vector3d d;
  double speed = 1.0;
};

/// d (unit, in the tangent plane of normal n at p, on the way to the other surface) lifted so
/// that the tangent row point p + h d stays above the centre plane: near the centre-plane ends
/// the tangent planes of a stem or a bulb's top run across the plane within h, and a section
/// whose tangent rows go below y = 0 dips under it (the half hull crosses its mirror image).
/// The height y = p.y + h d.y it would have is mapped by a C1 function that is y itself above
/// a = kRowAbovePlane p.y and a exp((y - a) / a) below (positive, so the rows turn smoothly,
/// with no kink where the turning starts). d is turned within the tangent plane toward
/// e = n x e_y (no y part, on d's side) as far as that lifts it, fully where |e . d| >=
/// kTurnFade and by a smoothstep share of it below; the handle is shortened for what the turn
/// leaves. Both depend continuously on d and n, so neighbouring sections stay neighbours.
LiftedRow keep_off_plane(const Eigen::Vector3d& p, const Eigen::Vector3d& n, const Eigen::Vector3d& d, double h) {
  const double a = kRowAbovePlane * p.y(), y = p.y() + h * d.y();
  if (!(a > 0.0) || y >= a) return {d};
  const double want = a * std::exp((y - a) / a);
  Eigen::Vector3d e = n.cross(Eigen::Vector3d::UnitY());
  Eigen::Vector3d t = d;
  if (e.norm() > 1e-9) {
    e.normalize();
    if (e.dot(d) < 0.0) e = -e;
    double lo = 0.0, hi = 1.0;  // the weight of e that lifts the row point to `want`, by bisection
    for (int it = 0; it < 50; ++it) {
      const double w = 0.5 * (lo + hi);
      const Eigen::Vector3d tw = ((1.0 - w) * d + w * e).normalized();
      (p.y() + h * tw.y() >= want ? hi : lo) = w;
    }
    const double f = std::min(1.0, e.dot(d) / kTurnFade), share = f * f * (3.0 - 2.0 * f);
    t = ((1.0 - share * hi) * d + share * hi * e).normalized();
  }
  const double drop = -h * t.y(), room = p.y() - want;  // room > 0: want <= a < p.y
  return {t, drop > room ? room / drop : 1.0};
}

/// A quintic section's speed across the boundaries, a share of the cubic's (tension |P_b - P_a|):
/// its first two legs then reach nearly as far along d as the cubic's handle (2/5 of 0.8 against
/// 1/3). At the full speed the quintic ran straight on along d for 2/5 of it (zero curvature
/// against a flat neighbour) and turned the harder after: where the container ship's blend comes
/// down the stem onto the bulb's top the 1.5 m mesh took slivers (scaled Jacobian 0.017; 0.31
/// at 0.8). At 5/6, with the cap below, 2 of bench_design_options' 500 composed hulls folded
/// their blends where cubic sections had not (1 at 0.8, a single pair of faces; 0.75 left none
/// but slivers in the 3 m mesh, scaled Jacobian 0.11).
constexpr double kQuinticSpeed = 0.8;
/// The curvature term kappa v^2 / 20 of Q2 (Q3) is at most this share of the handle v / 5,
/// approached as x / (1 + (|x| / cap)^p)^(1/p) with this p: where the hull curves hard across the
/// boundary (near a sonar dome, a sharp forefoot: up to 19 handles) the full term folded the
/// blend (7 of bench_design_options' 500 composed hulls self-intersecting against 3 with cubic
/// sections; 3 with the cap). Below it the term, and so G2, is kept within a few per cent.
constexpr double kCurvatureTermCap = 0.25, kCurvatureTermSharpness = 8.0;

/// The rows of one end's section points from its boundary frame f, the unit direction d across
/// it toward the other surface and the section's speed v there: Q0 = P, Q1 = P + v/5 d and
/// Q2 = 2 Q1 - Q0 + kappa v^2 n / 20 (quintic; the last term capped, kCurvatureTermCap), or
/// Q1 = P + v/3 d (cubic); first to last from the boundary inward.
std::vector<Eigen::Vector3d> end_rows(const Frame& f, const Eigen::Vector3d& d, double v, bool quintic) {
  if (!quintic) return {f.p, f.p + v / 3.0 * d};
  const Eigen::Vector3d q1 = f.p + v / 5.0 * d;
  const double h = v / 5.0, x = normal_curvature(f, d) * v * v / 20.0;
  return {f.p, q1, 2.0 * q1 - f.p + detail::soft_cap(x, kCurvatureTermCap * h, kCurvatureTermSharpness) * f.n};
}

/// Writes the section rows of sample j from both ends' rows (a's from Q0 inward, b's from the
/// last inward).
void put_section(SectionRows& rows, int j, const std::vector<Eigen::Vector3d>& at_a, const std::vector<Eigen::Vector3d>& at_b) {
  const int m = static_cast<int>(rows.size());
  for (std::size_t k = 0; k < at_a.size(); ++k) {
    rows[k].row(j) = at_a[k].transpose();
    rows[m - 1 - k].row(j) = at_b[k].transpose();
  }
}

/// The sections leave both boundaries in the surfaces' tangent planes, toward the other surface
/// (orient_by_continuity) and off the centre plane (keep_off_plane), at the speed tension times
/// the gap; quintic ones with the surfaces' normal curvature across (end_rows).
SectionRows hermite_rows(const std::vector<Frame>& fa, const std::vector<Frame>& fb, double tension, bool quintic) {
  const int n = static_cast<int>(fa.size());
  std::vector<Eigen::Vector3d> da(n), db(n);
  std::vector<double> toward_b(n), toward_a(n), len(n);
  for (int j = 0; j < n; ++j) {
    const int jp = std::min(j + 1, n - 1), jm = std::max(j - 1, 0);
    const Eigen::Vector3d ta = (fa[jp].p - fa[jm].p).normalized(), tb = (fb[jp].p - fb[jm].p).normalized();
    const Eigen::Vector3d gap = fb[j].p - fa[j].p;
    len[j] = gap.norm();
    if (!(len[j] > 0.0))
      detail::fail("boundaries touch at sample ", j, "; expected separate curves on the two surfaces");
    da[j] = fa[j].n.cross(ta);
    db[j] = fb[j].n.cross(tb);
    if (da[j].norm() < 1e-12 || db[j].norm() < 1e-12)
      detail::fail("boundary tangent is parallel to the surface normal at sample ", j);
    da[j].normalize();
    db[j].normalize();
    toward_b[j] = da[j].dot(gap) / len[j];
    toward_a[j] = -db[j].dot(gap) / len[j];
  }
  orient_by_continuity(da, toward_b);
  orient_by_continuity(db, toward_a);
  SectionRows rows(quintic ? 6 : 4, Eigen::MatrixXd(n, 3));
  for (int j = 0; j < n; ++j) {
    // the handle a cubic section would have is what keep_off_plane keeps above the plane
    const double v = tension * len[j], h = v / 3.0, vq = quintic ? kQuinticSpeed * v : v;
    const LiftedRow la = keep_off_plane(fa[j].p, fa[j].n, da[j], h), lb = keep_off_plane(fb[j].p, fb[j].n, db[j], h);
    put_section(rows, j, end_rows(fa[j], la.d, la.speed * vq, quintic), end_rows(fb[j], lb.d, lb.speed * vq, quintic));
  }
  return rows;
}

/// The end sections that lie in the centre plane y = 0 and the tangents their rows must arrive with.
struct PlaneEnds {
  bool start = false, end = false;
  EndTangents tangent;
  explicit PlaneEnds(std::size_t rows) : tangent(rows) {
    for (auto& row : tangent) row.fill(Eigen::Vector3d::Zero());
  }
};

/// An end section on the centre plane y = 0 must stay in it (the mirrored hull is then smooth
/// across it), and for C1 its cross-boundary tangent must lie in the surface's tangent plane
/// too: the one direction in both is n x e_y (the stem or keel line on the hull, the top or
/// bottom centre line on the bulb). Zeroing y of n x t instead would leave the tangent plane
/// wherever the boundary tangent t is not horizontal. Moves those ends' rows into the plane.
PlaneEnds hold_centre_plane_ends(const std::vector<Frame>& fa, const std::vector<Frame>& fb, double tension,
                                 SectionRows& rows) {
  const int n = static_cast<int>(fa.size()), m = static_cast<int>(rows.size());
  const bool quintic = m == 6;
  PlaneEnds ends(rows.size());
  const double tol = 1e-9 * std::max(1.0, (fb[0].p - fa[0].p).norm());
  const Eigen::Vector3d ey(0.0, 1.0, 0.0);
  for (int j : {0, n - 1})
    if (std::abs(fa[j].p.y()) <= tol && std::abs(fb[j].p.y()) <= tol) {
      const int e = j == 0 ? 0 : 1;
      (e == 0 ? ends.start : ends.end) = true;
      for (int q = 0; q < m; ++q) ends.tangent[q][e] = across_plane(q < m / 2 ? fa[j].n : fb[j].n);
      const double v = tension * (fb[j].p - fa[j].p).norm() * (quintic ? kQuinticSpeed : 1.0);
      Eigen::Vector3d da = fa[j].n.cross(ey), db = fb[j].n.cross(ey);
      if (da.norm() > 1e-9 && db.norm() > 1e-9) {
        da.normalize();
        db.normalize();
        // the side hermite_rows oriented this end's directions to
        if (da.dot((rows[1].row(j) - rows[0].row(j)).transpose()) < 0) da = -da;
        if (db.dot((rows[m - 2].row(j) - rows[m - 1].row(j)).transpose()) < 0) db = -db;
        put_section(rows, j, end_rows(fa[j], da, v, quintic), end_rows(fb[j], db, v, quintic));
      }
      for (auto& r : rows) r(j, 1) = 0.0;
    }
  return ends;
}

/// The sections' common parameters along the boundaries: the boundary rows' (P0, P3) chord
/// lengths summed, normalised to [0, 1]. The handle rows are left out: at a sharp stem the end
/// section's handle turns to the stem line, and counting that turn stretched the last interval.
Eigen::VectorXd row_parameters(const SectionRows& rows) {
  const Eigen::Index n = rows[0].rows();
  Eigen::VectorXd par = Eigen::VectorXd::Zero(n);
  for (Eigen::Index j = 1; j < n; ++j) {
    par[j] = par[j - 1] + ((rows.front().row(j) - rows.front().row(j - 1)).norm() + (rows.back().row(j) - rows.back().row(j - 1)).norm());
  }
  par /= par[n - 1];
  return par;
}

/// The cubic (along s) by Hermite (across: cubic or quintic) surface interpolating the rows.
NurbsSurface skin_rows(const SectionRows& rows, const Eigen::VectorXd& par, const PlaneEnds& ends) {
  const Eigen::Index n = rows[0].rows();
  const int p = 3, m = static_cast<int>(rows.size());
  Eigen::MatrixXd all(n, 3 * m);  // the rows share one interpolation matrix: one solve
  for (int r = 0; r < m; ++r) all.middleCols(3 * r, 3) = rows[r];
  Eigen::VectorXd K;
  Eigen::MatrixXd c;
  if (ends.start || ends.end) {
    c = rows_with_end_tangents(all, par, p, ends.tangent, ends.start, ends.end, K);
  } else {
    K = averaged_knots(par, p, static_cast<int>(n));
    c = fit_curve_with(all, par, K, p).curve.control_points();
  }
  const int nc = static_cast<int>(c.rows());
  Eigen::MatrixXd ctrl(static_cast<Eigen::Index>(nc) * m, 3);
  for (int r = 0; r < m; ++r)
    for (int i = 0; i < nc; ++i) ctrl.row(i * m + r) = c.block<1, 3>(i, 3 * r);
  Eigen::VectorXd kt(2 * m);
  kt << Eigen::VectorXd::Zero(m), Eigen::VectorXd::Ones(m);
  return NurbsSurface(p, m - 1, K, kt, nc, m, ctrl);
}

}  // namespace

BlendSurface blend_surface(const NurbsSurface& a, const Eigen::MatrixXd& boundary_a, const NurbsSurface& b,
                           const Eigen::MatrixXd& boundary_b, const BlendOptions& o) {
  if (o.samples < 4) detail::fail("samples is ", o.samples, "; expected >= 4");
  if (o.continuity != 1 && o.continuity != 2) detail::fail("continuity is ", o.continuity, "; expected 1 (G1) or 2 (G2)");
  detail::require_positive(o.tension, "tension");
  const int n = o.samples;
  const Eigen::MatrixXd ua = resample(a, boundary_a, n, "boundary_a");
  const Eigen::MatrixXd ub = resample(b, boundary_b, n, "boundary_b");
  std::vector<Frame> fa(n), fb(n);
  for (int j = 0; j < n; ++j) {
    fa[j] = frame(a, ua(j, 0), ua(j, 1));
    fb[j] = frame(b, ub(j, 0), ub(j, 1));
  }
  SectionRows rows = hermite_rows(fa, fb, o.tension, o.continuity == 2);
  PlaneEnds ends(rows.size());
  if (o.centre_plane_ends) ends = hold_centre_plane_ends(fa, fb, o.tension, rows);
  const Eigen::VectorXd par = row_parameters(rows);
  const NurbsSurface s = skin_rows(rows, par, ends);
  BlendSurface out{s, {}, {}, ua, ub, par};
  out.at_a = measure_boundary_continuity(s, false, a, o.check_samples);
  out.at_b = measure_boundary_continuity(s, true, b, o.check_samples);
  return out;
}

}  // namespace fairlines
