// Surface-surface intersection, bulb from Kracht coefficients and the composed hull.
#include <algorithm>
#include <array>
#include <cmath>

#include <gtest/gtest.h>

#include "compose_fixtures.hpp"
#include "fairlines/blend.hpp"
#include "fairlines/bulb.hpp"
#include "fairlines/compose.hpp"
#include "fairlines/conics.hpp"
#include "fairlines/errors.hpp"
#include "fairlines/intersect.hpp"
#include "fairlines/mesh_hydrostatics.hpp"

using namespace fairlines;
using fairlines::test::Forebody;

namespace {

NurbsSurface plane_z(double z0, double half) {  // bilinear plane z = z0 over [-half, half]^2
  Eigen::VectorXd k(4);
  k << 0, 0, 1, 1;
  Eigen::MatrixXd P(4, 3);
  P << -half, -half, z0, -half, half, z0, half, -half, z0, half, half, z0;
  return NurbsSurface(1, 1, k, k, 2, 2, P);
}

}  // namespace

TEST(Intersect, SphereAndPlaneGiveTheCircle) {
  // exact rational sphere of radius 3 cut by z = 1: circle of radius sqrt(8)
  const NurbsSurface s = sphere(Eigen::Vector3d::Zero(), 3.0);
  const auto curves = intersect_surfaces(s, plane_z(1.0, 5.0));
  ASSERT_GE(curves.size(), 1u);
  double max_r_err = 0.0, max_gap = 0.0;
  size_t n = 0;
  for (const auto& c : curves) {
    max_gap = std::max(max_gap, c.max_gap);
    for (const auto& p : c.points) {
      max_r_err = std::max(max_r_err, std::abs(std::hypot(p.point.x(), p.point.y()) - std::sqrt(8.0)));
      max_r_err = std::max(max_r_err, std::abs(p.point.z() - 1.0));
      ++n;
    }
  }
  EXPECT_GT(n, 20u);
  EXPECT_LT(max_r_err, 1e-6);
  EXPECT_LT(max_gap, 1e-6);
}

TEST(Intersect, DisjointSurfacesGiveNothing) {
  const NurbsSurface s = sphere(Eigen::Vector3d::Zero(), 1.0);
  EXPECT_TRUE(intersect_surfaces(s, plane_z(2.0, 5.0)).empty());
}

TEST(Bulb, AnalyticBodyMeetsTheKrachtQuantities) {
  Forebody fb;
  KrachtCoefficients k;
  const BulbousBow b = make_bulbous_bow(k, fb.ship());
  const ShipParticulars s = fb.ship();
  EXPECT_NEAR(b.shape.length, k.c_lpr * s.lpp, 1e-12);
  EXPECT_LT(b.max_fit_deviation, 0.02);
  // nose pole: foremost point at FP + L_PR and height Z_B
  const Eigen::Vector3d nose = b.surface.evaluate(1.0, 0.5);
  EXPECT_NEAR(nose.x(), s.lpp + k.c_lpr * s.lpp, 1e-9);
  EXPECT_NEAR(nose.z(), k.c_zb * s.draft_fp, 1e-9);
}

TEST(Bulb, ConflictingCoefficientsAreReported) {
  Forebody fb;
  KrachtCoefficients k;
  k.c_vpr = 0.02;  // far more volume than the section and length allow
  EXPECT_THROW(make_bulbous_bow(k, fb.ship()), InfeasibleFormParameters);
  k = KrachtCoefficients{};
  k.c_bb = -0.1;
  EXPECT_THROW(make_bulbous_bow(k, fb.ship()), InvalidInput);
}

TEST(Compose, BareHullIsClosedAndHasTheQuadratureVolume) {
  Forebody fb;
  const NurbsSurface h = fb.surface();
  const ComposedHull c = compose_hull(h, nullptr, ComposeOptions{});
  const auto chk = fairlines::test::check_edges(c.mesh);
  EXPECT_EQ(chk.open, 0);
  EXPECT_EQ(chk.non_manifold, 0);
  EXPECT_EQ(chk.misoriented, 0);
  // analytic volume of the half forebody: int int y dz dx
  // int_0^1 (1 - xi^4) dxi = 4/5; int_0^D (1 - (1 - z/D)^6) dz = 6 D / 7
  const double exact = 0.5 * fb.B * (0.5 * fb.L) * 0.8 * fb.D * 6.0 / 7.0;
  EXPECT_NEAR(mesh_volume(c.mesh) / exact, 1.0, 2e-3);
}

TEST(Compose, HullWithBulbIsWatertightOrientedAndSelfIntersectionFree) {
  Forebody fb;
  const NurbsSurface h = fb.surface();
  const BulbousBow b = make_bulbous_bow(KrachtCoefficients{}, fb.ship());
  const ComposedHull c = compose_hull(h, &b.surface, ComposeOptions{});
  const auto chk = fairlines::test::check_edges(c.mesh);
  EXPECT_EQ(chk.open, 0);
  EXPECT_EQ(chk.non_manifold, 0);
  EXPECT_EQ(chk.misoriented, 0);
  EXPECT_EQ(fairlines::test::count_self_intersections(c.mesh), 0);
  ASSERT_EQ(c.intersection_curves.size(), 1u);
  EXPECT_LT(c.intersection_curves[0].max_gap, 1e-6);
  // every seam vertex lies on both surfaces
  for (const auto& p : c.intersection_curves[0].points) {
    EXPECT_LT((c.hull.evaluate(p.uv_a.x(), p.uv_a.y()) - p.point).norm(), 1e-6);
    EXPECT_LT((b.surface.evaluate(p.uv_b.x(), p.uv_b.y()) - p.point).norm(), 1e-6);
  }
  EXPECT_GT(mesh_volume(c.mesh), 0.0);
  const TriMesh full = mirror_full_hull(c);
  const auto fchk = fairlines::test::check_edges(full);
  EXPECT_EQ(fchk.open, 0);
  EXPECT_EQ(fchk.non_manifold, 0);
  EXPECT_EQ(fchk.misoriented, 0);
  EXPECT_NEAR(mesh_volume(full), 2.0 * mesh_volume(c.mesh), 1e-6 * mesh_volume(full));
}

TEST(Compose, BulbAwayFromTheHullIsAClearError) {
  Forebody fb;
  ShipParticulars s = fb.ship();
  s.x_fp = s.lpp + 40.0;  // bulb entirely ahead of the stem
  const BulbousBow b = make_bulbous_bow(KrachtCoefficients{}, s);
  try {
    compose_hull(fb.surface(), &b.surface, ComposeOptions{});
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("bulb cannot meet the hull"), std::string::npos) << e.what();
  }
}

TEST(Blend, FilletFromPlaneToCylinderIsTangentPlaneContinuous) {
  const NurbsSurface plane = plane_z(0.0, 5.0);  // (u, v) -> (-5 + 10 u, -5 + 10 v, 0)
  const NurbsSurface cyl = cylinder(Eigen::Vector3d(0, 0, 2), Eigen::Vector3d(0, 0, 1), 1.0, 3.0);
  const int k = 129;
  Eigen::MatrixXd ca(k, 2), cb(k, 2);
  for (int i = 0; i < k; ++i) {
    const double a = 2.0 * M_PI * i / (k - 1);
    ca.row(i) << 0.5 + 0.3 * std::cos(a), 0.5 + 0.3 * std::sin(a);
    cb.row(i) << static_cast<double>(i) / (k - 1), 0.0;  // the cylinder's bottom circle
  }
  const BlendSurface b = blend_surface(plane, ca, cyl, cb);
  EXPECT_LT(b.at_a.max_angle_deg, 0.5);
  EXPECT_LT(b.at_b.max_angle_deg, 0.5);
  EXPECT_LT(b.at_a.max_gap, 1e-3);
  // independent check at the boundary: the blend's normal is vertical on the plane side
  for (int i = 0; i <= 20; ++i) {
    const Eigen::MatrixXd d = b.surface.derivatives(i / 20.0, 0.0, 1);
    const Eigen::Vector3d su = d.row(2).transpose(), sv = d.row(1).transpose();
    const Eigen::Vector3d n = su.cross(sv).normalized();
    EXPECT_GT(std::abs(n.z()), std::cos(0.5 * M_PI / 180.0));
  }
  Eigen::MatrixXd one(1, 2);
  one << 0.5, 0.5;
  EXPECT_THROW(blend_surface(plane, one, cyl, cb), InvalidInput);
}

TEST(Blend, QuinticSectionsGiveTheSphereItsCurvatureAcrossTheBoundary) {
  // A fillet from the plane z = 0 (a half circle of radius 8, y <= 0) up to a sphere of radius R
  // about c (its half circle 45 deg south of the equator, radius 5.7). A curve on a sphere has
  // normal curvature -n . n_out / R along any normal n (n_out the outward unit normal); on the
  // plane, 0. The blend's across its boundaries: its v = const edges' n . S_vv / |S_v|^2. The
  // sphere is large against the blend (R over the sections' speed, 4.9 m x 0.8: the curvature
  // term is an eighth of the handle, under kCurvatureTermCap). (At y > 0 the handles would turn
  // to keep a half hull's blend off its centre plane.)
  const NurbsSurface plane = plane_z(0.0, 20.0);  // (u, v) -> (-20 + 40 u, -20 + 40 v, 0)
  const Eigen::Vector3d c(0.0, 0.0, 10.0);
  const double R = 8.0;
  const NurbsSurface ball = sphere(c, R);  // u around z from +x, v from the south pole
  const int k = 65;
  Eigen::MatrixXd ca(k, 2), cb(k, 2);
  for (int i = 0; i < k; ++i) {
    const double a = M_PI + M_PI * i / (k - 1);
    ca.row(i) << 0.5 + 0.2 * std::cos(a), 0.5 + 0.2 * std::sin(a);
    cb.row(i) << 0.5 + 0.5 * i / (k - 1), 0.25;
  }
  auto across = [](const NurbsSurface& s, double u, double v, Eigen::Vector3d& p, Eigen::Vector3d& n) {
    const Eigen::MatrixXd d = s.derivatives(u, v, 2);  // row k * 3 + l: d^(k+l) / du^k dv^l
    const Eigen::Vector3d sv = d.row(1).transpose(), svv = d.row(2).transpose(), su = d.row(3).transpose();
    p = d.row(0).transpose();
    n = su.cross(sv).normalized();
    return n.dot(svv) / sv.squaredNorm();
  };
  for (const int continuity : {1, 2}) {
    BlendOptions o;
    o.continuity = continuity;
    o.centre_plane_ends = false;  // its ends on y = 0 are no half hull's
    const BlendSurface b = blend_surface(plane, ca, ball, cb, o);
    EXPECT_LT(b.at_a.max_angle_deg, 0.5);
    EXPECT_LT(b.at_b.max_angle_deg, 0.5);
    double miss_plane = 0.0, miss_ball = 0.0;
    for (int i = 0; i <= 100; ++i) {
      Eigen::Vector3d p, n;
      miss_plane = std::max(miss_plane, std::abs(across(b.surface, i / 100.0, 0.0, p, n)));
      const double kb = across(b.surface, i / 100.0, 1.0, p, n);
      miss_ball = std::max(miss_ball, std::abs(kb + n.dot((p - c) / R) / R));
    }
    if (continuity == 2) {
      EXPECT_EQ(b.surface.degree_v(), 5);
      EXPECT_LT(miss_plane, 1e-6 / R);
      EXPECT_LT(miss_ball, 1e-3 / R);
    } else {  // cubic sections meet both with curvatures of their own
      EXPECT_GT(miss_plane, 0.1 / R);
      EXPECT_GT(miss_ball, 0.1 / R);
    }
  }
  BlendOptions bad;
  bad.continuity = 3;
  EXPECT_THROW(blend_surface(plane, ca, ball, cb, bad), InvalidInput);
}

TEST(Compose, HullBulbAndBlendComposeWatertightWithC1Boundaries) {
  Forebody fb;
  const NurbsSurface h = fb.surface();
  const BulbousBow b = make_bulbous_bow(KrachtCoefficients{}, fb.ship());
  const ComposedHull u = compose_hull(h, &b.surface, ComposeOptions{});
  // hull boundary: a half ellipse in (u, v) around the union seam, ending on the stem edge
  double umin = 1.0, tlo = 1.0, thi = 0.0, ubmax = 0.0;
  for (const auto& p : u.intersection_curves[0].points) {
    umin = std::min(umin, p.uv_a.x());
    tlo = std::min(tlo, p.uv_a.y());
    thi = std::max(thi, p.uv_a.y());
    ubmax = std::max(ubmax, p.uv_b.x());
  }
  const double tc = 0.5 * (tlo + thi), R = 0.5 * (thi - tlo) + 0.03, du = 1.0 - umin + 0.02;
  ASSERT_GT(tc - R, 0.0);
  const int k = 65;
  BlendSpec spec;
  spec.hull_uv.resize(k, 2);
  for (int i = 0; i < k; ++i) {
    const double phi = M_PI * i / (k - 1);
    spec.hull_uv.row(i) << 1.0 - du * std::sin(phi), tc - R * std::cos(phi);
  }
  spec.bulb_u = std::min(0.95, ubmax + 0.08);
  const ComposedHull c = compose_hull(h, &b.surface, ComposeOptions{}, &spec);
  const auto chk = fairlines::test::check_edges(c.mesh);
  EXPECT_EQ(chk.open, 0);
  EXPECT_EQ(chk.non_manifold, 0);
  EXPECT_EQ(chk.misoriented, 0);
  EXPECT_EQ(fairlines::test::count_self_intersections(c.mesh), 0);
  EXPECT_LE(c.blend_at_hull.max_angle_deg, 0.5);
  EXPECT_LE(c.blend_at_bulb.max_angle_deg, 0.5);
  EXPECT_GT(mesh_volume(c.mesh), 0.0);
  const auto fchk = fairlines::test::check_edges(mirror_full_hull(c));
  EXPECT_EQ(fchk.open + fchk.non_manifold + fchk.misoriented, 0);
}

namespace {

double signed_area2(const Eigen::MatrixXd& P, const std::array<int, 3>& t) {
  const Eigen::Vector2d a = P.row(t[0]), b = P.row(t[1]), c = P.row(t[2]);
  return (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
}

/// A band like compose's: a flat arc of 24 points under a zigzag of 12 (a staircase's corners)
/// from x = 21 back to -1; ear clipping fans slivers from the zigzag to the arc.
Eigen::MatrixXd band_polygon() {
  Eigen::MatrixXd P(24 + 12, 2);
  for (int i = 0; i < 24; ++i) {
    const double t = M_PI * i / 23.0;
    P.row(i) << 10.0 - 10.0 * std::cos(t), 0.8 * std::sin(t);
  }
  for (int s = 0; s < 12; ++s) P.row(24 + s) << 21.0 - 2.0 * s, 1.6 + 0.3 * (s % 2);
  return P;
}

}  // namespace

TEST(Mesh, DelaunayFlipsLeaveNoEdgeWithItsOppositeVertexInsideTheCircle) {
  const Eigen::MatrixXd P = band_polygon();
  std::vector<std::array<int, 3>> tris = triangulate_polygon(P);
  double area_before = 0.0;
  for (const auto& t : tris) area_before += signed_area2(P, t);
  delaunay_flips(P, tris);
  ASSERT_EQ(static_cast<long>(tris.size()), P.rows() - 2);
  double area_after = 0.0;
  for (const auto& t : tris) {
    EXPECT_GT(signed_area2(P, t) * area_before, 0.0);  // every triangle keeps the polygon's orientation
    area_after += signed_area2(P, t);
  }
  EXPECT_NEAR(area_after, area_before, 1e-9 * std::abs(area_before));
  // locally Delaunay: across each shared edge, the other triangle's far vertex lies outside the
  // circumcircle (circumcentre and radius computed here)
  for (size_t i = 0; i < tris.size(); ++i)
    for (size_t j = 0; j < tris.size(); ++j) {
      int shared = 0, far = -1;
      for (int v : tris[j]) {
        if (std::find(tris[i].begin(), tris[i].end(), v) != tris[i].end()) ++shared;
        else far = v;
      }
      if (i == j || shared != 2) continue;
      const Eigen::Vector2d a = P.row(tris[i][0]), b = P.row(tris[i][1]), c = P.row(tris[i][2]);
      const double d = 2.0 * ((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
      const Eigen::Vector2d ab = b - a, ac = c - a;
      const Eigen::Vector2d o = a + Eigen::Vector2d(ac.y() * ab.squaredNorm() - ab.y() * ac.squaredNorm(),
                                                    ab.x() * ac.squaredNorm() - ac.x() * ab.squaredNorm()) / d;
      EXPECT_GE((Eigen::Vector2d(P.row(far)) - o).norm(), (a - o).norm() * (1.0 - 1e-9)) << i << " " << j;
    }
}

namespace {

TriMesh octahedron() {  // closed, outward: 8 faces about the origin
  TriMesh m;
  m.vertices.resize(6, 3);
  m.vertices << 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1;
  m.faces.resize(8, 3);
  m.faces << 0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5;
  return m;
}

void flip(TriMesh& m, Eigen::Index f) { std::swap(m.faces(f, 1), m.faces(f, 2)); }

}  // namespace

TEST(Mesh, OrientIfNeededLeavesWhatTheBreadthFirstPassLeaves) {
  const TriMesh good = octahedron();
  ASSERT_NEAR(mesh_volume(good), 4.0 / 3.0, 1e-12);  // two pyramids of base 2, height 1
  TriMesh inverted = good, one_flipped = good, two_flipped = good;
  for (Eigen::Index f = 0; f < 8; ++f) flip(inverted, f);
  flip(one_flipped, 3);
  flip(two_flipped, 0);
  flip(two_flipped, 6);
  for (const TriMesh* start : std::array<const TriMesh*, 4>{&good, &inverted, &one_flipped, &two_flipped}) {
    TriMesh a = *start, b = *start;
    const EdgeReport r = orient_if_needed(a);
    orient_consistently(b);
    EXPECT_TRUE(a.faces == b.faces);
    EXPECT_EQ(r.edges, 12);
    EXPECT_EQ(r.open + r.non_manifold + r.inconsistent + r.degenerate_faces, 0);
    EXPECT_NEAR(mesh_volume(a), 4.0 / 3.0, 1e-12);
  }
  const EdgeReport before = edge_report(one_flipped);  // face 3's three edges each met the same way
  EXPECT_EQ(before.inconsistent, 3);
  TriMesh open = good;
  open.faces.conservativeResize(7, 3);  // one face taken out: its three edges open
  const EdgeReport r = edge_report(open);
  EXPECT_EQ(r.edges, 12);
  EXPECT_EQ(r.open, 3);
  EXPECT_EQ(r.inconsistent, 0);
}

TEST(Compose, ChordDifferenceBringsTwoTessellationsOfOneHullToOneVolume) {
  // The forebody closed alone at 48 x 20 and 96 x 40 cells shares no face: the meshes' volumes
  // below T differ by their chords, which the chord difference (surface over each face's
  // parameter triangle less the flat face) accounts for.
  Forebody fb;
  const NurbsSurface h = fb.surface();
  ComposeOptions fine;
  fine.hull_u = 96;
  fine.hull_v = 40;
  const ComposedHull a = compose_hull(h, nullptr, ComposeOptions{}), b = compose_hull(h, nullptr, fine);
  const double va = mesh_hydrostatics(a.mesh, fb.T).volume, vb = mesh_hydrostatics(b.mesh, fb.T).volume;
  const BelowPlane d = hull_chord_difference(a, b, fb.T, 0.0, fb.L);
  EXPECT_GT(std::abs(va - vb), 1e-4 * vb);  // what there is to account for (full ship: twice the half)
  EXPECT_NEAR(va + 2.0 * d.volume, vb, 2e-5 * vb);
  const BelowPlane none = hull_chord_difference(a, a, fb.T, 0.0, fb.L);
  EXPECT_EQ(none.volume, 0.0);
  EXPECT_EQ(none.wetted, 0.0);
  EXPECT_THROW(hull_chord_difference(a, b, fb.T, 0.0, 0.0), InvalidInput);
}
