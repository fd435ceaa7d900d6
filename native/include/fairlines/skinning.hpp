// Fair skinning of section curves into one B-spline surface (Kim & Hwangbo 2008, eq. 6-9;
// Fig. 2): equally spaced points along every section, one common knot vector and control
// count for all sections, then for each row of section control points a longitudinal
// B-spline through (or near) the row that minimises E2 = int |C''(v)|^2 dv.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "fairlines/curve.hpp"
#include "fairlines/surface.hpp"

namespace fairlines {

/// How the longitudinal curves treat the rows of section control points.
enum class SkinMode {
  Interpolate,  ///< through every row point; among all such splines the one of least E2
  Approximate,  ///< near the row points: min (1/q) sum |C(v_d) - P_d|^2 + smoothing h^4 E2
};

/// Condition on the longitudinal curves at the first / last section.
enum class SkinEnd {
  Free,      ///< natural end (what E2 minimisation gives: no curvature imposed)
  Parallel,  ///< dy/dv = dz/dv = 0: the surface leaves the end section along x, so it meets a
             ///< parallel middle body (a cylinder along x) with tangent-plane (C1) continuity
  NotAKnot,  ///< the first (last) two knot spans are one polynomial (no jump of the degree_v-th
             ///< derivative at the first interior knot): the end keeps the curvature the rows'
             ///< trend gives it, where Free forces zero (a transom's waterline ends curved)
};

/// How the sections are placed in the longitudinal parameter v in [0, 1].
enum class SkinParams {
  Auto,   ///< Station when every section is planar at constant, strictly monotone x, else Chord
  Station,  ///< v_d = (x_d - x_0) / (x_last - x_0): then x(u, v) = x_0 + v (x_last - x_0) exactly
  Chord,    ///< chord length between consecutive sections, averaged over the control rows
};

struct SkinOptions {
  int n_control = 0;
  int degree_u = 3;
  int degree_v = 3;
  int samples = 0;
  /// Spacing metric of the section points: ds (1 + curvature_weight L |k|), L the section's
  /// length. 0 is plain arc length (Kim & Hwangbo 2008, Fig. 2b); > 0 puts more points -- and, through
  /// the common uniform knots, more control points -- where sections bend (tight bilges).
  double curvature_weight = 0.0;
  SkinMode mode = SkinMode::Interpolate;
  /// Fairness of the longitudinal curves: e2 E2 + e3 h^2 E3 (E_k = int |C^(k)(v)|^2 dv,
  /// h = 1/(q-1)). e2 = 1, e3 = 0 is Kim & Hwangbo 2008 eq. 9: the interpolant is then the natural
  /// spline, whose curvature is forced to 0 at the first and last section. e3 > 0 (degree_v
  /// >= 3) penalises the jumps of the third derivative instead: data varying quadratically
  /// along the hull are reproduced exactly and the ends keep their curvature.
  double e2 = 1.0;
  double e3 = 0.0;
  double smoothing = 1e-3;
  SkinEnd start = SkinEnd::Free;
  SkinEnd end = SkinEnd::Free;
  SkinParams params = SkinParams::Auto;
  /// Interior section indices (1..q-2) where the longitudinal curves are only C1 (knot of
  /// multiplicity degree_v - 1): the joint between fore and aft bodies. Elsewhere C^(degree_v-1).
  std::vector<int> c1_sections;
  /// Interior section indices where the longitudinal curves are only C0 (knot of multiplicity
  /// degree_v): a knuckle the sections cross, such as a transom's edge. Between two such
  /// sections (or a C0 section and an end) the least-E2 curve through the rows is a straight
  /// line, which cannot ring (a C2 spline through a knuckle rings with lobes of 2 - sqrt 3 of
  /// the last, station after station).
  std::vector<int> c0_sections;
  /// Planes the hull lies in over parts of its sections: (axis 0 / 1 / 2 for x / y / z, value
  /// in metres), e.g. the flat of side y = B/2 and the flat of bottom z = 0. Where a section
  /// lies in such a plane (to kFlatTolerance of the sections' size) the common-knot refit
  /// keeps every control point whose support lies there exactly on it, so the fitted section
  /// is exactly flat there instead of rippling about the plane by the fit's residuals.
  std::vector<std::pair<int, double>> flats;
  /// Where a row of control points keeps one coordinate (y or z) over kMinHeldRun or more
  /// consecutive sections -- a parallel middle body, a flat of side or bottom that ends -- its
  /// longitudinal curve keeps that value exactly over them (the controls whose support lies
  /// there are held) and leaves it with full continuity: one extra knot in the interval next to
  /// the run gives the curve beyond a well-posed fit. Without it an interpolating spline rings
  /// where a row leaves a constant stretch.
  bool hold_runs = true;
  /// Row ranges (first, last, inclusive) whose interior rows lie on the segment from row
  /// `first` to row `last` at the same fraction in every section (a hull's straight zones,
  /// fairlines/sections.hpp). The interior rows' longitudinal curves are built as that
  /// combination of the end rows' curves, so the segment stays straight between the sections
  /// while each end row holds its own runs. InvalidInput when the fractions differ.
  std::vector<std::pair<int, int>> straight_groups;
  /// Keep the skin at y >= 0 (a half hull never crosses its centre plane): where the surface
  /// dips below -kCentrePlaneTolerance of the sections' size, each row with a control below
  /// the plane there is solved again near the dip (kCentrePlaneReach) with its controls bounded
  /// at 0, meeting its row points as closely as the bound lets it (SkinResult::centre_plane_miss);
  /// the surface is looked at again (kCentrePlanePasses). Rows that run from a short section (a
  /// counter above a propeller boss) onto a web on the centre plane otherwise fold across it:
  /// 0.3 m on the KCS. Where that cannot be done within kCentrePlaneMaxMiss the skin is left as
  /// it was (SkinResult::centre_plane_refused_miss).
  bool y_nonnegative = false;

  /// Each field with its name and meaning: f(name, member pointer, doc).
  template <typename F>
  static void fields(F&& f) {
    f("n_control", &SkinOptions::n_control, "control points per section in u; 0: max(12, 2 x largest section count)");
    f("degree_u", &SkinOptions::degree_u, "degree across the sections (>= 1)");
    f("degree_v", &SkinOptions::degree_v, "degree of the longitudinal curves (>= 2)");
    f("samples", &SkinOptions::samples, "equally spaced points per section; 0: 4 x n_control, else >= n_control");
    f("curvature_weight", &SkinOptions::curvature_weight, "w >= 0: section points equally spaced in ds (1 + w L |k|), L the section length; 0 plain arc length");
    f("mode", &SkinOptions::mode, "'interpolate' (through every row point, least E2) or 'approximate' (least squares + smoothing h^4 E2)");
    f("e2", &SkinOptions::e2, "weight of E2 = int |C''(v)|^2 dv in the longitudinal fairness");
    f("e3", &SkinOptions::e3, "weight of h^2 E3 = h^2 int |C'''(v)|^2 dv, h = 1/(q-1)");
    f("smoothing", &SkinOptions::smoothing, "approximate mode: weight of h^4 E2 (>= 0)");
    f("start", &SkinOptions::start, "'free' (natural), 'parallel' (dy/dv = dz/dv = 0) or 'not_a_knot' (the first two spans one polynomial) at the first section");
    f("end", &SkinOptions::end, "'free' (natural), 'parallel' (dy/dv = dz/dv = 0) or 'not_a_knot' (the last two spans one polynomial) at the last section");
    f("params", &SkinOptions::params, "section parameters v: 'station' (proportional to x), 'chord', or 'auto' (station when planar at monotone x)");
    f("c1_sections", &SkinOptions::c1_sections, "interior section indices where the longitudinal curves are only C1");
    f("c0_sections", &SkinOptions::c0_sections, "interior section indices where the longitudinal curves are only C0 (straight between two such sections)");
    f("flats", &SkinOptions::flats, "planes (axis 0 / 1 / 2 for x / y / z, value m) the sections' fits keep exactly where they lie in them");
    f("hold_runs", &SkinOptions::hold_runs, "hold a row coordinate constant over three or more sections where the rows keep it");
    f("straight_groups", &SkinOptions::straight_groups, "row ranges (first, last) kept straight between their end rows' longitudinal curves");
    f("y_nonnegative", &SkinOptions::y_nonnegative, "keep the surface at y >= 0 (a half hull): rows under a dip below the centre plane solved again with their controls >= 0");
  }
};

/// Least number of consecutive sections over which a row coordinate must keep its value to be
/// held (SkinOptions::hold_runs). Three: two equal values happen on any curve with a maximum
/// between them (the middle stations of a symmetric hull), three equal ones only on a flat.
inline constexpr int kMinHeldRun = 3;
/// Values within this fraction of the sections' largest coordinate count as one (held runs).
inline constexpr double kRunTolerance = 1e-12;

/// Interpolate mode: the longitudinal curves must meet every row point within this fraction
/// of the sections' largest coordinate, else fair_skin throws (an ill-conditioned system: an
/// unscaled not-a-knot row once missed the KCS's rows by 237 m unnoticed). Designed hulls and
/// their edits meet their rows to about 1e-12 of it (200 designs of bench_hull's space, each
/// with its volume edited +-10 %).
inline constexpr double kInterpolationTolerance = 1e-8;

/// SkinOptions::y_nonnegative acts where the surface goes below minus this fraction of the
/// sections' largest coordinate (round-off below 0 is left alone) ...
inline constexpr double kCentrePlaneTolerance = 1e-9;
/// ... looked at on kCentrePlaneSamples + 1 points per knot span each way. The control points
/// alone would catch surfaces that stay on their side: a designed tanker's skeg end has a
/// control 0.10 m below the plane, and on 49 of bench_design_options' 500 designs a row's
/// curve dips below it; the surface does on one of them (a 2.1 mm fold at a raked stem head).
inline constexpr int kCentrePlaneSamples = 8;
/// ... and weighs its rows' misses by this multiple of the fairness block's largest entry:
/// the misses stay millimetres where the bound truly conflicts with the rows (KCS: 3.6 mm)
/// and vanish to the solve's accuracy where it does not.
inline constexpr double kCentrePlaneRowWeight = 1e6;
/// ... but leaves the whole skin as it was where keeping a row at y >= 0 would move a row
/// point more than this fraction of the sections' size (their largest coordinate, about the
/// ship's length): DTMB 5415's recess between the dome and the stem, where the bound pushed
/// the web on the centre plane out 16 mm (0.3 % of its 5.8 m, 2 % of B) to remove a 4.6 mm fold;
/// kept in the rows it could keep, the fold stayed (3.9 mm) and its waterlines took 10 more
/// curvature sign changes.
inline constexpr double kCentrePlaneMaxMiss = 1e-3;
/// ... and moves only the controls within this many of one below the plane; the rest of the
/// row keeps its least-E2 interpolant exactly. KCS: with 3 the rows missed its sections by
/// 4.3 cm; with 14 (or the whole row) two lobes came into its 9.4 m waterline at the bulb.
inline constexpr int kCentrePlaneReach = 8;
/// ... and looks again after moving them, at most this many times (lowering a row's controls
/// near one dip can uncover another); dips still there leave the skin as it was.
inline constexpr int kCentrePlanePasses = 3;

/// Relative distance (to the sections' largest coordinate) within which a section point
/// counts as lying in one of SkinOptions::flats.
inline constexpr double kFlatTolerance = 1e-9;

struct SkinResult {
  /// u across the sections (from each section's start to its end), v longitudinal from the
  /// first section (v = 0) to the last (v = 1). Non-rational, clamped in both directions.
  NurbsSurface surface;
  Eigen::VectorXd section_params;  ///< v of each section (q values)
  double section_fit_max = 0;      ///< max distance between the equally spaced section points
                                   ///< and the common-knot section fits (metres)
  double longitudinal_max = 0;     ///< max |C_i(v_d) - row point| over rows and sections
                                   ///< (metres; ~1e-12 in Interpolate mode; the y of rows
                                   ///< moved by y_nonnegative left out: centre_plane_miss)
  Eigen::VectorXd row_e2;          ///< E2 of each longitudinal control-point curve (n_control),
                                   ///< whatever the fairness weights
  int held_columns = 0;            ///< row coordinates with at least one held run
  int centre_plane_columns = 0;    ///< y columns solved again with y >= 0 (SkinOptions::y_nonnegative)
  double centre_plane_miss = 0;    ///< largest miss of a row point in those columns (metres)
  /// > 0 when y_nonnegative left the skin as it was (it crosses the centre plane): the largest
  /// row miss keeping it off would have cost (metres, over kCentrePlaneMaxMiss; infinite where
  /// the rows about a dip are all held by their runs).
  double centre_plane_refused_miss = 0;
};

/// Skin q >= 2 section curves (each a 3-D NurbsCurve, ordered along the hull; metres) into one
/// surface. Sections that already share one non-rational knot vector of degree degree_u (and
/// n_control, when given, equal to their count) are used as they are: their control points
/// are the rows (section_fit_max 0); otherwise they are resampled at equal arc length and
/// refitted to a common knot vector (Kim & Hwangbo 2008). Throws InvalidInput naming the bad
/// section / option (2-D curves, zero-length sections, coincident section parameters, bad counts).
SkinResult fair_skin(const std::vector<NurbsCurve>& sections, const SkinOptions& options = {});

/// Points at equal arc-length spacing along a curve: m >= 2 rows (curve dim columns), first
/// and last at the curve ends. With curvature_weight w > 0 the spacing is equal in the
/// measure ds (1 + w L |k|) instead (L the curve length). Arc length by 8-point Gauss-Legendre on quarter knot spans,
/// inverted by cubic Hermite interpolation of t(s) and one Newton step (spacing equal to
/// about 1e-3 relative on sections; the points are on the curve to round-off whatever the
/// spacing).
Eigen::MatrixXd equal_arc_length_points(const NurbsCurve& curve, int m,
                                        double curvature_weight = SkinOptions{}.curvature_weight);

/// Arc length of a curve (metres), same quadrature as above.
double arc_length(const NurbsCurve& curve);

/// E2 = int |C''(t)|^2 dt of a curve over its own parameter domain (exact for polynomial
/// B-splines: Gauss-Legendre with degree points per knot span).
double curve_e2(const NurbsCurve& curve);

SkinMode parse_skin_mode(const std::string& name);   ///< "interpolate" | "approximate"
SkinEnd parse_skin_end(const std::string& name);     ///< "free" | "parallel" | "not_a_knot"
SkinParams parse_skin_params(const std::string& name);  ///< "auto" | "station" | "chord"
const char* skin_mode_name(SkinMode mode);       ///< inverse of parse_skin_mode
const char* skin_end_name(SkinEnd end);          ///< inverse of parse_skin_end
const char* skin_params_name(SkinParams params); ///< inverse of parse_skin_params

}  // namespace fairlines
