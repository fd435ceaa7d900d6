// Quad-dominant surface meshes of NURBS surfaces and of composed hulls (Yoon & Kim 1997's
// pipeline, improved): curvature-adaptive nodes by binary subdivision of the parameter
// domain (2:1 balanced, shared corners kept once), constrained Delaunay triangulation,
// edge swaps by the 3-D max-min angle, quadrilaterals by a maximum matching of triangle
// pairs, optional split into an all-quad mesh, and smoothing that keeps nodes on the
// surface and never lowers an element's quality. See docs/meshing.md.
#pragma once

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "fairlines/surface.hpp"

namespace fairlines {

struct ComposedHull;

struct MeshOptions {
  double size = 1.0;
  double chordal_tolerance = 0.0;
  double min_size = 0.0;
  bool all_quad = false;
  int smoothing_passes = 6;
  double min_quad_quality = 0.3;

  /// Each field with its name and meaning: f(name, member pointer, doc).
  template <typename F>
  static void fields(F&& f) {
    f("size", &MeshOptions::size, "maximum element edge length (m), > 0");
    f("chordal_tolerance", &MeshOptions::chordal_tolerance, "max distance of an element from the surface (m); 0: size / 100");
    f("min_size", &MeshOptions::min_size, "no edge is made shorter for curvature (m); 0: size / 20");
    f("all_quad", &MeshOptions::all_quad, "quads only: a mesh at twice the size (for 0.8 x the tolerance) split into quads");
    f("smoothing_passes", &MeshOptions::smoothing_passes, "sweeps of quality-guarded smoothing");
    f("min_quad_quality", &MeshOptions::min_quad_quality, "triangle pairs whose quad's scaled Jacobian is lower stay triangles");
  }
};

/// Mixed quadrilateral / triangle mesh (metres).
struct SurfaceMesh {
  Eigen::MatrixXd vertices;   ///< (n, 3) node positions, each node once
  Eigen::MatrixXi faces;      ///< (m, 4) node indices counter-clockwise seen from outside
                              ///< (single surface: along S_u x S_v); -1 in column 3 marks a triangle
  Eigen::VectorXi face_part;  ///< (m) index into `parts` of each element
  std::vector<std::string> parts;  ///< names of the mesh parts (surfaces, lids)
};

/// Mesh of one NURBS surface (its whole parameter domain). Throws InvalidInput for bad options.
SurfaceMesh mesh_surface(const NurbsSurface& surface, const MeshOptions& options = {});

struct HullMeshOptions {
  double draft = std::numeric_limits<double>::quiet_NaN();  ///< cut at z = draft (m); NaN: the whole hull
  bool lids = true;   ///< close the mesh with planar faces: the waterplane (cut) or deck and aft
                      ///< face (whole hull), and the centre plane for a half hull
  bool full = false;  ///< mirror about y = 0 into the full hull (no centre-plane face)
  /// Called after each face is meshed: (faces done, faces in all, face name). May be empty.
  std::function<void(int, int, const std::string&)> progress;
};

/// Mesh of a composed hull (bare hull, bulb and blend as compose_hull joined them), conforming
/// across every seam: the nodes on a seam are shared by the faces on both sides. With a
/// draft, only the part below z = draft is meshed, cut exactly along the waterline.
/// Normals point out of the body. Throws InvalidInput for bad options.
SurfaceMesh mesh_hull(const ComposedHull& hull, const MeshOptions& mesh, const HullMeshOptions& options = {});

/// Element quality (Knupp 2000 scaled Jacobian; corner angles in degrees).
struct MeshQuality {
  long quads = 0, triangles = 0;
  long inverted = 0;              ///< elements with a non-positive corner Jacobian
  double min_scaled_jacobian = 0, mean_scaled_jacobian = 0;  ///< over all elements
  double corners_in_45_135 = 0;   ///< fraction of quad corners with 45 <= angle <= 135 deg
  double min_angle_deg = 0, max_angle_deg = 0;  ///< over all corners
  double min_edge = 0, max_edge = 0;             ///< metres
  long duplicate_nodes = 0;       ///< nodes closer than 1e-9 x mesh size to another node
  long open_edges = 0, non_manifold_edges = 0, misoriented_edges = 0;
};

/// Scaled Jacobian of every element: the minimum over its corners of
/// (e_next x e_prev) . n / (|e_next| |e_prev|), n the element normal (diagonal cross product
/// for a quad); triangles are scaled by 2 / sqrt(3) so an equilateral triangle scores 1.
Eigen::VectorXd scaled_jacobians(const SurfaceMesh& mesh);

MeshQuality mesh_quality(const SurfaceMesh& mesh);

}  // namespace fairlines
