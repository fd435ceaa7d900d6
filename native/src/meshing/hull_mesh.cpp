// mesh_surface and mesh_hull: the faces and shared edges of a surface or a composed hull,
// then mesh_brep (see brep.hpp). mesh_hull in steps: require_draft_inside -> add_faces ->
// trim_curve, trim_ends -> hull_boundary -> trimmed_bow (blend_face, bulb_face) -> close_lids
// -> Brep::cut_below (with a draft) -> mesh_brep -> mirrored (a full hull).
//
// Notation (the hull in the orient_bare_hull convention): H the hull on [u0, u1] x [v0, v1],
// keel v = v0, stem u = u1, deck v = v1, aft end u = u0; A = H(u0, v0) the aft keel point,
// C = H(u1, v1) the stem top, Dk = H(u0, v1) the aft deck point, E the aft end's corner on
// deck and centre plane; P0, P1 the ends of the trim curve (seam or blend boundary) on H,
// P0 the lower one along keel then stem; Bs the bulb surface, L the blend surface; F the
// B-rep's faces, te the trim edge, cl the centre line.
#include <algorithm>
#include <cmath>
#include <sstream>

#include <Eigen/Geometry>

#include "fairlines/compose.hpp"
#include "fairlines/errors.hpp"
#include "fairlines/intersect.hpp"
#include "fairlines/meshing.hpp"
#include "meshing/brep.hpp"
#include "nurbs/checks.hpp"

namespace fairlines {

namespace {

using meshing::Brep;
using meshing::EdgeSample;
using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;

constexpr int kIsoSamples = 129;       ///< samples of an iso-parameter edge
constexpr double kPi = 3.14159265358979323846;
constexpr double kDegenerate = 1e-9;   ///< an edge shorter than this x model size is a pole

double extent(const NurbsSurface& s) {
  const Eigen::MatrixXd& P = s.control_points();
  return (P.colwise().maxCoeff() - P.colwise().minCoeff()).norm();
}

/// Iso-parameter edge of face f (surface s) from (u, v) = a to b, shared with face g.
int iso_edge(Brep& b, int f, int g, const NurbsSurface& s, Vec2 a, Vec2 c) {
  const Vec3 pa = s.evaluate(a.x(), a.y()), pc = s.evaluate(c.x(), c.y());
  const Vec3 pm = s.evaluate(0.5 * (a.x() + c.x()), 0.5 * (a.y() + c.y()));
  const bool pole = (pa - pc).norm() + (pa - pm).norm() < kDegenerate * extent(s);
  return b.sampled_edge(
      f, g, kIsoSamples,
      [&](double t) {
        // samples crowd the ends (cosine spacing): a curvature spike at a corner such as the
        // cone-like stem top is then seen by the edge as by the faces' interiors
        const double w = 0.5 * (1.0 - std::cos(kPi * t));
        EdgeSample x;
        x.uv[0] = a + w * (c - a);
        x.uv[1] = Vec2::Zero();
        x.xyz = s.evaluate(x.uv[0].x(), x.uv[0].y());
        return x;
      },
      pole);
}

constexpr double kFoldDepth = 1e-6;       ///< y below -this x model size is a crossing of the centre plane
constexpr double kFoldScan = 0.1;         ///< fraction of the u range at each end searched for a fold
constexpr int kFoldWidths = 10;           ///< candidate strip widths (kFoldScan / kFoldWidths apart)
constexpr double kRuledNormalCos = 0.7;   ///< a ruled strip's normals stay within ~45 deg of the surface's

/// Unit normal of (1 - t) S(ua, v) + t S(ub, v) at t (ua < ub; derivatives rows: S, S_v, S_u).
Vec3 ruled_normal(const NurbsSurface& s, double ua, double ub, double v, double t) {
  const Eigen::MatrixXd a = s.derivatives(ua, v, 1), b = s.derivatives(ub, v, 1);
  const Vec3 su = (b.row(0) - a.row(0)).transpose(), sv = ((1 - t) * a.row(1) + t * b.row(1)).transpose();
  return su.cross(sv).normalized();
}

/// A blend skinned to end sections on the centre plane can fold over itself next to such an
/// end (its cross-boundary tangents turn against the neighbouring sections'), which shows as
/// the surface crossing y = 0. The face is then meshed on the ruled surface across the
/// narrowest strip at that end that covers every crossing and whose normals stay near the
/// surface's (each end on its own: a blend can fold at its stem end and at its keel end).
void guard_fold(const NurbsSurface& s, meshing::FaceGeometry& g) {
  const auto [u0, u1] = s.domain_u();
  const auto [v0, v1] = s.domain_v();
  const double depth = kFoldDepth * extent(s);
  constexpr int kU = 21, kV = 17, kT = 11;
  for (double end : {u1, u0}) {
    const double dir = end == u1 ? -1.0 : 1.0, range = kFoldScan * (u1 - u0);
    double reach = -1.0;  // farthest crossing from the end (fraction of range)
    for (int i = 0; i < kU; ++i)
      for (int j = 0; j < kV; ++j)
        if (s.evaluate(end + dir * range * i / (kU - 1), v0 + (v1 - v0) * j / (kV - 1)).y() < -depth)
          reach = std::max(reach, static_cast<double>(i) / (kU - 1));
    if (reach < 0) continue;
    for (int k = 2; k <= kFoldWidths; ++k) {
      if (static_cast<double>(k) / kFoldWidths <= reach) continue;  // the strip must cover the fold
      const double uf = end + dir * range * k / kFoldWidths;
      double worst = 1.0;
      for (int j = 0; j < kV; ++j) {
        const double v = v0 + (v1 - v0) * j / (kV - 1);
        const Eigen::MatrixXd d = s.derivatives(uf, v, 1);
        const Vec3 n = Vec3(d.row(2)).cross(Vec3(d.row(1))).normalized();  // S_u x S_v
        for (int t = 0; t < kT; ++t)
          worst = std::min(worst, std::abs(n.dot(ruled_normal(s, std::min(uf, end), std::max(uf, end), v,
                                                              static_cast<double>(t) / (kT - 1)))));
      }
      if (worst >= kRuledNormalCos) {
        g.ruled_strips.push_back({std::min(uf, end), std::max(uf, end), uf});
        break;
      }
    }
  }
}

/// Straight edge between planar faces f and g from p to q.
int line_edge(Brep& b, int f, int g, const Vec3& p, const Vec3& q) {
  return b.sampled_edge(f, g, 2, [&](double t) {
    EdgeSample x;
    x.xyz = p + t * (q - p);
    x.uv[0] = x.uv[1] = Vec2::Zero();
    return x;
  });
}

meshing::FaceGeometry plane(const Vec3& origin, const Vec3& ax, const Vec3& ay) {
  meshing::FaceGeometry g;
  g.origin = origin;
  g.ax = ax.normalized();
  g.ay = (ay - ay.dot(g.ax) * g.ax).normalized();
  return g;
}

int add_face(Brep& b, meshing::FaceGeometry g, const std::string& name, bool keep = true) {
  meshing::Face f;
  f.g = g;
  f.name = name;
  f.keep = keep;
  b.faces.push_back(f);
  return static_cast<int>(b.faces.size()) - 1;
}

/// Position along keel (u from 0 to 1) then stem (1 + v) of a point on H's centre-line edges.
double perimeter(const NurbsSurface& H, const Vec2& uv) {
  const auto [u0, u1] = H.domain_u();
  const auto [v0, v1] = H.domain_v();
  const double ds = (u1 - uv.x()) / (u1 - u0), dt = (uv.y() - v0) / (v1 - v0);
  return dt <= ds ? (uv.x() - u0) / (u1 - u0) : 1.0 + dt;
}

/// Iso edges of H's centre-line boundary (keel v = v0 from u0 to u1, then stem u = u1 from v0
/// to v1; either may be a pole) from uv `a` to uv `c` on it, shared with face fC, in order.
std::vector<int> centre_line_edges(Brep& b, int fH, int fC, const NurbsSurface& H, Vec2 a, Vec2 c) {
  const double u1 = H.domain_u().second, v0 = H.domain_v().first;
  const bool a_keel = perimeter(H, a) < 1.0, c_keel = perimeter(H, c) <= 1.0;
  std::vector<int> out;
  auto add = [&](Vec2 p, Vec2 q) {
    if ((p - q).norm() > 0.0) out.push_back(iso_edge(b, fH, fC, H, p, q));
  };
  if (a_keel) a.y() = v0;
  else a.x() = u1;
  if (c_keel) c.y() = v0;
  else c.x() = u1;
  if (a_keel && !c_keel) {
    add(a, {u1, v0});
    add({u1, v0}, c);
  } else {
    add(a, c);
  }
  for (int e : out)  // exactly on y = 0
    for (auto& x : b.edges[e].s) x.xyz.y() = 0.0;
  return out;
}

/// The trim curve between hull and what replaces its bow part: samples bottom to top with
/// uv[0] on H and uv[1] on the other face (bulb for a seam, blend for a blend boundary).
struct Trim {
  std::vector<EdgeSample> s;
  std::function<void(EdgeSample&)> refine;
};

/// Faces of the hull's B-rep in the order they are made (-1: absent).
struct HullFaces {
  int hull = -1, bulb = -1, blend = -1, centre = -1, deck = -1, aft = -1;
};

/// Throws InvalidInput unless the cut (if any) lies between the keel and the deck.
void require_draft_inside(const ComposedHull& ch, const HullMeshOptions& ho) {
  if (std::isnan(ho.draft)) return;
  const double zmin = ch.hull.control_points().col(2).minCoeff();
  if (!(ho.draft > zmin && ho.draft < ch.z_deck))
    detail::fail("draft is ", ho.draft, " m; expected between the keel (", zmin, " m) and the deck (", ch.z_deck, " m)");
}

/// A face on one of the composed hull's surfaces, clamped to y >= 0.
meshing::FaceGeometry on_surface(const NurbsSurface& s) {
  meshing::FaceGeometry g;
  g.surface = &s;
  g.clamp_y = true;
  return g;
}

/// Hull, bulb and blend faces, then the planar lids: centre plane, deck and the aft face of a
/// transom (kept as `ho` asks).
HullFaces add_faces(Brep& b, const ComposedHull& ch, const AftEnd& aft, const HullMeshOptions& ho) {
  HullFaces F;
  F.hull = add_face(b, on_surface(ch.hull), "hull");
  if (!ch.bulb.empty()) F.bulb = add_face(b, on_surface(ch.bulb[0]), "bulb");
  if (!ch.blend.empty()) {
    meshing::FaceGeometry g = on_surface(ch.blend[0]);
    guard_fold(ch.blend[0], g);
    F.blend = add_face(b, g, "blend");
  }
  const bool half = !ho.full, cut = !std::isnan(ho.draft);
  F.centre = add_face(b, plane(Vec3::Zero(), Vec3::UnitX(), Vec3::UnitZ()), "centre_plane", ho.lids && half);
  F.deck = add_face(b, plane(Vec3(0, 0, ch.z_deck), Vec3::UnitX(), Vec3::UnitY()), "deck", ho.lids && !cut);
  if (!aft.on_centre_plane)
    F.aft = add_face(b, plane(aft.deck_corner, Vec3::UnitY() - aft.normal.y() * aft.normal, aft.normal.cross(Vec3::UnitY())),
                     "aft");
  return F;
}

/// The blend's boundary on H (rows of blend_params: blend u, hull u, hull v, ...).
Trim blend_boundary(const ComposedHull& ch) {
  Trim trim;
  const Eigen::MatrixXd& P = ch.blend_params;
  for (Eigen::Index q = 0; q < P.rows(); ++q) {
    EdgeSample x;
    x.uv[0] = Vec2(P(q, 1), P(q, 2));
    x.uv[1] = Vec2(P(q, 0), 0.0);
    x.xyz = ch.hull.evaluate(P(q, 1), P(q, 2));
    trim.s.push_back(x);
  }
  return trim;
}

/// The seam of hull and bulb, its points between samples refined onto both surfaces.
Trim bulb_seam(const ComposedHull& ch) {
  const NurbsSurface &H = ch.hull, &B = ch.bulb[0];
  Trim trim;
  for (const auto& p : ch.intersection_curves.at(0).points) {
    EdgeSample x;
    x.uv[0] = p.uv_a;
    x.uv[1] = p.uv_b;
    x.xyz = H.evaluate(p.uv_a.x(), p.uv_a.y());
    trim.s.push_back(x);
  }
  trim.refine = [&H, &B](EdgeSample& x) {
    Eigen::Vector4d q;
    q << x.uv[0], x.uv[1];
    refine_intersection(H, B, q, 1e-10);
    x.uv[0] = q.head<2>();
    x.uv[1] = q.tail<2>();
    x.xyz = H.evaluate(q[0], q[1]);
  };
  return trim;
}

/// The trim curve (blend boundary, else seam, else none), its ends exactly on the keel or stem
/// edge and on y = 0.
Trim trim_curve(const ComposedHull& ch) {
  Trim trim = !ch.blend.empty() ? blend_boundary(ch) : !ch.bulb.empty() ? bulb_seam(ch) : Trim{};
  const NurbsSurface& H = ch.hull;
  if (trim.s.empty()) return trim;
  for (EdgeSample* end : {&trim.s.front(), &trim.s.back()}) {
    Vec2& uv = end->uv[0];
    if (perimeter(H, uv) < 1.0) uv.y() = H.domain_v().first;
    else uv.x() = H.domain_u().second;
    end->xyz = H.evaluate(uv.x(), uv.y());
    end->xyz.y() = 0.0;
  }
  return trim;
}

/// Where the trim curve meets H's centre line: P0 the lower end along keel then stem, P1 the
/// upper; `reversed` when the trim samples run from P1 (the hull walks it from its higher end).
struct TrimEnds {
  bool trimmed = false, reversed = false;
  Vec2 P0, P1;
};

TrimEnds trim_ends(const NurbsSurface& H, const Trim& trim) {
  TrimEnds t;
  t.trimmed = !trim.s.empty();
  if (!t.trimmed) return t;
  t.reversed = perimeter(H, trim.s.front().uv[0]) > perimeter(H, trim.s.back().uv[0]);
  t.P0 = (t.reversed ? trim.s.back() : trim.s.front()).uv[0];
  t.P1 = (t.reversed ? trim.s.front() : trim.s.back()).uv[0];
  return t;
}

/// H's boundary edges and the corners the lids meet at.
struct HullEdges {
  std::vector<int> cl_low, cl_high;  ///< centre line up to the trim curve and on from it (or all of it)
  int deck = -1, aft = -1;
  Vec3 A, C, Dk, E;
};

HullEdges hull_boundary(Brep& b, const HullFaces& F, const NurbsSurface& H, const AftEnd& aft, const TrimEnds& t) {
  const auto [u0, u1] = H.domain_u();
  const auto [v0, v1] = H.domain_v();
  HullEdges h;
  h.cl_low = centre_line_edges(b, F.hull, F.centre, H, {u0, v0}, t.trimmed ? t.P0 : Vec2(u1, v1));
  if (t.trimmed) h.cl_high = centre_line_edges(b, F.hull, F.centre, H, t.P1, {u1, v1});
  h.deck = iso_edge(b, F.hull, F.deck, H, {u1, v1}, {u0, v1});
  h.aft = iso_edge(b, F.hull, aft.on_centre_plane ? F.centre : F.aft, H, {u0, v1}, {u0, v0});
  if (aft.on_centre_plane)
    for (auto& x : b.edges[h.aft].s) x.xyz.y() = 0.0;
  h.C = b.edges[h.deck].s.front().xyz;
  h.Dk = b.edges[h.deck].s.back().xyz;
  h.A = b.edges[h.cl_low.front()].s.front().xyz;
  h.E = aft.on_centre_plane ? h.Dk : aft.deck_corner;
  return h;
}

/// The blend's edges: on the bulb, and its two ends on the centre plane (low, high).
struct BlendEdges {
  int bulb_side = -1, low = -1, high = -1;
};

/// Edge of the blend (face F.blend) at its u = sv on the centre plane, from `from` to `to`.
int blend_end(Brep& b, const HullFaces& F, const NurbsSurface& L, double sv, const Vec3& from, const Vec3& to) {
  std::vector<EdgeSample> e;
  for (int k = 0; k < kIsoSamples; ++k) {
    EdgeSample x;
    x.uv[0] = Vec2(sv, static_cast<double>(k) / (kIsoSamples - 1));
    x.uv[1] = Vec2::Zero();  // on the centre plane: add_edge locates it
    x.xyz = L.evaluate(x.uv[0].x(), x.uv[0].y());
    x.xyz.y() = 0.0;
    e.push_back(x);
  }
  e.front().xyz = from;
  e.back().xyz = to;
  return b.add_edge(F.blend, F.centre, e);
}

/// The blend face bounded by the trim edge te, its ends and its boundary on the bulb
/// (rows of blend_params: blend u, ..., bulb u, bulb v).
BlendEdges blend_face(Brep& b, const HullFaces& F, const ComposedHull& ch, const Trim& trim, int te) {
  const NurbsSurface &L = ch.blend[0], &Bs = ch.bulb[0];
  const Eigen::MatrixXd& P = ch.blend_params;
  std::vector<EdgeSample> s;
  for (Eigen::Index q = 0; q < P.rows(); ++q) {
    EdgeSample x;
    x.uv[0] = Vec2(P(q, 3), P(q, 4));
    x.uv[1] = Vec2(P(q, 0), 1.0);
    x.xyz = Bs.evaluate(P(q, 3), P(q, 4));
    s.push_back(x);
  }
  s.front().xyz.y() = s.back().xyz.y() = 0.0;
  BlendEdges e;
  e.bulb_side = b.add_edge(F.bulb, F.blend, s);
  const auto [s0, s1] = L.domain_u();
  e.low = blend_end(b, F, L, s0, trim.s.front().xyz, b.edges[e.bulb_side].s.front().xyz);
  e.high = blend_end(b, F, L, s1, trim.s.back().xyz, b.edges[e.bulb_side].s.back().xyz);
  b.faces[F.blend].loop = {{te, true}, {e.high, true}, {e.bulb_side, false}, {e.low, false}};
  return e;
}

/// The bulb face from its edge toward the hull (`bulb_side`, bulb u from ub_bottom to ub_top)
/// round its nose pole; returns its top and bottom edges on the centre plane.
std::pair<int, int> bulb_face(Brep& b, const HullFaces& F, const NurbsSurface& Bs, int bulb_side, double ub_bottom,
                              double ub_top) {
  const double bu1 = Bs.domain_u().second;
  const auto [bv0, bv1] = Bs.domain_v();
  const int top = iso_edge(b, F.bulb, F.centre, Bs, {ub_top, bv1}, {bu1, bv1});
  const int pole = iso_edge(b, F.bulb, -1, Bs, {bu1, bv1}, {bu1, bv0});
  const int bottom = iso_edge(b, F.bulb, F.centre, Bs, {bu1, bv0}, {ub_bottom, bv0});
  for (int e : {top, bottom})
    for (auto& x : b.edges[e].s) x.xyz.y() = 0.0;
  b.edges[top].s.front().xyz = b.edges[bulb_side].s.back().xyz;
  b.edges[bottom].s.back().xyz = b.edges[bulb_side].s.front().xyz;
  b.edges[top].v0 = b.vertex(b.edges[top].s.front().xyz);
  b.edges[bottom].v1 = b.vertex(b.edges[bottom].s.back().xyz);
  b.faces[F.bulb].loop = {{bulb_side, true}, {top, true}, {pole, true}, {bottom, true}};
  return {top, bottom};
}

/// The bow of a trimmed hull: the trim edge closing H's loop, the blend and the bulb. Returns
/// the centre-plane edges from P0 round the nose to P1.
std::vector<std::pair<int, bool>> trimmed_bow(Brep& b, const HullFaces& F, const ComposedHull& ch, const Trim& trim,
                                             const TrimEnds& t, const HullEdges& h) {
  const bool has_blend = !ch.blend.empty();
  const int te = b.add_edge(F.hull, has_blend ? F.blend : F.bulb, trim.s);
  b.edges[te].refine = trim.refine;
  std::vector<std::pair<int, bool>>& loop = b.faces[F.hull].loop;
  loop.clear();
  for (int e : h.cl_low) loop.push_back({e, true});
  loop.push_back({te, !t.reversed});
  for (int e : h.cl_high) loop.push_back({e, true});
  std::vector<std::pair<int, bool>> bow;  // bottom of the trim curve first
  int bulb_side = te;                     // the bulb's edge toward the hull
  double ub_bottom = trim.s.front().uv[1].x(), ub_top = trim.s.back().uv[1].x();
  BlendEdges be;
  if (has_blend) {
    be = blend_face(b, F, ch, trim, te);
    bulb_side = be.bulb_side;
    ub_bottom = ub_top = ch.blend_params(0, 3);
    bow.push_back({be.low, true});
  }
  const auto [top, bottom] = bulb_face(b, F, ch.bulb[0], bulb_side, ub_bottom, ub_top);
  bow.push_back({bottom, false});
  bow.push_back({top, false});
  if (has_blend) bow.push_back({be.high, false});
  if (t.reversed) {  // walk it the other way round
    std::reverse(bow.begin(), bow.end());
    for (auto& x : bow) x.second = !x.second;
  }
  return bow;
}

/// The loops of the centre plane, deck and aft face (straight edges where two lids meet).
void close_lids(Brep& b, const HullFaces& F, const AftEnd& aft, const HullEdges& h,
                const std::vector<std::pair<int, bool>>& centre_bow) {
  const int deck_centre = line_edge(b, F.centre, F.deck, h.C, h.E);
  std::vector<std::pair<int, bool>>& cl = b.faces[F.centre].loop;
  cl.clear();
  for (int e : h.cl_low) cl.push_back({e, true});
  cl.insert(cl.end(), centre_bow.begin(), centre_bow.end());
  for (int e : h.cl_high) cl.push_back({e, true});
  cl.push_back({deck_centre, true});
  if (aft.on_centre_plane) {
    cl.push_back({h.aft, true});
    b.faces[F.deck].loop = {{h.deck, true}, {deck_centre, false}};
  } else {
    const int aft_centre = line_edge(b, F.centre, F.aft, h.E, h.A);
    cl.push_back({aft_centre, true});
    const int deck_aft = line_edge(b, F.deck, F.aft, h.Dk, h.E);
    b.faces[F.deck].loop = {{h.deck, true}, {deck_aft, true}, {deck_centre, false}};
    b.faces[F.aft].loop = {{h.aft, true}, {aft_centre, false}, {deck_aft, false}};
  }
}

/// The half hull mirrored about y = 0 into the full hull, welding the nodes on y = 0.
SurfaceMesh mirrored(const SurfaceMesh& m) {
  const Eigen::Index n = m.vertices.rows(), nf = m.faces.rows();
  std::vector<int> mirror(n);
  std::vector<Vec3> extra;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (m.vertices(i, 1) == 0.0) {
      mirror[i] = static_cast<int>(i);
    } else {
      mirror[i] = static_cast<int>(n + extra.size());
      extra.push_back(Vec3(m.vertices(i, 0), -m.vertices(i, 1), m.vertices(i, 2)));
    }
  }
  SurfaceMesh full;
  full.parts = m.parts;
  full.vertices.resize(n + static_cast<Eigen::Index>(extra.size()), 3);
  full.vertices.topRows(n) = m.vertices;
  for (size_t k = 0; k < extra.size(); ++k) full.vertices.row(n + static_cast<Eigen::Index>(k)) = extra[k].transpose();
  full.faces.resize(2 * nf, 4);
  full.face_part.resize(2 * nf);
  for (Eigen::Index f = 0; f < nf; ++f) {
    full.faces.row(f) = m.faces.row(f);
    const int k = m.faces(f, 3) < 0 ? 3 : 4;
    for (int c = 0; c < k; ++c) full.faces(nf + f, c) = mirror[m.faces(f, k - 1 - c)];
    if (k == 3) full.faces(nf + f, 3) = -1;
    full.face_part[f] = full.face_part[nf + f] = m.face_part[f];
  }
  return full;
}

}  // namespace

SurfaceMesh mesh_surface(const NurbsSurface& surface, const MeshOptions& options) {
  const MeshOptions o = meshing::resolved(options);
  Brep b;
  meshing::FaceGeometry g;
  g.surface = &surface;
  const int f = add_face(b, g, "surface");
  const auto [u0, u1] = surface.domain_u();
  const auto [v0, v1] = surface.domain_v();
  const Vec2 c[4] = {{u0, v0}, {u1, v0}, {u1, v1}, {u0, v1}};
  for (int k = 0; k < 4; ++k) b.faces[f].loop.push_back({iso_edge(b, f, -1, surface, c[k], c[(k + 1) % 4]), true});
  return meshing::mesh_brep(b, o, {}, false);
}

SurfaceMesh mesh_hull(const ComposedHull& ch, const MeshOptions& options, const HullMeshOptions& ho) {
  const MeshOptions o = meshing::resolved(options);
  require_draft_inside(ch, ho);
  const NurbsSurface& H = ch.hull;
  const AftEnd aft = aft_end(H, ch.z_deck);
  Brep b;
  const HullFaces F = add_faces(b, ch, aft, ho);
  const Trim trim = trim_curve(ch);
  const TrimEnds t = trim_ends(H, trim);
  const HullEdges h = hull_boundary(b, F, H, aft, t);
  std::vector<std::pair<int, bool>> centre_bow;
  if (t.trimmed) centre_bow = trimmed_bow(b, F, ch, trim, t, h);
  else
    for (int e : h.cl_low) b.faces[F.hull].loop.push_back({e, true});
  b.faces[F.hull].loop.push_back({h.deck, true});
  b.faces[F.hull].loop.push_back({h.aft, true});
  close_lids(b, F, aft, h, centre_bow);
  if (!std::isnan(ho.draft)) b.cut_below(ho.draft, o.size, "waterplane", ho.lids);
  SurfaceMesh m = meshing::mesh_brep(b, o, ho.progress, true);
  const double tiny = kDegenerate * extent(H);
  for (Eigen::Index i = 0; i < m.vertices.rows(); ++i)
    if (std::abs(m.vertices(i, 1)) <= tiny) m.vertices(i, 1) = 0.0;
  if (!ho.full) return m;
  return mirrored(m);
}

}  // namespace fairlines
