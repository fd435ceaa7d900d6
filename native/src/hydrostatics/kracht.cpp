// Kracht coefficients of a mesh (see fairlines/kracht.hpp for the quantities).
#include "fairlines/kracht.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "nurbs/checks.hpp"
#include "triangles.hpp"

namespace fairlines {

namespace {

using detail::fail;
using triangles::Keep;
using triangles::Tri;
using triangles::Vec3;

/// Sums over the submerged surface forward of the FP (half hull).
struct Forward {
  double ax = 0, vol = 0, lateral = 0, y_max = 0;
  Vec3 nose{-std::numeric_limits<double>::infinity(), 0.0, 0.0};
};

void check_ship(const ShipParticulars& s) {
  if (!std::isfinite(s.x_fp)) fail("x_fp is ", s.x_fp, "; expected a finite x of the FP (m)");
  detail::require_positive({{s.lpp, "lpp"}, {s.beam, "beam"}, {s.draft_fp, "draft_fp"},
                            {s.midship_area, "midship_area"}, {s.displacement_volume, "displacement_volume"}});
}

/// Largest y where the edges of the submerged triangle `t` cross the plane x = x_fp.
void add_section_breadth(const Tri& t, double x_fp, Forward& f) {
  for (int k = 0; k < 3; ++k) {
    const Vec3& p = t[k];
    const Vec3& q = t[(k + 1) % 3];
    if ((p.x() - x_fp) * (q.x() - x_fp) <= 0 && p.x() != q.x())
      f.y_max = std::max(f.y_max, p.y() + (x_fp - p.x()) / (q.x() - p.x()) * (q.y() - p.y()));
  }
}

/// Area, volume, centre-plane and nose terms of a piece forward of x_fp.
void add_forward_piece(const Tri& t, double x_fp, bool centre_plane, Forward& f) {
  const Vec3 n = triangles::area_vector(t);
  f.ax += n.x();
  f.vol += ((t[0].x() + t[1].x() + t[2].x()) / 3.0 - x_fp) * n.x();
  if (centre_plane) f.lateral += n.norm();
  const Vec3& front = *std::max_element(t.begin(), t.end(), [](const Vec3& a, const Vec3& b) { return a.x() < b.x(); });
  if (front.x() > f.nose.x()) f.nose = front;
}

}  // namespace

KrachtCoefficients measure_kracht(const TriMesh& mesh, const ShipParticulars& ship) {
  triangles::check_mesh(mesh);
  check_ship(ship);
  const double x_fp = fp_x(ship);
  Forward f;
  std::vector<Tri> below, forward;
  for (Eigen::Index i = 0; i < mesh.faces.rows(); ++i) {
    const Tri t = triangles::triangle(mesh, i);
    const double x_max = std::max({t[0].x(), t[1].x(), t[2].x()});
    const double z_min = std::min({t[0].z(), t[1].z(), t[2].z()});
    if (!(x_max > x_fp && z_min < ship.draft_fp)) continue;
    const bool centre_plane = t[0].y() == 0.0 && t[1].y() == 0.0 && t[2].y() == 0.0;
    below.clear();
    triangles::clip(t, 2, ship.draft_fp, Keep::Below, below);
    for (const Tri& low : below) {
      add_section_breadth(low, x_fp, f);
      forward.clear();
      triangles::clip(low, 0, x_fp, Keep::Above, forward);
      for (const Tri& piece : forward) add_forward_piece(piece, x_fp, centre_plane, f);
    }
  }
  KrachtCoefficients k;
  k.c_lpr = (f.nose.x() - x_fp) / ship.lpp;
  k.c_bb = 2.0 * f.y_max / ship.beam;
  k.c_zb = f.nose.z() / ship.draft_fp;
  k.c_abt = 2.0 * f.ax / ship.midship_area;
  k.c_abl = f.lateral / ship.midship_area;
  k.c_vpr = 2.0 * f.vol / ship.displacement_volume;
  return k;
}

}  // namespace fairlines
