// mesh_surface and mesh_hull: the faces and shared edges of a surface or a composed hull,
// then mesh_brep (see brep.hpp).
//
// Notation (the hull in the orient_bare_hull convention): H the hull on [u0, u1] x [v0, v1],
// keel v = v0, stem u = u1, deck v = v1, aft end u = u0; A = H(u0, v0) the aft keel point,
// C = H(u1, v1) the stem top, Dk = H(u0, v1) the aft deck point, E the aft end's corner on
// deck and centre plane; P0, P1 the ends of the trim curve (seam or blend boundary) on H,
// P0 the lower one along keel then stem; N the bulb's nose pole.
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
  const NurbsSurface& H = ch.hull;
  const auto [u0, u1] = H.domain_u();
  const auto [v0, v1] = H.domain_v();
  const double z_deck = ch.z_deck;
  const bool cut = !std::isnan(ho.draft);
  if (cut) {
    const double zmin = H.control_points().col(2).minCoeff();
    if (!(ho.draft > zmin && ho.draft < z_deck))
      detail::fail("draft is ", ho.draft, " m; expected between the keel (", zmin, " m) and the deck (", z_deck, " m)");
  }
  const AftEnd aft = aft_end(H, z_deck);
  const bool has_bulb = !ch.bulb.empty(), has_blend = !ch.blend.empty();
  Brep b;
  meshing::FaceGeometry gh;
  gh.surface = &H;
  gh.clamp_y = true;
  const int fH = add_face(b, gh, "hull");
  int fB = -1, fL = -1;
  if (has_bulb) {
    meshing::FaceGeometry g;
    g.surface = &ch.bulb[0];
    g.clamp_y = true;
    fB = add_face(b, g, "bulb");
  }
  if (has_blend) {
    meshing::FaceGeometry g;
    g.surface = &ch.blend[0];
    g.clamp_y = true;
    guard_fold(ch.blend[0], g);
    fL = add_face(b, g, "blend");
  }
  const bool half = !ho.full;
  const int fC = add_face(b, plane(Vec3::Zero(), Vec3::UnitX(), Vec3::UnitZ()), "centre_plane", ho.lids && half);
  const int fD = add_face(b, plane(Vec3(0, 0, z_deck), Vec3::UnitX(), Vec3::UnitY()), "deck", ho.lids && !cut);
  int fA = -1;
  if (!aft.on_centre_plane)
    fA = add_face(b, plane(aft.deck_corner, Vec3::UnitY() - aft.normal.y() * aft.normal, aft.normal.cross(Vec3::UnitY())),
                  "aft");
  // the trim curve on H, if any
  Trim trim;
  if (has_blend) {
    const Eigen::MatrixXd& P = ch.blend_params;
    for (Eigen::Index q = 0; q < P.rows(); ++q) {
      EdgeSample x;
      x.uv[0] = Vec2(P(q, 1), P(q, 2));
      x.uv[1] = Vec2(P(q, 0), 0.0);
      x.xyz = H.evaluate(P(q, 1), P(q, 2));
      trim.s.push_back(x);
    }
  } else if (has_bulb) {
    const NurbsSurface& B = ch.bulb[0];
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
  }
  const bool trimmed = !trim.s.empty();
  if (trimmed)  // the ends lie exactly on the keel or stem edge, and on y = 0
    for (EdgeSample* end : {&trim.s.front(), &trim.s.back()}) {
      Vec2& uv = end->uv[0];
      if (perimeter(H, uv) < 1.0) uv.y() = v0;
      else uv.x() = u1;
      end->xyz = H.evaluate(uv.x(), uv.y());
      end->xyz.y() = 0.0;
    }
  bool reversed = false;  // the hull walks the trim curve from its higher end
  Vec2 P0, P1;
  if (trimmed) {
    reversed = perimeter(H, trim.s.front().uv[0]) > perimeter(H, trim.s.back().uv[0]);
    P0 = (reversed ? trim.s.back() : trim.s.front()).uv[0];
    P1 = (reversed ? trim.s.front() : trim.s.back()).uv[0];
  }
  // hull boundary edges: the centre line up to the trim curve and on from it (or all of it)
  const std::vector<int> cl_low = centre_line_edges(b, fH, fC, H, {u0, v0}, trimmed ? P0 : Vec2(u1, v1));
  const std::vector<int> cl_high = trimmed ? centre_line_edges(b, fH, fC, H, P1, {u1, v1}) : std::vector<int>{};
  const int deck = iso_edge(b, fH, fD, H, {u1, v1}, {u0, v1});
  const int aft_edge = iso_edge(b, fH, aft.on_centre_plane ? fC : fA, H, {u0, v1}, {u0, v0});
  if (aft.on_centre_plane)
    for (auto& x : b.edges[aft_edge].s) x.xyz.y() = 0.0;
  const int keel = cl_low.front();
  const Vec3 C = b.edges[deck].s.front().xyz, Dk = b.edges[deck].s.back().xyz, A = b.edges[keel].s.front().xyz;
  const Vec3 E = aft.on_centre_plane ? Dk : aft.deck_corner;
  // bow: trim edge, bulb and blend
  std::vector<std::pair<int, bool>> centre_bow;  // centre-plane edges from P0 round the bow to P1
  if (trimmed) {
    const int te = b.add_edge(fH, has_blend ? fL : fB, trim.s);
    b.edges[te].refine = trim.refine;
    const NurbsSurface* Bs = has_bulb ? &ch.bulb[0] : nullptr;
    const auto [bu0, bu1] = Bs->domain_u();
    const auto [bv0, bv1] = Bs->domain_v();
    b.faces[fH].loop.clear();
    for (int e : cl_low) b.faces[fH].loop.push_back({e, true});
    b.faces[fH].loop.push_back({te, !reversed});
    for (int e : cl_high) b.faces[fH].loop.push_back({e, true});
    double ub_bottom = trim.s.front().uv[1].x(), ub_top = trim.s.back().uv[1].x();
    int bulb_side = te;  // the bulb's edge toward the hull
    std::vector<std::pair<int, bool>> blend_centre_low, blend_centre_high;
    if (has_blend) {
      const NurbsSurface& L = ch.blend[0];
      const Eigen::MatrixXd& P = ch.blend_params;
      std::vector<EdgeSample> s;
      for (Eigen::Index q = 0; q < P.rows(); ++q) {
        EdgeSample x;
        x.uv[0] = Vec2(P(q, 3), P(q, 4));
        x.uv[1] = Vec2(P(q, 0), 1.0);
        x.xyz = Bs->evaluate(P(q, 3), P(q, 4));
        s.push_back(x);
      }
      s.front().xyz.y() = s.back().xyz.y() = 0.0;
      bulb_side = b.add_edge(fB, fL, s);
      ub_bottom = ub_top = P(0, 3);
      auto blend_end = [&](double sv, const Vec3& from, const Vec3& to) {
        std::vector<EdgeSample> e;
        for (int k = 0; k < kIsoSamples; ++k) {
          EdgeSample x;
          x.uv[0] = Vec2(sv, static_cast<double>(k) / (kIsoSamples - 1));
          x.xyz = L.evaluate(x.uv[0].x(), x.uv[0].y());
          x.xyz.y() = 0.0;
          e.push_back(x);
        }
        e.front().xyz = from;
        e.back().xyz = to;
        return b.add_edge(fL, fC, e);
      };
      const auto [s0, s1] = L.domain_u();
      const int low = blend_end(s0, trim.s.front().xyz, b.edges[bulb_side].s.front().xyz);
      const int high = blend_end(s1, trim.s.back().xyz, b.edges[bulb_side].s.back().xyz);
      b.faces[fL].loop = {{te, true}, {high, true}, {bulb_side, false}, {low, false}};
      blend_centre_low = {{low, true}};
      blend_centre_high = {{high, false}};
    }
    const int top = iso_edge(b, fB, fC, *Bs, {ub_top, bv1}, {bu1, bv1});
    const int pole = iso_edge(b, fB, -1, *Bs, {bu1, bv1}, {bu1, bv0});
    const int bottom = iso_edge(b, fB, fC, *Bs, {bu1, bv0}, {ub_bottom, bv0});
    for (int e : {top, bottom})
      for (auto& x : b.edges[e].s) x.xyz.y() = 0.0;
    b.edges[top].s.front().xyz = b.edges[bulb_side].s.back().xyz;
    b.edges[bottom].s.back().xyz = b.edges[bulb_side].s.front().xyz;
    b.edges[top].v0 = b.vertex(b.edges[top].s.front().xyz);
    b.edges[bottom].v1 = b.vertex(b.edges[bottom].s.back().xyz);
    b.faces[fB].loop = {{bulb_side, true}, {top, true}, {pole, true}, {bottom, true}};
    // centre plane from P0 round the nose to P1 (bottom of the trim curve first)
    std::vector<std::pair<int, bool>> bow = blend_centre_low;
    bow.push_back({bottom, false});
    bow.push_back({top, false});
    bow.insert(bow.end(), blend_centre_high.begin(), blend_centre_high.end());
    if (reversed) {  // walk it the other way round
      std::reverse(bow.begin(), bow.end());
      for (auto& x : bow) x.second = !x.second;
    }
    centre_bow = bow;
  } else {
    for (int e : cl_low) b.faces[fH].loop.push_back({e, true});
  }
  b.faces[fH].loop.push_back({deck, true});
  b.faces[fH].loop.push_back({aft_edge, true});
  // closing faces
  const int deck_centre = line_edge(b, fC, fD, C, E);
  std::vector<std::pair<int, bool>>& cl = b.faces[fC].loop;
  cl.clear();
  for (int e : cl_low) cl.push_back({e, true});
  cl.insert(cl.end(), centre_bow.begin(), centre_bow.end());
  for (int e : cl_high) cl.push_back({e, true});
  cl.push_back({deck_centre, true});
  if (aft.on_centre_plane) {
    cl.push_back({aft_edge, true});
    b.faces[fD].loop = {{deck, true}, {deck_centre, false}};
  } else {
    const int aft_centre = line_edge(b, fC, fA, E, A);
    cl.push_back({aft_centre, true});
    const int deck_aft = line_edge(b, fD, fA, Dk, E);
    b.faces[fD].loop = {{deck, true}, {deck_aft, true}, {deck_centre, false}};
    b.faces[fA].loop = {{aft_edge, true}, {aft_centre, false}, {deck_aft, false}};
  }
  if (cut) b.cut_below(ho.draft, o.size, "waterplane", ho.lids);
  SurfaceMesh m = meshing::mesh_brep(b, o, ho.progress, true);
  const double tiny = kDegenerate * extent(H);
  for (Eigen::Index i = 0; i < m.vertices.rows(); ++i)
    if (std::abs(m.vertices(i, 1)) <= tiny) m.vertices(i, 1) = 0.0;
  if (!ho.full) return m;
  // mirror about y = 0, welding the nodes on it
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

}  // namespace fairlines
