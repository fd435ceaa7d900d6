// Triangles of a TriMesh for the mesh integrals: area vectors and clipping by an axis plane.
#pragma once

#include <array>
#include <sstream>
#include <vector>

#include <Eigen/Geometry>

#include "fairlines/errors.hpp"
#include "fairlines/mesh.hpp"

namespace fairlines::triangles {

using Vec3 = Eigen::Vector3d;
using Tri = std::array<Vec3, 3>;

/// Which side of the plane coordinate[axis] = value a clip keeps.
enum class Keep { Below = -1, Above = 1 };

/// Area vector (p1 - p0) x (p2 - p0) / 2 (m^2): outward normal times area for an outward face.
inline Vec3 area_vector(const Tri& t) { return 0.5 * (t[1] - t[0]).cross(t[2] - t[0]); }

/// Face f of the mesh, its vertex order reversed when `flip`.
inline Tri triangle(const TriMesh& mesh, Eigen::Index f, bool flip = false) {
  Tri t;
  for (int k = 0; k < 3; ++k) t[k] = mesh.vertices.row(mesh.faces(f, flip ? 2 - k : k)).transpose();
  return t;
}

/// Appends to `out` the part of `t` with coordinate `axis` <= value (Keep::Below) or >= value
/// (Keep::Above), as a fan of triangles (a triangle or a quadrilateral cut from it, in the
/// triangle's own orientation).
inline void clip(const Tri& t, int axis, double value, Keep keep, std::vector<Tri>& out) {
  const double side = static_cast<double>(keep);
  std::array<Vec3, 4> poly;
  int n = 0;
  for (int k = 0; k < 3; ++k) {
    const Vec3& p = t[k];
    const Vec3& q = t[(k + 1) % 3];
    if (side * (p[axis] - value) >= 0) poly[n++] = p;
    if ((p[axis] - value) * (q[axis] - value) < 0) poly[n++] = p + (value - p[axis]) / (q[axis] - p[axis]) * (q - p);
  }
  for (int i = 1; i + 1 < n; ++i) out.push_back({poly[0], poly[i], poly[i + 1]});
}

/// Throws InvalidInput unless the mesh has 3 columns of finite vertices and faces of 3 indices
/// into them.
inline void check_mesh(const TriMesh& mesh) {
  if (mesh.vertices.cols() != 3) throw InvalidInput("vertices must have 3 columns (x, y, z)");
  if (mesh.faces.size() && mesh.faces.cols() != 3) throw InvalidInput("faces must have 3 columns (triangles)");
  if (!mesh.vertices.allFinite()) throw InvalidInput("vertices contain NaN or inf; expected finite coordinates");
  const long n = static_cast<long>(mesh.vertices.rows());
  for (Eigen::Index i = 0; i < mesh.faces.size(); ++i) {
    const int v = mesh.faces.data()[i];
    if (v < 0 || v >= n) {
      std::ostringstream os;
      os << "face index " << v << " is out of range; expected 0 <= index < " << n;
      throw InvalidInput(os.str());
    }
  }
}

}  // namespace fairlines::triangles
