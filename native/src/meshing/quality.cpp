// Element quality of a mixed quad / triangle mesh (scaled Jacobian after Knupp 2000).
#include <algorithm>
#include <cmath>
#include <map>
#include <unordered_map>

#include <Eigen/Geometry>

#include "fairlines/meshing.hpp"
#include "meshing/patch.hpp"

namespace fairlines {

namespace {

using Vec3 = Eigen::Vector3d;

constexpr double kDuplicate = 1e-9;  ///< nodes closer than this x mesh size count as duplicates

int corners(const SurfaceMesh& m, Eigen::Index f) { return m.faces(f, 3) < 0 ? 3 : 4; }

Vec3 element_normal(const SurfaceMesh& m, Eigen::Index f) {
  auto P = [&](int k) { return Vec3(m.vertices.row(m.faces(f, k))); };
  const Vec3 n = corners(m, f) == 4 ? Vec3((P(2) - P(0)).cross(P(3) - P(1))) : Vec3((P(1) - P(0)).cross(P(2) - P(0)));
  const double len = n.norm();
  return len > 0 ? Vec3(n / len) : n;
}

}  // namespace

Eigen::VectorXd scaled_jacobians(const SurfaceMesh& m) {
  Eigen::VectorXd q(m.faces.rows());
  for (Eigen::Index f = 0; f < m.faces.rows(); ++f) {
    Vec3 p[4];
    const int k = corners(m, f);
    for (int c = 0; c < k; ++c) p[c] = m.vertices.row(m.faces(f, c));
    q[f] = meshing::element_quality(p, k, element_normal(m, f));
  }
  return q;
}

namespace {

// Element counts, corner angles (deg) and edge lengths (m) into r; sj: each face's scaled Jacobian.
void measure_elements(const SurfaceMesh& m, const Eigen::VectorXd& sj, MeshQuality& r) {
  long quad_corners = 0, good = 0;
  r.min_angle_deg = 360;
  r.max_angle_deg = 0;
  r.min_edge = 1e300;
  for (Eigen::Index f = 0; f < m.faces.rows(); ++f) {
    const int k = corners(m, f);
    (k == 4 ? r.quads : r.triangles)++;
    if (sj[f] <= 0) ++r.inverted;
    for (int c = 0; c < k; ++c) {
      const Vec3 a = m.vertices.row(m.faces(f, c)), b = m.vertices.row(m.faces(f, (c + 1) % k)),
                 d = m.vertices.row(m.faces(f, (c + k - 1) % k));
      const double ang = std::acos(std::clamp((b - a).normalized().dot((d - a).normalized()), -1.0, 1.0)) * 180 / M_PI;
      r.min_angle_deg = std::min(r.min_angle_deg, ang);
      r.max_angle_deg = std::max(r.max_angle_deg, ang);
      if (k == 4) {
        ++quad_corners;
        if (ang >= 45 && ang <= 135) ++good;
      }
      const double len = (b - a).norm();
      r.min_edge = std::min(r.min_edge, len);
      r.max_edge = std::max(r.max_edge, len);
    }
  }
  r.corners_in_45_135 = quad_corners ? static_cast<double>(good) / quad_corners : 1.0;
}

// Open, non-manifold and misoriented edges into r: each undirected edge's uses and the sum of
// its directions (a consistently oriented interior edge is used once each way).
void count_edges(const SurfaceMesh& m, MeshQuality& r) {
  std::unordered_map<long long, std::pair<int, int>> edges;  // count, direction sum
  const long long N = m.vertices.rows() + 1;
  for (Eigen::Index f = 0; f < m.faces.rows(); ++f) {
    const int k = corners(m, f);
    for (int c = 0; c < k; ++c) {
      const int i = m.faces(f, c), j = m.faces(f, (c + 1) % k);
      auto& e = edges[std::min(i, j) * N + std::max(i, j)];
      e.first++;
      e.second += i < j ? 1 : -1;
    }
  }
  for (const auto& [key, e] : edges) {
    if (e.first == 1) ++r.open_edges;
    else if (e.first > 2) ++r.non_manifold_edges;
    else if (e.second != 0) ++r.misoriented_edges;
  }
}

// Nodes within kDuplicate x the mesh's size of another, found in a grid of cells that size.
long duplicate_nodes(const SurfaceMesh& m) {
  const double size = (m.vertices.colwise().maxCoeff() - m.vertices.colwise().minCoeff()).norm();
  const double cell = std::max(kDuplicate * size, 1e-300);
  std::map<std::array<long long, 3>, std::vector<Eigen::Index>> grid;
  for (Eigen::Index i = 0; i < m.vertices.rows(); ++i) {
    std::array<long long, 3> key;
    for (int c = 0; c < 3; ++c) key[c] = static_cast<long long>(std::floor(m.vertices(i, c) / cell));
    grid[key].push_back(i);
  }
  long count = 0;
  for (const auto& [key, ids] : grid) {
    bool dup = ids.size() > 1;
    for (int dx = -1; dx <= 1 && !dup; ++dx)
      for (int dy = -1; dy <= 1 && !dup; ++dy)
        for (int dz = -1; dz <= 1 && !dup; ++dz) {
          if (!dx && !dy && !dz) continue;
          auto it = grid.find({key[0] + dx, key[1] + dy, key[2] + dz});
          if (it == grid.end()) continue;
          for (Eigen::Index a : ids)
            for (Eigen::Index b : it->second)
              if ((m.vertices.row(a) - m.vertices.row(b)).norm() <= cell) dup = true;
        }
    if (dup) count += static_cast<long>(ids.size());
  }
  return count;
}

}  // namespace

MeshQuality mesh_quality(const SurfaceMesh& m) {
  MeshQuality r;
  const Eigen::VectorXd sj = scaled_jacobians(m);
  if (m.faces.rows() == 0) return r;
  r.min_scaled_jacobian = sj.minCoeff();
  r.mean_scaled_jacobian = sj.mean();
  measure_elements(m, sj, r);
  count_edges(m, r);
  r.duplicate_nodes = duplicate_nodes(m);
  return r;
}

}  // namespace fairlines
