// Shared edges, the waterline cut and the assembly of face meshes, see brep.hpp.
//
// Notation: e an edge, f a face, s an edge's samples; I the integral of ds / h along an edge
// (h the target size), so an edge gets ceil(I) segments of equal I; T the draft of a cut,
// g(u, v) = z(u, v) - T on a face, whose zero set is the waterline; a piece is the part of an
// edge below T, ex the vertex where a face's loop leaves the cut (a waterline starts there).
#include "meshing/brep.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <queue>
#include <sstream>
#include <unordered_map>

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include "common/used_nodes.hpp"
#include "fairlines/errors.hpp"

namespace fairlines::meshing {

namespace {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;

constexpr int kPoleSegments = 4;        ///< copies of a pole node along its parameter edge, minus one
constexpr double kTraceStep = 0.25;     ///< waterline trace step / size
constexpr double kTraceStall = 1e-3;    ///< a trace step shorter than this fraction of its stride has stalled
constexpr double kTraceDrift = 0.5;     ///< corrector move / predictor step above which the step is halved
constexpr double kTraceChord = 2.0;     ///< a trace step's chord is at most this x its stride
constexpr int kTraceHalvings = 30;     ///< at most this many halvings of one trace step
constexpr int kTraceMaxSteps = 100000; ///< a waterline trace longer than this many steps has lost its way
constexpr int kBisections = 60;         ///< bisection steps for an edge's crossing of the cut
constexpr double kVertexMatch = 1e-9;   ///< vertices closer than this x model size are one
constexpr double kSubstep = 0.25;       ///< integration step of an edge's size / the size
constexpr double kMinSubstep = 1e-3;    ///< sub-steps are at least this fraction of the sample spacing
constexpr double kAllQuadTolerance = 0.8;  ///< chordal tolerance factor of the all-quad split's coarse pass
constexpr double kEdgeGrading = 0.6;    ///< an edge's size grows by at most this x the distance from its ends' sizes
constexpr double kFacing = 0.2;         ///< |cos| of the gap to both edges' tangents at most this: they face each other (within 11.5 deg)
constexpr double kGapElements = 1.0;    ///< a gap between facing edges caps their size at its width / this
constexpr double kGapFloor = 0.1;       ///< ... but not below this x the size (a cusp's tip is one sliver however fine)

EdgeSample lerp(const EdgeSample& a, const EdgeSample& b, double t) {
  EdgeSample r;
  r.xyz = (1 - t) * a.xyz + t * b.xyz;
  r.uv[0] = (1 - t) * a.uv[0] + t * b.uv[0];
  r.uv[1] = (1 - t) * a.uv[1] + t * b.uv[1];
  return r;
}

/// Side of edge e that belongs to face f.
int side_of(const Edge& e, int f) { return e.face[0] == f ? 0 : 1; }

}  // namespace

int Brep::vertex(const Vec3& p) {
  double scale = 1.0;
  for (const Vec3& q : vertices) scale = std::max(scale, q.cwiseAbs().maxCoeff());
  for (size_t i = 0; i < vertices.size(); ++i)
    if ((vertices[i] - p).norm() <= kVertexMatch * scale) return static_cast<int>(i);
  vertices.push_back(p);
  return static_cast<int>(vertices.size()) - 1;
}

int Brep::add_edge(int f0, int f1, std::vector<EdgeSample> s, bool degenerate) {
  Edge e;
  e.face[0] = f0;
  e.face[1] = f1;
  for (int k = 0; k < 2; ++k) {
    const int f = e.face[k];
    if (f >= 0 && !faces[f].g.surface)
      for (auto& x : s) x.uv[k] = faces[f].g.locate(x.xyz, x.uv[k]);
  }
  e.v0 = vertex(s.front().xyz);
  e.v1 = degenerate ? e.v0 : vertex(s.back().xyz);
  e.s = std::move(s);
  e.degenerate = degenerate;
  edges.push_back(std::move(e));
  return static_cast<int>(edges.size()) - 1;
}

int Brep::sampled_edge(int f0, int f1, int n, const std::function<EdgeSample(double)>& at, bool degenerate) {
  std::vector<EdgeSample> s(n);
  for (int k = 0; k < n; ++k) s[k] = at(static_cast<double>(k) / (n - 1));
  return add_edge(f0, f1, std::move(s), degenerate);
}

// ---- the waterline cut -------------------------------------------------------------------

namespace {

/// The exact sample at fraction t between samples k and k + 1 of e.
EdgeSample edge_point(const Brep& b, const Edge& e, int k, double t) {
  EdgeSample r = lerp(e.s[k], e.s[std::min<size_t>(k + 1, e.s.size() - 1)], t);
  if (e.degenerate) return r;
  if (e.refine) {
    e.refine(r);
    return r;
  }
  const Face& f0 = b.faces[e.face[0]];
  r.xyz = f0.g.point(r.uv[0]);
  if (e.face[1] >= 0) r.uv[1] = b.faces[e.face[1]].g.locate(r.xyz, r.uv[1]);
  return r;
}

/// uv moved onto z = T by Newton along the gradient of z(u, v) (clamped to the face's domain).
Vec2 onto_level(const FaceGeometry& g, Vec2 q, double T) {
  for (int it = 0; it < 6; ++it) {
    Vec3 p, su, sv;
    g.first(q, p, su, sv);
    const Vec2 gr(su.z(), sv.z());
    const double n2 = gr.squaredNorm();
    if (n2 <= 0) break;
    q = g.clamp(q - (p.z() - T) * gr / n2);
    if (std::abs(p.z() - T) < 1e-12 * std::max(1.0, std::abs(T))) break;
  }
  return q;
}

/// Fraction of the segment a -> b (a inside the face's parameter domain) that stays inside it.
double domain_fraction(const FaceGeometry& g, const Vec2& a, const Vec2& b) {
  const Vec2 c = g.clamp(b);
  double f = 1.0;
  for (int k = 0; k < 2; ++k)
    if (c[k] != b[k] && b[k] != a[k]) f = std::min(f, std::clamp((c[k] - a[k]) / (b[k] - a[k]), 0.0, 1.0));
  return f;
}

/// Unit tangent of the level curve of z through q (uv, either sense); throws InvalidInput `what`
/// where z's gradient vanishes (a draft at a horizontal point).
Vec2 level_tangent(const FaceGeometry& g, const Vec2& q, const char* what) {
  Vec3 p, su, sv;
  g.first(q, p, su, sv);
  Vec2 t(-sv.z(), su.z());
  if (t.norm() <= 0) throw InvalidInput(what);
  return t.normalized();
}

/// |dS| per unit uv step along t at q.
double speed(const FaceGeometry& g, const Vec2& q, const Vec2& t) {
  Vec3 p, su, sv;
  g.first(q, p, su, sv);
  return (su * t.x() + sv * t.y()).norm();
}

/// Predictor from q along t by d (uv), corrector onto z = T; where the corrector lands far
/// from the prediction (a tight turn of the level curve) d is halved (and left so).
Vec2 level_step(const FaceGeometry& g, const Vec2& q, const Vec2& t, double& d, double T) {
  Vec2 next = q;
  for (int h = 0; h < kTraceHalvings; ++h, d *= 0.5) {
    const Vec2 pred = g.clamp(q + d * t);
    next = onto_level(g, pred, T);
    if ((next - pred).norm() <= kTraceDrift * (pred - q).norm()) break;
  }
  return next;
}

/// Level-set march of z = T on face f from uv `from` into the face until it leaves `poly`.
std::vector<Vec2> trace_waterline(const FaceGeometry& g, const Vec2& from, const std::vector<Vec2>& poly, double T,
                                  double step3d) {
  std::vector<Vec2> out{from};
  Vec2 t = level_tangent(g, from, "mesh: the waterline is tangent to a face edge (horizontal surface at the draft)");
  {  // into the face
    const double d = step3d / std::max(1e-300, speed(g, from, t));
    const bool fwd_in = point_in_polygon(from + 0.5 * d * t, poly);
    const bool back_in = point_in_polygon(from - 0.5 * d * t, poly);
    if (!fwd_in && back_in) t = -t;
  }
  for (int n = 0; n < kTraceMaxSteps; ++n) {
    const Vec2 q = out.back();
    Vec2 tn = level_tangent(g, q, "mesh: the waterline trace met a horizontal point of a face");
    if (tn.dot(t) < 0) tn = -tn;
    t = tn;
    double d = step3d / std::max(1e-300, speed(g, q, t));
    // the level curve leaves the parameter domain within this step (where the loop runs along
    // the domain's edge, as a transom's): end on the edge, where the clamped corrector would
    // slide along it instead
    const Vec2 raw = q + d * t;
    if (n > 0 && g.clamp(raw) != raw) {
      out.push_back(q + domain_fraction(g, q, raw) * (raw - q));
      return out;
    }
    Vec2 next = level_step(g, q, t, d, T);
    // where the surface is nearly degenerate (a stem's end) a step of step3d at q's speed
    // can land far along the level curve: halve it until its chord is near step3d
    const Vec3 at = g.point(q);
    for (int h = 0; h < kTraceHalvings && (g.point(next) - at).norm() > kTraceChord * step3d; ++h) {
      d *= 0.5;
      next = level_step(g, q, t, d, T);
    }
    out.push_back(next);
    // out of the face, or pinned against its parameter domain's edge (the clamp holds it
    // there): the waterline has reached the face's boundary
    if (!point_in_polygon(next, poly) || (next - q).norm() < kTraceStall * d) return out;
  }
  std::ostringstream msg;
  msg << "mesh: the waterline trace did not leave the face (from uv " << from.transpose() << ", at uv "
      << out.back().transpose() << ")";
  throw ConvergenceError(msg.str());
}

/// Where edge e crosses z = T between its samples k and k + 1 (bisection on the exact edge).
EdgeSample crossing(const Brep& b, const Edge& e, int k, double T) {
  double lo = 0, hi = 1;
  const bool start_below = e.s[k].xyz.z() <= T;
  for (int it = 0; it < kBisections; ++it) {
    const double mid = 0.5 * (lo + hi);
    ((edge_point(b, e, k, mid).xyz.z() <= T) == start_below ? lo : hi) = mid;
  }
  EdgeSample c = edge_point(b, e, k, 0.5 * (lo + hi));
  c.xyz.z() = T;
  return c;
}

/// Splits edge ei at z = T: adds its pieces below as new edges, first to last; returns them.
std::vector<int> split_below(Brep& b, size_t ei, double T) {
  const Edge e = b.edges[ei];  // a copy: add_edge grows b.edges
  std::vector<int> kept;
  std::vector<EdgeSample> run;
  auto below = [&](const EdgeSample& x) { return x.xyz.z() <= T; };
  auto flush = [&] {
    if (run.size() >= 2) {
      const int id = b.add_edge(e.face[0], e.face[1], run, e.degenerate);
      b.edges[id].refine = e.refine;
      kept.push_back(id);
    }
    run.clear();
  };
  for (size_t k = 0; k < e.s.size(); ++k) {
    if (k > 0 && below(e.s[k - 1]) != below(e.s[k])) {
      run.push_back(crossing(b, e, static_cast<int>(k) - 1, T));
      if (below(e.s[k - 1])) flush();
    }
    if (below(e.s[k])) run.push_back(e.s[k]);
  }
  flush();
  return kept;
}

/// Appends the waterplane face z = T (its loops come last); returns its index.
int add_waterplane(Brep& b, double T, const std::string& name, bool keep) {
  Face lid;
  lid.g.origin = Vec3(0, 0, T);
  lid.g.ax = Vec3::UnitX();
  lid.g.ay = Vec3::UnitY();
  lid.name = name;
  lid.keep = keep;
  b.faces.push_back(lid);
  return static_cast<int>(b.faces.size()) - 1;
}

/// The pieces below the cut of face f's loop, in loop order, and where they start and end.
struct FacePieces {
  const Brep& b;
  int f;
  std::vector<std::pair<int, bool>> kept;  ///< (piece, forward)
  std::vector<Vec2> poly;                  ///< the whole loop before the cut, in the face's (u, v)
  bool cut = false;                        ///< some edge of the loop was split or dropped
  std::map<int, size_t> start_index;       ///< start vertex -> piece

  int start_of(size_t i) const { return kept[i].second ? b.edges[kept[i].first].v0 : b.edges[kept[i].first].v1; }
  int end_of(size_t i) const { return kept[i].second ? b.edges[kept[i].first].v1 : b.edges[kept[i].first].v0; }
  Vec2 uv_at(size_t i, bool at_end) const {
    const Edge& e = b.edges[kept[i].first];
    const bool last = at_end == kept[i].second;
    return (last ? e.s.back() : e.s.front()).uv[side_of(e, f)];
  }
  /// Whether piece j starts where another piece ends (not an entry of a waterline).
  bool continued(size_t j) const {
    for (size_t m = 0; m < kept.size(); ++m)
      if (end_of(m) == start_of(j)) return true;
    return false;
  }
};

FacePieces face_pieces(const Brep& b, int fi, const std::vector<std::vector<int>>& pieces) {
  FacePieces p{b, fi, {}, {}, false, {}};
  for (const auto& [e, fwd] : b.faces[fi].loop) {
    const int sd = side_of(b.edges[e], fi);
    std::vector<EdgeSample> s = b.edges[e].s;
    if (!fwd) std::reverse(s.begin(), s.end());
    for (const auto& x : s) p.poly.push_back(x.uv[sd]);
    std::vector<int> q = pieces[e];
    if (q.size() != 1 || b.edges[q[0]].s.size() != b.edges[e].s.size()) p.cut = true;
    if (!fwd) std::reverse(q.begin(), q.end());
    for (int id : q) p.kept.push_back({id, fwd});
  }
  for (size_t i = 0; i < p.kept.size(); ++i) p.start_index[p.start_of(i)] = i;
  return p;
}

constexpr double kTraceSnap = 0.3;  ///< a trace's last point nearer its entry than this x the step is dropped

/// The waterline edge of face f (to the lid) along the traced uv points `tr`, from the
/// vertex `ex` to the start of piece `entry`; nodes between its samples stay on z = T.
int waterline_edge(Brep& b, const Face& f, int fi, const FacePieces& p, const std::vector<Vec2>& tr, int ex,
                   size_t entry, int lid, double T, double size) {
  std::vector<EdgeSample> s;
  for (size_t k = 0; k + 1 < tr.size(); ++k) {
    EdgeSample x;
    x.uv[0] = tr[k];
    x.uv[1] = Vec2::Zero();  // on the lid: add_edge locates it
    x.xyz = f.g.point(tr[k]);
    x.xyz.z() = T;
    s.push_back(x);
  }
  EdgeSample last;
  last.uv[0] = p.uv_at(entry, false);
  last.uv[1] = Vec2::Zero();
  last.xyz = b.vertices[p.start_of(entry)];
  if (s.size() >= 2 && (f.g.point(s.back().uv[0]) - last.xyz).norm() < kTraceSnap * kTraceStep * size) s.pop_back();
  s.push_back(last);
  s.front().xyz = b.vertices[ex];
  const int id = b.add_edge(fi, lid, s);
  b.edges[id].refine = [g = f.g, T](EdgeSample& x) {
    x.uv[0] = onto_level(g, x.uv[0], T);
    x.xyz = g.point(x.uv[0]);
    x.xyz.z() = T;
  };
  return id;
}

/// exit vertex -> (traced waterline edge, the piece it leads to)
using Bridges = std::map<int, std::pair<int, size_t>>;

/// Traces the waterline from every piece's end that no piece continues to the nearest
/// piece start that no piece reaches; adds the traced edges to `traced`.
Bridges bridge_gaps(Brep& b, const Face& f, const FacePieces& p, int lid, double T, double size,
                    std::vector<int>& traced) {
  Bridges bridge;
  for (size_t i = 0; i < p.kept.size(); ++i) {
    const int ex = p.end_of(i);
    if (p.start_index.count(ex)) continue;
    std::vector<Vec2> tr;
    try {
      tr = trace_waterline(f.g, p.uv_at(i, true), p.poly, T, kTraceStep * size);
    } catch (const InvalidInput& err) {  // the face named, the kind kept
      throw InvalidInput(std::string(err.what()) + " on face '" + f.name + "'");
    } catch (const ConvergenceError& err) {
      throw ConvergenceError(std::string(err.what()) + " on face '" + f.name + "'");
    }
    size_t best = p.kept.size();
    double bd = 1e300;
    for (size_t j = 0; j < p.kept.size(); ++j) {
      if (p.continued(j)) continue;
      const double d = (p.uv_at(j, false) - tr.back()).norm();
      if (d < bd) {
        bd = d;
        best = j;
      }
    }
    if (best == p.kept.size()) throw InvalidInput("mesh: a waterline on face '" + f.name + "' ends nowhere; expected a draft a little higher or lower");
    const int id = waterline_edge(b, f, p.f, p, tr, ex, best, lid, T, size);
    traced.push_back(id);
    bridge[ex] = {id, best};
  }
  return bridge;
}

/// The faces a cut makes, the old face each comes from, and the waterline edges traced.
struct CutFaces {
  std::vector<Face> faces;
  std::vector<int> origin;
  std::vector<int> traced;
};

/// Closed loops of face f after the cut: pieces joined by the bridges, each a new face.
void follow_loops(const Face& f, const FacePieces& p, const Bridges& bridge, CutFaces& out) {
  std::vector<char> used(p.kept.size(), 0);
  for (size_t s0 = 0; s0 < p.kept.size(); ++s0) {
    if (used[s0]) continue;
    Face g = f;
    g.loop.clear();
    size_t i = s0;
    for (size_t guard = 0; guard <= 2 * p.kept.size() && !used[i]; ++guard) {
      used[i] = 1;
      g.loop.push_back(p.kept[i]);
      const int ex = p.end_of(i);
      auto br = bridge.find(ex);
      if (br != bridge.end()) {
        g.loop.push_back({br->second.first, true});
        i = br->second.second;
      } else {
        // the next piece in the face's own order first: a pole edge starts and ends at one
        // vertex, where the piece after it starts too, and must stay between them
        const size_t next = (i + 1) % p.kept.size();
        auto st = p.start_index.find(ex);
        if (!used[next] && p.start_of(next) == ex) i = next;
        else if (st == p.start_index.end()) throw InvalidInput("mesh: the cut loop of face '" + f.name + "' does not close; expected a draft a little higher or lower");
        else i = st->second;
      }
    }
    out.faces.push_back(g);
    out.origin.push_back(p.f);
  }
}

/// Face fi cut at z = T: nothing if all above, itself if uncut, else its loops closed by
/// traced waterlines.
void cut_face(Brep& b, int fi, const std::vector<std::vector<int>>& pieces, int lid, double T, double size,
              CutFaces& out) {
  const Face f = b.faces[fi];
  const FacePieces p = face_pieces(b, fi, pieces);
  if (p.kept.empty()) return;
  if (!p.cut) {
    Face g = f;
    g.loop = p.kept;
    out.faces.push_back(g);
    out.origin.push_back(fi);
    return;
  }
  const Bridges bridge = bridge_gaps(b, f, p, lid, T, size, out.traced);
  follow_loops(f, p, bridge, out);
}

/// Edges name their faces by index: points them at the new faces (a face cut into several
/// loops keeps each edge on the loop that uses it); edges to the lid are left without one.
void renumber_edge_faces(Brep& b, const CutFaces& c, int lid) {
  std::vector<std::array<int, 2>> sides(b.edges.size(), {-1, -1});
  for (int f = 0; f < static_cast<int>(c.faces.size()); ++f)
    for (const auto& [e, fwd] : c.faces[f].loop)
      for (int k = 0; k < 2; ++k)
        if (b.edges[e].face[k] == c.origin[f]) sides[e][k] = f;
  for (size_t e = 0; e < b.edges.size(); ++e) {
    const bool to_lid = b.edges[e].face[1] == lid;
    b.edges[e].face[0] = sides[e][0];
    b.edges[e].face[1] = to_lid ? -1 : sides[e][1];
  }
}

/// The waterplane's faces: the traced edges chained into loops, appended to c.faces.
void add_waterplane_loops(Brep& b, CutFaces& c, int lid) {
  std::multimap<int, int> at_vertex;
  for (int id : c.traced) {
    at_vertex.insert({b.edges[id].v0, id});
    at_vertex.insert({b.edges[id].v1, id});
  }
  std::vector<char> done(b.edges.size(), 0);
  for (int id : c.traced) {
    if (done[id]) continue;
    Face l = b.faces[lid];
    int e = id, v = b.edges[id].v0;
    while (!done[e]) {
      done[e] = 1;
      const bool fwd = b.edges[e].v0 == v;
      l.loop.push_back({e, fwd});
      v = fwd ? b.edges[e].v1 : b.edges[e].v0;
      int next = -1;
      auto range = at_vertex.equal_range(v);
      for (auto it = range.first; it != range.second; ++it)
        if (!done[it->second]) next = it->second;
      if (next < 0) break;
      e = next;
    }
    const int fidx = static_cast<int>(c.faces.size());
    for (const auto& [e2, fwd] : l.loop) b.edges[e2].face[1] = fidx;
    c.faces.push_back(l);
  }
}

}  // namespace

void Brep::cut_below(double T, double size, const std::string& lid_name, bool keep_lid) {
  std::vector<std::vector<int>> pieces(edges.size());  // kept pieces of each old edge, first to last
  for (size_t ei = 0; ei < pieces.size(); ++ei) pieces[ei] = split_below(*this, ei, T);
  const int lid = add_waterplane(*this, T, lid_name, keep_lid);
  CutFaces c;
  for (int fi = 0; fi < lid; ++fi) cut_face(*this, fi, pieces, lid, T, size, c);
  renumber_edge_faces(*this, c, lid);
  add_waterplane_loops(*this, c, lid);
  faces = std::move(c.faces);
}

// ---- meshing -----------------------------------------------------------------------------

namespace {

struct Discrete {
  std::vector<int> ids;
  std::vector<EdgeSample> pts;
  std::vector<double> at;  // I at each node
};

struct Mesher {
  Brep& b;
  const MeshOptions& o;
  double scale;  // interior size factor (2 for all-quad)
  std::vector<Vec3> nodes;
  std::vector<Discrete> disc;
  std::map<std::pair<int, int>, LoopNode> mids;  // (edge, segment) -> midpoint node (all-quad)
  /// I along every edge: (sample interval k, fraction t in it, I) at every integration step
  struct Station {
    int k;
    double t, I;
  };
  std::vector<std::vector<Station>> cum_I;
  std::vector<double> vertex_h;                   // size at each end vertex, over all its edges
  std::vector<std::vector<double>> gap_h;         // proximity cap at each sample of every edge (m)

  /// Arc length (m) from the first sample at every sample of edge e.
  std::vector<double> arc(const Edge& e) const {
    std::vector<double> s(e.s.size(), 0.0);
    for (size_t k = 1; k < e.s.size(); ++k) s[k] = s[k - 1] + (e.s[k].xyz - e.s[k - 1].xyz).norm();
    return s;
  }

  /// Where two edges of one face run close and face each other (a waterline a few centimetres
  /// above a trim curve), the gap caps the size along both, graded along each edge, so the strip
  /// between them is meshed by elements as wide as it is rather than by slivers. Segments are
  /// bucketed in cubes of the size: only gaps below it matter.
  void proximity_caps(const std::vector<char>& needed) {
    gap_h.assign(b.edges.size(), {});
    const double cell = o.size;
    auto key = [&](const Vec3& p) {
      const auto c = [&](double t) { return static_cast<long long>(std::floor(t / cell)) & 0x1fffff; };
      return (c(p.x()) << 42) | (c(p.y()) << 21) | c(p.z());
    };
    std::unordered_map<long long, std::vector<std::pair<int, int>>> buckets;  // (edge, segment)
    for (size_t ei = 0; ei < b.edges.size(); ++ei) {
      if (!needed[ei] || b.edges[ei].degenerate) continue;
      gap_h[ei].assign(b.edges[ei].s.size(), 1e300);
      const auto& x = b.edges[ei].s;
      for (size_t k = 0; k + 1 < x.size(); ++k)
        for (const Vec3& p : {x[k].xyz, x[k + 1].xyz}) {
          auto& v = buckets[key(p)];
          if (v.empty() || v.back() != std::pair<int, int>(static_cast<int>(ei), static_cast<int>(k)))
            v.emplace_back(static_cast<int>(ei), static_cast<int>(k));
        }
    }
    for (size_t ei = 0; ei < b.edges.size(); ++ei)
      if (!gap_h[ei].empty()) edge_gaps(static_cast<int>(ei), buckets, key);
  }

  template <class Buckets, class Key>
  void edge_gaps(int ei, const Buckets& buckets, const Key& key) {
    const Edge& e = b.edges[ei];
    // a curved face only: a lid's waterline meets the centre plane's edge in a cusp at the stem,
    // where refining only makes its tip sliver smaller
    auto shares_face = [&](const Edge& f) {
      for (int a : e.face)
        if (a >= 0 && (a == f.face[0] || a == f.face[1]) && b.faces[a].g.surface) return true;
      return false;
    };
    std::vector<double>& h = gap_h[ei];
    const size_t n = e.s.size();
    for (size_t k = 0; k < n; ++k) {
      const Vec3& p = e.s[k].xyz;
      const Vec3 t = (e.s[std::min(k + 1, n - 1)].xyz - e.s[k > 0 ? k - 1 : 0].xyz).normalized();
      double gap = o.size * kGapElements;
      for (int dx = -1; dx <= 1; ++dx)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dz = -1; dz <= 1; ++dz) {
            auto it = buckets.find(key(p + o.size * Vec3(dx, dy, dz)));
            if (it == buckets.end()) continue;
            for (const auto& [fj, j] : it->second) {
              const Edge& f = b.edges[fj];
              if (fj == ei || !shares_face(f)) continue;
              const Vec3 &a = f.s[j].xyz, &c = f.s[j + 1].xyz, ac = c - a;
              if (ac.squaredNorm() == 0.0) continue;
              const double w = std::clamp((p - a).dot(ac) / ac.squaredNorm(), 0.0, 1.0);
              const Vec3 d = a + w * ac - p;
              const double dist = d.norm();
              // a shared vertex (dist 0) or a corner (the gap along an edge) is no strip
              if (dist <= 0.0 || dist >= gap) continue;
              if (std::abs(d.dot(t)) > kFacing * dist || std::abs(d.dot(ac.normalized())) > kFacing * dist) continue;
              gap = dist;
            }
          }
      h[k] = std::max({gap / kGapElements, kGapFloor * o.size, o.min_size});
    }
    // graded along the edge, both ways
    for (size_t k = 1; k < n; ++k)
      h[k] = std::min(h[k], h[k - 1] + kEdgeGrading * (e.s[k].xyz - e.s[k - 1].xyz).norm());
    for (size_t k = n - 1; k-- > 0;)
      h[k] = std::min(h[k], h[k + 1] + kEdgeGrading * (e.s[k + 1].xyz - e.s[k].xyz).norm());
  }

  /// The proximity cap at arc length `at` of edge ei (samples' arc lengths s), times the scale.
  double gap_at(int ei, const std::vector<double>& s, double at) const {
    const std::vector<double>& h = gap_h[ei];
    const size_t k = std::upper_bound(s.begin(), s.end(), at) - s.begin();
    if (k == 0) return scale * h.front();
    if (k >= s.size()) return scale * h.back();
    const double w = (at - s[k - 1]) / std::max(s[k] - s[k - 1], 1e-300);
    return scale * ((1.0 - w) * h[k - 1] + w * h[k]);
  }

  /// The smallest size each vertex sees along any of its edges, graded by the distance, so an
  /// edge that meets a finely divided one (at a cone-like corner such as a stem top) is graded
  /// down to it instead of ending in a fan of slivers.
  void vertex_sizes(const std::vector<char>& needed) {
    vertex_h.assign(nodes.size(), 1e300);
    for (size_t ei = 0; ei < b.edges.size(); ++ei) {
      const Edge& e = b.edges[ei];
      if (!needed[ei] || e.degenerate) continue;
      const std::vector<double> s = arc(e);
      // an edge shorter than the size (a draft just above a trim curve's end on the stem) sizes
      // its ends: the elements round it grade up from it instead of fanning round it
      vertex_h[e.v0] = std::min(vertex_h[e.v0], s.back());
      vertex_h[e.v1] = std::min(vertex_h[e.v1], s.back());
      for (size_t k = 0; k < e.s.size(); ++k) {
        const double h = std::min(h_at(e, e.s[k]), scale * gap_h[ei][k]);
        vertex_h[e.v0] = std::min(vertex_h[e.v0], h + kEdgeGrading * s[k]);
        vertex_h[e.v1] = std::min(vertex_h[e.v1], h + kEdgeGrading * (s.back() - s[k]));
      }
    }
  }

  double h_at(const Edge& e, const EdgeSample& x) const {
    double h = o.size;
    for (int k = 0; k < 2; ++k)
      if (e.face[k] >= 0) h = std::min(h, target_size(b.faces[e.face[k]].g, x.uv[k], o));
    return scale * h;
  }

  EdgeSample point_at_I(int ei, double I) const {
    const Edge& e = b.edges[ei];
    const auto& c = cum_I[ei];
    const auto it = std::lower_bound(c.begin() + 1, c.end() - 1, I, [](const Station& a, double x) { return a.I < x; });
    const Station& hi = *it;
    Station lo = *(it - 1);
    if (lo.k != hi.k) lo = {hi.k, 0.0, lo.I};  // a step that starts at a sample
    const double w = hi.I > lo.I ? std::clamp((I - lo.I) / (hi.I - lo.I), 0.0, 1.0) : 0.0;
    return edge_point(b, e, hi.k, lo.t + w * (hi.t - lo.t));
  }

  void discretise(int ei) {
    const Edge& e = b.edges[ei];
    Discrete d;
    cum_I[ei].clear();
    if (e.degenerate) {
      for (int k = 0; k <= kPoleSegments; ++k) {
        d.pts.push_back(lerp(e.s.front(), e.s.back(), static_cast<double>(k) / kPoleSegments));
        d.ids.push_back(e.v0);
        d.at.push_back(k);
      }
      disc[ei] = std::move(d);
      return;
    }
    auto& c = cum_I[ei];
    const std::vector<double> s = arc(e);
    auto graded = [&](const EdgeSample& x, double at) {
      return std::min({h_at(e, x), gap_at(ei, s, at), vertex_h[e.v0] + kEdgeGrading * at,
                       vertex_h[e.v1] + kEdgeGrading * (s.back() - at)});
    };
    double prev_h = graded(e.s[0], 0.0), I = 0.0;
    c.push_back({0, 0.0, 0.0});
    for (size_t k = 1; k < e.s.size(); ++k) {
      // sub-steps where the size is small against the sample spacing (a straight edge has two
      // samples; its graded size still varies along it)
      const double len = s[k] - s[k - 1];
      for (double t = 0.0; t < 1.0;) {
        const double next = std::min(1.0, t + std::max(kSubstep * prev_h / std::max(len, 1e-300), kMinSubstep));
        const double h = graded(lerp(e.s[k - 1], e.s[k], next), s[k - 1] + next * len);
        I += (next - t) * len * 0.5 * (1.0 / h + 1.0 / prev_h);
        c.push_back({static_cast<int>(k) - 1, next, I});
        prev_h = h;
        t = next;
      }
    }
    const double total = c.back().I;
    const int n = std::max(1, static_cast<int>(std::ceil(total - 1e-6)));
    d.ids.push_back(e.v0);
    d.pts.push_back(e.s.front());
    d.at.push_back(0.0);
    for (int i = 1; i < n; ++i) {
      const double Ii = total * i / n;
      EdgeSample x = point_at_I(ei, Ii);
      d.ids.push_back(static_cast<int>(nodes.size()));
      nodes.push_back(x.xyz);
      d.pts.push_back(x);
      d.at.push_back(Ii);
    }
    d.ids.push_back(e.v1);
    d.pts.push_back(e.s.back());
    d.at.push_back(total);
    disc[ei] = std::move(d);
  }

  LoopNode midpoint(int ei, int seg, int face) {
    const Edge& e = b.edges[ei];
    const int sd = side_of(e, face);
    auto it = mids.find({ei, seg});
    LoopNode n;
    if (it == mids.end()) {
      const Discrete& d = disc[ei];
      EdgeSample x;
      if (e.degenerate) {
        x = lerp(d.pts[seg], d.pts[seg + 1], 0.5);
        n.id = e.v0;
      } else {
        x = point_at_I(ei, 0.5 * (d.at[seg] + d.at[seg + 1]));
        n.id = static_cast<int>(nodes.size());
        nodes.push_back(x.xyz);
      }
      n.xyz = x.xyz;
      n.uv = x.uv[0];
      LoopNode other = n;
      other.uv = x.uv[1];
      mids[{ei, seg}] = n;
      mids[{ei, -1 - seg}] = other;
      it = mids.find({ei, seg});
    }
    return sd == 0 ? it->second : mids[{ei, -1 - seg}];
  }
};

/// Polygon elements made consistent across shared edges, then outward by int y n_y dS > 0.
void orient(std::vector<std::array<int, 4>>& el, const std::vector<Vec3>& x) {
  const int m = static_cast<int>(el.size());
  auto corners = [&](int f) { return el[f][3] < 0 ? 3 : 4; };
  std::unordered_map<long long, std::vector<int>> by_edge;
  const long long N = static_cast<long long>(x.size()) + 1;
  auto key = [&](int a, int b) { return std::min(a, b) * N + std::max(a, b); };
  for (int f = 0; f < m; ++f)
    for (int k = 0; k < corners(f); ++k) by_edge[key(el[f][k], el[f][(k + 1) % corners(f)])].push_back(f);
  auto has_directed = [&](int f, int a, int b) {
    for (int k = 0; k < corners(f); ++k)
      if (el[f][k] == a && el[f][(k + 1) % corners(f)] == b) return true;
    return false;
  };
  auto flip = [&](int f) { std::reverse(el[f].begin(), el[f].begin() + corners(f)); };
  std::vector<char> seen(m, 0);
  for (int s = 0; s < m; ++s) {
    if (seen[s]) continue;
    seen[s] = 1;
    std::queue<int> q;
    q.push(s);
    std::vector<int> comp{s};
    while (!q.empty()) {
      const int f = q.front();
      q.pop();
      for (int k = 0; k < corners(f); ++k) {
        const int a = el[f][k], b = el[f][(k + 1) % corners(f)];
        const auto& nb = by_edge[key(a, b)];
        if (nb.size() != 2) continue;
        const int g = nb[0] == f ? nb[1] : nb[0];
        if (seen[g]) continue;
        seen[g] = 1;
        if (has_directed(g, a, b)) flip(g);
        q.push(g);
        comp.push_back(g);
      }
    }
    double flux = 0.0;  // int y n_y dS of this component
    for (int f : comp)
      for (int k = 1; k + 1 < corners(f); ++k) {
        const Vec3 &a = x[el[f][0]], &b = x[el[f][k]], &c = x[el[f][k + 1]];
        const Vec3 n = 0.5 * (b - a).cross(c - a);
        flux += (a.y() + b.y() + c.y()) / 3.0 * n.y();
      }
    if (flux < 0)
      for (int f : comp) flip(f);
  }
}

/// Edges on the loop of a kept face (the only ones discretised).
std::vector<char> needed_edges(const Brep& b) {
  std::vector<char> needed(b.edges.size(), 0);
  for (const Face& f : b.faces)
    if (f.keep)
      for (const auto& [e, fwd] : f.loop) needed[e] = 1;
  return needed;
}

/// A face's boundary as nodes of its discretised edges, in loop order, and the (edge,
/// segment) of the segment from each node to the next.
struct FaceLoop {
  std::vector<LoopNode> nodes;
  std::vector<std::pair<int, int>> seg_of;
};

FaceLoop face_loop(const Brep& b, const Mesher& M, int fi) {
  const Face& f = b.faces[fi];
  FaceLoop out;
  for (const auto& [e, fwd] : f.loop) {
    if (!f.g.surface && b.edges[e].degenerate) continue;  // a pole is one point of a plane: its copies fold the loop
    const Discrete& d = M.disc[e];
    const int sd = side_of(b.edges[e], fi);
    const int n = static_cast<int>(d.ids.size());
    for (int k = 0; k + 1 < n; ++k) {
      const int i = fwd ? k : n - 1 - k;
      LoopNode ln;
      ln.id = d.ids[i];
      ln.uv = f.g.surface ? d.pts[i].uv[sd] : f.g.locate(d.pts[i].xyz, Vec2::Zero());
      ln.xyz = i == 0 || i == n - 1 ? M.nodes[d.ids[i]] : d.pts[i].xyz;
      out.nodes.push_back(ln);
      out.seg_of.push_back({e, fwd ? k : n - 2 - k});
    }
  }
  return out;
}

/// Global node ids of a patch's nodes: its boundary's own, new ones for its interior.
std::vector<int> global_ids(Mesher& M, const PatchMesh& pm) {
  std::vector<int> gid(pm.xyz.size());
  for (size_t i = 0; i < pm.xyz.size(); ++i) {
    if (pm.global[i] >= 0) {
      gid[i] = pm.global[i];
    } else {
      gid[i] = static_cast<int>(M.nodes.size());
      M.nodes.push_back(pm.xyz[i]);
    }
  }
  return gid;
}

/// Index of the part `name` in parts, appended if new.
int part_index(std::vector<std::string>& parts, const std::string& name) {
  const int i = static_cast<int>(std::find(parts.begin(), parts.end(), name) - parts.begin());
  if (i == static_cast<int>(parts.size())) parts.push_back(name);
  return i;
}

/// A patch's elements in global ids (a corner repeated, as at a pole, collapses; fewer than
/// three distinct corners drop the element), appended to el with their part.
void append_elements(const PatchMesh& pm, const std::vector<int>& gid, int pidx, std::vector<std::array<int, 4>>& el,
                     std::vector<int>& part) {
  for (const auto& e : pm.elements) {
    std::array<int, 4> g{-1, -1, -1, -1};
    int k = 0;
    const int corners = e[3] < 0 ? 3 : 4;
    for (int c = 0; c < corners; ++c) {
      const int id = gid[e[c]];
      if (k > 0 && g[k - 1] == id) continue;
      g[k++] = id;
    }
    if (k > 1 && g[k - 1] == g[0]) --k;
    if (k < 3) continue;
    if (k == 3) g[3] = -1;
    el.push_back(g);
    part.push_back(pidx);
  }
}

/// The elements and their parts into `out`, keeping only the nodes they use.
void compact(std::vector<std::array<int, 4>>& el, const std::vector<int>& part, const std::vector<Vec3>& nodes,
             SurfaceMesh& out) {
  out.vertices = detail::keep_used_nodes(el, nodes);
  out.faces = detail::element_rows(el);
  out.face_part = Eigen::Map<const Eigen::VectorXi>(part.data(), static_cast<Eigen::Index>(el.size()));
}

}  // namespace

SurfaceMesh mesh_brep(Brep& b, const MeshOptions& options, const std::function<void(int, int, const std::string&)>& progress,
                      bool outward) {
  // the all-quad split's coarse pass sizes for a tighter tolerance: a coarse quad's split
  // quarters sag about a quarter as much, but smoothing and the 2:1 steps of the sizes add some
  MeshOptions o = options;
  if (o.all_quad) o.chordal_tolerance *= kAllQuadTolerance;
  Mesher M{b, o, o.all_quad ? 2.0 : 1.0, b.vertices, {}, {}, {}, {}, {}};
  M.disc.resize(b.edges.size());
  M.cum_I.resize(b.edges.size());
  const std::vector<char> needed = needed_edges(b);
  M.proximity_caps(needed);
  M.vertex_sizes(needed);
  for (size_t e = 0; e < b.edges.size(); ++e)
    if (needed[e]) M.discretise(static_cast<int>(e));
  std::vector<std::array<int, 4>> el;
  std::vector<int> part;
  SurfaceMesh out;
  int done = 0, total = 0;
  for (const Face& f : b.faces) total += f.keep;
  for (size_t fi = 0; fi < b.faces.size(); ++fi) {
    const Face& f = b.faces[fi];
    if (!f.keep) continue;
    const FaceLoop loop = face_loop(b, M, static_cast<int>(fi));
    if (loop.nodes.empty()) continue;
    auto mid = [&](int i) {
      LoopNode m = M.midpoint(loop.seg_of[i].first, loop.seg_of[i].second, static_cast<int>(fi));
      if (!f.g.surface) m.uv = f.g.locate(m.xyz, Vec2::Zero());
      return m;
    };
    const PatchMesh pm = mesh_patch(f.g, loop.nodes, o, mid);
    append_elements(pm, global_ids(M, pm), part_index(out.parts, f.name), el, part);
    if (progress) progress(++done, total, f.name);
  }
  if (outward) orient(el, M.nodes);
  compact(el, part, M.nodes, out);
  return out;
}

}  // namespace fairlines::meshing
