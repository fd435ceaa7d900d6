// A planar triangulation with neighbour links: constrained Delaunay triangulation of a simple
// polygon plus interior points (ear clipping, then Lawson flips, then incremental insertion
// with Lawson flips), and edge flips by any criterion (the 3-D swaps of the surface mesher).
//
// Notation: triangle t has vertices v[t][0..2] counter-clockwise; its edge k runs from
// v[t][k] to v[t][k+1 mod 3] and n[t][k] is the triangle across it (-1 on the boundary).
#pragma once

#include <array>
#include <functional>
#include <initializer_list>
#include <vector>

#include <Eigen/Core>

namespace fairlines::meshing {

class Triangulation {
 public:
  /// points  2-D positions (any consistent unit); loop: indices into points of a simple
  /// polygon, either orientation, without repeats. Its edges are constrained.
  Triangulation(std::vector<Eigen::Vector2d> points, const std::vector<int>& loop);

  /// Inserts interior point `index` (already in points) keeping the triangulation
  /// constrained Delaunay. Returns false (point skipped) when it lies outside the polygon or
  /// on a constrained edge.
  bool insert(int index);

  /// Flips every edge ab (triangles abc and bad) for which better(a, b, c, d) says the flipped
  /// pair is better, until none does or `max_passes` sweeps are done; only flips whose
  /// quadrilateral is strictly convex (in the plane, or by `convex(a, b, c, d)` if given: the
  /// flipped triangles adc and dbc turn counter-clockwise), and none of a triangle t with
  /// keep[t] (keep empty: none kept). Returns the number of flips. With `convex` the planar
  /// points may no longer be a triangulation of the plane: insert nothing after it.
  long flip_while(const std::function<bool(int a, int b, int c, int d)>& better, int max_passes,
                  const std::vector<char>& keep = {},
                  const std::function<bool(int a, int b, int c, int d)>& convex = {});

  /// Makes the segment a-b an edge by flipping the edges that cross it (Sloan 1993), for a
  /// segment inside the polygon crossed by no constrained edge. False (nothing more flipped)
  /// where it cannot: a vertex on the segment, a crossing edge that is constrained, or no
  /// convex crossing quadrilateral left. The triangulation is no longer Delaunay about it.
  bool enforce(int a, int b);

  const std::vector<std::array<int, 3>>& triangles() const { return v_; }
  const std::vector<Eigen::Vector2d>& points() const { return p_; }
  bool constrained(int a, int b) const;

 private:
  double orient(int a, int b, int c) const;
  double orient(int a, int b, const Eigen::Vector2d& q) const;
  bool in_circle(int a, int b, int c, int d) const;
  int locate(const Eigen::Vector2d& q) const;
  /// Appends triangle `corners` (counter-clockwise) with no neighbours yet; returns its index.
  int append_triangle(const std::array<int, 3>& corners);
  /// Triangle `outer` (-1: none), which holds the directed edge (a, b), now has t across it.
  void point_across(int outer, int a, int b, int t);
  int edge_index(int t, int a, int b) const;
  /// The edges (x, y) the segment a-b crosses, from a on; empty if a-b is an edge. False where
  /// the walk fails (the segment leaves the polygon or runs through a vertex).
  bool crossing_edges(int a, int b, std::vector<std::pair<int, int>>& out) const;
  /// Points at_ of t's corners to t.
  void own(int t);
  /// The first triangle t about point a (a at its corner i) for which found(t, i) holds, -1 if
  /// none: counter-clockwise from at_[a], then clockwise where that meets the boundary.
  template <typename F>
  int about(int a, F&& found) const;
  bool flip(int t, int k);
  /// Lawson flips from the given (triangle, side) edges on until every edge they reach is
  /// locally Delaunay.
  void legalize(std::initializer_list<std::pair<int, int>> edges);
  /// The same from the edges in stack_; `from_new_point`: each is the side of its triangle
  /// across from a point just inserted (corner prev3(k)), as are the edges a flip leaves to check.
  void legalize_stack(bool from_new_point);
  void split_triangle(int t, int idx);
  void split_edge(int t, int k, int idx);

  std::vector<Eigen::Vector2d> p_;
  std::vector<std::array<int, 3>> v_, n_;
  std::vector<int> at_;  ///< a triangle at each point (-1: none yet)
  std::vector<std::pair<int, int>> stack_;  ///< legalize's work list
  std::vector<int> loop_at_;  ///< position of each point in the boundary loop, -1 if not on it
  int loop_size_ = 0;
  mutable int hint_ = 0;
  double scale_ = 1.0;
  double circle_eps_ = 0.0;  ///< in_circle's threshold, kCollinear x scale^4 (once, not per test)
};

}  // namespace fairlines::meshing
