// Hull sections: the fairest curve from the deck point to the keel point that meets a
// section's form parameters and has the shape a naval architect expects.
//
// Notation (a section in the plane x = const, coordinates (y, z), metres):
//   P_D = (y_deck, z_deck)  deck point (deck at side), the section's start (t = 0)
//   K   = (0, z_keel)       keel point on the centre plane, its end (t = 1)
//   Q   = (y_dwl, T)        design-waterline point
//   L, d, n                 chord length |K - P_D|, its unit direction and the unit normal
//                           n = (-d_z, d_y), pointing out of the hull (away from the centre plane)
//   xi, eta                 coordinates along d and n from P_D
//
// The section is a graph over its chord: control point k is P_D + L g_k d + eta_k n, with g_k
// the Greville abscissae of one clamped uniform cubic knot vector shared by every section of a
// hull (fair skinning uses the control points as its rows, without refitting). Every form
// parameter -- end tangents, the DWL point, the area below the DWL, passing near data points --
// is linear in eta, and so are the shape conditions:
//   below the DWL the section is convex (no inflection: eta'' <= 0 on every span),
//   above it the section keeps one curvature sign: convex where the deck tangent leans out of
//   the chord P_D -> Q, concave (flare) where it leans in, straight in between, so the only
//   inflection a flared section has is at the waterline,
//   the control polygon stays inside 0 <= y <= y_max (B/2) and z_keel <= z <= z_deck.
// The fairest such curve (least int eta''(t)^2 dt, plus any data term) is one small convex QP
// (fairlines/qp.hpp). Where the area asks for it the y <= B/2 and z >= z_keel bounds become
// active on runs of control points: the flat of side and the flat of bottom appear by
// themselves, exactly flat, and leave the bilge with curvature continuity (a cubic B-spline is
// C2). Optional explicit flats and a skeg put runs of control points on given lines.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "fairlines/curve.hpp"

namespace fairlines {

/// Shape of the part of a section above the design waterline.
enum class SectionAbove {
  Auto,     ///< convex or flared (concave) as the deck tangent says (see the file comment)
  Convex,   ///< no inflection from the deck to the keel
  Flare,    ///< concave above the DWL (flare), convex below: one inflection, at the DWL
  Free,     ///< no shape condition above the DWL
};

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Parameters of one section at station x (metres; angles in degrees).
struct SectionSpec {
  double x = 0;                ///< station (m from the AP)
  double y_deck = 0;           ///< deck-at-side half-breadth (>= 0)
  double z_deck = 0;           ///< deck-at-side height (> z_keel)
  /// Tangent at the deck, degrees from the downward vertical toward +y (0 vertical, < 0 the
  /// section goes inward as it goes down: flare; > 0 tumblehome). NaN: free.
  double alpha_deck = kNaN;
  /// Alternative to alpha_deck: the flare of the top as a fraction of its lean. The line from the
  /// deck point to the DWL point (to the keel point when there is no DWL) leans `lean` degrees
  /// from the vertical; the deck tangent leans (1 + flare) times that: > 0 a flared (concave)
  /// top, < 0 a convex shoulder, 0 a straight top. Where deck and DWL are both at B/2 the lean
  /// is zero and so is any flare, so the parallel body stays wall-sided. Used when alpha_deck
  /// is NaN; NaN: the deck tangent is free.
  double flare = kNaN;
  double z_keel = 0;           ///< keel / centre-profile height (the section's lowest point)
  /// Tangent arriving at the keel, same convention: -90 horizontal (a flat keel), -60 a 30 deg
  /// deadrise, 0 a vertical knife edge. NaN: free.
  double alpha_keel = -90;
  double draft = kNaN;         ///< DWL height T (NaN: no DWL condition)
  double y_dwl = kNaN;         ///< half-breadth at the DWL (NaN: free)
  double half_area = kNaN;     ///< area below the DWL between the section and the centre plane (m^2, one side; NaN: free)
  /// Section angle at the DWL (deg from the downward vertical toward +y: 0 wall-sided, < 0
  /// leaning in as it goes down, a V), held by a penalty of weight alpha_dwl_weight (0 .. 1;
  /// 1 holds it to a fraction of a degree, 0 leaves the angle to the fairness), so a weight that
  /// fades along the hull changes the sections smoothly. NaN: free.
  double alpha_dwl = kNaN;
  double alpha_dwl_weight = 1.0;
  double y_max = 0;            ///< half-breadth bound B/2 (> 0)
  SectionAbove above = SectionAbove::Auto;
  /// Height (m) where a flared top turns into the convex bottom (the one inflection of a flared
  /// section). NaN: at the DWL (at mid-height for a section wholly above it). A counter just
  /// below the waterline needs it higher: its bilge turns above the DWL.
  double z_inflection = kNaN;
  bool convex_below = true;    ///< false: no shape condition below the DWL (data-driven sections)
  /// Optional explicit flat of side: the section lies on y = y_max from the deck down to this
  /// height (needs y_deck = y_max). NaN: none (a flat still appears where the area needs it).
  double z_fos = kNaN;
  /// Optional explicit flat of bottom: on z = z_keel from the centre plane out to this
  /// half-breadth. NaN: none.
  double y_fob = kNaN;
  /// Optional skeg (or sonar-dome neck) side: the section lies on y = skeg_half_thickness for
  /// skeg_bottom <= z <= skeg_top, concave in the fillet above it. NaN: none.
  double skeg_half_thickness = kNaN;
  double skeg_bottom = kNaN;
  double skeg_top = kNaN;
  /// Data points (y, z) the section passes near (least squares, weight points_weight per
  /// point relative to the fairness term); empty: none.
  std::vector<Eigen::Vector2d> points;
  double points_weight = 1.0;
  int n_control = 20;          ///< control points of every section of the hull (8 .. 64)
  /// Fairness of the section: e2 int eta''(t)^2 dt + e3 int eta'''(t)^2 dt (eta over the chord).
  double e2 = 1.0;
  double e3 = 0.0;
};

/// Least and largest number of control points of a section.
inline constexpr int kMinSectionControls = 8;
inline constexpr int kMaxSectionControls = 64;
/// Sections narrower than this fraction of y_max are the centre-line segment from the deck to
/// the keel (the stem or a cruiser stern's end): every control point on the centre plane.
inline constexpr double kStemBreadth = 1e-9;
/// Constraint residuals within this fraction of the section's size count as met.
inline constexpr double kSectionTol = 1e-9;

/// The knot vector every section with n_control control points shares: clamped uniform cubic.
Eigen::VectorXd section_knot_vector(int n_control);

/// The result of designing one section: the curve and what the solver needed (for warm starts
/// and diagnostics).
struct SectionDesign {
  NurbsCurve curve;              ///< 3-D cubic (x, y, z) on section_knot_vector(n_control), deck to keel
  std::vector<int> active;       ///< active inequality rows (warm start for a neighbouring section)
  double fullness = kNaN;        ///< half_area / (y_dwl (T - z_keel)): the section's area coefficient
};

/// One section. `warm`: the `active` of a similar section (optional). Throws InvalidInput for
/// malformed values (naming x and the field) and InfeasibleFormParameters when the section's
/// form parameters contradict each other or its shape conditions; the message names the
/// station, the parameters and, for the area, the range a fair section can hold there.
SectionDesign design_section(const SectionSpec& spec, const std::vector<int>& warm = {});

/// Sections in order, each warm-started from the previous one.
std::vector<NurbsCurve> design_sections(const std::vector<SectionSpec>& specs);

/// Least and largest half area below the DWL (m^2) a section with these parameters can hold
/// with its shape conditions (its own half_area ignored); {NaN, NaN} when it has no DWL part.
std::pair<double, double> section_area_range(const SectionSpec& spec);

/// The same as fullness, half_area / (y_dwl (T - z_keel)), for each spec: (q, 2) rows
/// (least, largest), NaN where a section has no DWL part.
Eigen::MatrixXd section_fullness_bands(const std::vector<SectionSpec>& specs);

}  // namespace fairlines
