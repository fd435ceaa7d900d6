// Hull sections: a fair, convex section from a few numbers read off the basic curves.
//
// A section in the plane x = const runs from the deck point D (deck at side) down to the keel
// point K on the centre plane. Where the hull is immersed it passes through the design-
// waterline point Q = (y_dwl, T) and holds the asked area below T. It is built in two steps:
//
//  1. A template: the guide polygon D -> Y -> Q -> X -> K. X is the bilge corner (where the
//     side below the waterline would meet the bottom), Y the top corner on the waterline
//     tangent's upward extension. The top D..Q is one rounded corner at Y (a flared top where D
//     lies outboard of the line Y-Q, a convex shoulder where it lies inboard, straight where it
//     lies on it); below Q the section is one conic arc Q -> X -> K (a rational quadratic, no
//     inflection). One number, the shape knob lambda, moves the template from the fullest (the
//     arc hugging the box corner: flat of side and flat of bottom in all but name) through
//     rounder, leaning bilges to a straight V (lambda 2, X on the chord Q-K); every point of
//     the arc moves inward as lambda grows, and lambda is solved so that the area below the
//     waterline is the asked one. With a flat of bottom (flat_bottom) the floor runs straight
//     from K out to F, the arc is the family's in the box beyond it, and a fillet rounds F; a
//     section asked less area than the finest with the whole flat holds narrows its flat.
//  2. The section spline: a cubic B-spline on one knot vector shared by every section of a hull
//     (fair skinning uses its control points as the surface's rows). It is a graph over the
//     chord D -> K: control point k is D + xi_k d + eta_k n with xi_k the Greville abscissae,
//     and eta_k the template's ordinate at xi_k. Samples of a concave (convex, flat) template
//     give a convex (convex, exactly flat) spline, and the ordinates are smooth functions of
//     the inputs, so sections change smoothly along the hull. A last small correction (least
//     squares, linear) makes the spline pass exactly through Q with the area unchanged.
//
// Where the immersed part vanishes (at the stem, and at a dry transom or cruiser stern, where
// the waterline ends) the waterline point and the area fade out over a band of the breadth and
// draught (kEndBand), and the section tends to the above-water template D -> Y -> K, whose
// lower end arrives at K at `lower_angle`: nothing jumps where the waterline ends.
#pragma once

#include <limits>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "fairlines/curve.hpp"

namespace fairlines {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Least and largest number of control points of a section.
inline constexpr int kMinSectionControls = 8;
inline constexpr int kMaxSectionControls = 64;
/// Width of the band (fraction of B/2 in breadth and of T in depth) over which the waterline
/// point and the area fade out as the immersed part of the sections vanishes.
inline constexpr double kEndBand = 0.1;
/// Largest value of the shape knob: the straight V (the bilge corner on the chord Q-K).
inline constexpr double kMaxShapeKnob = 2.0;
/// Largest |lower_angle| (deg) a section accepts: a dry section beyond a waterline's end
/// continues the immersed ones' chord, which lies flatter the flatter the keel crosses T there.
inline constexpr double kMaxLowerAngle = 89.0;

/// One section's numbers (metres; angles in degrees).
struct SectionSpec {
  double x = 0;
  double y_deck = 0, z_deck = 0;
  double z_keel = 0;
  double y_max = 0;
  double draft = kNaN;
  double y_dwl = kNaN;
  double half_area = kNaN;
  double shape = 1.0;
  /// Where the top corner Y lies above the waterline point Q, on the waterline tangent, as a
  /// fraction of the distance |D - Q|: small values round the top near the waterline, large
  /// ones near the deck (more flare at the deck).
  double top_corner = 0.5;
  double deadrise = 0.0;
  /// Where the bilge corner heads as the section fines (lambda 1 .. 2): the point at this
  /// fraction of the chord from Q (0) to K (1). 0.5 a symmetric V; < 0.5 the side leans in
  /// first (deadrise first), > 0.5 the bottom rises first.
  double character = 0.5;
  /// Above-water sections (and the limit of immersed ones as the immersed part vanishes): the
  /// angle at which the section arrives at the keel point, deg from the downward vertical
  /// toward the centre plane (0 a vertical knife edge). NaN: 0.
  double lower_angle = kNaN;
  /// The bilge corner X of the arc below the waterline given directly (both or neither): its
  /// half-breadth as a fraction of y_dwl (0 < corner_y <= 1) and its height above the keel
  /// point as a fraction of the immersed depth T - z_keel (0 <= corner_z < 1). The waterline
  /// tangent then heads from Q to X, the keel tangent from K to X, and the shape knob (or
  /// half_area) sets only the arc's weight: X at (1, 0.5) with the weight of a parabola holds a
  /// parabolic (Wigley) section, X inside the chord Q-K a hollow one. NaN: the template family
  /// places X from deadrise and character.
  double corner_y = kNaN, corner_z = kNaN;
  /// Flat of bottom: the floor runs straight from the keel point out to this half-breadth f, a
  /// fraction of y_dwl (0 <= flat_bottom < 1), rising at the deadrise, to F; below T the bilge
  /// arc is the family's in the box beyond F (a given corner_y / corner_z then being fractions of
  /// that box's breadth y_dwl - f and depth, from F), the corner at F rounded. 0: none. A section
  /// asked less area than its finest shape with the whole flat holds narrows the flat
  /// (SectionDesign::flat_kept; not with a given corner). Immersed template sections only (no
  /// effect on given shapes or dry sections).
  double flat_bottom = 0.0;
  int n_control = 20;
  /// A given shape (an auxiliary section, e.g. measured offsets) instead of the template: #m by 2
  /// points (y, z) in metres from the deck edge down to the keel on the centre plane. It is
  /// mapped onto this station's deck, waterline and keel points (heights stretched piecewise
  /// between them, half-breadths scaled to the waterline's and the deck's), fitted, and then
  /// corrected by half-breadth shifts through Q and to half_area. Empty: the template family.
  Eigen::MatrixXd given;
  /// A second given shape blended with `given` as (1 - given_mix) given + given_mix given_fore
  /// (a station between two given ones); empty: `given` alone.
  Eigen::MatrixXd given_fore;
  double given_mix = 0.0;
  /// Bending penalty of the given shape's fit (second differences of the control points, per
  /// knot span) against its least squares over the points (chord-length parameters, weighted by
  /// their spacing, summing to 1). The default only carries the spline across stretches with
  /// few points (a shape read off fair lines); a measured shape is smoothed (import_design:
  /// its points carry the data's noise and the interpolation between its offsets).
  double given_smoothing = 1e-6;
  /// A skeg below the hull body: where skeg_bottom (m above base) lies below z_keel (the body's
  /// bottom on the centre plane), the section runs down the skeg's side at y = skeg_half_thickness
  /// to skeg_bottom and across it to the centre plane, joined to the body's section by a hollow
  /// fillet of about skeg_fillet (m). NaN: no skeg. skeg_share: how far the skeg is developed
  /// here, 0 .. 1 (it tapers to its ends): its thickness and fillet scale with it.
  double skeg_bottom = kNaN, skeg_half_thickness = 0.5, skeg_fillet = 1.0, skeg_share = 1.0;
  /// A sonar dome below the hull body: where dome_bottom (m above base) lies below z_keel, the
  /// section comes in to a neck of half-width dome_neck (m) and bulges below it into the half
  /// of an ellipse of half-breadth dome_half_breadth (m) from z_keel down to dome_bottom, joined
  /// to the body by a hollow fillet. NaN: no dome.
  double dome_bottom = kNaN, dome_half_breadth = 1.0, dome_neck = 0.5;

  /// Each field with its name and meaning: f(name, member pointer, doc).
  template <typename F>
  static void fields(F&& f) {
    f("x", &SectionSpec::x, "station (m from the AP); the section lies in the plane x = const");
    f("y_deck", &SectionSpec::y_deck, "deck-at-side half-breadth (m), 0 <= y_deck <= y_max");
    f("z_deck", &SectionSpec::z_deck, "deck-at-side height (m above base)");
    f("z_keel", &SectionSpec::z_keel, "keel point height on the centre plane (m, <= z_deck)");
    f("y_max", &SectionSpec::y_max, "half-breadth bound B/2 (m, > 0)");
    f("draft", &SectionSpec::draft, "waterline height T (m; NaN: no waterline condition)");
    f("y_dwl", &SectionSpec::y_dwl, "waterline half-breadth at T (m; NaN or <= 0: not immersed)");
    f("half_area", &SectionSpec::half_area, "area below T between the section and the centre plane, one side (m^2; NaN: free)");
    f("shape", &SectionSpec::shape, "shape knob when half_area is NaN (0 fullest .. 2 straight V)");
    f("top_corner", &SectionSpec::top_corner, "height of the top corner, fraction of the freeboard");
    f("deadrise", &SectionSpec::deadrise, "bottom rise at the bilge corner (deg from the horizontal, >= 0)");
    f("character", &SectionSpec::character, "where the bilge corner heads as the section fines (fraction of the chord Q-K)");
    f("lower_angle", &SectionSpec::lower_angle, "above-water sections: arrival angle at the keel point (deg from vertical; NaN: 0)");
    f("corner_y", &SectionSpec::corner_y, "bilge corner half-breadth, fraction of y_dwl (NaN: from the template)");
    f("corner_z", &SectionSpec::corner_z, "bilge corner height above the keel, fraction of T - z_keel (NaN: from the template)");
    f("flat_bottom", &SectionSpec::flat_bottom, "flat of bottom: half-breadth of the straight floor from the keel point, fraction of y_dwl (0: none)");
    f("n_control", &SectionSpec::n_control, "control points of every section of a hull");
    f("given", &SectionSpec::given, "given shape: (m, 2) points (y, z), m, deck edge to keel (empty: the template family)");
    f("given_fore", &SectionSpec::given_fore, "second given shape blended with `given` (empty: none)");
    f("given_mix", &SectionSpec::given_mix, "weight of given_fore in the blend, 0 to 1");
    f("given_smoothing", &SectionSpec::given_smoothing, "bending penalty of the given shape's fit against its points (>= 0; small: near-interpolation)");
    f("skeg_bottom", &SectionSpec::skeg_bottom, "height of the skeg's bottom (m above base; NaN: no skeg)");
    f("skeg_half_thickness", &SectionSpec::skeg_half_thickness, "half the skeg's thickness (m, > 0)");
    f("skeg_fillet", &SectionSpec::skeg_fillet, "size of the hollow fillet between the hull body and the skeg (m, >= 0)");
    f("skeg_share", &SectionSpec::skeg_share, "how far the skeg is developed here (0 .. 1): scales its thickness and fillet");
    f("dome_bottom", &SectionSpec::dome_bottom, "height of a sonar dome's bottom (m above base; NaN: no dome)");
    f("dome_half_breadth", &SectionSpec::dome_half_breadth, "the dome's half-breadth (m, > 0)");
    f("dome_neck", &SectionSpec::dome_neck, "half-width of the neck where the dome meets the hull body (m, 0 < neck < half-breadth)");
  }
};

/// A designed section and what was needed to build it.
struct SectionDesign {
  NurbsCurve curve;          ///< 3-D cubic (x, y, z) on section_knot_vector(n_control), deck (t = 0) to keel (t = 1)
  double shape = kNaN;       ///< shape knob used
  double fullness = kNaN;    ///< area below T / (y_dwl (T - z_keel)) achieved (NaN: not immersed)
  double fullness_min = kNaN, fullness_max = kNaN;  ///< what the family can hold here
  bool area_met = true;      ///< false when half_area lies outside [fullness_min, fullness_max] (the knob is clamped)
  double immersion = 0.0;    ///< weight (0 .. 1) of the waterline and area conditions (fades at the waterline's ends)
  double flat_kept = 1.0;    ///< share of the asked flat of bottom kept (< 1: the asked area is too fine for all of it)
};

/// The knot vector every section with n_control control points shares: clamped uniform cubic on [0, 1].
Eigen::VectorXd section_knot_vector(int n_control);

/// One section. Throws InvalidInput for malformed numbers (naming the station and the field)
/// and InfeasibleFormParameters when the deck, waterline and keel points make no section that
/// is one curve over its chord (the message names the station and the points).
SectionDesign design_section(const SectionSpec& spec);

/// design_section for each spec, in order.
std::vector<SectionDesign> design_sections(const std::vector<SectionSpec>& specs);

/// The fullness (area below T / (y_dwl (T - z_keel))) the section family can hold at this
/// station; NaN where the section is not immersed.
struct FullnessBounds {
  double least_whole_flat = kNaN;  ///< least keeping the whole flat of bottom (= least without one)
  double least = kNaN;             ///< least, the flat of bottom narrowed as far as it goes
  double largest = kNaN;
};
FullnessBounds section_fullness_bounds(const SectionSpec& spec);

/// {least, largest} of section_fullness_bounds.
std::pair<double, double> section_fullness_range(const SectionSpec& spec);

}  // namespace fairlines
