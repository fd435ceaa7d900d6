// Boolean composition (union) of a bare hull and a bulbous bow into one watertight,
// consistently oriented half-hull mesh closed by the centre plane, the deck and an aft cut.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "fairlines/blend.hpp"
#include "fairlines/intersect.hpp"
#include "fairlines/mesh.hpp"
#include "fairlines/surface.hpp"

namespace fairlines {

struct ComposeOptions {
  int hull_u = 48;
  int hull_v = 20;
  int bulb_u = 24;
  int bulb_v = 32;
  double tolerance = 1e-7;
  double margin = 0.3;
  double plane_tolerance = 1e-6;
  int blend_rows = 8;
  int blend_check_samples = 200;

  /// Each field with its name and meaning: f(name, member pointer, doc).
  template <typename F>
  static void fields(F&& f) {
    f("hull_u", &ComposeOptions::hull_u, "hull tessellation cells along u (>= 4)");
    f("hull_v", &ComposeOptions::hull_v, "hull tessellation cells along v (>= 4)");
    f("bulb_u", &ComposeOptions::bulb_u, "bulb cells from the seam to the nose (>= 2)");
    f("bulb_v", &ComposeOptions::bulb_v, "bulb cells around the half section; also seam segments (>= 4)");
    f("tolerance", &ComposeOptions::tolerance, "surface-surface intersection tolerance (m, <= 1e-6)");
    f("margin", &ComposeOptions::margin, "clearance kept between the seam and whole hull cells (in cells)");
    f("plane_tolerance", &ComposeOptions::plane_tolerance, "relative tolerance of the centre plane / deck / aft checks");
    f("blend_rows", &ComposeOptions::blend_rows, "blend cells from the hull boundary to the bulb boundary (>= 1)");
    f("blend_check_samples", &ComposeOptions::blend_check_samples, "boundary points at which the blend's continuity is measured (>= 2)");
  }
};

/// The blending subdomain of a composition: its boundary on the hull (a (k, 2) (u, v)
/// polyline on orient_bare_hull(hull), from one centre-plane edge point to another) and on
/// the bulb (the section u = bulb_u of the bulb, v from bottom to top).
struct BlendSpec {
  Eigen::MatrixXd hull_uv;
  double bulb_u = 0.5;
  double tension = 1.0;

  /// Each field with its name and meaning: f(name, member pointer, doc).
  template <typename F>
  static void fields(F&& f) {
    f("hull_uv", &BlendSpec::hull_uv, "(k, 2) (u, v) polyline on the oriented hull from one centre-plane edge point to another");
    f("bulb_u", &BlendSpec::bulb_u, "the bulb section u = bulb_u where the blend meets the bulb");
    f("tension", &BlendSpec::tension, "cross-boundary tangent length / (|B - A| / 3), > 0");
  }
};

/// A subdomain surface restricted by trimming loops in its own (u, v) parameter space.
struct TrimmedSurface {
  int subdomain = 0;                   ///< 0: bare hull, 1: bulb
  std::vector<Eigen::MatrixXd> loops;  ///< each (k, 2): (u, v) vertices, counter-clockwise, kept side inside
};

/// Face labels of the composed mesh.
enum class FacePart { Hull = 0, Bulb = 1, CentrePlane = 2, Deck = 3, AftCut = 4, Blend = 5 };

struct ComposedHull {
  TriMesh mesh;                                   ///< closed half hull, outward-oriented
  Eigen::VectorXi face_part;                      ///< FacePart of each face
  std::vector<TrimmedSurface> trimmed_surfaces;   ///< hull (and bulb) with their loops
  std::vector<IntersectionCurve> intersection_curves;  ///< seam(s) at the mesh resolution
  Eigen::VectorXi seam_vertices;                  ///< mesh vertex index of each seam point
  double x_aft = 0.0;                             ///< aft cut plane x (m; a raked transom's: its mean x)
  double z_deck = 0.0;                            ///< deck plane z (m)
  NurbsSurface hull;                              ///< the hull as used (re-oriented to the convention)
  std::vector<NurbsSurface> blend;                ///< the blending surface, when composed with one
  BoundaryContinuity blend_at_hull, blend_at_bulb;  ///< its measured continuity
  std::vector<NurbsSurface> bulb;                 ///< the bulb surface, when composed with one
  /// Blend sections, bottom to top: (k, 5) rows (s on the blend, u and v on `hull`, u and v
  /// on the bulb); empty without a blend.
  Eigen::MatrixXd blend_params;
  /// #faces by 6: each hull face's corners (u, v) on `hull` as (u0, v0, u1, v1, u2, v2), the
  /// flat face's chord of that parameter triangle; NaN rows for the other faces.
  Eigen::MatrixXd hull_face_uv;
  /// k by 6: the hull's parameter triangles that have no face, collapsed to a line or point at a
  /// pole (the stem head), as hull_face_uv's rows: hull surface all the same.
  Eigen::MatrixXd hull_collapsed_uv;
};

/// The aft end of an oriented bare hull (its u = u_min edge): either in a plane -- a transom,
/// upright (x = const) or raked -- which a planar face closes, or on the centre plane y = 0 (a
/// cruiser stern), which needs no face.
struct AftEnd {
  bool on_centre_plane = false;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitX();  ///< unit normal of the transom plane, normal.x() > 0
  double offset = 0.0;                                 ///< the plane is normal . p = offset (m)
  /// The transom's corner on the deck and the centre plane (m); for a cruiser stern the aft
  /// edge's top end.
  Eigen::Vector3d deck_corner = Eigen::Vector3d::Zero();
};

/// Classifies the aft edge of a hull in the orient_bare_hull convention. `z_deck`: the deck
/// height. Throws InvalidInput when the edge is neither on y = 0 nor in one plane whose normal
/// has an x component of at least 0.2 (a rake under about 78 degrees).
AftEnd aft_end(const NurbsSurface& oriented_hull, double z_deck,
               double plane_tolerance = ComposeOptions{}.plane_tolerance);

/// Brings a bare hull surface to the convention used here by swapping / reversing its
/// directions: u = u_min on the aft end (in one plane, upright or raked, or on the centre
/// plane: see aft_end), v = v_min on the centre plane (keel, y = 0), v = v_max on the deck
/// (z constant), u = u_max on the centre plane (stem).
/// Throws InvalidInput naming the edge that fits no plane.
NurbsSurface orient_bare_hull(const NurbsSurface& hull, double plane_tolerance = ComposeOptions{}.plane_tolerance);

/// Union of the bare hull (any orientation accepted by orient_bare_hull) and, if `bulb` is
/// non-null, a bulb surface laid out as make_bulbous_bow makes it (u aft -> nose pole, v
/// bottom -> top centre line). Throws InvalidInput when the bulb does not meet the hull in
/// one seam from the keel/stem line around to the stem ("bulb cannot meet the hull").
/// With `blend`, hull and bulb do not intersect: the hull is trimmed along blend->hull_uv,
/// the bulb along u = blend->bulb_u, and a blending surface (blend_surface, G2 along both)
/// joins them; the three meshes share the boundary vertices.
ComposedHull compose_hull(const NurbsSurface& hull, const NurbsSurface* bulb, const ComposeOptions& options = {},
                          const BlendSpec* blend = nullptr);

/// The union seam of a bare hull and a bulb without the mesh: `hull` re-oriented as in
/// compose_hull and the seam as compose_hull([hull, bulb]) reports it (intersection_curves[0],
/// re-sampled at the options.bulb_v + 1 bulb columns), with the same checks on the seam (one
/// branch around the bulb, ends on the keel/stem centre line). For placing a blend around the
/// seam, which needs the seam and not the union mesh.
struct HullBulbSeam {
  NurbsSurface hull;      ///< the hull as used (re-oriented to the convention)
  IntersectionCurve seam;  ///< uv_a on `hull`, uv_b on the bulb
};
HullBulbSeam hull_bulb_seam(const NurbsSurface& hull, const NurbsSurface& bulb, const ComposeOptions& options = {});

/// Full hull: the half hull mirrored in y = 0 and welded along the centre plane, with the
/// centre-plane faces dropped.
TriMesh mirror_full_hull(const ComposedHull& composed);

/// Half-hull volume (m^3), its moments about x = 0 and z = 0 (m^4) and wetted area (m^2) below
/// a waterplane, in the waterplane's frame (see hull_chord_difference).
struct BelowPlane {
  double volume = 0.0, mx = 0.0, mz = 0.0, wetted = 0.0;
};

/// What the flat hull faces of `a` miss of the hull surface below the waterplane, less what
/// those of `b` miss: the sum over a's hull faces (ComposedHull::hull_face_uv) and the parameter
/// triangles a pole collapses (hull_collapsed_uv, no flat face) that b does not have of (the
/// surface over the triangle - the flat face), minus the same over b's that a does not have;
/// triangles both have cancel, so of a composed hull
/// (`a`) and the bare hull closed alone (`b`, same hull and grid) it is the correction of the
/// meshes' difference (the bulb's share) for the hull cells the bulb removes and the band round
/// the seam. The waterplane: `draft` (m) at x = lpp / 2 with `trim` (m by the stern over `lpp`),
/// figures in its frame (the ship rotated about the y axis through (lpp / 2, 0, draft) by
/// atan(trim / lpp)), half hull. Each term is the flux of (0, 0, g) with div = 1, x, z below
/// the plane (and the area there) by a 7-point rule per face, on 8 x 8 sub-triangles where a
/// face reaches the plane. Throws InvalidInput for lpp <= 0.
BelowPlane hull_chord_difference(const ComposedHull& a, const ComposedHull& b, double draft, double trim, double lpp);

}  // namespace fairlines
