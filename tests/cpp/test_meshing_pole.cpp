// The mesher's pole merge (meshing::merged_triangles): flat triangles beside a pole flipped
// with their neighbours, every triangle keeping its counter-clockwise turn.
#include <array>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "meshing/patch.hpp"

using fairlines::meshing::merged_triangles;
using Tri = std::array<int, 3>;

namespace {

constexpr double kFlatRatio = 1e-2;  ///< the mesher's flat test: |2 area| <= this x longest side^2

double twice_area_z(const std::vector<Eigen::Vector3d>& p, const Tri& t) {
  return (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]).z();
}

bool flat(const std::vector<Eigen::Vector3d>& p, const Tri& t) {
  double longest = 0.0;
  for (int j = 0; j < 3; ++j) longest = std::max(longest, (p[t[(j + 1) % 3]] - p[t[j]]).squaredNorm());
  return std::abs(twice_area_z(p, t)) <= kFlatRatio * longest;
}

/// Every triangle turns counter-clockwise about +z (the plane's normal), none is flat, and
/// they cover the same area as the input (a flip only moves a diagonal).
void expect_valid(const std::vector<Eigen::Vector3d>& p, const std::vector<Tri>& in, const std::vector<Tri>& out) {
  double area_in = 0.0, area_out = 0.0;
  for (const Tri& t : in) area_in += twice_area_z(p, t);
  ASSERT_EQ(out.size(), in.size());
  for (const Tri& t : out) {
    EXPECT_GT(twice_area_z(p, t), 0.0) << t[0] << " " << t[1] << " " << t[2];
    EXPECT_FALSE(flat(p, t)) << t[0] << " " << t[1] << " " << t[2];
    area_out += twice_area_z(p, t);
  }
  EXPECT_NEAR(area_out, area_in, 1e-12);
}

std::vector<int> identity(size_t n) {
  std::vector<int> c(n);
  for (size_t i = 0; i < n; ++i) c[i] = static_cast<int>(i);
  return c;
}

}  // namespace

TEST(MergedTriangles, FlatTriangleFlipKeepsTheTurn) {
  // p, m, q nearly on a line (a straight stem), x off it: (p, q, m) is flat, (q, p, x) not
  const std::vector<Eigen::Vector3d> pts{{0, 0, 0}, {2, 0, 0}, {1, 0.001, 0}, {1, -1, 0}};
  const std::vector<Tri> in{{0, 1, 2}, {1, 0, 3}};
  expect_valid(pts, in, merged_triangles(pts, in, identity(pts.size())));
}

TEST(MergedTriangles, RowOfFlatTrianglesIsFlippedThroughout) {
  // stem nodes C, A, B, D nearly on a line: (A, B, D) lies against the flat (D, C, A), whose
  // other side has the proper triangle (C, D, X); the inner one comes first in the list, so it
  // can be flipped only after the outer one is
  const std::vector<Eigen::Vector3d> pts{{0, 0, 0}, {1, -0.01, 0}, {2, -0.02, 0}, {3, 0, 0}, {1.5, 1, 0}};
  const int C = 0, A = 1, B = 2, D = 3, X = 4;
  const std::vector<Tri> in{{A, B, D}, {D, C, A}, {C, D, X}};
  expect_valid(pts, in, merged_triangles(pts, in, identity(pts.size())));
}

TEST(MergedTriangles, PoleCopiesMergedAndCollapsedTrianglesDropped) {
  // a pole's two copies P0, P1 (one point) on the loop: the triangle on both collapses
  const std::vector<Eigen::Vector3d> pts{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 1, 0}, {1, 1, 0}};
  const std::vector<Tri> in{{0, 1, 4}, {0, 4, 2}, {2, 4, 3}};
  const std::vector<int> canon{0, 1, 2, 2, 4};
  const auto out = merged_triangles(pts, in, canon);
  expect_valid(pts, {{0, 1, 4}, {0, 4, 2}}, out);
}
