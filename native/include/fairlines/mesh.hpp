// Triangle meshes: the composed hull's output, planar polygon triangulation, orientation,
// volume, edge checks and OBJ / STL export.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace fairlines {

/// Indexed triangle mesh (metres).
struct TriMesh {
  Eigen::MatrixXd vertices;  ///< (n, 3) vertex positions
  Eigen::MatrixXi faces;     ///< (m, 3) vertex indices, counter-clockwise seen from outside
};

/// Edge census of a mesh: an undirected edge is `open` when one face uses it, `non_manifold`
/// when three or more do; `inconsistent` counts two-face edges traversed in the same direction
/// by both faces (orientation flips).
struct EdgeReport {
  long edges = 0;
  long open = 0;
  long non_manifold = 0;
  long inconsistent = 0;
  long degenerate_faces = 0;  ///< faces with a repeated vertex index
};

EdgeReport edge_report(const TriMesh& mesh);

/// Ear-clipping triangulation of a simple polygon.
/// points  (n, 2) polygon vertices in order (either orientation), n >= 3, metres or any
///         consistent planar unit.
/// Returns n - 2 triangles as indices into points, each with the polygon's own orientation.
/// Throws InvalidInput for fewer than 3 points or non-finite coordinates.
/// avoid   optional n flags: no triangle gets three flagged vertices while another ear exists
///         (used to keep surface triangles out of a closing plane).
std::vector<std::array<int, 3>> triangulate_polygon(const Eigen::MatrixXd& points,
                                                    const std::vector<char>& avoid = {});

/// Lawson edge flips of a polygon's triangulation toward its constrained Delaunay one (the
/// polygon's own edges stay): removes the slivers ear clipping leaves, which fold in 3D where
/// the plane is a map of a curved surface.
/// points  (n, 2) the polygon's vertices, as given to triangulate_polygon
/// tris    its triangles (indices into points), changed in place; orientation kept
/// avoid   as for triangulate_polygon: no flip makes a triangle of three flagged vertices
/// positions  optional (n, 3) places in space of the points (metres) when the polygon is a
///         map of a curved surface: an edge is then flipped when its opposite angles in space
///         sum to more than pi (Delaunay on the surface); the flips stay valid in the plane
/// Throws InvalidInput for points not (n, 2), avoid not n flags, positions not (n, 3) or
/// empty, or a triangle index outside 0 .. n - 1.
void delaunay_flips(const Eigen::MatrixXd& points, std::vector<std::array<int, 3>>& tris,
                    const std::vector<char>& avoid = {}, const Eigen::MatrixXd& positions = Eigen::MatrixXd());

/// Signed enclosed volume by the divergence theorem (m^3; positive for outward orientation
/// of a closed mesh).
double mesh_volume(const TriMesh& mesh);

/// Total triangle area (m^2).
double mesh_area(const TriMesh& mesh);

/// Makes face orientation consistent across every two-face edge (breadth-first flips over
/// each connected component) and then makes the enclosed volume positive. Returns the number
/// of faces flipped.
long orient_consistently(TriMesh& mesh);

/// The mesh as orient_consistently leaves it, checked first: when no two-face edge is traversed
/// the same way by both faces (and none is non-manifold, no face degenerate) the faces are only
/// all flipped if the enclosed volume is negative, without the breadth-first pass. Returns the
/// edge_report of the mesh as left.
EdgeReport orient_if_needed(TriMesh& mesh);

/// Writes Wavefront OBJ (v / f records, 1-based). Throws Error when the file cannot be written.
void write_obj(const TriMesh& mesh, const std::string& path);
/// Writes STL, binary (default) or ASCII, with facet normals from the vertex order.
void write_stl(const TriMesh& mesh, const std::string& path, bool binary = true);

}  // namespace fairlines
