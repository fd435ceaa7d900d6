// What a composed hull's flat hull faces miss of the hull surface below a waterplane, against
// another composition of the same hull: see hull_chord_difference in fairlines/compose.hpp.
//
// Notation:
//   (s, t)       a face's reference coordinates, corners (0, 0), (1, 0), (0, 1)
//   q, N         a point and the normal q_s x q_t (not unit), in the waterplane's frame
//   z0           the waterplane's height in its frame (the draft)
//   g            the flux's z component below the plane: z - z0 (volume), x (z - z0) (moment
//                about x = 0), (z^2 - z0^2) / 2 (about z = 0); nothing above it
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "fairlines/compose.hpp"
#include "fairlines/errors.hpp"

namespace fairlines {

namespace {

/// Dunavant's 7-point rule of degree 5 on the reference triangle: (s, t, weight), weights
/// summing to 1 (times the reference area 1/2 where used).
constexpr double kA1 = 0.059715871789770, kB1 = 0.470142064105115;
constexpr double kA2 = 0.797426985353087, kB2 = 0.101286507323456;
constexpr double kW0 = 0.225, kW1 = 0.132394152788506, kW2 = 0.125939180544827;
constexpr std::array<std::array<double, 3>, 7> kRule = {{{1.0 / 3, 1.0 / 3, kW0},
                                                        {kB1, kB1, kW1}, {kA1, kB1, kW1}, {kB1, kA1, kW1},
                                                        {kB2, kB2, kW2}, {kA2, kB2, kW2}, {kB2, kA2, kW2}}};
/// A face whose corners come within this share of its longest edge of the plane is integrated
/// on kSplit x kSplit sub-triangles: the integrand has a kink along the plane.
constexpr double kNearPlane = 0.25;
constexpr int kSplit = 8;
/// orient_bare_hull's convention (u aft -> stem, v keel -> deck) turns S_u x S_v into the hull.
constexpr double kCollapsedSide = -1.0;

/// The waterplane's frame: rotation about the y axis through (x0, 0, z0).
struct Frame {
  double x0, z0, c, s;
  Eigen::Vector3d point(const Eigen::Vector3d& p) const {
    const double dx = p.x() - x0, dz = p.z() - z0;
    return {x0 + c * dx - s * dz, p.y(), z0 + s * dx + c * dz};
  }
  Eigen::Vector3d vector(const Eigen::Vector3d& v) const { return {c * v.x() - s * v.z(), v.y(), s * v.x() + c * v.z()}; }
};

BelowPlane& operator+=(BelowPlane& a, const BelowPlane& b) {
  a.volume += b.volume;
  a.mx += b.mx;
  a.mz += b.mz;
  a.wetted += b.wetted;
  return a;
}

BelowPlane& operator-=(BelowPlane& a, const BelowPlane& b) {
  a.volume -= b.volume;
  a.mx -= b.mx;
  a.mz -= b.mz;
  a.wetted -= b.wetted;
  return a;
}

void accumulate(BelowPlane& acc, const Eigen::Vector3d& q, const Eigen::Vector3d& n, double w, double z0) {
  const double dz = q.z() - z0;
  if (dz >= 0.0) return;
  acc.volume += w * dz * n.z();
  acc.mx += w * q.x() * dz * n.z();
  acc.mz += w * 0.5 * (q.z() * q.z() - z0 * z0) * n.z();
  acc.wetted += w * n.norm();
}

/// (surface over the parameter triangle `uv` (u0, v0, u1, v1, u2, v2) of H) - (the flat face
/// P, in the frame), below the plane. A face's surface normal is turned to the flat face's side;
/// a collapsed triangle (no face: P null) has no flat part and takes H's S_u x S_v turned
/// outward (kCollapsedSide), whatever its corners' order.
BelowPlane face_difference(const NurbsSurface& H, const std::array<double, 6>& uv, const std::array<Eigen::Vector3d, 3>* P,
                           const Frame& fr) {
  const Eigen::Vector2d a(uv[0], uv[1]), b(uv[2], uv[3]), c(uv[4], uv[5]);
  std::array<Eigen::Vector3d, 3> corner;
  if (P) corner = *P;
  else
    for (int k = 0; k < 3; ++k) corner[k] = fr.point(H.evaluate(uv[2 * k], uv[2 * k + 1]));
  const double zmin = std::min({corner[0].z(), corner[1].z(), corner[2].z()});
  const double zmax = std::max({corner[0].z(), corner[1].z(), corner[2].z()});
  const double size = std::max({(corner[1] - corner[0]).norm(), (corner[2] - corner[1]).norm(), (corner[0] - corner[2]).norm()});
  BelowPlane d;
  if (zmin > fr.z0 + kNearPlane * size) return d;  // wholly above: neither the face nor its surface is wetted
  const int split = (zmax > fr.z0 - kNearPlane * size) ? kSplit : 1;
  const double w_sub = 0.5 / (split * split);
  std::vector<double> us, vs, st;
  for (int i = 0; i < split; ++i)
    for (int j = 0; i + j < split; ++j)
      for (int up = 0; up < 2; ++up) {
        if (up && i + j + 1 >= split) continue;
        // sub-triangle corners in (s, t): lower (i, j) (i+1, j) (i, j+1); upper (i+1, j) (i+1, j+1) (i, j+1)
        const double s0 = double(i + up) / split, t0 = double(j) / split;
        const double ds1 = up ? 0.0 : 1.0 / split, dt1 = up ? 1.0 / split : 0.0;
        const double ds2 = up ? -1.0 / split : 0.0, dt2 = 1.0 / split;
        for (const auto& r : kRule) {
          const double s = s0 + r[0] * ds1 + r[1] * ds2, t = t0 + r[0] * dt1 + r[1] * dt2;
          const Eigen::Vector2d p = a + s * (b - a) + t * (c - a);
          us.push_back(p.x());
          vs.push_back(p.y());
          st.insert(st.end(), {s, t, r[2]});
        }
      }
  const long n = static_cast<long>(us.size());
  std::vector<double> D(9 * n);
  H.evaluate_first_derivatives_into(us.data(), vs.data(), n, D.data());
  const Eigen::Vector2d e1 = b - a, e2 = c - a;
  std::vector<Eigen::Vector3d> q(n), nn(n);
  const Eigen::Vector3d n_flat = P ? ((*P)[1] - (*P)[0]).cross((*P)[2] - (*P)[0]).eval() : Eigen::Vector3d::Zero();
  double side = 0.0;  // the surface's normal turned to the flat face's side (the mesh's orientation pass may flip a face)
  for (long k = 0; k < n; ++k) {
    const Eigen::Map<const Eigen::Vector3d> S(&D[9 * k]), Su(&D[9 * k + 3]), Sv(&D[9 * k + 6]);
    q[k] = fr.point(S);
    // a collapsed triangle: H's own normal S_u x S_v, scaled by the triangle's parameter area
    nn[k] = P ? fr.vector((Su * e1.x() + Sv * e1.y()).cross(Su * e2.x() + Sv * e2.y()))
              : fr.vector(Su.cross(Sv)) * std::abs(e1.x() * e2.y() - e1.y() * e2.x()) * kCollapsedSide;
    side += P ? nn[k].dot(n_flat) * st[3 * k + 2] : 1.0;
  }
  const double sign = side < 0.0 ? -1.0 : 1.0;
  BelowPlane flat;
  for (long k = 0; k < n; ++k) {
    const double s = st[3 * k], t = st[3 * k + 1], w = st[3 * k + 2] * w_sub;
    accumulate(d, q[k], sign * nn[k], w, fr.z0);
    if (P) accumulate(flat, (*P)[0] + s * ((*P)[1] - (*P)[0]) + t * ((*P)[2] - (*P)[0]), n_flat, w, fr.z0);
  }
  return d -= flat;
}

/// A parameter triangle's corners sorted, so it keys alike whatever its corner order.
std::array<double, 6> corner_key(const Eigen::MatrixXd& uv, Eigen::Index f) {
  std::array<std::array<double, 2>, 3> c = {{{uv(f, 0), uv(f, 1)}, {uv(f, 2), uv(f, 3)}, {uv(f, 4), uv(f, 5)}}};
  std::sort(c.begin(), c.end());
  return {c[0][0], c[0][1], c[1][0], c[1][1], c[2][0], c[2][1]};
}

/// The sorted keys of m's hull parameter triangles, faces' and collapsed ones'.
std::vector<std::array<double, 6>> hull_keys(const ComposedHull& m) {
  std::vector<std::array<double, 6>> keys;
  for (Eigen::Index f = 0; f < m.hull_face_uv.rows(); ++f)
    if (!std::isnan(m.hull_face_uv(f, 0))) keys.push_back(corner_key(m.hull_face_uv, f));
  for (Eigen::Index f = 0; f < m.hull_collapsed_uv.rows(); ++f) keys.push_back(corner_key(m.hull_collapsed_uv, f));
  std::sort(keys.begin(), keys.end());
  return keys;
}

std::array<double, 6> row(const Eigen::MatrixXd& uv, Eigen::Index f) {
  return {uv(f, 0), uv(f, 1), uv(f, 2), uv(f, 3), uv(f, 4), uv(f, 5)};
}

/// Sum of face_difference over m's hull parameter triangles whose key `other` does not hold.
BelowPlane unshared(const ComposedHull& m, const std::vector<std::array<double, 6>>& other, const Frame& fr) {
  BelowPlane acc;
  auto shared = [&](const Eigen::MatrixXd& uv, Eigen::Index f) {
    return std::binary_search(other.begin(), other.end(), corner_key(uv, f));
  };
  for (Eigen::Index f = 0; f < m.hull_face_uv.rows(); ++f) {
    if (std::isnan(m.hull_face_uv(f, 0)) || shared(m.hull_face_uv, f)) continue;
    std::array<Eigen::Vector3d, 3> P;
    for (int k = 0; k < 3; ++k) P[k] = fr.point(m.mesh.vertices.row(m.mesh.faces(f, k)).transpose());
    acc += face_difference(m.hull, row(m.hull_face_uv, f), &P, fr);
  }
  for (Eigen::Index f = 0; f < m.hull_collapsed_uv.rows(); ++f)
    if (!shared(m.hull_collapsed_uv, f)) acc += face_difference(m.hull, row(m.hull_collapsed_uv, f), nullptr, fr);
  return acc;
}

}  // namespace

BelowPlane hull_chord_difference(const ComposedHull& a, const ComposedHull& b, double draft, double trim, double lpp) {
  if (!(lpp > 0.0)) throw InvalidInput("lpp is " + std::to_string(lpp) + "; expected a length > 0 (m)");
  const double theta = std::atan2(trim, lpp);
  const Frame fr{0.5 * lpp, draft, std::cos(theta), std::sin(theta)};
  BelowPlane d = unshared(a, hull_keys(b), fr);
  return d -= unshared(b, hull_keys(a), fr);
}

}  // namespace fairlines
