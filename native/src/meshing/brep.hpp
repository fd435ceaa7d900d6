// Faces bounded by shared edges (a small boundary representation) and its meshing: every
// edge is discretised once, so faces that share it share its nodes; each face is then meshed
// inside its loop; a plane cut (z <= draft) splits edges at the crossings and closes each
// face's loop along the traced waterline.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "meshing/patch.hpp"

namespace fairlines::meshing {

/// An edge's samples: positions and (u, v) on each adjacent face (side 0, optional side 1).
struct EdgeSample {
  Eigen::Vector3d xyz;
  Eigen::Vector2d uv[2];
};

struct Edge {
  int face[2] = {-1, -1};        ///< faces on both sides (-1: none)
  std::vector<EdgeSample> s;     ///< dense samples, first to last
  bool degenerate = false;       ///< all samples at one point (a pole)
  /// Optional exact point between samples (e.g. Newton onto both surfaces of a seam).
  std::function<void(EdgeSample&)> refine;
  int v0 = -1, v1 = -1;          ///< global node ids of the end vertices
};

struct Face {
  FaceGeometry g;
  std::string name;
  std::vector<std::pair<int, bool>> loop;  ///< (edge, forward) in loop order
  bool keep = true;                        ///< part of the output
};

struct Brep {
  std::vector<Face> faces;
  std::vector<Edge> edges;
  std::vector<Eigen::Vector3d> vertices;  ///< end vertices (global nodes 0 .. n-1)

  int vertex(const Eigen::Vector3d& p);
  /// Edge from samples; its end vertices are looked up (or made) by position.
  int add_edge(int face0, int face1, std::vector<EdgeSample> samples, bool degenerate = false);
  /// Iso-parameter or straight edge sampled `n` times by a function of t in [0, 1].
  int sampled_edge(int face0, int face1, int n, const std::function<EdgeSample(double)>& at, bool degenerate = false);
  /// Everything below z = draft: splits edges at the crossings, traces the waterline on every
  /// face whose loop crosses it, drops what lies above, and adds the waterplane face (named
  /// `lid_name`, kept if `keep_lid`) bounded by the traced waterlines and the lids' cuts.
  void cut_below(double draft, double size, const std::string& lid_name, bool keep_lid);
};

/// Meshes the kept faces of `b`. Elements come counter-clockwise in each face's (u, v); with
/// `outward` they are then made consistent across shared edges and turned out of the body
/// (int y n_y dS > 0 per connected part, which holds for a closed body and for a half or
/// full hull open at the waterline or the centre plane).
SurfaceMesh mesh_brep(Brep& b, const MeshOptions& o, const std::function<void(int, int, const std::string&)>& progress,
                      bool outward);

}  // namespace fairlines::meshing
