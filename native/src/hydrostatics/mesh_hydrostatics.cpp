// Mesh hydrostatics (see fairlines/mesh_hydrostatics.hpp for the integrals).
//
// Notation: a triangle is (p0, p1, p2); a = (p1 - p0) x (p2 - p0) / 2 its area vector;
// m_k the midpoint of edge k; T the draft; x_m the x of the measured section.
#include "fairlines/mesh_hydrostatics.hpp"

#include <array>
#include <cmath>
#include <vector>

#include <Eigen/Geometry>

#include "fairlines/errors.hpp"
#include "triangles.hpp"

namespace fairlines {

namespace {

using triangles::area_vector;
using triangles::Keep;
using triangles::Tri;
using triangles::triangle;
using triangles::Vec3;

/// Sums of the surface integrals over the submerged triangles (half hull, before doubling).
struct Sums {
  double V = 0, Mx = 0, Mz = 0, S = 0, Awp = 0, Mwp = 0, Am = 0;
};

/// Adds one submerged triangle's volume, moment, area and waterplane terms.
void add_triangle(const Tri& t, Sums& s) {
  const Vec3 a = area_vector(t);
  const Vec3 c = (t[0] + t[1] + t[2]) / 3.0;
  double xy = 0, zy = 0;
  for (int k = 0; k < 3; ++k) {
    const Vec3 m = 0.5 * (t[k] + t[(k + 1) % 3]);
    xy += m.x() * m.y() / 3.0;
    zy += m.z() * m.y() / 3.0;
  }
  s.V += c.y() * a.y();
  s.Mx += xy * a.y();
  s.Mz += zy * a.y();
  s.S += a.norm();
  s.Awp -= a.z();
  s.Mwp -= c.x() * a.z();
}

/// Green's theorem term oint y dz of the segment where the plane x = x_m cuts `t`, traversed
/// with the triangle's outward normal on its right in the (y, z) plane.
double section_term(const Tri& t, double xm) {
  int above = 0;
  for (const Vec3& p : t) above += p.x() > xm;
  if (above == 0 || above == 3) return 0.0;
  int lone = 0;  // the vertex alone on its side of the plane
  for (int k = 0; k < 3; ++k)
    if ((t[k].x() > xm) == (above == 1)) lone = k;
  const Vec3& p = t[lone];
  const Vec3& b = t[(lone + 1) % 3];
  const Vec3& c = t[(lone + 2) % 3];
  const Vec3 q1 = p + (xm - p.x()) / (b.x() - p.x()) * (b - p);
  const Vec3 q2 = p + (xm - p.x()) / (c.x() - p.x()) * (c - p);
  const Vec3 n = (t[1] - t[0]).cross(t[2] - t[0]);
  const Vec3 d = q2 - q1;
  const double side = d.z() * n.y() - d.y() * n.z();
  const double sgn = side > 0 ? 1.0 : (side < 0 ? -1.0 : 0.0);
  return sgn * 0.5 * (q1.y() + q2.y()) * (q2.z() - q1.z());
}

/// True when the mesh is oriented inwards by the side / end rule of the options.
bool inward(const TriMesh& mesh, double xm) {
  double ay = 0, ax = 0, side = 0, end = 0;
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    const Tri t = triangle(mesh, f, false);
    const Vec3 a = area_vector(t);
    const Vec3 c = (t[0] + t[1] + t[2]) / 3.0;
    ay += std::abs(a.y());
    ax += std::abs(a.x());
    side += c.y() * a.y();
    end += (c.x() - xm) * a.x();
  }
  return (ay >= ax ? side : end) < 0;
}

}  // namespace

MeshHydrostatics mesh_hydrostatics(const TriMesh& mesh, double draft, const MeshHydrostaticsOptions& options) {
  if (!std::isfinite(draft)) throw InvalidInput("draft is not finite; expected a finite height in metres");
  triangles::check_mesh(mesh);
  MeshHydrostatics h;
  h.draft = draft;
  h.midship_x = options.midship_x;
  if (std::isnan(h.midship_x))
    h.midship_x = mesh.vertices.rows() ? 0.5 * (mesh.vertices.col(0).minCoeff() + mesh.vertices.col(0).maxCoeff()) : 0.0;
  h.flipped = options.orient && inward(mesh, h.midship_x);
  Sums s;
  std::vector<Tri> below;
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    below.clear();
    triangles::clip(triangle(mesh, f, h.flipped), 2, draft, Keep::Below, below);
    for (const Tri& t : below) {
      add_triangle(t, s);
      s.Am += section_term(t, h.midship_x);
    }
  }
  const double k = options.half_hull ? 2.0 : 1.0;
  h.volume = k * s.V;
  h.lcb = s.V != 0 ? s.Mx / s.V : 0.0;
  h.vcb = s.V != 0 ? s.Mz / s.V : 0.0;
  h.waterplane_area = k * s.Awp;
  h.lcf = s.Awp != 0 ? s.Mwp / s.Awp : 0.0;
  h.wetted_surface = k * s.S;
  h.midship_area = k * s.Am;
  return h;
}

}  // namespace fairlines
