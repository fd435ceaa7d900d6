// Bare-hull sections on one shared knot vector (seed 000 step 2; SPEC §2, §5).
//
// Every section is designed directly on the same cubic knot vector, so fair skinning needs no
// refit (the refit of seed 000 Fig. 2c rings about flats and tight bilges) and the surface's
// control rows are smooth functions of the basic curves. A section is three pieces joined at
// knots of multiplicity 3 at fixed parameters:
//
//   u in [0, kTopZoneEnd]          top zone: a straight segment from the deck point along the
//                                  deck tangent -- the flat of side where there is one
//   u in [kTopZoneEnd, kBottomZoneStart]
//                                  curved part: the fairest curve (least E2) meeting the form
//                                  parameters, leaving both zones with G2 continuity
//   u in [kBottomZoneStart, 1]     bottom zone: a straight segment into the keel point along the
//                                  bottom tangent -- the flat of bottom where there is one
//
// Where the hull has no flat of side (or bottom) the zone keeps a short floor length (a few
// centimetres, kZoneFloor) instead of collapsing, so the surface stays regular; the zone length
// passes from the flat's length to the floor through a smooth soft maximum, so nothing jumps
// where a flat ends. The curved part is a graph over its chord (the straight line from the top
// zone's end A to the bottom zone's start E): control points A + xi_k d + eta_k n with the
// abscissae xi_k fixed (Greville abscissae times the chord length) and the ordinates eta_k the
// unknowns. Every condition used -- end points, end tangents with zero end curvature, the DWL
// point, the area below the DWL -- is then linear in eta, the fairest curve is one small KKT
// solve, and the section depends smoothly on the basic curves (no active sets, no switches).
#pragma once

#include <limits>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "fairlines/curve.hpp"

namespace fairlines {

/// Parameter where every section's top zone ends (the flat of side, or the short deck leg).
inline constexpr double kTopZoneEnd = 0.05;
/// Parameter where every section's bottom zone starts (the flat of bottom, or the keel leg).
inline constexpr double kBottomZoneStart = 0.95;
/// Least length of a zone, as a fraction of the section's depth (deck to keel): where there is
/// no flat the zone is this long (4.75 cm on a 19 m deep hull), never zero, so the surface has
/// no degenerate strip. Near a stem (breadth -> 0) it shrinks with the breadth (at most a
/// quarter of it, but not below a tenth of the floor) so that narrow sections keep their shape.
inline constexpr double kZoneFloor = 2.5e-3;
/// The curved part's end tangents must make an angle below acos(kMinTangentChordCos) (87 deg)
/// with its chord; a tangent pointing across or away from the chord cannot carry a graph.
inline constexpr double kMinTangentChordCos = 0.05;
/// Flat-side departure band, as a fraction of the draught: sections whose flat of side ends
/// less than this below the DWL blend their departure from the flat toward the rate the design
/// waterline has where it leaves the flat (SectionSpec::flat_departure); see design_section.
inline constexpr double kDepartureBand = 1.0;
/// Fore-side band, as a fraction of the draught: sections whose flat of side ends less than
/// this above the DWL blend from that departure condition to the exact DWL point (near the
/// crossing the DWL point sits within millimetres of the flat's end and pins the same rate).
inline constexpr double kDwlNearBand = 0.05;
/// Length over which a section's end passes from zero curvature (G2 with a flat of side or
/// bottom) to a free end curvature (no flat), as a fraction of the depth: the two designs are
/// blended with the flat's length (a smooth step from 0 to this length), so nothing jumps
/// where a flat ends, and cuts near the deck and keel of the fine bow keep a definite curvature.
inline constexpr double kG2Blend = 0.05;
/// Near a stem the end angles fade to vertical: a section narrower than this fraction of B/2
/// (largest of its deck, DWL and flat-bottom half-breadths) uses its deck and bottom angles
/// times a smooth step of its breadth, and the stem itself (zero breadth) is vertical. An angle
/// at a section only centimetres wide would swing its end legs across the centre plane.
inline constexpr double kAngleFadeBreadth = 0.1;
/// A designed section may exceed 0 <= y <= y_max by this fraction of y_max (round-off) before
/// it counts as infeasible.
inline constexpr double kSectionBoundTol = 1e-6;

/// Parameters of one section at station x, read off the basic curves (metres, degrees).
struct SectionSpec {
  double x = 0;            ///< station (m from AP)
  double z_deck = 0;       ///< deck height (m)
  double y_deck = 0;       ///< half-breadth at the deck (deck curve)
  double draft = 0;        ///< DWL height T (m)
  double y_dwl = 0;        ///< half-breadth at the DWL (design waterline)
  double z_keel = 0;       ///< keel / forefoot height (centre profile)
  double half_area = 0;    ///< half of the section area below the DWL (SAC / 2, m^2)
  double z_centroid = std::numeric_limits<double>::quiet_NaN();  ///< height of that area's centroid (optional)
  /// Lower end of the flat of side (m). The flat runs from the deck down to it; at or above the
  /// deck (or NaN) there is none. Beyond the end of the flat-of-side curve pass its linear
  /// extrapolation (above the deck), so the zone shrinks smoothly to its floor.
  double z_fos = std::numeric_limits<double>::quiet_NaN();
  /// Half-breadth of the flat of bottom (m); <= 0: none (pass the flat-of-bottom curve's
  /// extrapolation beyond its end, as for z_fos).
  double y_fob = 0;
  double alpha_deck = 0;      ///< tangent at the deck, deg from the downward vertical toward +y (0 vertical, < 0 flare); 0 under a flat of side
  double alpha_bottom = -90;  ///< tangent at the keel, same convention (-90 horizontal); -90 under a flat of bottom
  /// Departure rate K (1/m^2) of the design waterline from the flat of side where the flat's
  /// lower end crosses the DWL: there the waterline's deficit from B/2 grows as c dx^3 and the
  /// flat's end rises with slope s, so a section leaving the flat with zero curvature must lose
  /// K d^3 of breadth at depth d below the flat, K = c / s^3. Sections near the crossing (see
  /// kDepartureBand) blend toward it so the DWL can be met exactly without a jump; NaN: none.
  double flat_departure = std::numeric_limits<double>::quiet_NaN();
  int n_control = 16;  ///< control points of the curved part (>= 8: six make the G2 legs)
  int degree = 3;      ///< only cubic sections (the zones and the G2 legs are built for degree 3)
};

/// The knot vector every section with `n_control` curved-part control points shares
/// (n_control + 10 values on [0, 1]): clamped ends, triple knots at kTopZoneEnd and
/// kBottomZoneStart, uniform in between. Sections have n_control + 6 control points.
Eigen::VectorXd section_knot_vector(int n_control);

/// Control-point rows (first, last, inclusive) of the two zones: the interior rows lie at the
/// fractions 1/3 and 2/3 of the segment between the end rows in every section (fair_skin
/// straight_groups keeps them straight between the sections). fair_skin
/// keeps each group's longitudinal curves consistent (SkinOptions::straight_groups).
std::vector<std::pair<int, int>> section_straight_groups(int n_control);

/// One section as a 3-D cubic curve (x, y, z) on section_knot_vector(n_control), from the deck
/// point to the keel point on the centre line. y_max is the half-breadth limit B/2 (m).
/// The control polygon is kept inside 0 <= y <= y_max (points that would leave it are pinned
/// to the bound), and under a flat the zone is vertical / horizontal whatever the angles say.
/// Throws InvalidInput for malformed values (naming x and the field) and
/// InfeasibleFormParameters when the basic curves contradict each other at this station (no
/// section fits inside the bounds, it would fold back, or the DWL half-breadth contradicts a
/// flat of side reaching below the DWL); the message names the curves involved.
NurbsCurve design_section(const SectionSpec& spec, double y_max);

/// All sections in one call (what a hull rebuild uses).
std::vector<NurbsCurve> design_sections(const std::vector<SectionSpec>& specs, double y_max);

}  // namespace fairlines
