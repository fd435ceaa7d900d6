// Boolean union of bare hull and bulb into one closed half-hull mesh, see fairlines/compose.hpp.
//
// Method: the seam is traced by intersect_surfaces, then re-sampled at the bulb's mesh
// columns v_j with Newton (bulb v fixed), so hull and bulb meshes share those seam vertices.
// Bulb: a structured strip from the seam to the nose pole. Hull: whole grid cells clear of
// the hole; the band between the cells and the seam is one simple polygon in scaled
// parameter space, triangulated by ear clipping. The open boundary (centre plane, deck, aft
// cut) is split into its three planar runs and each is capped by a planar polygon.
//
// compose_hull in steps: validate_options -> orient_bare_hull, aft_end -> HullGrid ->
// join_bulb (trace_seam or seam_from_blend, add_seam_and_blend, add_bulb_strip,
// cells_under_seam, fill_pockets_and_pinches, trace_staircase, add_band,
// add_trimming_loops) -> add_kept_cells -> close_half_hull -> finish_mesh (closure check).
//
// Notation:
//   H            the bare hull in the orient_bare_hull convention: u from the aft cut (u0) to
//                the stem (u1), v from the keel (v0) to the deck (v1)
//   B            the bulb: u from its aft end (bu0) to the nose pole (bu1), v from the bottom
//                centre line (bv0) around to the top one (bv1)
//   I, K         hull cells along u and v (hull_u, hull_v); node (i, k), cell (i, k) has
//                index i K + k, node key i (K + 1) + k
//   NV, NU, NT   bulb columns (bulb_v, also seam segments), bulb cells from seam to nose
//                (bulb_u), blend rows (blend_rows)
//   x_j          seam point at bulb column j: (u_h, v_h) on H and (u_b, v_b) on B
//   perimeter p  position along the hull's centre-plane edges: keel p = (u - u0)/(u1 - u0)
//                in [0, 1), stem p = 1 + (v - v0)/(v1 - v0); the seam spans [pa, pb]
//   scaled space (u, v) mapped to metres: Ls (u - u0)/(u1 - u0), Lt (v - v0)/(v1 - v0), with
//                Ls the hull length at half depth and Lt its girth at half length
#include "fairlines/compose.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <tuple>
#include <unordered_map>

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include "fairlines/errors.hpp"
#include "common/used_nodes.hpp"
#include "nurbs/checks.hpp"

namespace fairlines {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

NurbsSurface transform(const NurbsSurface& s, bool swap, bool rev_u, bool rev_v) {
  int nu = s.nu(), nv = s.nv(), pu = s.degree_u(), pv = s.degree_v();
  Eigen::VectorXd ku = s.knots_u(), kv = s.knots_v();
  Eigen::MatrixXd pw = s.homogeneous();
  if (swap) {
    Eigen::MatrixXd q(pw.rows(), 4);
    for (int i = 0; i < nu; ++i)
      for (int j = 0; j < nv; ++j) q.row(j * nu + i) = pw.row(i * nv + j);
    pw = q;
    std::swap(nu, nv);
    std::swap(pu, pv);
    std::swap(ku, kv);
  }
  auto reverse_knots = [](const Eigen::VectorXd& k) {
    Eigen::VectorXd r(k.size());
    const double a = k[0], b = k[k.size() - 1];
    for (Eigen::Index i = 0; i < k.size(); ++i) r[i] = a + b - k[k.size() - 1 - i];
    return r;
  };
  if (rev_u || rev_v) {
    Eigen::MatrixXd q(pw.rows(), 4);
    for (int i = 0; i < nu; ++i)
      for (int j = 0; j < nv; ++j)
        q.row(i * nv + j) = pw.row((rev_u ? nu - 1 - i : i) * nv + (rev_v ? nv - 1 - j : j));
    pw = q;
    if (rev_u) ku = reverse_knots(ku);
    if (rev_v) kv = reverse_knots(kv);
  }
  return NurbsSurface::from_homogeneous(pu, pv, ku, kv, nu, nv, pw);
}

Eigen::MatrixXd edge_points(const NurbsSurface& s, bool fix_u, bool at_max, int n = 25) {
  const auto [u0, u1] = s.domain_u();
  const auto [v0, v1] = s.domain_v();
  Eigen::VectorXd us(n), vs(n);
  for (int k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) / (n - 1);
    us[k] = fix_u ? (at_max ? u1 : u0) : u0 + (u1 - u0) * t;
    vs[k] = fix_u ? v0 + (v1 - v0) * t : (at_max ? v1 : v0);
  }
  return s.evaluate(us, vs);
}

double size_of(const NurbsSurface& s) {
  const Eigen::MatrixXd& P = s.control_points();
  return (P.colwise().maxCoeff() - P.colwise().minCoeff()).norm();
}

/// Newton on S_h(s, t) = S_b(u, v) with v fixed: x = (s, t, u, v). Clamped to the domains.
double seam_newton(const NurbsSurface& h, const NurbsSurface& b, Eigen::Vector4d& x, double tol) {
  const auto [hu0, hu1] = h.domain_u();
  const auto [hv0, hv1] = h.domain_v();
  const auto [bu0, bu1] = b.domain_u();
  double r = 1e300;
  for (int it = 0; it < 50; ++it) {
    x[0] = std::clamp(x[0], hu0, hu1);
    x[1] = std::clamp(x[1], hv0, hv1);
    x[2] = std::clamp(x[2], bu0, bu1);
    const Eigen::MatrixXd dh = h.derivatives(x[0], x[1], 1), db = b.derivatives(x[2], x[3], 1);
    const Eigen::Vector3d res = (dh.row(0) - db.row(0)).transpose();
    r = res.norm();
    if (r < tol) break;
    Eigen::Matrix3d J;
    J.col(0) = dh.row(2).transpose();
    J.col(1) = dh.row(1).transpose();
    J.col(2) = -db.row(2).transpose();
    const Eigen::Vector3d d = J.colPivHouseholderQr().solve(-res);
    if (!d.allFinite()) break;
    x.head<3>() += d;
  }
  return r;
}

bool point_in_polygon(const Eigen::Vector2d& q, const std::vector<Eigen::Vector2d>& poly) {
  bool in = false;
  const size_t n = poly.size();
  for (size_t i = 0, j = n - 1; i < n; j = i++) {
    const auto& a = poly[i];
    const auto& c = poly[j];
    if ((a.y() > q.y()) != (c.y() > q.y()) &&
        q.x() < (c.x() - a.x()) * (q.y() - a.y()) / (c.y() - a.y()) + a.x())
      in = !in;
  }
  return in;
}

double seg_dist(const Eigen::Vector2d& q, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double L2 = ab.squaredNorm();
  const double t = L2 > 0 ? std::clamp((q - a).dot(ab) / L2, 0.0, 1.0) : 0.0;
  return (a + t * ab - q).norm();
}

/// A u edge of the hull grid whose nodes lie within this fraction of the hull's size of each
/// other is a pole (the stem top): its nodes share one mesh vertex, and the cells at it give
/// one triangle each instead of a triangle and a face of zero area.
constexpr double kPoleTolerance = 1e-9;

/// Where a vertex that fell across the centre plane is held (m): off the plane by far less
/// than any tolerance of the mesh, so it is not taken for a centre-plane vertex.
constexpr double kOffCentrePlane = 1e-9;

struct MeshBuilder {
  std::vector<Eigen::Vector3d> verts;
  std::vector<std::array<int, 3>> faces;
  std::vector<int> part;
  std::vector<std::array<double, 6>> uv;  ///< a hull face's corners on the hull, else NaN
  std::vector<std::array<double, 6>> collapsed_uv;  ///< hull parameter triangles whose face is a point or line
  int add(const Eigen::Vector3d& p) {
    verts.push_back(p);
    return static_cast<int>(verts.size()) - 1;
  }
  void tri(int a, int b, int c, FacePart fp, const std::array<double, 6>& corners = kNoCorners) {
    if (a == b || b == c || c == a) {  // a cell or ear at a pole: no face, but its surface is the hull's
      if (!std::isnan(corners[0])) collapsed_uv.push_back(corners);
      return;
    }
    faces.push_back({a, b, c});
    part.push_back(static_cast<int>(fp));
    uv.push_back(corners);
  }
  static constexpr std::array<double, 6> kNoCorners = {kNaN, kNaN, kNaN, kNaN, kNaN, kNaN};
  /// The quad a b c d as two triangles, split along the diagonal that folds it least (where
  /// the blend wraps a sharp stem its quads twist, and the other diagonal saws the shading).
  void quad(int a, int b, int c, int d, FacePart fp) {
    auto n = [&](int p, int q, int r) { return (verts[q] - verts[p]).cross(verts[r] - verts[p]).normalized(); };
    if (n(a, b, c).dot(n(a, c, d)) >= n(a, b, d).dot(n(b, c, d))) {
      tri(a, b, c, fp);
      tri(a, c, d, fp);
    } else {
      tri(a, b, d, fp);
      tri(b, c, d, fp);
    }
  }
  TriMesh mesh() const {
    TriMesh m;
    m.vertices.resize(static_cast<Eigen::Index>(verts.size()), 3);
    for (size_t i = 0; i < verts.size(); ++i) m.vertices.row(static_cast<Eigen::Index>(i)) = verts[i].transpose();
    m.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
    for (size_t f = 0; f < faces.size(); ++f)
      for (int k = 0; k < 3; ++k) m.faces(static_cast<Eigen::Index>(f), k) = faces[f][k];
    return m;
  }
};

/// The open boundary of the oriented surface faces as one loop, run against the surface (so a
/// cap made on it faces the other way). Throws when the boundary branches or is not one loop.
std::vector<int> boundary_loop(const MeshBuilder& mb) {
  const auto key = [](int a, int b) {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(std::min(a, b))) << 32) |
           static_cast<std::uint32_t>(std::max(a, b));
  };
  // every face side's undirected edge, sorted: a side alone on its edge is on the boundary
  std::vector<std::uint64_t> sides;
  sides.reserve(mb.faces.size() * 3);
  for (const auto& f : mb.faces)
    for (int k = 0; k < 3; ++k) sides.push_back(key(f[k], f[(k + 1) % 3]));
  std::sort(sides.begin(), sides.end());
  const auto alone = [&](std::uint64_t e) {
    const auto it = std::lower_bound(sides.begin(), sides.end(), e);
    return std::next(it) == sides.end() || *std::next(it) != e;
  };
  std::unordered_map<int, int> next;
  for (const auto& f : mb.faces)
    for (int k = 0; k < 3; ++k) {
      int a = f[k], b = f[(k + 1) % 3];
      if (alone(key(a, b))) {
        if (next.count(b)) throw InvalidInput("compose: the open hull boundary branches (non-manifold boundary vertex)");
        next[b] = a;  // reversed: the cap runs against the surface boundary
      }
    }
  if (next.empty()) throw InvalidInput("compose: the hull surface has no open boundary to close");
  std::vector<int> loop;
  const int start = next.begin()->first;
  int v = start;
  do {
    loop.push_back(v);
    auto it = next.find(v);
    if (it == next.end()) throw InvalidInput("compose: the open hull boundary is not a closed loop");
    v = it->second;
    if (loop.size() > next.size()) throw InvalidInput("compose: the open hull boundary is not a single loop");
  } while (v != start);
  if (loop.size() != next.size())
    throw InvalidInput("compose: the open hull boundary has several loops; expected one (centre plane, deck, aft cut)");
  return loop;
}

/// The plane of the boundary edge a-b: 0 centre plane, 1 deck, 2 aft cut (transom plane).
int boundary_plane(const std::vector<Eigen::Vector3d>& P, int a, int b, const AftEnd& aft, double z_deck, double tol) {
  if (P[a].y() == 0.0 && P[b].y() == 0.0) return 0;
  if (P[a].z() == z_deck && P[b].z() == z_deck) return 1;
  if (!aft.on_centre_plane && std::abs(aft.normal.dot(P[a]) - aft.offset) <= tol &&
      std::abs(aft.normal.dot(P[b]) - aft.offset) <= tol)
    return 2;
  std::ostringstream os;
  os << "compose: a boundary edge from (" << P[a].transpose() << ") to (" << P[b].transpose()
     << ") lies on none of the centre plane, deck or aft cut";
  throw InvalidInput(os.str());
}

/// Triangulates one planar run of boundary vertices (closed by the deck corner of a transom
/// when there is one) in its plane's coordinates, as a cap of that plane.
void cap_run(MeshBuilder& mb, std::vector<int> run, int plane, int corner) {
  if (corner >= 0) run.push_back(corner);
  Eigen::MatrixXd poly(static_cast<Eigen::Index>(run.size()), 2);
  for (size_t k = 0; k < run.size(); ++k) {
    const Eigen::Vector3d& q = mb.verts[run[k]];
    if (plane == 0) poly.row(static_cast<Eigen::Index>(k)) << q.x(), q.z();
    else if (plane == 1) poly.row(static_cast<Eigen::Index>(k)) << q.x(), q.y();
    else poly.row(static_cast<Eigen::Index>(k)) << q.y(), q.z();
  }
  const FacePart part = plane == 0 ? FacePart::CentrePlane : plane == 1 ? FacePart::Deck : FacePart::AftCut;
  std::vector<std::array<int, 3>> tris = triangulate_polygon(poly);
  delaunay_flips(poly, tris);
  for (const auto& t : tris) mb.tri(run[t[0]], run[t[1]], run[t[2]], part);
}

/// Caps the planar boundary runs of an open half-hull surface (oriented consistently): the
/// centre plane, the deck and, unless the aft end lies on the centre plane, the transom plane.
void close_half_hull(MeshBuilder& mb, const AftEnd& aft, double z_deck, double tol) {
  TriMesh open = mb.mesh();
  orient_if_needed(open);
  for (size_t f = 0; f < mb.faces.size(); ++f)
    for (int k = 0; k < 3; ++k) mb.faces[f][k] = open.faces(static_cast<Eigen::Index>(f), k);
  const std::vector<int> loop = boundary_loop(mb);
  const int n = static_cast<int>(loop.size());
  std::vector<int> cls(n);
  for (int i = 0; i < n; ++i) cls[i] = boundary_plane(mb.verts, loop[i], loop[(i + 1) % n], aft, z_deck, tol);
  int s0 = -1;
  for (int i = 0; i < n && s0 < 0; ++i)
    if (cls[i] != cls[(i + n - 1) % n]) s0 = i;
  if (s0 < 0) throw InvalidInput("compose: the open boundary lies in one plane only");
  const int corner = aft.on_centre_plane ? -1 : mb.add(aft.deck_corner);
  int runs = 0, seen_mask = 0;
  for (int i = 0; i < n;) {
    const int c = cls[(s0 + i) % n];
    std::vector<int> run{loop[(s0 + i) % n]};
    for (; i < n && cls[(s0 + i) % n] == c; ++i) run.push_back(loop[(s0 + i + 1) % n]);
    ++runs;
    seen_mask |= 1 << c;
    cap_run(mb, std::move(run), c, corner);
  }
  const int want = aft.on_centre_plane ? 2 : 3;
  if (runs != want || seen_mask != (aft.on_centre_plane ? 3 : 7)) {
    std::ostringstream os;
    os << "compose: the open boundary splits into " << runs << " planar runs; expected " << want
       << (aft.on_centre_plane ? " (centre plane, deck)" : " (centre plane, deck, aft cut) in that cyclic order");
    throw InvalidInput(os.str());
  }
}

/// Whether a point lies on the bulb's aft end u = bu0 (which must be inside the hull).
bool reaches_aft_end(const std::vector<IntersectionPoint>& pts, const NurbsSurface& B) {
  const auto [bu0, bu1] = B.domain_u();
  for (const auto& q : pts)
    if (q.uv_b.x() <= bu0 + 1e-6 * (bu1 - bu0)) return true;
  return false;
}

/// The one intersection branch that runs around the bulb from its bottom to its top centre
/// line, its points in increasing bulb v. Throws InvalidInput saying why the bulb cannot meet
/// the hull in such a seam.
std::vector<IntersectionPoint> seam_around_bulb(const std::vector<IntersectionCurve>& curves, const NurbsSurface& B) {
  const auto [bv0, bv1] = B.domain_v();
  if (curves.empty())
    throw InvalidInput("bulb cannot meet the hull: the bulb surface does not intersect the bare hull "
                       "(move it aft / into the hull, or lengthen its aft body)");
  const double vt = 1e-6 * (bv1 - bv0);
  const IntersectionCurve* seam = nullptr;
  for (const auto& c : curves) {
    if (c.closed) continue;
    const double va = c.points.front().uv_b.y(), vb = c.points.back().uv_b.y();
    if (std::min(va, vb) <= bv0 + vt && std::max(va, vb) >= bv1 - vt) seam = &c;
  }
  if (!seam || curves.size() != 1) {
    std::ostringstream os;
    os << "bulb cannot meet the hull: the surfaces intersect in " << curves.size()
       << " curve(s) but the union needs one seam running around the bulb from its bottom to its top centre line";
    if (std::any_of(curves.begin(), curves.end(), [&](const IntersectionCurve& c) { return reaches_aft_end(c.points, B); }))
      os << "; the bulb's aft end is not inside the hull (lengthen aft_length)";
    throw InvalidInput(os.str());
  }
  if (reaches_aft_end(seam->points, B))
    throw InvalidInput("bulb cannot meet the hull: the seam reaches the bulb's aft end, which is not inside the "
                       "hull (lengthen aft_length or move the bulb aft)");
  std::vector<IntersectionPoint> pts = seam->points;
  if (pts.front().uv_b.y() > pts.back().uv_b.y()) std::reverse(pts.begin(), pts.end());
  for (size_t k = 1; k < pts.size(); ++k)
    if (pts[k].uv_b.y() < pts[k - 1].uv_b.y() - vt)
      throw InvalidInput("bulb cannot meet the hull in a simple seam: the intersection turns back around the bulb");
  return pts;
}

/// The seam of the union of the oriented bare hull H and bulb B: the one intersection branch
/// that runs around the bulb from its bottom to its top centre line, re-sampled by Newton at the
/// bulb's mesh columns v_j (j = 0 .. bulb_v) so that hull and bulb meshes can share those
/// points. seam_x[j] = (u_h, v_h, u_b, v_b); curve holds the same points with their positions. Used by
/// compose_hull and by hull_bulb_seam (the blend boundaries need the seam, not the mesh).
void trace_seam(const NurbsSurface& H, const NurbsSurface& B, const ComposeOptions& o,
                std::vector<Eigen::Vector4d>& seam_x, IntersectionCurve& curve) {
  const auto [bv0, bv1] = B.domain_v();
  const int NV = o.bulb_v;
  seam_x.assign(NV + 1, Eigen::Vector4d::Zero());
  curve = IntersectionCurve{};
  IntersectOptions io;
  io.tolerance = o.tolerance;
  const std::vector<IntersectionPoint> pts = seam_around_bulb(intersect_surfaces(H, B, io), B);
  // re-sample at the bulb columns
  for (int j = 0; j <= NV; ++j) {
    const double vj = j == NV ? bv1 : bv0 + (bv1 - bv0) * j / NV;
    size_t k = 1;
    while (k + 1 < pts.size() && pts[k].uv_b.y() < vj) ++k;
    const auto& a = pts[k - 1];
    const auto& c = pts[k];
    const double dv = c.uv_b.y() - a.uv_b.y();
    const double w = dv > 0 ? std::clamp((vj - a.uv_b.y()) / dv, 0.0, 1.0) : 0.0;
    Eigen::Vector4d x;
    x << (1 - w) * a.uv_a + w * c.uv_a, (1 - w) * a.uv_b.x() + w * c.uv_b.x(), vj;
    const double r = seam_newton(H, B, x, o.tolerance);
    if (r > 1e-6) {
      std::ostringstream os;
      os << "compose: seam point at bulb v = " << vj << " did not converge (gap " << r << " m)";
      throw ConvergenceError(os.str());
    }
    seam_x[j] = x;
    const Eigen::Vector3d ph = H.evaluate(x[0], x[1]), pb = B.evaluate(x[2], x[3]);
    curve.points.push_back({0.5 * (ph + pb), {x[0], x[1]}, {x[2], x[3]}});
    curve.max_gap = std::max(curve.max_gap, (ph - pb).norm());
  }
}

/// Perimeter coordinates of the seam's ends on the hull's centre-plane edges (keel: u in
/// [0, 1), stem: 1 + v); throws when an end is elsewhere.
void seam_ends_on_centre_line(const NurbsSurface& H, const std::vector<Eigen::Vector4d>& seam_x, double& pa,
                              double& pb) {
  const auto [u0, u1] = H.domain_u();
  const auto [v0, v1] = H.domain_v();
  auto perim = [&](const Eigen::Vector4d& x, double& p) {
    const double ds = (u1 - x[0]) / (u1 - u0), dt = (x[1] - v0) / (v1 - v0);
    if (dt <= 1e-6 && dt <= ds) p = (x[0] - u0) / (u1 - u0);
    else if (ds <= 1e-6) p = 1.0 + dt;
    else return false;
    return true;
  };
  if (!perim(seam_x.front(), pa) || !perim(seam_x.back(), pb))
    throw InvalidInput("bulb cannot meet the hull: the seam does not end on the hull's keel/stem centre line "
                       "(the bulb must be attached at the stem)");
}

/// Smallest rake allowed for a transom plane: |normal.x| >= this.
constexpr double kMinTransomNormalX = 0.2;

/// Plane through the points (PCA: the normal is the direction of least spread), normal.x >= 0;
/// false when a point is farther than tol from it or the normal is too far from x.
bool fit_transom_plane(const Eigen::MatrixXd& pts, double tol, AftEnd& out) {
  const Eigen::RowVector3d c = pts.colwise().mean();
  const Eigen::MatrixXd d = pts.rowwise() - c;
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(d, Eigen::ComputeFullV);
  Eigen::Vector3d n = svd.matrixV().col(2);
  if (svd.singularValues()[1] <= tol) {  // a straight edge: the plane through it and the y axis
    const Eigen::Vector3d dir = svd.matrixV().col(0);
    n = dir.cross(Eigen::Vector3d::UnitY());
    if (n.norm() < 1e-12) return false;
    n.normalize();
  }
  if (n.x() < 0) n = -n;
  if (n.x() < kMinTransomNormalX) return false;
  const double offset = n.dot(c.transpose());
  if ((d * n).cwiseAbs().maxCoeff() > tol) return false;
  out.on_centre_plane = false;
  out.normal = n;
  out.offset = offset;
  return true;
}

}  // namespace

AftEnd aft_end(const NurbsSurface& H, double z_deck, double tol_rel) {
  const double tol = tol_rel * size_of(H);
  const Eigen::MatrixXd aft = edge_points(H, true, false);
  AftEnd a;
  if (aft.col(1).cwiseAbs().maxCoeff() <= tol) {
    a.on_centre_plane = true;
    const auto [v0, v1] = H.domain_v();
    a.deck_corner = H.evaluate(H.domain_u().first, v1);
    a.deck_corner.y() = 0.0;
    a.deck_corner.z() = z_deck;
    return a;
  }
  if (!fit_transom_plane(aft, tol, a))
    throw InvalidInput("hull surface: the aft edge (u = u_min) lies neither on the centre plane y = 0 nor in one "
                       "plane (a transom) whose normal is within 78 deg of x");
  a.deck_corner = Eigen::Vector3d((a.offset - a.normal.z() * z_deck) / a.normal.x(), 0.0, z_deck);
  return a;
}

NurbsSurface orient_bare_hull(const NurbsSurface& hull, double tol_rel) {
  if (!(tol_rel > 0.0) || !std::isfinite(tol_rel)) detail::fail("plane_tolerance is ", tol_rel, "; expected > 0");
  const double tol = tol_rel * size_of(hull);
  std::string why;
  for (int c = 0; c < 8; ++c) {
    const NurbsSurface s = transform(hull, c & 1, c & 2, c & 4);
    const Eigen::MatrixXd aft = edge_points(s, true, false), stem = edge_points(s, true, true);
    const Eigen::MatrixXd keel = edge_points(s, false, false), deck = edge_points(s, false, true);
    AftEnd plane;
    const bool ok_aft = aft.col(1).cwiseAbs().maxCoeff() <= tol || fit_transom_plane(aft, tol, plane);
    const bool ok_keel = keel.col(1).cwiseAbs().maxCoeff() <= tol;
    const bool ok_stem = stem.col(1).cwiseAbs().maxCoeff() <= tol;
    const bool ok_deck = deck.col(2).maxCoeff() - deck.col(2).minCoeff() <= tol;
    const bool up = deck.col(2).mean() > keel.col(2).mean();
    const bool fwd = stem.col(0).mean() > aft.col(0).mean();
    if (ok_aft && ok_keel && ok_stem && ok_deck && up && fwd) return s;
    if (c == 0) {
      std::ostringstream os;
      os << (ok_aft ? "" : " u=u_min edge neither in one plane (aft cut, a transom) nor at y = 0;") << (ok_keel ? "" : " v=v_min edge not at y = 0 (keel);")
         << (ok_stem ? "" : " u=u_max edge not at y = 0 (stem);") << (ok_deck ? "" : " v=v_max edge not at one z (deck);");
      why = os.str();
    }
  }
  throw InvalidInput("hull surface: no orientation has one edge on the deck z = const, the opposite one (keel) and "
                     "one of the others (stem) on the centre plane y = 0, and the last (aft cut) in one plane or on "
                     "y = 0 (as given:" + why + ")");
}

HullBulbSeam hull_bulb_seam(const NurbsSurface& hull, const NurbsSurface& bulb, const ComposeOptions& o) {
  if (o.bulb_v < 4) detail::fail("bulb_v is ", o.bulb_v, "; expected >= 4");
  HullBulbSeam out{orient_bare_hull(hull, o.plane_tolerance), {}};
  std::vector<Eigen::Vector4d> seam_x;
  trace_seam(out.hull, bulb, o, seam_x, out.seam);
  double pa = 0, pb = 0;
  seam_ends_on_centre_line(out.hull, seam_x, pa, pb);
  return out;
}

namespace {

void validate_options(const ComposeOptions& o, const NurbsSurface* bulb, const BlendSpec* blend) {
  if (o.hull_u < 4) detail::fail("hull_u is ", o.hull_u, "; expected >= 4");
  if (o.hull_v < 4) detail::fail("hull_v is ", o.hull_v, "; expected >= 4");
  if (o.bulb_u < 2) detail::fail("bulb_u is ", o.bulb_u, "; expected >= 2");
  if (o.bulb_v < 4) detail::fail("bulb_v is ", o.bulb_v, "; expected >= 4");
  if (!(o.margin > 0.0) || o.margin > 1.0) detail::fail("margin is ", o.margin, "; expected a fraction of a cell in (0, 1]");
  if (o.blend_rows < 1) detail::fail("blend_rows is ", o.blend_rows, "; expected >= 1");
  if (o.blend_check_samples < 2)
    detail::fail("blend_check_samples is ", o.blend_check_samples, "; expected >= 2");
  if (blend && !bulb) detail::fail("a blend needs a bulb to blend into; got no bulb");
}

/// The hull's tessellation grid: I x K cells, node (i, k) at (su[i], tv[k]), node key
/// i (K + 1) + k. Mesh vertices are added on first use, snapped onto the closing planes.
struct HullGrid {
  const NurbsSurface& H;
  int I, K;
  double u0, u1, v0, v1;
  Eigen::VectorXd su, tv;
  Eigen::MatrixXd pts;  ///< node positions, row = node key
  AftEnd aft;
  double z_deck;
  std::vector<int> gid;  ///< mesh vertex of each node, -1 until used
  std::vector<int> pole_u;  ///< i of each u edge (0, I) that collapses to a point: one vertex
  double Ls = 0.0, Lt = 0.0;  ///< lengths (m) of the scaled parameter space along u and v

  HullGrid(const NurbsSurface& hull, int cells_u, int cells_v, const AftEnd& aft_end, double deck)
      : H(hull), I(cells_u), K(cells_v), aft(aft_end), z_deck(deck) {
    std::tie(u0, u1) = H.domain_u();
    std::tie(v0, v1) = H.domain_v();
    su.resize(I + 1);
    tv.resize(K + 1);
    for (int i = 0; i <= I; ++i) su[i] = u0 + (u1 - u0) * i / I;
    for (int k = 0; k <= K; ++k) tv[k] = v0 + (v1 - v0) * k / K;
    su[I] = u1;
    tv[K] = v1;
    pts = H.evaluate_grid(su, tv);
    gid.assign((I + 1) * (K + 1), -1);
    const double tol = kPoleTolerance * size_of(H);
    for (int i : {0, I}) {  // a u edge collapsed to one point (the stem top) is one vertex
      bool pole = true;
      for (int k = 1; k <= K && pole; ++k) pole = (pts.row(key(i, k)) - pts.row(key(i, 0))).norm() <= tol;
      if (pole) pole_u.push_back(i);
    }
    // the stem-to-aft length at half depth and the keel-to-deck girth at half length
    Ls = (pts.row(key(I, K / 2)) - pts.row(key(0, K / 2))).norm();
    for (int k = 0; k < K; ++k) Lt += (pts.row(key(I / 2, k + 1)) - pts.row(key(I / 2, k))).norm();
  }
  int key(int i, int k) const { return i * (K + 1) + k; }
  int vertex(MeshBuilder& mb, int i, int k) {
    const bool pole = std::find(pole_u.begin(), pole_u.end(), i) != pole_u.end();
    if (pole) k = 0;
    int& g = gid[key(i, k)];
    if (g < 0) {
      Eigen::Vector3d p = pts.row(key(i, k)).transpose();
      if (i == 0) p -= (aft.normal.dot(p) - aft.offset) * aft.normal;  // onto the transom plane
      if (k == 0 || i == I || (i == 0 && aft.on_centre_plane)) p.y() = 0.0;
      if (k == K || pole) p.z() = z_deck;  // a pole holds its deck node (i, K)
      g = mb.add(p);
    }
    return g;
  }
  int vertex(MeshBuilder& mb, int node) { return vertex(mb, node / (K + 1), node % (K + 1)); }
  /// (u, v) mapped to roughly metres, so that distances and ear clipping are not skewed
  Eigen::Vector2d scaled(double s, double t) const {
    return {Ls * (s - u0) / (u1 - u0), Lt * (t - v0) / (v1 - v0)};
  }
  Eigen::Vector2d scaled_node(int node) const { return scaled(su[node / (K + 1)], tv[node % (K + 1)]); }
  /// Perimeter coordinate p of a node on the centre-plane edges; false elsewhere.
  bool perimeter(int node, double& p) const {
    const int i = node / (K + 1), k = node % (K + 1);
    if (k == 0) p = (su[i] - u0) / (u1 - u0);
    else if (i == I) p = 1.0 + (tv[k] - v0) / (v1 - v0);
    else return false;
    return true;
  }
};

/// The seam at the mesh resolution and its mesh vertices: x[j] = (u_h, v_h, u_b, v_b) at
/// bulb column j; [pa, pb] the perimeter interval it spans (pa < pb; `reversed` when x runs
/// from pb to pa).
struct MeshSeam {
  std::vector<Eigen::Vector4d> x;
  IntersectionCurve curve;
  std::vector<Eigen::Vector3d> blend_pts;  ///< with a blend: (NV + 1) x (NT - 1) interior points
  double pa = 0.0, pb = 0.0;
  bool reversed = false;
  std::vector<int> hull_id, bulb_id;  ///< mesh vertices on the hull side and the bulb side
  std::vector<Eigen::Vector2d> scaled;  ///< hull side in HullGrid::scaled coordinates
};

/// With a blend the seam is the blend's two boundaries: skins the blend (finer than the
/// mesh columns) and reads the hull and bulb boundary points at the bulb columns.
void seam_from_blend(const NurbsSurface& H, const NurbsSurface& B, const ComposeOptions& o, const BlendSpec& blend,
                     MeshSeam& seam, ComposedHull& out) {
  const auto [bu0, bu1] = B.domain_u();
  const auto [bv0, bv1] = B.domain_v();
  const int NV = o.bulb_v, NT = o.blend_rows;
  Eigen::MatrixXd on_hull = blend.hull_uv;
  if (on_hull.cols() != 2 || on_hull.rows() < 2)
    detail::fail("blend hull boundary has shape (", on_hull.rows(), ", ", on_hull.cols(), "); expected (k, 2), k >= 2");
  if (!(blend.bulb_u > bu0 && blend.bulb_u < bu1))
    detail::fail("blend bulb_u is ", blend.bulb_u, "; expected inside the bulb's u domain (", bu0, ", ", bu1, ")");
  const Eigen::Index last = on_hull.rows() - 1;
  if (H.evaluate(on_hull(0, 0), on_hull(0, 1)).z() > H.evaluate(on_hull(last, 0), on_hull(last, 1)).z())
    on_hull = on_hull.colwise().reverse().eval();  // bottom -> top, like the bulb's v
  Eigen::MatrixXd on_bulb(129, 2);
  for (int q = 0; q < 129; ++q) on_bulb.row(q) << blend.bulb_u, bv0 + (bv1 - bv0) * q / 128.0;
  BlendOptions bo;
  constexpr int kSectionsPerColumn = 4;  // the skin is finer than the mesh columns
  bo.samples = kSectionsPerColumn * NV + 1;
  bo.tension = blend.tension;
  bo.check_samples = o.blend_check_samples;
  const BlendSurface bs = blend_surface(H, on_hull, B, on_bulb, bo);
  out.blend.push_back(bs.surface);
  out.blend_params.resize(bs.params_s.size(), 5);
  out.blend_params << bs.params_s, bs.params_a, bs.params_b;
  out.blend_at_hull = bs.at_a;
  out.blend_at_bulb = bs.at_b;
  seam.x.assign(NV + 1, Eigen::Vector4d::Zero());
  for (int j = 0; j <= NV; ++j) {
    const int q = kSectionsPerColumn * j;
    seam.x[j] << bs.params_a(q, 0), bs.params_a(q, 1), bs.params_b(q, 0), bs.params_b(q, 1);
    seam.curve.points.push_back({H.evaluate(seam.x[j][0], seam.x[j][1]), {seam.x[j][0], seam.x[j][1]}, {bs.params_s[q], 0.0}});
    for (int k = 1; k < NT; ++k) {
      Eigen::Vector3d p = bs.surface.evaluate(bs.params_s[q], static_cast<double>(k) / NT);
      if (j == 0 || j == NV) p.y() = 0.0;
      seam.blend_pts.push_back(p);
    }
  }
}

/// Seam vertices on the hull side; with a blend also those on the bulb side and the blend
/// strip between them (NT rows of quads per column).
void add_seam_and_blend(MeshBuilder& mb, const NurbsSurface& B, MeshSeam& seam, int NT, bool with_blend) {
  const int NV = static_cast<int>(seam.x.size()) - 1;
  seam.hull_id.resize(NV + 1);
  for (int j = 0; j <= NV; ++j) {
    Eigen::Vector3d p = seam.curve.points[j].point;
    if (j == 0 || j == NV) p.y() = 0.0;
    seam.hull_id[j] = mb.add(p);
  }
  if (!with_blend) {
    seam.bulb_id = seam.hull_id;
    return;
  }
  seam.bulb_id.resize(NV + 1);
  std::vector<int> col(NT + 1), prev;
  for (int j = 0; j <= NV; ++j) {
    Eigen::Vector3d pb = B.evaluate(seam.x[j][2], seam.x[j][3]);
    if (j == 0 || j == NV) pb.y() = 0.0;
    seam.bulb_id[j] = mb.add(pb);
    col[0] = seam.hull_id[j];
    for (int k = 1; k < NT; ++k) col[k] = mb.add(seam.blend_pts[static_cast<size_t>(j) * (NT - 1) + k - 1]);
    col[NT] = seam.bulb_id[j];
    if (j > 0)
      for (int k = 0; k < NT; ++k) mb.quad(prev[k], col[k], col[k + 1], prev[k + 1], FacePart::Blend);
    prev = col;
  }
}

/// The bulb ahead of the seam: NU structured cells per column from the seam to the nose
/// pole, the last closed by a fan to the pole.
void add_bulb_strip(MeshBuilder& mb, const NurbsSurface& B, const MeshSeam& seam, int NU) {
  const int NV = static_cast<int>(seam.x.size()) - 1;
  const auto [bu0, bu1] = B.domain_u();
  const auto [bv0, bv1] = B.domain_v();
  Eigen::Vector3d pole = B.evaluate(bu1, 0.5 * (bv0 + bv1));
  pole.y() = 0.0;
  const int pole_id = mb.add(pole);
  std::vector<int> bid((NV + 1) * NU);
  for (int j = 0; j <= NV; ++j) {
    bid[j * NU] = seam.bulb_id[j];
    for (int i = 1; i < NU; ++i) {
      const double ui = seam.x[j][2] + (bu1 - seam.x[j][2]) * i / NU;
      Eigen::Vector3d p = B.evaluate(ui, seam.x[j][3]);
      if (j == 0 || j == NV) p.y() = 0.0;
      bid[j * NU + i] = mb.add(p);
    }
  }
  for (int j = 0; j < NV; ++j) {
    for (int i = 0; i + 1 < NU; ++i) {
      const int a = bid[j * NU + i], b = bid[(j + 1) * NU + i], c = bid[(j + 1) * NU + i + 1], d = bid[j * NU + i + 1];
      mb.tri(a, b, c, FacePart::Bulb);
      mb.tri(a, c, d, FacePart::Bulb);
    }
    mb.tri(bid[j * NU + NU - 1], bid[(j + 1) * NU + NU - 1], pole_id, FacePart::Bulb);
  }
}

/// Hull cells (index i K + k) that touch the hole the seam cuts or lie within `margin`
/// cells of the seam, and every cell the seam passes through.
std::vector<char> cells_under_seam(const HullGrid& g, const MeshSeam& seam, double margin) {
  const int I = g.I, K = g.K, NV = static_cast<int>(seam.x.size()) - 1;
  std::vector<Eigen::Vector2d> hole = seam.scaled;  // closed along the centre-plane edges (short way)
  const double p_first = seam.reversed ? seam.pb : seam.pa, p_last = seam.reversed ? seam.pa : seam.pb;
  if ((p_first - 1.0) * (p_last - 1.0) < 0.0) hole.push_back(g.scaled(g.u1, g.v0));  // around the stem foot
  const double clearance = margin * std::min(g.Ls / I, g.Lt / K);
  std::vector<char> node_out((I + 1) * (K + 1), 0);
  for (int i = 0; i <= I; ++i)
    for (int k = 0; k <= K; ++k) {
      const Eigen::Vector2d q = g.scaled(g.su[i], g.tv[k]);
      bool r = point_in_polygon(q, hole);
      for (int j = 0; j < NV && !r; ++j) r = seg_dist(q, seam.scaled[j], seam.scaled[j + 1]) < clearance;
      node_out[g.key(i, k)] = r;
    }
  std::vector<char> removed(I * K, 0);
  for (int i = 0; i < I; ++i)
    for (int k = 0; k < K; ++k)
      removed[i * K + k] = node_out[g.key(i, k)] || node_out[g.key(i + 1, k)] || node_out[g.key(i, k + 1)] ||
                           node_out[g.key(i + 1, k + 1)];
  constexpr int kSeamProbes = 16;  // points per seam segment at which its cell is removed
  for (int j = 0; j < NV; ++j)
    for (int s = 0; s <= kSeamProbes; ++s) {
      const Eigen::Vector2d q = seam.scaled[j] + (seam.scaled[j + 1] - seam.scaled[j]) * (s / double(kSeamProbes));
      const int ci = std::clamp(static_cast<int>(std::floor(q.x() / (g.Ls / I))), 0, I - 1);
      const int ck = std::clamp(static_cast<int>(std::floor(q.y() / (g.Lt / K))), 0, K - 1);
      removed[ci * K + ck] = 1;
    }
  return removed;
}

/// Kept cells 4-connected to the aft deck cell (0, K - 1); the others are pockets.
std::vector<char> reachable_from_aft_deck(const std::vector<char>& removed, int I, int K) {
  std::vector<char> reach(I * K, 0);
  std::vector<int> stack;
  if (!removed[K - 1]) {
    reach[K - 1] = 1;
    stack.push_back(K - 1);
  }
  while (!stack.empty()) {
    const int c = stack.back();
    stack.pop_back();
    const int ci = c / K, ck = c % K;
    const int nb[4][2] = {{ci - 1, ck}, {ci + 1, ck}, {ci, ck - 1}, {ci, ck + 1}};
    for (const auto& q : nb) {
      if (q[0] < 0 || q[0] >= I || q[1] < 0 || q[1] >= K) continue;
      const int d = q[0] * K + q[1];
      if (removed[d] || reach[d]) continue;
      reach[d] = 1;
      stack.push_back(d);
    }
  }
  return reach;
}

/// Regularizes the removed region until it is stable: fills kept pockets and removes the
/// kept pair of a diagonal pinch, so that its boundary is one simple staircase.
void fill_pockets_and_pinches(std::vector<char>& removed, int I, int K) {
  for (bool changed = true; changed;) {
    changed = false;
    const std::vector<char> reach = reachable_from_aft_deck(removed, I, K);
    for (int c = 0; c < I * K; ++c)
      if (!removed[c] && !reach[c]) {
        removed[c] = 1;
        changed = true;
      }
    for (int i = 0; i + 1 < I; ++i)
      for (int k = 0; k + 1 < K; ++k) {
        char& a = removed[i * K + k];
        char& b = removed[(i + 1) * K + k];
        char& c = removed[i * K + k + 1];
        char& d = removed[(i + 1) * K + k + 1];
        if (a == d && b == c && a != b) {
          a = b = c = d = 1;
          changed = true;
        }
      }
  }
  for (int i = 0; i < I; ++i)
    if (removed[i * K + K - 1])
      throw InvalidInput("bulb cannot meet the hull: the bulb seam reaches the deck; the bulb is too high or too large");
  for (int k = 0; k < K; ++k)
    if (removed[k]) throw InvalidInput("bulb cannot meet the hull: the bulb seam reaches the aft cut of the hull surface");
}

/// Node keys along the boundary between removed and kept cells, removed region on the left
/// (its counter-clockwise edges), from one centre-plane edge to the other.
std::vector<int> trace_staircase(const std::vector<char>& removed, const HullGrid& g) {
  const int I = g.I, K = g.K;
  std::unordered_map<int, int> nxt, has_in;
  for (int i = 0; i < I; ++i)
    for (int k = 0; k < K; ++k) {
      if (!removed[i * K + k]) continue;
      if (k > 0 && !removed[i * K + k - 1]) nxt[g.key(i, k)] = g.key(i + 1, k);                  // bottom
      if (i + 1 < I && !removed[(i + 1) * K + k]) nxt[g.key(i + 1, k)] = g.key(i + 1, k + 1);  // right
      if (k + 1 < K && !removed[i * K + k + 1]) nxt[g.key(i + 1, k + 1)] = g.key(i, k + 1);    // top
      if (i > 0 && !removed[(i - 1) * K + k]) nxt[g.key(i, k + 1)] = g.key(i, k);              // left
    }
  for (const auto& [a, b] : nxt) has_in[b] = 1;
  int start = -1, n_starts = 0;
  for (const auto& [a, b] : nxt)
    if (!has_in.count(a)) {
      start = a;
      ++n_starts;
    }
  if (n_starts != 1) throw InvalidInput("compose: the trimmed hull band is not one simple strip; refine hull_u / hull_v");
  std::vector<int> stair{start};
  while (nxt.count(stair.back())) {
    stair.push_back(nxt[stair.back()]);
    if (stair.size() > nxt.size() + 1) throw InvalidInput("compose: staircase of the hull band loops");
  }
  if (stair.size() != nxt.size() + 1)
    throw InvalidInput("compose: the removed hull region has more than one boundary; refine hull_u / hull_v");
  return stair;
}

/// The band between the staircase and the seam as one simple polygon (staircase, the
/// centre-plane edge up to the seam, the seam, the edge back), ear-clipped in scaled space.
void add_band(MeshBuilder& mb, HullGrid& g, const std::vector<int>& stair, const MeshSeam& seam) {
  double ps = 0, pe = 0;
  if (!g.perimeter(stair.front(), ps) || !g.perimeter(stair.back(), pe) || !(pe <= seam.pa && seam.pb <= ps))
    throw InvalidInput("compose: the hull band does not end on the centre-plane edges around the seam; refine the grid");
  std::vector<int> poly_id;
  std::vector<Eigen::Vector2d> poly2, poly_uv;  // scaled and (u, v) on the hull
  auto push_node = [&](int node) {
    poly_id.push_back(g.vertex(mb, node));
    poly2.push_back(g.scaled_node(node));
    poly_uv.push_back({g.su[node / (g.K + 1)], g.tv[node % (g.K + 1)]});
  };
  for (int node : stair) push_node(node);
  std::vector<std::pair<double, int>> edge_nodes;  // nodes on the centre-plane edges by perimeter
  for (int i = 0; i <= g.I; ++i) edge_nodes.push_back({(g.su[i] - g.u0) / (g.u1 - g.u0), g.key(i, 0)});
  for (int k = 1; k <= g.K; ++k) edge_nodes.push_back({1.0 + (g.tv[k] - g.v0) / (g.v1 - g.v0), g.key(g.I, k)});
  constexpr double kPerimeterEps = 1e-9;
  for (const auto& [p, node] : edge_nodes)
    if (p > pe + kPerimeterEps && p < seam.pa - kPerimeterEps) push_node(node);
  const int NV = static_cast<int>(seam.x.size()) - 1;
  for (int j = 0; j <= NV; ++j) {
    const int jj = seam.reversed ? NV - j : j;
    poly_id.push_back(seam.hull_id[jj]);
    poly2.push_back(seam.scaled[jj]);
    poly_uv.push_back(seam.x[jj].head<2>());
  }
  for (const auto& [p, node] : edge_nodes)
    if (p > seam.pb + kPerimeterEps && p < ps - kPerimeterEps) push_node(node);
  for (size_t q = poly_id.size(); q-- > 0;)  // a pole's nodes are one vertex: keep it once
    if (poly_id.size() > 3 && poly_id[q] == poly_id[(q + 1) % poly_id.size()]) {
      // the parameter triangle the polygon loses with q (the last of a run: all the run's)
      const size_t n = poly_id.size();
      const Eigen::Vector2d &a = poly_uv[(q + n - 1) % n], &b = poly_uv[q], &c = poly_uv[(q + 1) % n];
      mb.collapsed_uv.push_back({a.x(), a.y(), b.x(), b.y(), c.x(), c.y()});
      poly_id.erase(poly_id.begin() + static_cast<long>(q));
      poly2.erase(poly2.begin() + static_cast<long>(q));
      poly_uv.erase(poly_uv.begin() + static_cast<long>(q));
    }
  Eigen::MatrixXd P2(static_cast<Eigen::Index>(poly2.size()), 2);
  for (size_t q = 0; q < poly2.size(); ++q) P2.row(static_cast<Eigen::Index>(q)) = poly2[q].transpose();
  std::vector<char> flat(poly_id.size());
  for (size_t q = 0; q < poly_id.size(); ++q) flat[q] = mb.verts[poly_id[q]].y() == 0.0;
  std::vector<std::array<int, 3>> tris = triangulate_polygon(P2, flat);
  Eigen::MatrixXd X(static_cast<Eigen::Index>(poly_id.size()), 3);
  for (size_t q = 0; q < poly_id.size(); ++q) X.row(static_cast<Eigen::Index>(q)) = mb.verts[poly_id[q]].transpose();
  delaunay_flips(P2, tris, flat, X);
  for (const auto& t : tris) {
    const Eigen::Vector2d &a = poly_uv[t[0]], &b = poly_uv[t[1]], &c = poly_uv[t[2]];
    mb.tri(poly_id[t[0]], poly_id[t[1]], poly_id[t[2]], FacePart::Hull, {a.x(), a.y(), b.x(), b.y(), c.x(), c.y()});
  }
}

/// Trimming loops in parameter space: the hull outside the seam, the bulb ahead of it.
void add_trimming_loops(const HullGrid& g, const NurbsSurface& B, const MeshSeam& seam, ComposedHull& out) {
  const int NV = static_cast<int>(seam.x.size()) - 1;
  TrimmedSurface hull_trim;
  hull_trim.subdomain = 0;
  Eigen::MatrixXd hl(NV + 6, 2);
  int r = 0;
  hl.row(r++) << g.u0, g.v0;
  if (seam.pa > 1.0) hl.row(r++) << g.u1, g.v0;
  for (int j = 0; j <= NV; ++j) hl.row(r++) = seam.x[seam.reversed ? NV - j : j].head<2>().transpose();
  if (seam.pb < 1.0) hl.row(r++) << g.u1, g.v0;
  hl.row(r++) << g.u1, g.v1;
  hl.row(r++) << g.u0, g.v1;
  hull_trim.loops.push_back(hl.topRows(r));
  TrimmedSurface bulb_trim;
  bulb_trim.subdomain = 1;
  const auto [bu0, bu1] = B.domain_u();
  const auto [bv0, bv1] = B.domain_v();
  Eigen::MatrixXd bl(NV + 3, 2);
  bl.row(0) << bu1, bv0;
  bl.row(1) << bu1, bv1;
  for (int j = 0; j <= NV; ++j) bl.row(2 + j) << seam.x[NV - j][2], seam.x[NV - j][3];
  bulb_trim.loops.push_back(bl);
  out.trimmed_surfaces.push_back(std::move(hull_trim));
  out.trimmed_surfaces.push_back(std::move(bulb_trim));
}

/// Meshes the bulb (and blend) and the hull band around the seam; returns the hull cells the
/// bulb removes.
std::vector<char> join_bulb(MeshBuilder& mb, HullGrid& g, const NurbsSurface& B, const ComposeOptions& o,
                            const BlendSpec* blend, ComposedHull& out) {
  out.bulb.push_back(B);
  MeshSeam seam;
  if (blend) seam_from_blend(g.H, B, o, *blend, seam, out);
  else trace_seam(g.H, B, o, seam.x, seam.curve);
  seam_ends_on_centre_line(g.H, seam.x, seam.pa, seam.pb);
  seam.reversed = seam.pa > seam.pb;  // walk the seam from lower to higher perimeter coordinate
  if (seam.reversed) std::swap(seam.pa, seam.pb);
  add_seam_and_blend(mb, B, seam, o.blend_rows, blend != nullptr);
  add_bulb_strip(mb, B, seam, o.bulb_u);
  for (const auto& x : seam.x) seam.scaled.push_back(g.scaled(x[0], x[1]));
  std::vector<char> removed = cells_under_seam(g, seam, o.margin);
  fill_pockets_and_pinches(removed, g.I, g.K);
  add_band(mb, g, trace_staircase(removed, g), seam);
  add_trimming_loops(g, B, seam, out);
  const int NV = static_cast<int>(seam.x.size()) - 1;
  out.seam_vertices.resize(NV + 1);
  for (int j = 0; j <= NV; ++j) out.seam_vertices[j] = seam.hull_id[j];
  out.intersection_curves.push_back(std::move(seam.curve));
  return removed;
}

/// Two triangles per kept hull cell, split so that no triangle lies in the centre plane.
void add_kept_cells(MeshBuilder& mb, HullGrid& g, const std::vector<char>& removed) {
  for (int i = 0; i < g.I; ++i)
    for (int k = 0; k < g.K; ++k) {
      if (removed[i * g.K + k]) continue;
      const int a = g.vertex(mb, i, k), b = g.vertex(mb, i + 1, k), c = g.vertex(mb, i + 1, k + 1),
                d = g.vertex(mb, i, k + 1);
      auto on_cp = [&](int q) { return mb.verts[q].y() == 0.0; };
      const double u0 = g.su[i], u1 = g.su[i + 1], v0 = g.tv[k], v1 = g.tv[k + 1];  // a b c d's (u, v)
      if (on_cp(a) && on_cp(b) && on_cp(c)) {
        mb.tri(a, b, d, FacePart::Hull, {u0, v0, u1, v0, u0, v1});
        mb.tri(b, c, d, FacePart::Hull, {u1, v0, u1, v1, u0, v1});
      } else {
        mb.tri(a, b, c, FacePart::Hull, {u0, v0, u1, v0, u1, v1});
        mb.tri(a, c, d, FacePart::Hull, {u0, v0, u1, v1, u0, v1});
      }
    }
}

/// The builder's mesh, oriented outward, with its face labels; throws unless it is closed.
void finish_mesh(const MeshBuilder& mb, ComposedHull& out) {
  out.mesh = mb.mesh();
  // A half hull's mesh lies at y >= 0. Where a blend's thin end folds a few cm across the centre
  // plane (a known defect of the blend surface) its vertices are held just off the plane: not
  // on it, where they would count as centre-plane vertices and be shared with their mirror.
  for (Eigen::Index i = 0; i < out.mesh.vertices.rows(); ++i)
    if (out.mesh.vertices(i, 1) < 0.0) out.mesh.vertices(i, 1) = kOffCentrePlane;
  const EdgeReport er = orient_if_needed(out.mesh);
  out.face_part.resize(static_cast<Eigen::Index>(mb.part.size()));
  for (size_t f = 0; f < mb.part.size(); ++f) out.face_part[static_cast<Eigen::Index>(f)] = mb.part[f];
  out.hull_face_uv.resize(static_cast<Eigen::Index>(mb.uv.size()), 6);
  for (size_t f = 0; f < mb.uv.size(); ++f)
    for (int c = 0; c < 6; ++c) out.hull_face_uv(static_cast<Eigen::Index>(f), c) = mb.uv[f][c];
  out.hull_collapsed_uv.resize(static_cast<Eigen::Index>(mb.collapsed_uv.size()), 6);
  for (size_t f = 0; f < mb.collapsed_uv.size(); ++f)
    for (int c = 0; c < 6; ++c) out.hull_collapsed_uv(static_cast<Eigen::Index>(f), c) = mb.collapsed_uv[f][c];
  if (er.open || er.non_manifold || er.inconsistent) {
    std::ostringstream os;
    os << "compose: the composed mesh is not closed (" << er.open << " open, " << er.non_manifold
       << " non-manifold, " << er.inconsistent << " inconsistent edges)";
    throw InvalidInput(os.str());
  }
}

}  // namespace

ComposedHull compose_hull(const NurbsSurface& hull_in, const NurbsSurface* bulb, const ComposeOptions& o,
                          const BlendSpec* blend) {
  validate_options(o, bulb, blend);
  const NurbsSurface H = orient_bare_hull(hull_in, o.plane_tolerance);
  ComposedHull out{TriMesh{}, Eigen::VectorXi(), {}, {}, Eigen::VectorXi(), 0.0, 0.0, H, {}, {}, {}, {}, {}, {}, {}};
  out.x_aft = edge_points(H, true, false).col(0).mean();
  out.z_deck = edge_points(H, false, true).col(2).mean();
  AftEnd aft = aft_end(H, out.z_deck, o.plane_tolerance);
  if (aft.on_centre_plane) aft.normal.setZero();  // the aft edge stays where it is
  HullGrid grid(H, o.hull_u, o.hull_v, aft, out.z_deck);
  MeshBuilder mb;
  std::vector<char> removed(o.hull_u * o.hull_v, 0);
  if (bulb) {
    removed = join_bulb(mb, grid, *bulb, o, blend, out);
  } else {
    TrimmedSurface hull_trim;
    Eigen::MatrixXd hl(4, 2);
    hl << grid.u0, grid.v0, grid.u1, grid.v0, grid.u1, grid.v1, grid.u0, grid.v1;
    hull_trim.loops.push_back(hl);
    out.trimmed_surfaces.push_back(std::move(hull_trim));
  }
  add_kept_cells(mb, grid, removed);
  close_half_hull(mb, aft, out.z_deck, o.plane_tolerance * size_of(H));
  finish_mesh(mb, out);
  return out;
}


TriMesh mirror_full_hull(const ComposedHull& c) {
  const TriMesh& m = c.mesh;
  const Eigen::Index n = m.vertices.rows();
  std::vector<int> mirror(n);
  std::vector<Eigen::Vector3d> verts;
  for (Eigen::Index i = 0; i < n; ++i) verts.push_back(m.vertices.row(i).transpose());
  for (Eigen::Index i = 0; i < n; ++i) {
    if (m.vertices(i, 1) == 0.0) {
      mirror[i] = static_cast<int>(i);
    } else {
      Eigen::Vector3d p = m.vertices.row(i).transpose();
      p.y() = -p.y();
      verts.push_back(p);
      mirror[i] = static_cast<int>(verts.size()) - 1;
    }
  }
  std::vector<std::array<int, 3>> faces;
  for (Eigen::Index f = 0; f < m.faces.rows(); ++f) {
    if (c.face_part[f] == static_cast<int>(FacePart::CentrePlane)) continue;
    faces.push_back({m.faces(f, 0), m.faces(f, 1), m.faces(f, 2)});
    faces.push_back({mirror[m.faces(f, 0)], mirror[m.faces(f, 2)], mirror[m.faces(f, 1)]});
  }
  // drop vertices only the centre-plane faces used (the aft-deck corner of the caps stays)
  TriMesh out;
  out.vertices = detail::keep_used_nodes(faces, verts);
  out.faces = detail::element_rows(faces);
  return out;
}

}  // namespace fairlines
