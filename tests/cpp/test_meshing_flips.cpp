// Edge flips judged in space (the surface mesher's swaps and its flat-triangle flips) never
// make an edge that is there already: a second copy joins four triangles (non-manifold).
#include <algorithm>
#include <array>
#include <map>
#include <utility>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "meshing/patch.hpp"
#include "meshing/triangulation.hpp"

using fairlines::meshing::merged_triangles;
using fairlines::meshing::Triangulation;
using Tri = std::array<int, 3>;

namespace {

/// The most triangles any one undirected edge belongs to.
int most_triangles_on_an_edge(const std::vector<Tri>& tris) {
  std::map<std::pair<int, int>, int> count;
  for (const Tri& t : tris)
    for (int k = 0; k < 3; ++k) ++count[std::minmax(t[k], t[(k + 1) % 3])];
  int most = 0;
  for (const auto& [edge, n] : count) most = std::max(most, n);
  return most;
}

}  // namespace

TEST(SpaceFlips, NeverDoubleAnEdge) {
  // d inside triangle abc: flipping a-d (triangles c,a,d and a,b,d) would make b-c, the
  // outer side, a second time. A predicate that calls every quadrilateral convex and every
  // flip better (as a surface folding in its planar coordinates can) must still not do it.
  std::vector<Eigen::Vector2d> p{{0, 0}, {4, 0}, {0, 4}, {1, 1}};
  Triangulation tr(p, {0, 1, 2});
  ASSERT_TRUE(tr.insert(3));
  ASSERT_EQ(tr.triangles().size(), 3u);
  auto yes = [](int, int, int, int) { return true; };
  tr.flip_while(yes, 4, {}, yes);
  EXPECT_EQ(tr.triangles().size(), 3u);
  EXPECT_LE(most_triangles_on_an_edge(tr.triangles()), 2);
}

TEST(MergedTriangles, FlatTriangleIsNotFlippedOntoAnEdgeThatExists) {
  // (p, q, m) flat, (q, p, x) across its longest side; m-x is an edge already (of m, x, y), so
  // the flip to (p, x, m) + (x, q, m) would join m-x to three triangles
  const std::vector<Eigen::Vector3d> pts{{0, 0, 0}, {2, 0, 0}, {1, 0.001, 0}, {1, -1, 0}, {3, -1, 0}};
  const int P = 0, Q = 1, M = 2, X = 3, Y = 4;
  const std::vector<Tri> in{{P, Q, M}, {Q, P, X}, {M, X, Y}};
  std::vector<int> canon{0, 1, 2, 3, 4};
  const auto out = merged_triangles(pts, in, canon);
  EXPECT_LE(most_triangles_on_an_edge(out), 2);
}
