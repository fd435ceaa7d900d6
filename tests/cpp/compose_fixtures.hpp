// Analytic stand-ins for the composition tests: a Wigley-type forebody and a Panamax-like
// ship's particulars, plus mesh checks written independently of the engine's own.
#pragma once

#include <array>
#include <cmath>
#include <map>
#include <set>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "fairlines/bulb.hpp"
#include "fairlines/fitting.hpp"
#include "fairlines/mesh.hpp"

namespace fairlines::test {

/// Forebody from midship (x = L/2) to FP (x = L): y = B/2 (1 - xi^4) (1 - (1 - z/D)^6),
/// xi = (x - L/2) / (L/2); y = 0 on the keel and along the vertical stem at FP.
struct Forebody {
  double L = 244.8, B = 32.25, T = 11.0, D = 19.0;
  double y(double x, double z) const {
    const double xi = (x - 0.5 * L) / (0.5 * L);
    return 0.5 * B * (1.0 - std::pow(xi, 4)) * (1.0 - std::pow(1.0 - z / D, 6));
  }
  NurbsSurface surface(int rows = 41, int cols = 25) const {
    Eigen::MatrixXd g(rows * cols, 3);
    for (int r = 0; r < rows; ++r)
      for (int c = 0; c < cols; ++c) {
        const double x = 0.5 * L + 0.5 * L * (1.0 - std::cos(M_PI * 0.5 * r / (rows - 1)));
        const double z = D * (1.0 - std::cos(M_PI * 0.5 * c / (cols - 1)));
        g.row(r * cols + c) << x, y(x, z), z;
      }
    FitOptions ou, ov;
    ou.n_control = 16;
    ov.n_control = 12;
    return fit_surface(g, rows, cols, ou, ov).surface;
  }
  ShipParticulars ship() const {
    ShipParticulars s;
    s.lpp = L;
    s.beam = B;
    s.draft_fp = T;
    s.midship_area = 0.97 * B * T;
    s.displacement_volume = 0.65 * L * B * T;
    return s;
  }
};

struct MeshCheck {
  long open = 0, non_manifold = 0, misoriented = 0;
};

/// Independent edge census: sorted undirected edges counted, directed edges compared.
inline MeshCheck check_edges(const TriMesh& m) {
  std::map<std::pair<int, int>, int> und;
  std::map<std::pair<int, int>, int> dir;
  for (Eigen::Index f = 0; f < m.faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = m.faces(f, k), b = m.faces(f, (k + 1) % 3);
      und[{std::min(a, b), std::max(a, b)}]++;
      dir[{a, b}]++;
    }
  MeshCheck c;
  for (const auto& [e, n] : und) {
    if (n == 1) ++c.open;
    if (n > 2) ++c.non_manifold;
  }
  for (const auto& [e, n] : dir)
    if (n > 1) ++c.misoriented;  // the same directed edge twice: neighbours disagree
  return c;
}

/// Triangle-triangle intersection by edge-against-triangle segment tests (Moller-Trumbore
/// style), on non-adjacent pairs whose boxes overlap (uniform-grid broad phase).
inline bool segment_hits_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& a,
                                  const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d d = q - p, e1 = b - a, e2 = c - a;
  const Eigen::Vector3d h = d.cross(e2);
  const double det = e1.dot(h);
  const double scale = e1.norm() * e2.norm() * d.norm();
  if (std::abs(det) < 1e-12 * scale) return false;  // parallel: treated as no crossing
  const double f = 1.0 / det;
  const Eigen::Vector3d s = p - a;
  const double u = f * s.dot(h);
  if (u < 1e-9 || u > 1.0 - 1e-9) return false;
  const Eigen::Vector3d qq = s.cross(e1);
  const double v = f * d.dot(qq);
  if (v < 1e-9 || u + v > 1.0 - 1e-9) return false;
  const double t = f * e2.dot(qq);
  return t > 1e-9 && t < 1.0 - 1e-9;
}

inline long count_self_intersections(const TriMesh& m) {
  const Eigen::Index nf = m.faces.rows();
  std::vector<Eigen::Vector3d> lo(nf), hi(nf);
  Eigen::Vector3d glo = m.vertices.colwise().minCoeff().transpose(), ghi = m.vertices.colwise().maxCoeff().transpose();
  for (Eigen::Index f = 0; f < nf; ++f) {
    lo[f] = hi[f] = m.vertices.row(m.faces(f, 0)).transpose();
    for (int k = 1; k < 3; ++k) {
      lo[f] = lo[f].cwiseMin(m.vertices.row(m.faces(f, k)).transpose());
      hi[f] = hi[f].cwiseMax(m.vertices.row(m.faces(f, k)).transpose());
    }
  }
  const int G = 48;
  const Eigen::Vector3d cell = (ghi - glo) / G + Eigen::Vector3d::Constant(1e-9);
  std::map<std::array<int, 3>, std::vector<int>> grid;
  for (Eigen::Index f = 0; f < nf; ++f) {
    Eigen::Array3i a = ((lo[f] - glo).array() / cell.array()).floor().cast<int>();
    Eigen::Array3i b = ((hi[f] - glo).array() / cell.array()).floor().cast<int>();
    for (int i = a[0]; i <= b[0]; ++i)
      for (int j = a[1]; j <= b[1]; ++j)
        for (int k = a[2]; k <= b[2]; ++k) grid[{i, j, k}].push_back(static_cast<int>(f));
  }
  std::set<std::pair<int, int>> hits, tested;
  for (const auto& [key, fs] : grid)
    for (size_t x = 0; x < fs.size(); ++x)
      for (size_t y = x + 1; y < fs.size(); ++y) {
        const int f = std::min(fs[x], fs[y]), g = std::max(fs[x], fs[y]);
        if (!tested.insert({f, g}).second) continue;
        bool share = false;
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b) share |= m.faces(f, a) == m.faces(g, b);
        if (share) continue;
        if ((lo[f].array() > hi[g].array()).any() || (lo[g].array() > hi[f].array()).any()) continue;
        auto V = [&](int face, int k) { return Eigen::Vector3d(m.vertices.row(m.faces(face, k)).transpose()); };
        bool hit = false;
        for (int k = 0; k < 3 && !hit; ++k) {
          hit = segment_hits_triangle(V(f, k), V(f, (k + 1) % 3), V(g, 0), V(g, 1), V(g, 2)) ||
                segment_hits_triangle(V(g, k), V(g, (k + 1) % 3), V(f, 0), V(f, 1), V(f, 2));
        }
        if (hit) hits.insert({f, g});
      }
  return static_cast<long>(hits.size());
}

}  // namespace fairlines::test
