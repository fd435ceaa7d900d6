// Triangle-mesh utilities: ear clipping, orientation, volume, edge census, OBJ / STL.
#include "fairlines/mesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <queue>
#include <unordered_map>

#include <Eigen/Geometry>

#include "fairlines/errors.hpp"
#include "nurbs/checks.hpp"

namespace fairlines {

namespace {

std::uint64_t edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
         static_cast<std::uint32_t>(b);
}

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

/// Relative round-off allowance of the flip tests (in-circle determinant, convexity).
constexpr double kFlipTolerance = 1e-12;

}  // namespace

EdgeReport edge_report(const TriMesh& mesh) {
  EdgeReport r;
  // each face side as (undirected edge, +1 for an a < b traversal, -1 for a > b), sorted by
  // edge: a run of equal edges gives its count and the sum of its directions
  std::vector<std::pair<std::uint64_t, int>> sides;
  sides.reserve(static_cast<size_t>(mesh.faces.rows()) * 3);
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    const int a = mesh.faces(f, 0), b = mesh.faces(f, 1), c = mesh.faces(f, 2);
    if (a == b || b == c || a == c) ++r.degenerate_faces;
    const int tri[3] = {a, b, c};
    for (int k = 0; k < 3; ++k) {
      const int p = tri[k], q = tri[(k + 1) % 3];
      sides.emplace_back(edge_key(p, q), p < q ? 1 : -1);
    }
  }
  std::sort(sides.begin(), sides.end());
  for (size_t i = 0; i < sides.size();) {
    size_t j = i;
    int direction = 0;
    for (; j < sides.size() && sides[j].first == sides[i].first; ++j) direction += sides[j].second;
    ++r.edges;
    if (j - i == 1) ++r.open;
    else if (j - i > 2) ++r.non_manifold;
    else if (direction != 0) ++r.inconsistent;
    i = j;
  }
  return r;
}

namespace {

// Ear clipping of a simple polygon that clips, at each step, the best-shaped ear of the
// remaining polygon (largest area over the sum of squared sides; the first in polygon order
// among equals). Per vertex the triangle with its neighbours is kept with its convexity, score
// and the number of remaining vertices inside it: a clip changes the triangles of the two
// neighbours only, and for every other vertex it can only remove the clipped vertex from inside
// its triangle. That makes ear clipping O(n^2) instead of re-testing every vertex against every
// triangle at each step (O(n^3)), with the same choices, so the same triangles.
class EarClipper {
 public:
  EarClipper(std::vector<Eigen::Vector2d> p, const std::vector<char>& avoid)
      : p_(std::move(p)), avoid_(avoid), n_(static_cast<int>(p_.size())), idx_(n_), ta_(n_), tc_(n_),
        blockers_(n_, 0), convex_(n_), score_(n_, -1.0), candidate_(n_, 0) {
    double area2 = 0.0;
    for (int i = 0; i < n_; ++i) {
      const auto& a = p_[i];
      const auto& b = p_[(i + 1) % n_];
      area2 += a.x() * b.y() - a.y() * b.x();
    }
    sign_ = area2 >= 0.0 ? 1.0 : -1.0;  // work as if counter-clockwise
    for (int i = 0; i < n_; ++i) idx_[i] = i;
  }

  std::vector<std::array<int, 3>> run() {
    std::vector<std::array<int, 3>> out;
    out.reserve(n_ - 2);
    for (int k = 0; k < n_; ++k) measure(k);
    while (idx_.size() > 3) out.push_back(clip(best_ear()));
    out.push_back({idx_[0], idx_[1], idx_[2]});
    return out;
  }

 private:
  // Closed triangle test (points on an edge count as inside, which keeps ears honest).
  bool inside(const Eigen::Vector2d& q, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
              const Eigen::Vector2d& c) const {
    const double d1 = sign_ * cross2(a, b, q), d2 = sign_ * cross2(b, c, q), d3 = sign_ * cross2(c, a, q);
    return d1 >= 0.0 && d2 >= 0.0 && d3 >= 0.0;
  }

  // Does remaining vertex iq keep the triangle (ia, ib, ic) from being an ear? Vertices of the
  // triangle, and points that coincide with one of them, do not.
  bool blocks(int iq, int ia, int ib, int ic) const {
    if (iq == ia || iq == ib || iq == ic) return false;
    if (p_[iq] == p_[ia] || p_[iq] == p_[ib] || p_[iq] == p_[ic]) return false;
    return inside(p_[iq], p_[ia], p_[ib], p_[ic]);
  }

  // The triangle of the vertex at position k of the remaining polygon with its neighbours.
  void measure(int k) {
    const int m = static_cast<int>(idx_.size());
    const int ia = idx_[(k + m - 1) % m], ib = idx_[k], ic = idx_[(k + 1) % m];
    ta_[ib] = ia;
    tc_[ib] = ic;
    const double c = sign_ * cross2(p_[ia], p_[ib], p_[ic]);
    convex_[ib] = c;
    candidate_[ib] = c > 0.0 && !(!avoid_.empty() && avoid_[ia] && avoid_[ib] && avoid_[ic]);
    blockers_[ib] = 0;
    if (!candidate_[ib]) return;
    for (const int iq : idx_) blockers_[ib] += blocks(iq, ia, ib, ic);
    const double s = (p_[ia] - p_[ib]).squaredNorm() + (p_[ib] - p_[ic]).squaredNorm() + (p_[ic] - p_[ia]).squaredNorm();
    score_[ib] = c / s;
  }

  // Position of the ear to clip; in a numerically degenerate remainder, the most convex vertex.
  int best_ear() const {
    const int m = static_cast<int>(idx_.size());
    int best = -1;
    double best_score = -1.0;
    for (int k = 0; k < m; ++k) {
      const int ib = idx_[k];
      if (candidate_[ib] && blockers_[ib] == 0 && score_[ib] > best_score) best_score = score_[ib], best = k;
    }
    if (best >= 0) return best;
    double bc = -1e300;
    for (int k = 0; k < m; ++k)
      if (convex_[idx_[k]] > bc) bc = convex_[idx_[k]], best = k;
    return best;
  }

  // Clip the vertex at position best; update its neighbours' triangles and the others' blockers.
  std::array<int, 3> clip(int best) {
    const int m = static_cast<int>(idx_.size());
    const int x = idx_[best];
    const std::array<int, 3> tri{idx_[(best + m - 1) % m], x, idx_[(best + 1) % m]};
    idx_.erase(idx_.begin() + best);
    const int mm = m - 1;
    const int kp = (best + mm - 1) % mm, kn = best % mm;  // the clipped vertex's neighbours, now adjacent
    const int vp = idx_[kp], vn = idx_[kn];
    for (const int v : idx_)
      if (v != vp && v != vn && candidate_[v] && blocks(x, ta_[v], v, tc_[v])) --blockers_[v];
    if (mm > 3) {
      measure(kp);
      measure(kn);
    }
    return tri;
  }

  std::vector<Eigen::Vector2d> p_;
  const std::vector<char>& avoid_;
  int n_;
  double sign_ = 1.0;
  std::vector<int> idx_, ta_, tc_, blockers_;
  std::vector<double> convex_, score_;
  std::vector<char> candidate_;
};

}  // namespace

std::vector<std::array<int, 3>> triangulate_polygon(const Eigen::MatrixXd& points, const std::vector<char>& avoid) {
  const int n = static_cast<int>(points.rows());
  if (n < 3) detail::fail("polygon has ", n, " points; expected at least 3");
  if (points.cols() != 2) detail::fail("polygon has ", points.cols(), " columns; expected 2");
  detail::require_finite(points, "polygon");
  if (!avoid.empty() && static_cast<int>(avoid.size()) != n)
    detail::fail("avoid has ", avoid.size(), " flags; expected one per polygon point (", n, ")");
  std::vector<Eigen::Vector2d> p(n);
  for (int i = 0; i < n; ++i) p[i] = points.row(i).transpose();
  return EarClipper(std::move(p), avoid).run();
}

namespace {

/// Is d inside the circumcircle of the triangle (a, b, c) of orientation `sign`?
bool in_circumcircle(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                     const Eigen::Vector2d& d, double sign) {
  const Eigen::Vector2d p = a - d, q = b - d, r = c - d;
  const double det = p.squaredNorm() * (q.x() * r.y() - q.y() * r.x()) - q.squaredNorm() * (p.x() * r.y() - p.y() * r.x()) +
                     r.squaredNorm() * (p.x() * q.y() - p.y() * q.x());
  // det is of length^4: the allowance scales with |p| |q| |r| max(|p|, |q|, |r|)
  const double scale = std::sqrt(p.squaredNorm() * q.squaredNorm() * r.squaredNorm()) *
                       std::sqrt(std::max({p.squaredNorm(), q.squaredNorm(), r.squaredNorm()}));
  return sign * det > kFlipTolerance * scale;
}

/// Do the angles at c and d opposite the edge a-b of the triangles (a, b, c), (b, a, d) sum to
/// more than pi in space (the edge is not Delaunay on the surface the triangles sample)?
bool opposite_angles_exceed_pi(const Eigen::MatrixXd& X, int a, int b, int c, int d) {
  auto angle = [&](int at, int p, int q) {
    const Eigen::Vector3d u = X.row(p) - X.row(at), v = X.row(q) - X.row(at);
    return std::atan2(u.cross(v).norm(), u.dot(v));
  };
  return angle(c, a, b) + angle(d, a, b) > M_PI * (1.0 + kFlipTolerance);
}

void check_flip_inputs(const Eigen::MatrixXd& points, const std::vector<std::array<int, 3>>& tris,
                       const std::vector<char>& avoid, const Eigen::MatrixXd& positions) {
  const int n = static_cast<int>(points.rows());
  if (points.cols() != 2) detail::fail("polygon has ", points.cols(), " columns; expected 2");
  if (!avoid.empty() && static_cast<int>(avoid.size()) != n)
    detail::fail("avoid has ", avoid.size(), " flags; expected one per polygon point (", n, ")");
  if (positions.rows() != 0 && (positions.rows() != n || positions.cols() != 3))
    detail::fail("positions has shape (", positions.rows(), ", ", positions.cols(), "); expected (", n, ", 3) or empty");
  for (const auto& t : tris)
    for (int v : t)
      if (v < 0 || v >= n) detail::fail("a triangle has vertex ", v, "; expected 0 to ", n - 1);
}

}  // namespace

void delaunay_flips(const Eigen::MatrixXd& points, std::vector<std::array<int, 3>>& tris, const std::vector<char>& avoid,
                    const Eigen::MatrixXd& positions) {
  check_flip_inputs(points, tris, avoid, positions);
  const int n = static_cast<int>(points.rows());
  auto pt = [&](int i) { return Eigen::Vector2d(points(i, 0), points(i, 1)); };
  auto area2 = [&](int a, int b, int c) { return cross2(pt(a), pt(b), pt(c)); };
  auto all_avoided = [&](int a, int b, int c) { return !avoid.empty() && avoid[a] && avoid[b] && avoid[c]; };
  double total = 0.0;  // the polygon's orientation: the sign of its area
  for (const auto& t : tris) total += area2(t[0], t[1], t[2]);
  const double sign = total >= 0.0 ? 1.0 : -1.0;
  // Flip the diagonal a-b of the quad a d b c to c-d? A flat triangle (collinear boundary
  // points) goes whenever the other diagonal gives two proper ones; two proper ones only when
  // the edge is not Delaunay. The quad must be strictly convex (both new triangles keep the
  // orientation), and no new triangle may have three avoided vertices.
  auto flips = [&](int a, int b, int c, int d) {
    const bool flat = sign * area2(a, b, c) <= 0.0 || sign * area2(b, a, d) <= 0.0;
    if (!flat && !(positions.rows() ? opposite_angles_exceed_pi(positions, a, b, c, d)
                                    : in_circumcircle(pt(a), pt(b), pt(c), pt(d), sign)))
      return false;
    const double n1 = sign * area2(a, d, c), n2 = sign * area2(d, b, c);
    const double tol = kFlipTolerance * (std::abs(n1) + std::abs(n2));
    return n1 > tol && n2 > tol && !all_avoided(a, d, c) && !all_avoided(d, b, c);
  };
  std::unordered_map<std::uint64_t, std::vector<int>> on_edge;
  auto link = [&](int t, bool add) {
    for (int k = 0; k < 3; ++k) {
      auto& v = on_edge[edge_key(tris[t][k], tris[t][(k + 1) % 3])];
      if (add) v.push_back(t);
      else v.erase(std::remove(v.begin(), v.end(), t), v.end());
    }
  };
  for (int t = 0; t < static_cast<int>(tris.size()); ++t) link(t, true);
  std::vector<std::uint64_t> stack;
  for (const auto& [e, ts] : on_edge)
    if (ts.size() == 2) stack.push_back(e);
  const long budget = 8L * n * n + 64;  // Lawson's flips end; this only bounds round-off cycling
  for (long step = 0; !stack.empty() && step < budget; ++step) {
    const std::uint64_t e = stack.back();
    stack.pop_back();
    const auto& ts = on_edge[e];
    if (ts.size() != 2) continue;
    const int t1 = ts[0], t2 = ts[1];
    int k1 = 0;  // t1 = (a, b, c) with a -> b the shared edge
    while (edge_key(tris[t1][k1], tris[t1][(k1 + 1) % 3]) != e) ++k1;
    const int a = tris[t1][k1], b = tris[t1][(k1 + 1) % 3], c = tris[t1][(k1 + 2) % 3];
    int d = -1;
    for (int v : tris[t2])
      if (v != a && v != b) d = v;
    if (d < 0 || !flips(a, b, c, d)) continue;
    link(t1, false);
    link(t2, false);
    tris[t1] = {a, d, c};
    tris[t2] = {d, b, c};
    link(t1, true);
    link(t2, true);
    for (const auto& [p, q] : {std::pair{a, d}, std::pair{d, b}, std::pair{b, c}, std::pair{c, a}}) stack.push_back(edge_key(p, q));
  }
}

namespace {

/// The sum over the faces of term(a, b, c), the face's corners in their order (metres).
template <typename Term>
double sum_over_faces(const TriMesh& mesh, Term term) {
  double s = 0.0;
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    const Eigen::Vector3d a = mesh.vertices.row(mesh.faces(f, 0));
    const Eigen::Vector3d b = mesh.vertices.row(mesh.faces(f, 1));
    const Eigen::Vector3d c = mesh.vertices.row(mesh.faces(f, 2));
    s += term(a, b, c);
  }
  return s;
}

}  // namespace

double mesh_volume(const TriMesh& mesh) {
  const auto six_tetra_volume = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    return a.dot(b.cross(c));
  };
  return sum_over_faces(mesh, six_tetra_volume) / 6.0;
}

double mesh_area(const TriMesh& mesh) {
  const auto area = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    return 0.5 * (b - a).cross(c - a).norm();
  };
  return sum_over_faces(mesh, area);
}

namespace {

/// The faces on each undirected edge of a triangle mesh: (edge, face, side) sorted, then each
/// face side's run of equal edges (one sort instead of a hash map of vectors). Sides are found
/// by their edge, so the table stays valid while faces are flipped.
class EdgeFaces {
 public:
  explicit EdgeFaces(const TriMesh& mesh) : sides_(static_cast<size_t>(mesh.faces.rows()) * 3) {
    for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f)
      for (int k = 0; k < 3; ++k)
        sides_[f * 3 + k] = {edge_key(mesh.faces(f, k), mesh.faces(f, (k + 1) % 3)), static_cast<int>(f), k};
    std::sort(sides_.begin(), sides_.end(), [](const Side& x, const Side& y) {
      return x.edge != y.edge ? x.edge < y.edge : x.face != y.face ? x.face < y.face : x.side < y.side;
    });
    run_of_.resize(sides_.size());
    for (size_t i = 0; i < sides_.size();) {
      size_t j = i;
      while (j < sides_.size() && sides_[j].edge == sides_[i].edge) ++j;
      for (size_t r = i; r < j; ++r)
        run_of_[static_cast<size_t>(sides_[r].face) * 3 + sides_[r].side] = {static_cast<int>(i), static_cast<int>(j - i)};
      i = j;
    }
    side_edge_.resize(sides_.size());
    for (const Side& x : sides_) side_edge_[static_cast<size_t>(x.face) * 3 + x.side] = x.edge;
  }

  /// The other face on the edge (a, b) of face f when exactly two faces share it, else -1.
  int across(int f, int a, int b) const {
    const std::uint64_t e = edge_key(a, b);
    int k = 0;
    while (k < 2 && side_edge_[static_cast<size_t>(f) * 3 + k] != e) ++k;
    const auto [first, count] = run_of_[static_cast<size_t>(f) * 3 + k];
    if (count != 2) return -1;
    return sides_[first].face == f ? sides_[first + 1].face : sides_[first].face;
  }

 private:
  struct Side {
    std::uint64_t edge;
    int face, side;
  };
  std::vector<Side> sides_;
  std::vector<std::pair<int, int>> run_of_;  // (first, count) in sides_ of each face side's edge
  std::vector<std::uint64_t> side_edge_;     // the edge of each face side as first listed
};

/// Does face f traverse a -> b?
bool traverses(const TriMesh& mesh, int f, int a, int b) {
  for (int k = 0; k < 3; ++k)
    if (mesh.faces(f, k) == a && mesh.faces(f, (k + 1) % 3) == b) return true;
  return false;
}

}  // namespace

long orient_consistently(TriMesh& mesh) {
  const Eigen::Index m = mesh.faces.rows();
  const EdgeFaces edges(mesh);
  // breadth first over each connected component: a neighbour traversing a shared edge the
  // same way is flipped
  std::vector<char> seen(m, 0);
  long flips = 0;
  for (Eigen::Index start = 0; start < m; ++start) {
    if (seen[start]) continue;
    seen[start] = 1;
    std::queue<int> q;
    q.push(static_cast<int>(start));
    while (!q.empty()) {
      const int f = q.front();
      q.pop();
      for (int k = 0; k < 3; ++k) {
        const int a = mesh.faces(f, k), b = mesh.faces(f, (k + 1) % 3);
        const int g = edges.across(f, a, b);
        if (g < 0 || seen[g]) continue;
        seen[g] = 1;
        if (traverses(mesh, g, a, b)) {
          std::swap(mesh.faces(g, 1), mesh.faces(g, 2));
          ++flips;
        }
        q.push(g);
      }
    }
  }
  if (mesh_volume(mesh) < 0.0) {
    for (Eigen::Index f = 0; f < m; ++f) std::swap(mesh.faces(f, 1), mesh.faces(f, 2));
    flips = m - flips;
  }
  return flips;
}

EdgeReport orient_if_needed(TriMesh& mesh) {
  EdgeReport r = edge_report(mesh);
  if (r.inconsistent || r.non_manifold || r.degenerate_faces) {
    orient_consistently(mesh);
    return edge_report(mesh);
  }
  // every two-face edge already consistent: the breadth-first pass would flip nothing
  if (mesh_volume(mesh) < 0.0)
    for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) std::swap(mesh.faces(f, 1), mesh.faces(f, 2));
  return r;
}

void write_obj(const TriMesh& mesh, const std::string& path) {
  std::ofstream os(path);
  if (!os) throw InvalidInput("cannot open '" + path + "' for writing; expected a path in a writable folder");
  os.precision(10);
  os << "# Fairlines composed hull: " << mesh.vertices.rows() << " vertices, " << mesh.faces.rows()
     << " faces (metres)\n";
  for (Eigen::Index i = 0; i < mesh.vertices.rows(); ++i)
    os << "v " << mesh.vertices(i, 0) << ' ' << mesh.vertices(i, 1) << ' ' << mesh.vertices(i, 2) << '\n';
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f)
    os << "f " << mesh.faces(f, 0) + 1 << ' ' << mesh.faces(f, 1) + 1 << ' ' << mesh.faces(f, 2) + 1 << '\n';
  if (!os) throw InvalidInput("failed writing '" + path + "'; expected a disk with room for it");
}

void write_stl(const TriMesh& mesh, const std::string& path, bool binary) {
  std::ofstream os(path, binary ? std::ios::binary : std::ios::out);
  if (!os) throw InvalidInput("cannot open '" + path + "' for writing; expected a path in a writable folder");
  auto facet = [&](Eigen::Index f, Eigen::Vector3d& n, Eigen::Vector3d (&v)[3]) {
    for (int k = 0; k < 3; ++k) v[k] = mesh.vertices.row(mesh.faces(f, k)).transpose();
    n = (v[1] - v[0]).cross(v[2] - v[0]);
    const double len = n.norm();
    if (len > 0.0) n /= len;
  };
  if (binary) {
    char header[80];
    std::memset(header, 0, sizeof header);
    std::strncpy(header, "Fairlines composed hull (metres)", sizeof header - 1);
    os.write(header, 80);
    const std::uint32_t count = static_cast<std::uint32_t>(mesh.faces.rows());
    os.write(reinterpret_cast<const char*>(&count), 4);
    for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
      Eigen::Vector3d n, v[3];
      facet(f, n, v);
      float buf[12];
      for (int k = 0; k < 3; ++k) buf[k] = static_cast<float>(n[k]);
      for (int t = 0; t < 3; ++t)
        for (int k = 0; k < 3; ++k) buf[3 + 3 * t + k] = static_cast<float>(v[t][k]);
      os.write(reinterpret_cast<const char*>(buf), sizeof buf);
      const std::uint16_t attr = 0;
      os.write(reinterpret_cast<const char*>(&attr), 2);
    }
  } else {
    os.precision(9);
    os << "solid fairlines\n";
    for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
      Eigen::Vector3d n, v[3];
      facet(f, n, v);
      os << " facet normal " << n[0] << ' ' << n[1] << ' ' << n[2] << "\n  outer loop\n";
      for (int t = 0; t < 3; ++t) os << "   vertex " << v[t][0] << ' ' << v[t][1] << ' ' << v[t][2] << '\n';
      os << "  endloop\n endfacet\n";
    }
    os << "endsolid fairlines\n";
  }
  if (!os) throw InvalidInput("failed writing '" + path + "'; expected a disk with room for it");
}

}  // namespace fairlines
