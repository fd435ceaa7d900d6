// Triangle-mesh utilities: ear clipping, orientation, volume, edge census, OBJ / STL.
#include "fairlines/mesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
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

}  // namespace

EdgeReport edge_report(const TriMesh& mesh) {
  EdgeReport r;
  // per undirected edge: count, and the sum of +1 (a<b traversal) / -1 (a>b)
  std::unordered_map<std::uint64_t, std::pair<int, int>> edges;
  edges.reserve(static_cast<size_t>(mesh.faces.rows()) * 2);
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    int a = mesh.faces(f, 0), b = mesh.faces(f, 1), c = mesh.faces(f, 2);
    if (a == b || b == c || a == c) ++r.degenerate_faces;
    const int tri[3] = {a, b, c};
    for (int k = 0; k < 3; ++k) {
      int p = tri[k], q = tri[(k + 1) % 3];
      auto& e = edges[edge_key(p, q)];
      e.first += 1;
      e.second += p < q ? 1 : -1;
    }
  }
  r.edges = static_cast<long>(edges.size());
  for (const auto& [key, e] : edges) {
    if (e.first == 1) ++r.open;
    else if (e.first > 2) ++r.non_manifold;
    else if (e.second != 0) ++r.inconsistent;
  }
  return r;
}

std::vector<std::array<int, 3>> triangulate_polygon(const Eigen::MatrixXd& points, const std::vector<char>& avoid) {
  const int n = static_cast<int>(points.rows());
  if (n < 3) detail::fail("polygon has ", n, " points; expected at least 3");
  if (points.cols() != 2) detail::fail("polygon has ", points.cols(), " columns; expected 2");
  detail::require_finite(points, "polygon");
  if (!avoid.empty() && static_cast<int>(avoid.size()) != n)
    detail::fail("avoid has ", avoid.size(), " flags; expected one per polygon point (", n, ")");
  std::vector<Eigen::Vector2d> p(n);
  for (int i = 0; i < n; ++i) p[i] = points.row(i).transpose();
  double area2 = 0.0;
  for (int i = 0; i < n; ++i) {
    const auto& a = p[i];
    const auto& b = p[(i + 1) % n];
    area2 += a.x() * b.y() - a.y() * b.x();
  }
  const double sign = area2 >= 0.0 ? 1.0 : -1.0;  // work as if counter-clockwise
  std::vector<int> idx(n);
  for (int i = 0; i < n; ++i) idx[i] = i;
  std::vector<std::array<int, 3>> out;
  out.reserve(n - 2);
  auto inside = [&](const Eigen::Vector2d& q, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                    const Eigen::Vector2d& c) {
    // closed triangle test (points on an edge count as inside, which keeps ears honest)
    const double d1 = sign * cross2(a, b, q), d2 = sign * cross2(b, c, q), d3 = sign * cross2(c, a, q);
    return d1 >= 0.0 && d2 >= 0.0 && d3 >= 0.0;
  };
  // Does remaining vertex iq keep the triangle (ia, ib, ic) from being an ear? Vertices of the
  // triangle, and points that coincide with one of them, do not.
  auto blocks = [&](int iq, int ia, int ib, int ic) {
    if (iq == ia || iq == ib || iq == ic) return false;
    if (p[iq] == p[ia] || p[iq] == p[ib] || p[iq] == p[ic]) return false;
    return inside(p[iq], p[ia], p[ib], p[ic]);
  };
  // Each step clips the best-shaped ear of the remaining polygon (largest area over the sum of
  // squared sides; the first in polygon order among equals). Per vertex the triangle with its
  // neighbours is kept with its convexity, score and the number of remaining vertices inside
  // it: a clip changes the triangles of the two neighbours only, and for every other vertex it
  // can only remove the clipped vertex from inside its triangle. That makes ear clipping
  // O(n^2) instead of re-testing every vertex against every triangle at each step (O(n^3)),
  // with the same choices, so the same triangles.
  std::vector<int> ta(n), tc(n), blockers(n, 0);
  std::vector<double> convex(n), score(n, -1.0);
  std::vector<char> candidate(n, 0);
  auto measure = [&](int k) {
    const int m = static_cast<int>(idx.size());
    const int ia = idx[(k + m - 1) % m], ib = idx[k], ic = idx[(k + 1) % m];
    ta[ib] = ia;
    tc[ib] = ic;
    const double c = sign * cross2(p[ia], p[ib], p[ic]);
    convex[ib] = c;
    candidate[ib] = c > 0.0 && !(!avoid.empty() && avoid[ia] && avoid[ib] && avoid[ic]);
    blockers[ib] = 0;
    if (!candidate[ib]) return;
    for (const int iq : idx) blockers[ib] += blocks(iq, ia, ib, ic);
    const double s = (p[ia] - p[ib]).squaredNorm() + (p[ib] - p[ic]).squaredNorm() + (p[ic] - p[ia]).squaredNorm();
    score[ib] = c / s;
  };
  for (int k = 0; k < n; ++k) measure(k);
  while (idx.size() > 3) {
    const int m = static_cast<int>(idx.size());
    int best = -1;
    double best_score = -1.0;
    for (int k = 0; k < m; ++k) {
      const int ib = idx[k];
      if (!candidate[ib] || blockers[ib] != 0) continue;
      if (score[ib] > best_score) {
        best_score = score[ib];
        best = k;
      }
    }
    if (best < 0) {
      // numerically degenerate remainder: clip the most convex vertex
      double bc = -1e300;
      for (int k = 0; k < m; ++k)
        if (convex[idx[k]] > bc) {
          bc = convex[idx[k]];
          best = k;
        }
    }
    const int x = idx[best];
    out.push_back({idx[(best + m - 1) % m], x, idx[(best + 1) % m]});
    idx.erase(idx.begin() + best);
    const int mm = m - 1;
    const int kp = (best + mm - 1) % mm, kn = best % mm;  // the clipped vertex's neighbours, now adjacent
    const int vp = idx[kp], vn = idx[kn];
    for (const int v : idx)
      if (v != vp && v != vn && candidate[v] && blocks(x, ta[v], v, tc[v])) --blockers[v];
    if (mm > 3) {
      measure(kp);
      measure(kn);
    }
  }
  out.push_back({idx[0], idx[1], idx[2]});
  return out;
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

long orient_consistently(TriMesh& mesh) {
  const Eigen::Index m = mesh.faces.rows();
  // The faces on each undirected edge, in face order: (edge, face, side) sorted, then each
  // face side's run of equal edges (one sort instead of a hash map of vectors).
  struct Side {
    std::uint64_t edge;
    int face, side;
  };
  std::vector<Side> sides(static_cast<size_t>(m) * 3);
  for (Eigen::Index f = 0; f < m; ++f)
    for (int k = 0; k < 3; ++k)
      sides[f * 3 + k] = {edge_key(mesh.faces(f, k), mesh.faces(f, (k + 1) % 3)), static_cast<int>(f), k};
  std::sort(sides.begin(), sides.end(), [](const Side& x, const Side& y) {
    return x.edge != y.edge ? x.edge < y.edge : x.face != y.face ? x.face < y.face : x.side < y.side;
  });
  std::vector<std::pair<int, int>> run_of(sides.size());  // (first, count) in sides of each face side's edge
  for (size_t i = 0; i < sides.size();) {
    size_t j = i;
    while (j < sides.size() && sides[j].edge == sides[i].edge) ++j;
    for (size_t r = i; r < j; ++r)
      run_of[static_cast<size_t>(sides[r].face) * 3 + sides[r].side] = {static_cast<int>(i), static_cast<int>(j - i)};
    i = j;
  }
  // A flipped face lists its edges in another order: find the side by its edge.
  std::vector<std::uint64_t> side_edge(sides.size());
  for (const Side& x : sides) side_edge[static_cast<size_t>(x.face) * 3 + x.side] = x.edge;
  auto edge_run = [&](int f, std::uint64_t e) {
    int k = 0;
    while (k < 2 && side_edge[static_cast<size_t>(f) * 3 + k] != e) ++k;
    return run_of[static_cast<size_t>(f) * 3 + k];
  };
  auto directed = [&](int f, int a, int b) {  // does face f traverse a -> b ?
    for (int k = 0; k < 3; ++k)
      if (mesh.faces(f, k) == a && mesh.faces(f, (k + 1) % 3) == b) return true;
    return false;
  };
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
        const auto [first, count] = edge_run(f, edge_key(a, b));
        if (count != 2) continue;
        const int g = sides[first].face == f ? sides[first + 1].face : sides[first].face;
        if (seen[g]) continue;
        seen[g] = 1;
        if (directed(g, a, b)) {  // same direction: flip g
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

void write_obj(const TriMesh& mesh, const std::string& path) {
  std::ofstream os(path);
  if (!os) throw Error("cannot open '" + path + "' for writing");
  os.precision(10);
  os << "# Fairlines composed hull: " << mesh.vertices.rows() << " vertices, " << mesh.faces.rows()
     << " faces (metres)\n";
  for (Eigen::Index i = 0; i < mesh.vertices.rows(); ++i)
    os << "v " << mesh.vertices(i, 0) << ' ' << mesh.vertices(i, 1) << ' ' << mesh.vertices(i, 2) << '\n';
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f)
    os << "f " << mesh.faces(f, 0) + 1 << ' ' << mesh.faces(f, 1) + 1 << ' ' << mesh.faces(f, 2) + 1 << '\n';
  if (!os) throw Error("failed writing '" + path + "'");
}

void write_stl(const TriMesh& mesh, const std::string& path, bool binary) {
  std::ofstream os(path, binary ? std::ios::binary : std::ios::out);
  if (!os) throw Error("cannot open '" + path + "' for writing");
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
  if (!os) throw Error("failed writing '" + path + "'");
}

}  // namespace fairlines
