// Constrained Delaunay triangulation by ear clipping and Lawson flips (Lawson 1977; de Berg
// et al., Computational Geometry, ch. 9), see triangulation.hpp.
#include "meshing/triangulation.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "fairlines/errors.hpp"
#include "fairlines/mesh.hpp"

namespace fairlines::meshing {

namespace {

/// Relative size below which an orientation counts as zero (points on a line).
constexpr double kCollinear = 1e-12;
/// Rounds of flips Triangulation::enforce tries (each flips every convex crossing edge).
constexpr int kEnforceRounds = 8;

// a triangle's next and previous corner (k in 0..2): the hot loops' % 3 was a multiply each
constexpr int next3(int k) { return k == 2 ? 0 : k + 1; }
constexpr int prev3(int k) { return k == 0 ? 2 : k - 1; }

}  // namespace

Triangulation::Triangulation(std::vector<Eigen::Vector2d> points, const std::vector<int>& loop) : p_(std::move(points)) {
  const int m = static_cast<int>(loop.size());
  loop_size_ = m;
  if (m < 3) throw InvalidInput("triangulation: a boundary loop needs at least 3 points");
  Eigen::Vector2d lo = p_[loop[0]], hi = lo;
  for (int i : loop) {
    lo = lo.cwiseMin(p_[i]);
    hi = hi.cwiseMax(p_[i]);
  }
  scale_ = std::max((hi - lo).norm(), 1e-300);
  circle_eps_ = kCollinear * scale_ * scale_ * scale_ * scale_;
  Eigen::MatrixXd poly(m, 2);
  for (int i = 0; i < m; ++i) poly.row(i) = p_[loop[i]].transpose();
  double area2 = 0.0;
  for (int i = 0; i < m; ++i) area2 += poly(i, 0) * poly((i + 1) % m, 1) - poly(i, 1) * poly((i + 1) % m, 0);
  for (const auto& t : triangulate_polygon(poly)) {
    std::array<int, 3> tri{loop[t[0]], loop[t[1]], loop[t[2]]};
    if (area2 < 0) std::swap(tri[1], tri[2]);
    v_.push_back(tri);
  }
  n_.assign(v_.size(), {-1, -1, -1});
  at_.assign(p_.size(), -1);
  for (int t = 0; t < static_cast<int>(v_.size()); ++t) own(t);
  std::map<std::pair<int, int>, std::pair<int, int>> half;
  for (int t = 0; t < static_cast<int>(v_.size()); ++t)
    for (int k = 0; k < 3; ++k) half[{v_[t][k], v_[t][(k + 1) % 3]}] = {t, k};
  for (const auto& [e, tk] : half) {
    auto it = half.find({e.second, e.first});
    if (it != half.end()) n_[tk.first][tk.second] = it->second.first;
  }
  loop_at_.assign(p_.size(), -1);
  for (int i = 0; i < m; ++i) loop_at_[loop[i]] = i;
  stack_.clear();
  for (int t = 0; t < static_cast<int>(v_.size()); ++t)
    for (int k = 0; k < 3; ++k) stack_.push_back({t, k});
  legalize_stack(false);
}

bool Triangulation::constrained(int a, int b) const {
  const int i = loop_at_[a], j = loop_at_[b], last = loop_size_ - 1;
  if (i < 0 || j < 0) return false;
  // neighbours along the loop, its last and first too (no integer division: a hot test of the
  // flips)
  return i - j == 1 || j - i == 1 || (i == last && j == 0) || (j == last && i == 0);
}

double Triangulation::orient(int a, int b, int c) const { return orient(a, b, p_[c]); }

double Triangulation::orient(int a, int b, const Eigen::Vector2d& q) const {
  const Eigen::Vector2d& pa = p_[a];
  const Eigen::Vector2d& pb = p_[b];
  return (pb.x() - pa.x()) * (q.y() - pa.y()) - (pb.y() - pa.y()) * (q.x() - pa.x());
}

bool Triangulation::in_circle(int a, int b, int c, int d) const {
  const Eigen::Vector2d A = p_[a] - p_[d], B = p_[b] - p_[d], C = p_[c] - p_[d];
  const double det = (A.squaredNorm()) * (B.x() * C.y() - C.x() * B.y()) -
                     (B.squaredNorm()) * (A.x() * C.y() - C.x() * A.y()) +
                     (C.squaredNorm()) * (A.x() * B.y() - B.x() * A.y());
  return det > circle_eps_;
}

int Triangulation::edge_index(int t, int a, int b) const {
  for (int k = 0; k < 3; ++k)
    if (v_[t][k] == a && v_[t][next3(k)] == b) return k;
  return -1;
}

void Triangulation::own(int t) {
  for (int v : v_[t]) at_[v] = t;
}

int Triangulation::append_triangle(const std::array<int, 3>& corners) {
  v_.push_back(corners);
  for (int v : corners) at_[v] = static_cast<int>(v_.size()) - 1;
  n_.push_back({-1, -1, -1});
  return static_cast<int>(v_.size()) - 1;
}

void Triangulation::point_across(int outer, int a, int b, int t) {
  if (outer >= 0) n_[outer][edge_index(outer, a, b)] = t;
}

int Triangulation::locate(const Eigen::Vector2d& q) const {
  const double eps = kCollinear * scale_ * scale_;
  int t = std::clamp(hint_, 0, static_cast<int>(v_.size()) - 1);
  for (size_t steps = 0; steps < v_.size() + 8; ++steps) {
    int next = -2;  // -2: q is inside t
    for (int r = 0; r < 3; ++r) {
      const int kk = (r + static_cast<int>(steps)) % 3;  // rotate the first edge tested: no walking in circles
      if (orient(v_[t][kk], v_[t][next3(kk)], q) < -eps) {
        next = n_[t][kk];
        break;
      }
    }
    if (next == -2) return hint_ = t;
    if (next < 0) break;
    t = next;
  }
  for (int u = 0; u < static_cast<int>(v_.size()); ++u) {  // walk blocked by the boundary
    bool inside = true;
    for (int k = 0; k < 3; ++k)
      if (orient(v_[u][k], v_[u][next3(k)], q) < -eps) inside = false;
    if (inside) return hint_ = u;
  }
  return -1;
}

bool Triangulation::flip(int t, int k) {
  const int u = n_[t][k];
  if (u < 0) return false;
  const int a = v_[t][k], b = v_[t][next3(k)], c = v_[t][prev3(k)];
  const int j = edge_index(u, b, a);
  if (j < 0) return false;
  const int d = v_[u][prev3(j)];
  // outer neighbours: t has (b,c) and (c,a); u has (a,d) and (d,b)
  const int n_bc = n_[t][next3(k)], n_ca = n_[t][prev3(k)];
  const int n_ad = n_[u][next3(j)], n_db = n_[u][prev3(j)];
  v_[t] = {a, d, c};  // edges: (a,d) (d,c) (c,a)
  v_[u] = {d, b, c};  // edges: (d,b) (b,c) (c,d)
  own(t);
  own(u);
  auto relink = [&](int outer, int x, int y, int tri, int kk) {  // outer triangle holds edge (y, x)
    n_[tri][kk] = outer;
    if (outer >= 0) {
      const int e = edge_index(outer, y, x);
      if (e >= 0) n_[outer][e] = tri;
    }
  };
  relink(n_ad, a, d, t, 0);
  n_[t][1] = u;
  relink(n_ca, c, a, t, 2);
  relink(n_db, d, b, u, 0);
  relink(n_bc, b, c, u, 1);
  n_[u][2] = t;
  return true;
}

void Triangulation::legalize(std::initializer_list<std::pair<int, int>> edges) {
  stack_.assign(edges.begin(), edges.end());  // a member: no allocation per insertion
  legalize_stack(true);
}

void Triangulation::legalize_stack(bool from_new_point) {
  std::vector<std::pair<int, int>>& stack = stack_;
  while (!stack.empty()) {
    const auto [t, k] = stack.back();
    stack.pop_back();
    const int u = n_[t][k];
    if (u < 0) continue;
    const int a = v_[t][k], b = v_[t][next3(k)], c = v_[t][prev3(k)];
    if (constrained(a, b)) continue;
    const int j = edge_index(u, b, a);
    if (j < 0) continue;
    const int d = v_[u][prev3(j)];
    if (!in_circle(a, b, c, d)) continue;
    if (orient(c, a, d) <= 0 || orient(d, b, c) <= 0) continue;  // not convex: keep
    flip(t, k);
    // the new outer edges of both triangles may now be illegal; after an insertion c is the
    // new point, and the edges at it (t's side 2, u's side 1) are locally Delaunay (Lawson's
    // insertion: a triangle at the new point has an empty circle), so only the sides across
    // from it are checked (checking the others flipped none of 150 000 on the mesh cases)
    stack.push_back({t, 0});
    if (!from_new_point) stack.push_back({t, 2});
    stack.push_back({u, 0});
    if (!from_new_point) stack.push_back({u, 1});
  }
}

void Triangulation::split_triangle(int t, int idx) {
  const int a = v_[t][0], b = v_[t][1], c = v_[t][2];
  const int n_ab = n_[t][0], n_bc = n_[t][1], n_ca = n_[t][2];
  v_[t] = {a, b, idx};
  own(t);
  const int t1 = append_triangle({b, c, idx}), t2 = append_triangle({c, a, idx});
  n_[t] = {n_ab, t1, t2};
  n_[t1] = {n_bc, t2, t};
  n_[t2] = {n_ca, t, t1};
  point_across(n_bc, c, b, t1);
  point_across(n_ca, a, c, t2);
  legalize({{t, 0}, {t1, 0}, {t2, 0}});
}

void Triangulation::split_edge(int t, int k, int idx) {
  const int u = n_[t][k];
  const int a = v_[t][k], b = v_[t][(k + 1) % 3], c = v_[t][(k + 2) % 3];
  const int j = edge_index(u, b, a);
  const int d = v_[u][(j + 2) % 3];
  const int n_bc = n_[t][(k + 1) % 3], n_ca = n_[t][(k + 2) % 3];
  const int n_ad = n_[u][(j + 1) % 3], n_db = n_[u][(j + 2) % 3];
  // t: (a, idx, c)  t2: (idx, b, c)  u: (b, idx, d)  u2: (idx, a, d)
  v_[t] = {a, idx, c};
  v_[u] = {b, idx, d};
  own(t);
  own(u);
  const int t2 = append_triangle({idx, b, c}), u2 = append_triangle({idx, a, d});
  n_[t] = {u2, t2, n_ca};
  n_[t2] = {u, n_bc, t};
  n_[u] = {t2, u2, n_db};
  n_[u2] = {t, n_ad, u};
  point_across(n_bc, c, b, t2);
  point_across(n_ad, d, a, u2);
  legalize({{t, 2}, {t2, 1}, {u, 2}, {u2, 1}});
}

bool Triangulation::insert(int idx) {
  const Eigen::Vector2d& q = p_[idx];
  const int t = locate(q);
  if (t < 0) return false;
  const double eps = kCollinear * scale_ * scale_;
  for (int k = 0; k < 3; ++k) {
    const int a = v_[t][k], b = v_[t][(k + 1) % 3];
    if (std::abs(orient(a, b, q)) <= eps) {
      if (constrained(a, b) || n_[t][k] < 0) return false;
      if ((p_[a] - q).norm() <= 1e-9 * scale_ || (p_[b] - q).norm() <= 1e-9 * scale_) return false;
      split_edge(t, k, idx);
      return true;
    }
  }
  split_triangle(t, idx);
  return true;
}

template <typename F>
int Triangulation::about(int a, F&& found) const {
  // counter-clockwise from at_[a] (across the side ending at a), then, if that meets the
  // boundary, clockwise from it (across the side starting at a)
  for (int dir = 0; dir < 2; ++dir)
    for (int t = at_[a], guard = 0; t >= 0 && guard <= static_cast<int>(v_.size()); ++guard) {
      const int i = v_[t][0] == a ? 0 : v_[t][1] == a ? 1 : 2;
      if (found(t, i)) return t;
      t = n_[t][dir == 0 ? (i + 2) % 3 : i];
      if (t == at_[a]) return -1;  // all the way round
    }
  return -1;
}

bool Triangulation::crossing_edges(int a, int b, std::vector<std::pair<int, int>>& out) const {
  out.clear();
  const double eps = kCollinear * scale_ * scale_;
  bool there = false;
  int k = -1;  // the triangle at a whose wedge holds the direction to b, and its side ab leaves by
  int t = about(a, [&](int tt, int i) {
    const int x = v_[tt][(i + 1) % 3], y = v_[tt][(i + 2) % 3];
    if (x == b || y == b) return there = true;
    if (orient(a, x, b) > eps && orient(a, b, y) > eps) return k = (i + 1) % 3, true;
    return false;
  });
  if (there) return true;
  if (t < 0) return false;  // outside the polygon at a, or along an edge through a vertex
  for (int guard = 0; guard < static_cast<int>(v_.size()); ++guard) {
    const int x = v_[t][k], y = v_[t][(k + 1) % 3];
    out.push_back({x, y});
    const int u = n_[t][k];
    if (u < 0) return false;
    const int j = edge_index(u, y, x);
    const int z = v_[u][(j + 2) % 3];
    if (z == b) return true;
    const double side = orient(a, b, z);
    if (std::abs(side) <= eps) return false;  // through a vertex: not a plain crossing
    // x lies right of ab and y left (so far); u is y, x, z counter-clockwise: ab leaves it
    // across x -> z where z lies left, else across z -> y
    t = u;
    k = side > 0 ? (j + 1) % 3 : (j + 2) % 3;
  }
  return false;
}

bool Triangulation::enforce(int a, int b) {
  std::vector<std::pair<int, int>> cross;
  for (int round = 0; round < kEnforceRounds; ++round) {
    if (!crossing_edges(a, b, cross)) return false;
    if (cross.empty()) return true;
    bool flipped = false;
    for (const auto& [x, y] : cross) {  // flip each crossing edge whose quadrilateral is convex
      if (constrained(x, y)) return false;
      int k = -1;
      const int t = about(x, [&](int tt, int) { return (k = edge_index(tt, x, y)) >= 0; });
      if (t < 0 || n_[t][k] < 0) continue;  // changed by a flip this round: tried again next round
      const int u = n_[t][k];
      const int c = v_[t][(k + 2) % 3], d = v_[u][(edge_index(u, y, x) + 2) % 3];
      if (orient(c, x, d) <= 0 || orient(d, y, c) <= 0) continue;
      flip(t, k);
      flipped = true;
    }
    if (!flipped) return false;
  }
  return false;
}

long Triangulation::flip_while(const std::function<bool(int, int, int, int)>& better, int max_passes,
                               const std::vector<char>& keep, const std::function<bool(int, int, int, int)>& convex) {
  long flips = 0;
  // pass in which each triangle last changed: an edge whose two triangles are older than the
  // last pass was checked since they changed, on the same four points, so it is skipped
  std::vector<int> changed(v_.size(), -1);
  for (int pass = 0; pass < max_passes; ++pass) {
    long here = 0;
    for (int t = 0; t < static_cast<int>(v_.size()); ++t)
      for (int k = 0; k < 3; ++k) {
        const int u = n_[t][k];
        if (u < 0 || u < t) continue;
        if (!keep.empty() && (keep[t] || keep[u])) continue;  // a flip rewrites both (t and u)
        if (pass > 0 && changed[t] < pass - 1 && changed[u] < pass - 1) continue;
        const int a = v_[t][k], b = v_[t][(k + 1) % 3], c = v_[t][(k + 2) % 3];
        if (constrained(a, b)) continue;
        const int j = edge_index(u, b, a);
        const int d = v_[u][(j + 2) % 3];
        if (convex ? !convex(a, b, c, d) : orient(c, a, d) <= 0 || orient(d, b, c) <= 0) continue;
        // convex in space only, the planar points may fold: c-d can be an edge already, and a
        // second one would join four triangles (a valid planar flip never meets one)
        if (convex && about(c, [&](int tt, int i) { return v_[tt][(i + 1) % 3] == d || v_[tt][(i + 2) % 3] == d; }) >= 0)
          continue;
        if (!better(a, b, c, d)) continue;
        flip(t, k);
        changed[t] = changed[u] = pass;
        ++here;
      }
    flips += here;
    if (!here) break;
  }
  return flips;
}

}  // namespace fairlines::meshing
