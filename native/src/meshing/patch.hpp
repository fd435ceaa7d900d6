// Meshing one face (a NURBS surface or a plane) inside one boundary loop of fixed nodes.
#pragma once

#include <array>
#include <functional>
#include <limits>
#include <vector>

#include <Eigen/Core>

#include "fairlines/meshing.hpp"
#include "fairlines/surface.hpp"

namespace fairlines::meshing {

/// A face's geometry: a NURBS surface, or the plane origin + u ax + v ay (ax, ay orthonormal).
struct FaceGeometry {
  const NurbsSurface* surface = nullptr;
  /// Points held at y >= 0: a half hull's surface that dips across the centre plane (a blend
  /// skinned to an end section on it can overshoot by centimetres) is meshed on the plane there.
  bool clamp_y = false;
  /// A strip between the iso-lines u = a and u = b (a < b) where the surface is replaced by the
  /// ruled surface joining them: a strip where the surface folds over itself (see guard_fold in
  /// hull_mesh.cpp) is meshed on its chord surface. `inner`: the strip's end inside the domain.
  struct RuledStrip {
    double a, b, inner;
  };
  std::vector<RuledStrip> ruled_strips;  ///< at most one at each end of the u range
  Eigen::Vector3d origin = Eigen::Vector3d::Zero(), ax = Eigen::Vector3d::UnitX(), ay = Eigen::Vector3d::UnitY();

  Eigen::Vector3d point(const Eigen::Vector2d& uv) const;
  /// Position and first partials.
  void first(const Eigen::Vector2d& uv, Eigen::Vector3d& p, Eigen::Vector3d& su, Eigen::Vector3d& sv) const;
  /// |k1| + |k2| (1/m), 0 for a plane or where the surface is singular.
  double curvature_sum(const Eigen::Vector2d& uv) const;
  /// (u, v) of a point on the plane; for a surface, Newton from `start` (clamped to the domain).
  Eigen::Vector2d locate(const Eigen::Vector3d& p, const Eigen::Vector2d& start) const;
  Eigen::Vector2d clamp(const Eigen::Vector2d& uv) const;
  /// The ruled strip u lies in (its outer edge, the domain end, included), or null.
  const RuledStrip* ruled(double u) const;
};

/// One fixed node of the boundary loop: global node id, (u, v) on this face and position.
struct LoopNode {
  int id = -1;
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();
  Eigen::Vector3d xyz = Eigen::Vector3d::Zero();
};

/// A meshed face: nodes 0 .. loop.size()-1 are the loop's (global ids loop[i].id), the rest
/// are new (`xyz`, `uv` hold every node, loop nodes first). Elements index these local
/// nodes, counter-clockwise in (u, v); column 3 is -1 for a triangle.
struct PatchMesh {
  std::vector<Eigen::Vector3d> xyz;
  std::vector<Eigen::Vector2d> uv;
  std::vector<std::array<int, 4>> elements;
  std::vector<int> global;  ///< global id of each local node (-1 for new ones until assigned)
};

/// The midpoint node of loop edge (i, i + 1 mod n), for the all-quad split; shared faces must
/// get the same node, so the caller provides it.
using LoopMidpoint = std::function<LoopNode(int)>;

/// Meshes the face inside `loop` (a simple polygon in (u, v), either orientation; nodes given
/// in order, spaced about the local size). `size_scale`: the interior node spacing factor
/// (2 for the all-quad split's coarse pass).
PatchMesh mesh_patch(const FaceGeometry& g, const std::vector<LoopNode>& loop, const MeshOptions& o,
                     const LoopMidpoint& midpoint);

/// Target element size (m) at (u, v): the chordal tolerance's size from the curvature,
/// clamped to [min_size, size].
double target_size(const FaceGeometry& g, const Eigen::Vector2d& uv, const MeshOptions& o);

/// Options with their defaults resolved (tolerance, minimum size); throws InvalidInput.
MeshOptions resolved(const MeshOptions& o);

/// Scaled Jacobian of a quad (d = -1: triangle) with reference normal n.
double element_quality(const Eigen::Vector3d* p, int corners, const Eigen::Vector3d& n);

/// Triangles (counter-clockwise about the surface normals) on canonical node ids `canon` (a
/// pole's copies merged into one node): those the merge collapses dropped, and each flat one
/// (|2 area| <= 1e-2 x its longest side^2: three nodes of a straight stem joined across the
/// pole's copies in the planar triangulation) flipped with its neighbour across its longest side
/// where that raises the pair's least angle, keeping every triangle's orientation.
std::vector<std::array<int, 3>> merged_triangles(const std::vector<Eigen::Vector3d>& xyz,
                                                 const std::vector<std::array<int, 3>>& triangles,
                                                 const std::vector<int>& canon);

/// Even-odd test of q against the closed polygon `poly` (its last point joins its first).
bool point_in_polygon(const Eigen::Vector2d& q, const std::vector<Eigen::Vector2d>& poly);

}  // namespace fairlines::meshing
