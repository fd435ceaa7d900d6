// Hull sections from their template: see fairlines/sections.hpp.
//
// Notation (a section in the plane x = const, coordinates (y, z), metres):
//   D, K, Q     deck point, keel point, waterline point (y_dwl, T)
//   b, d        the immersed box: b = y_dwl, d = T - z_keel
//   C, M        where the bilge corner starts (the box corner, raised by the deadrise) and
//               where it heads (the point at `character` of the chord Q-K)
//   X, Y        bilge corner and top corner of the guide polygon D -> Y -> Q -> X -> K
//   t_w         unit direction Q -> X: the section's tangent at the waterline, going down
//   F, F0, F1   flat of bottom: its outer end F = K + (f, rise), and where the fillet rounding its
//               corner with the bilge arc meets the floor (F0) and the arc's leg X -> F (F1)
//   lambda      the shape knob: the bilge arc's weight falls and its corner X moves from C to M
//               over [0, kMaxShapeKnob]
//   t           the area knob: lambda up to its limit, then the flat of bottom narrowing (knob_at)
//   L, dir, nrm chord length |K - D|, its unit direction and the unit normal (-dir_z, dir_y),
//               which points out of the hull
//   xi, eta     abscissa along dir and ordinate along nrm from D; control point k of the
//               spline is D + xi_k dir + eta_k nrm with xi_k = L g_k (g the Greville abscissae)
//   w           immersion weight (0 .. 1): how much of the waterline point and area is asked
#include "fairlines/sections.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <optional>
#include <thread>
#include <tuple>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>

#include <Eigen/Cholesky>

#include "fairlines/basis.hpp"
#include "fairlines/errors.hpp"
#include "fairlines/knots.hpp"
#include "common/soft_cap.hpp"
#include "nurbs/checks.hpp"
#include "nurbs/gauss.hpp"

namespace fairlines {

namespace {

using detail::fail;
using V2 = Eigen::Vector2d;

constexpr int kDegree = 3;
/// Fillet control points at these fractions of each leg from its far end toward the corner:
/// with (0.105, 0.611) the quintic fillet of two equal perpendicular legs follows a circular arc
/// to 3e-4 of its radius, and it leaves both legs with zero curvature (three control points in
/// line), so a straight part and a fillet join with continuous curvature.
constexpr double kFilletNear = 0.105, kFilletFar = 0.611;
/// The topside fillet (deck point to Q; a dry section's deck point to its keel) holds its middle
/// control points nearer its corner Y: it turns more about Y and less just above the waterline,
/// where a run's fine sections under a flared top turned most and the buttocks crossing T took a
/// hollow. bench_fairness_space's reading by hand, hulls 0-299 / held-out 300-599, 0.611 -> 0.68:
/// upper waterlines clean 812 -> 826 / 813 -> 816 of 900 (stem-tip wobbles 37 -> 34 / 30 -> 21),
/// waterlines over two sign changes 175 -> 171 / 185 -> 180, sign changes a buttock 1.82 -> 1.80 /
/// 1.86 -> 1.85; the cost: S frames above T on 6 -> 8 / 8 -> 10 hulls. 0.7 read alike but left the
/// example's mesh a quad of 0.29 m among 1 m ones at x 45 m (docs/sections.md); 0.8: buttocks 1.96.
constexpr double kTopFilletFar = 0.68;
/// Below the waterline the section is one conic arc Q -> X -> K. Its middle weight falls
/// geometrically from kFullWeight (lambda 0: the arc hugs the box corner, fullness about 0.997)
/// to kFineWeight (lambda kMaxShapeKnob), while the corner X leans from the box corner C toward
/// the heading M as (lambda / kMaxShapeKnob)^kLeanPower: the bilge rounds first and leans later.
/// Both motions move every point of the arc inward, so the half-breadth at any height falls
/// strictly as lambda grows (no plateau, no shoulder-hollow-shoulder along a waterline).
/// A fine weight of 0.5, not 0.7: a section of given area then sits at a smaller lambda, its
/// corner leaning less, and the run's buttocks no longer turned back just above T (bench_hull's
/// first 300 hulls: 2.07 -> 1.89 sign changes a buttock; 0.7 -> 1.0 made it 2.27).
constexpr double kFullWeight = 60.0, kFineWeight = 0.5, kLeanPower = 3.0;
/// With the bilge corner given (corner_y, corner_z) the weight alone falls over the knob's
/// range, from kFullWeight to this (a near chord: hollow corners need weights below 1).
constexpr double kCornerFineWeight = 0.2;
/// The topside fillet ends with the bilge arc's curvature at Q (a fillet ending straight left a
/// curvature jump at the waterline that buttocks crossing it showed as lobes), in full where the
/// bilge's leg |X - Q| is at least the fillet's end reach |p3 - Q|, fading as r^p / (1 + r^p) of
/// their ratio r below: a short bilge's tight curvature would bend metres of topside.
constexpr double kCurvatureMatchPower = 4.0;
/// ... and the move keeps the fillet's control polygon convex: it takes at most this share of
/// the turn at that control point (a topside with little turn, a wall side, gets little of the
/// bilge's curvature: a straight wall over a round bilge would otherwise dent), approached as
/// h / (1 + (h / cap)^p)^(1/p) with this p so the move changes smoothly along the hull.
constexpr double kCurvatureMatchShare = 0.5, kCurvatureMatchSharpness = 4.0;
/// Width of the smooth minimum of the chord's lean and the top's room (see heading()), in the
/// logarithm of their sines: they are blended where their ratio lies within e^kHeadingBlend, so
/// the heading changes over a span of stations, not a few metres; the plain minimum holds beyond.
constexpr double kHeadingBlend = 0.8;
/// The top's room is measured out to this share of the way from the deck's half-breadth to B/2:
/// where the deck narrows (a forward shoulder) the heading leans in as the deck does, not as fast
/// as the room to B/2 opens. On the container ship its sine rose 0.19 -> 0.67 over x 176-195 m
/// (now 0.16 -> 0.54) and its buttocks y = 12 and 14 m took lobes of 1.3 and 2.0 deg there.
constexpr double kRoomBeyondDeck = 0.5;
/// Knob solve: area tolerance relative to the immersed box, and iteration limit.
constexpr double kAreaTol = 1e-13;
constexpr int kKnobIterations = 100;
/// An area outside the family's range by less than this fraction of the box still counts as met.
constexpr double kAreaMetTol = 1e-9;
/// Width (fraction of the immersed box) of the smooth floor at the family's least area: an asked
/// area below the least is raised to it, and one within a few widths above it a little (at most
/// ln 2 widths, at the least itself), so the knob leaves its end smoothly along the hull.
constexpr double kAreaFloorSmoothing = 0.002;
/// The asked area's excess over the template's V (half the box) is laid on the sampled family's
/// least area in the share exp(-excess / kVeeExcessFade) (excess over the box): the sampled V holds
/// more than half the box near a waterline's end (0.503-0.53 within 4 m of the container ship's
/// dry one), so the knob stayed at the floor there and then left it with a kink (see solve_knob).
constexpr double kVeeExcessFade = 0.01;
/// Gauss points per knot span of the area integral (exact for the cubic-times-quadratic integrand).
constexpr int kAreaGauss = 4;
/// The correction that puts the spline through Q: weight of a straight stretch of the spline
/// against a curved one (flats keep their plane), the curvature scale (fraction of the chord)
/// below which a stretch counts as straight, and the weight of the correction's smoothness. The
/// smoothness weighs 2, not 1: the spline, sampling its template, misses Q by millimetres near
/// the stem (1-9 mm at the last stations of bench_hull's hulls 37 and 66) and by up to 10 cm
/// where the bilge turns just under Q (a run's section whose side the top's room holds steep:
/// 20 cm of correction at 3-5 % Lpp on its second hull), and a correction of weight 1 put
/// it back as a bump over the three or four control points under Q, which the waterlines crossing
/// it took as wobbles, most at the stem's tip. Measured (bench_fairness_space's reading, hulls
/// 0-299 / 300-599): upper waterlines clean 791 -> 804 / 792 -> 808 of 900, the stem tip's
/// wobbles 61 -> 45 / 60 -> 39, hulls meeting every mark 71 -> 72 / 65 -> 68, sign changes a
/// buttock 1.895 -> 1.902 / 1.960 -> 1.964. Weight 3 cleared more (807 / 814, all marks 73 / 72)
/// but the example's buttock at y = 10 m took back a hollow of 0.78 deg just above T.
constexpr double kFlatGuard = 1e4, kStraightScale = 1e-5, kCorrectionSmoothing = 2.0;
/// ... and the correction stays near Q: its weight grows as the fourth power of the distance
/// from Q beyond this many knot spans.
constexpr double kCorrectionReach = 3.0;
/// Above Q the correction is nearly free in size but stiff in bend: it tilts the topside as a
/// line from the fixed deck point (a linear change of the ordinates keeps every bend), where a
/// correction held near Q would dent the topside just above the waterline.
constexpr double kTopsideFreedom = 1.0, kTopsideStiffness = 1e3;
/// ... and the topside's weights take over from those below Q over this many knot spans about Q.
constexpr double kTopsideBlend = 1.0;
/// Within the end band the spline goes through Q in the share w^kThroughQPower of the immersion
/// weight w. Where Q nears K (t_q -> 1) passing through Q and holding K fight over the last
/// control points, and a share w let the correction rotate the whole section: 3 mm at z = 15 m
/// within 0.3 m of the container ship's dry waterline end (its waterline slope there dipped from
/// 0.29 to 0.26). A cube vanishes fast enough for the correction to stay small there.
constexpr double kThroughQPower = 3.0;
/// A flared section's side leans this much more than the line from Q to the deck point, so
/// its top still turns inward (convex) ...
constexpr double kFlareMargin = 1.05;
/// ... but its bilge corner keeps at least this fraction of the waterline half-breadth, or the
/// less whose polygon's area over the V the asked area's is kCornerConicShare of (never under
/// kLeastCornerShare of b; least_corner_breadth), so a fine, flared section forward of a dry
/// transom can lean as its flare asks. A share, not a margin of fullness: a fixed margin (0.25)
/// held the corners of sections a little finer than their flare's bound upright, and they
/// flared hollow above T (measured in docs/sections.md). The share is 0.6, not 0.45: with the
/// fine weight 0.5 a share of 0.45 kept the corners of fine aft sections (fullness about 0.72)
/// out at 0.75 b, inboard of their flare's, and their topsides turned hollow (S frames above T
/// on 18 of 300 hulls, 5 then). The fraction is 0.7, not 0.75: in a fine, flared run (hull 188 of
/// bench_fairness_space at 0.1 Lpp) 0.75 b still held the corner inboard of the flare's, the leg
/// Q -> X steeper than the chord Q -> D, and the topside turned hollow (hulls with S frames above
/// T 8 -> 5 of bench_fairness_space's hulls 0-299, 10 -> 6 of 300-599).
constexpr double kMinCornerBreadth = 0.7;
constexpr double kCornerConicShare = 0.6, kLeastCornerShare = 0.1;
/// ... reached smoothly: the two corners are blended where their ratio lies within e^kCornerBlend
/// (narrow enough that the blended corner stays inside the waterline point: 0.75 e^0.25 < 1).
constexpr double kCornerBlend = 0.25;
/// The topside fillet's corner lies at most this share of the way up from the waterline point
/// (a dry section's virtual one) to the deck (below_deck).
constexpr double kDeckCornerShare = 0.9;
/// An immersed section's top corner Y lies no further out than the deck point D (inside_deck_edge):
/// one further out left the fillet turning back in to D, the frame standing out past its deck
/// edge above T (tumblehome at the bow, where the forward deck follows the narrowing waterline
/// and the side leans out along the bilge: the container ship's by 0.29 m, 1.80 % of B/2; 30
/// sampled hulls 1.07 % median, 2.15 % at most; now 0.02 % and over the 30 0.27 % at most). The leg keeps
/// at least kLeastSideLeg of itself (a deck inside the waterline asks for tumblehome) and is
/// shortened by a smooth minimum (kDeckEdgeBlend). bench_fairness_space's reading (with
/// kCornerBlend's blend), hulls 0-99 / held-out 100-199: every mark 40 -> 37 / 41 -> 40,
/// buttocks over two 29 -> 27 / 30 -> 29, waterlines over two 46 -> 49 / 46 -> 49 (lobes of
/// 0.1-0.6 deg in the lowest waterlines over the forefoot, 0.88-0.95 Lpp, where the shorter leg
/// bends the section's top nearer Q). Part of them was the knob's: it met the area on the drawn
/// top, whose bend the spline carries below T, and so moved the whole bilge. It now reads the
/// natural leg (knob_template) and the correction puts the difference back near Q: hulls 0-99 /
/// 100-199 / 200-399 (bench_fairness_space's first reading), hulls meeting every mark 42 -> 44 /
/// 40 -> 42 / 81 -> 82, with a T/4-0.74 T waterline over two sign changes 33 -> 30 / 31 -> 27 /
/// 64 -> 64, with a buttock over two 24 -> 24 / 23 -> 22 / 70 -> 69.
constexpr double kLeastSideLeg = 0.5;
/// The leg's minimum and maximum are rounded over e^kDeckEdgeBlend, wider than kCornerBlend's
/// e^0.25, which turned the leg to the room within a few stations over the forefoot.
/// bench_fairness_space, hulls 0-99 / 100-199 with 0.25 -> 0.6: every mark 37 -> 38 / 40 -> 40,
/// waterlines over two 49 -> 48 / 49 -> 48, wobbles in the T/4-0.74 T waterlines 81 -> 79 / 52 -> 51,
/// buttocks over two 27 -> 27 / 29 -> 29 (0.45: 37, 0.8: 37, 1.2: 30 on hulls 0-99, buttocks 36).
constexpr double kDeckEdgeBlend = 0.6;
/// A flat of bottom's corner with the bilge arc is rounded over this share of the shorter leg:
/// a knuckle, sampled by the control polygon at another place at every station, rippled the
/// lowest waterlines (0.5 m and 1 m of the container ship, turns of 0.1-0.9 deg).
constexpr double kFlatRound = 0.5;
/// A section whose immersion weight is below this is dry: its waterline point and area carry
/// no weight, and a waterline point a rounding error off the centre plane must not be checked.
constexpr double kMinImmersion = 1e-9;
/// How far below the keel point a dry section's virtual waterline point may lie, as a fraction of
/// the reach that keeps its top corner above K (see above_template).
constexpr double kVirtualReach = 0.5;
/// ... approached as raw / (1 + (raw / cap)^p)^(1/p) with this p: near the waterline's end Q_v
/// moves at the immersed sections' rate (raw cap / (raw + cap), p = 1, slowed it by a third at a
/// dry transom 0.05 T above the water, and the waterlines over it turned hollow).
constexpr double kVirtualSharpness = 4.0;
/// A dry section's template ends this smoothly at K: the miss at K is taken out of the
/// ordinates as g^kEndFixPower (g the Greville abscissa).
constexpr double kEndFixPower = 6.0;
/// ... when it misses by more than this fraction of the chord (a template ending at K misses
/// it only by the abscissa solve's round-off).
constexpr double kEndMissTol = 1e-12;
/// Sections shorter than this fraction of B/2 are a point (the stem head).
constexpr double kPointSection = 1e-9;
/// design_sections: at most this many threads, each with at least kSectionsPerThread sections.
constexpr std::size_t kSectionThreads = 4, kSectionsPerThread = 16;
/// Samples per template piece of the check that the template is a graph over its chord.
constexpr int kGraphChecks = 8;
/// Given shapes (SectionSpec::given): at least this many points; a half-breadth below this
/// fraction of B/2 is a point on the centre plane (no scale is read from it).
constexpr int kMinGivenPoints = 3;
constexpr double kGivenTiny = 1e-6;
/// A given shape's points at its keel point's height within this fraction of its height, from
/// the centre plane out, are its flat of bottom: the control points whose support lies on them
/// keep that height exactly. Fitted freely they sat a few millimetres off it, so the skin, which
/// holds a row only where its height repeats exactly along the hull, rippled the flat (the
/// rebuilt Series 60's fairness report: 77 sign changes on its buttocks, 172 on its frames, 65 and
/// 110 held).
constexpr double kGivenFlatTol = 1e-9;
/// The half-breadth shifts that put a given shape through Q and to its area: their size weighs
/// 1, their bend (second differences) this much (a smooth change over the section).
constexpr double kGivenShiftSmoothing = 10.0;
/// ... less mobile within this fraction of y_max of a bound, down to this mobility on it.
constexpr double kGivenBoundBand = 0.02;
constexpr double kGivenMobility = 0.05;
/// Shifts past the bound [0, y_max] by more than this fraction of y_max are held on it.
constexpr double kGivenBoundTol = 1e-12;
/// Skegs: samples of the body's section the neck point J is bracketed on, points along the
/// fillet, the skeg's side and its bottom, and the least room (fraction of the skeg's depth) the
/// fillet leaves the side above the bottom.
constexpr int kSkegBodySamples = 401;
constexpr int kSkegFilletPoints = 24;
constexpr int kSkegSidePoints = 12;
constexpr double kSkegBottomRoom = 0.2;
/// The neck point J (where a body's section comes in to an appendage's width): Newton's
/// iterations at most, and its tolerance on the half-breadth (fraction of max(1 m, the width)).
constexpr int kNeckIterations = 60;
constexpr double kNeckTol = 1e-13;
/// Samples of the body's section the appendage's fit reads above t_s and from t_s down to J.
constexpr int kAppendageUpperSamples = 48, kAppendageLowerSamples = 96;
/// Bending penalty of a skeg section's fit (second differences of the control points, per knot
/// span, against the data's weight). Not a given shape's near-interpolation: the tail's fillet
/// and side slide past the knots as the skeg grows along its aft end, and a near-interpolating fit
/// rang as they did (4 mm ripples of the sections' half-breadth, 0.4 m long, over the skegged
/// tanker's aft end). 0.07 and more thinned its side by more than a tenth 0.3-0.6 m above its
/// bottom (SkegAndDomeHangBelowTheBody). A dome's the same way, less: 0.01 took 3.8 % off its
/// breadth (the designer promises 3 %), 0.1 12 %.
constexpr double kSkegSmoothing = 0.05, kDomeSmoothing = 0.005;
/// An appendage's tail shares the parameter with the body's lowest this many knot spans.
constexpr int kAppendageSpans = 6;
/// Points along a dome's half ellipse.
constexpr int kDomePoints = 40;
/// The fillet is at most this fraction of the skeg's depth below the body.
constexpr double kSkegFilletDepth = 0.8;
/// The thinnest a tapering skeg gets, fraction of its half thickness.
constexpr double kSkegThinnest = 0.02;
/// Samples per knot span in the search of the spline's first crossing of z = T.
constexpr int kCrossingSamples = 8;

/// The z component of a x b (the plane cross product).
double cross(const V2& a, const V2& b) { return a.x() * b.y() - a.y() * b.x(); }

double smoothstep(double r) {
  r = std::clamp(r, 0.0, 1.0);
  return r * r * r * (10.0 - 15.0 * r + 6.0 * r * r);
}

std::string fmt(double v) { return detail::format_number(v, 6); }

/// What every section with n control points shares: knots, Greville abscissae, and the basis
/// (value and first derivative) at kAreaGauss points per span.
struct Layout {
  int n = 0;
  Eigen::VectorXd U, g;
  /// Basis rows (value N, first derivative dN) at the kAreaGauss points of each whole knot
  /// span [a, b]: the area row's quadrature, the same for every section.
  struct SpanRows {
    double a, b;
    std::vector<Eigen::RowVectorXd> N, dN;
  };
  std::vector<SpanRows> span_rows;
};

Layout make_layout(int n) {
  if (n < kMinSectionControls || n > kMaxSectionControls)
    fail("sections.n_control is ", n, "; expected ", kMinSectionControls, " to ", kMaxSectionControls);
  Layout l;
  l.n = n;
  l.U = clamped_uniform_knots(n, kDegree);
  l.g = greville_abscissae(l.U, kDegree);
  const auto& gr = detail::gauss_rule(kAreaGauss);
  for (int i = kDegree; i < n; ++i) {
    if (!(l.U[i + 1] > l.U[i])) continue;
    const double h = 0.5 * (l.U[i + 1] - l.U[i]), m = 0.5 * (l.U[i + 1] + l.U[i]);
    Layout::SpanRows& rows = l.span_rows.emplace_back(Layout::SpanRows{l.U[i], l.U[i + 1], {}, {}});
    for (std::size_t q = 0; q < gr.x.size(); ++q) {
      const double t = m + h * gr.x[q];
      rows.N.push_back(basis_row(l.U, kDegree, t));
      rows.dN.push_back(basis_row(l.U, kDegree, t, 1));
    }
  }
  return l;
}

const Layout& layout(int n) {
  thread_local std::vector<Layout> cache;
  for (const Layout& l : cache)
    if (l.n == n) return l;
  cache.push_back(make_layout(n));
  return cache.back();
}

/// A quintic Bezier fillet (six points) or a conic arc (a rational quadratic Bezier: three
/// points and the middle weight w), in (y, z).
struct Piece {
  std::array<V2, 6> p;
  bool conic = false;
  double w = 1.0;
  V2 at(double s) const {
    if (conic) {
      const double b0 = (1.0 - s) * (1.0 - s), b1 = 2.0 * w * s * (1.0 - s), b2 = s * s;
      return (b0 * p[0] + b1 * p[1] + b2 * p[2]) / (b0 + b1 + b2);
    }
    std::array<V2, 6> q = p;  // de Casteljau
    for (int r = 1; r < 6; ++r)
      for (int i = 0; i < 6 - r; ++i) q[i] = (1.0 - s) * q[i] + s * q[i + 1];
    return q[0];
  }
  V2 tangent(double s) const {
    if (conic) {
      const double b0 = (1.0 - s) * (1.0 - s), b1 = 2.0 * w * s * (1.0 - s), b2 = s * s;
      const double d0 = -2.0 * (1.0 - s), d1 = 2.0 * w * (1.0 - 2.0 * s), d2 = 2.0 * s;
      const double den = b0 + b1 + b2, dden = d0 + d1 + d2;
      const V2 num = b0 * p[0] + b1 * p[1] + b2 * p[2], dnum = d0 * p[0] + d1 * p[1] + d2 * p[2];
      return (dnum * den - num * dden) / (den * den);
    }
    std::array<V2, 5> q;
    for (int i = 0; i < 5; ++i) q[i] = 5.0 * (p[i + 1] - p[i]);
    for (int r = 1; r < 5; ++r)
      for (int i = 0; i < 5 - r; ++i) q[i] = (1.0 - s) * q[i] + s * q[i + 1];
    return q[0];
  }
};

/// The conic arc from A to B with corner X and middle weight w (a line for w = 0, a parabola
/// for w = 1, toward the corner as w grows).
Piece conic(const V2& A, const V2& X, const V2& B, double w) {
  Piece pc;
  pc.p.fill(V2::Zero());  // a conic uses three of the six points
  pc.conic = true, pc.w = w;
  pc.p[0] = A, pc.p[1] = X, pc.p[2] = B;
  return pc;
}

/// The fillet from A to B with corner X (A and B on the legs X-A and X-B), its middle control
/// points at `far` of each leg.
Piece fillet(const V2& A, const V2& X, const V2& B, double far = kFilletFar) {
  Piece pc;
  pc.p = {A, A + kFilletNear * (X - A), A + far * (X - A), B + far * (X - B), B + kFilletNear * (X - B), B};
  return pc;
}

struct Frame {
  V2 D = V2::Zero(), dir = V2::Zero(), nrm = V2::Zero();
  double L = 0;
  double xi(const V2& q) const { return (q - D).dot(dir); }
  double eta(const V2& q) const { return (q - D).dot(nrm); }
};

/// A section being built: its numbers, frame and the immersed box.
struct Section {
  const SectionSpec& s;
  const Layout& l;
  std::string at;
  Frame f{};
  V2 K = V2::Zero(), Q = V2::Zero();
  bool immersed = false;
  double b = 0, d = 0, w = 0;  // box and immersion weight
  double t_q = 0;              // parameter of Q (its abscissa over L)
};

/// A given shape: (m, 2) finite points (y >= 0, z) running from the deck edge down to the keel.
void validate_given(const Eigen::MatrixXd& P, const char* field, const std::string& at) {
  if (P.size() == 0) return;
  if (P.cols() != 2 || P.rows() < kMinGivenPoints)
    fail(at, ": ", field, " has shape (", P.rows(), ", ", P.cols(), "); expected (m, 2) points (y, z) with m >= ", kMinGivenPoints);
  if (!P.allFinite()) fail(at, ": ", field, " holds a value that is not finite; expected (y, z) in metres");
  if ((P.col(0).array() < 0).any()) fail(at, ": ", field, " has a half-breadth ", P.col(0).minCoeff(), " m; expected y >= 0");
  if (!(P(0, 1) > P(P.rows() - 1, 1)))
    fail(at, ": ", field, " runs from z = ", P(0, 1), " m to z = ", P(P.rows() - 1, 1),
         " m; expected the deck edge first and the keel point, lower, last");
}

void validate(const SectionSpec& s, const std::string& at) {
  auto finite = [&](double v, const char* field) {
    if (!std::isfinite(v)) fail(at, ": ", field, " is ", v, "; expected a finite number");
  };
  finite(s.x, "x"), finite(s.y_deck, "y_deck"), finite(s.z_deck, "z_deck"), finite(s.z_keel, "z_keel"), finite(s.y_max, "y_max");
  finite(s.shape, "shape"), finite(s.flat_bottom, "flat_bottom"), finite(s.top_corner, "top_corner"), finite(s.deadrise, "deadrise"), finite(s.character, "character");
  for (auto [v, field] : {std::pair{s.draft, "draft"}, {s.y_dwl, "y_dwl"}, {s.half_area, "half_area"}, {s.lower_angle, "lower_angle"}})
    if (std::isinf(v)) fail(at, ": ", field, " is ", v, "; expected a number or NaN (not given)");
  if (!(s.y_max > 0)) fail(at, ": y_max is ", s.y_max, "; expected the half-breadth bound B/2 > 0 (m)");
  const double tol = 1e-9 * (s.y_max + std::abs(s.z_deck));
  if (s.y_deck < -tol || s.y_deck > s.y_max + tol) fail(at, ": y_deck is ", s.y_deck, " m; expected 0 <= y_deck <= B/2 = ", s.y_max, " m");
  if (s.z_keel > s.z_deck + tol) fail(at, ": z_keel is ", s.z_keel, " m; expected at most the deck height ", s.z_deck, " m");
  if (!std::isnan(s.y_dwl) && (s.y_dwl < -tol || s.y_dwl > s.y_max + tol))
    fail(at, ": y_dwl is ", s.y_dwl, " m; expected 0 <= y_dwl <= B/2 = ", s.y_max, " m");
  if (!std::isnan(s.draft) && !std::isnan(s.y_dwl) && s.y_dwl > 0 && !(s.draft < s.z_deck))
    fail(at, ": draft is ", s.draft, " m; expected a waterline below the deck (", s.z_deck, " m)");
  if (!std::isnan(s.half_area) && s.half_area < 0) fail(at, ": half_area is ", s.half_area, " m^2; expected >= 0");
  if (!(s.shape >= 0 && s.shape <= kMaxShapeKnob)) fail(at, ": shape is ", s.shape, "; expected 0 to ", kMaxShapeKnob);
  if (!(s.top_corner > 0 && s.top_corner < 1)) fail(at, ": top_corner is ", s.top_corner, "; expected a fraction between 0 and 1");
  if (!(s.deadrise >= 0 && s.deadrise < 45)) fail(at, ": deadrise is ", s.deadrise, " deg; expected 0 <= deadrise < 45");
  if (!(s.flat_bottom >= 0 && s.flat_bottom < 1))
    fail(at, ": flat_bottom is ", s.flat_bottom, "; expected a fraction of the waterline half-breadth in [0, 1)");
  if (!(s.character > 0 && s.character < 1)) fail(at, ": character is ", s.character, "; expected a fraction between 0 and 1");
  if (std::isnan(s.corner_y) != std::isnan(s.corner_z))
    fail(at, ": corner_y is ", s.corner_y, " and corner_z is ", s.corner_z, "; expected both given or both NaN");
  if (!std::isnan(s.corner_y) && !(s.corner_y > 0 && s.corner_y <= 1))
    fail(at, ": corner_y is ", s.corner_y, "; expected a fraction of the waterline half-breadth in (0, 1]");
  if (!std::isnan(s.corner_z) && !(s.corner_z >= 0 && s.corner_z < 1))
    fail(at, ": corner_z is ", s.corner_z, "; expected a fraction of the immersed depth in [0, 1)");
  if (!std::isnan(s.lower_angle) && !(s.lower_angle > -kMaxLowerAngle && s.lower_angle < kMaxLowerAngle))
    fail(at, ": lower_angle is ", s.lower_angle, " deg; expected -", kMaxLowerAngle, " < angle < ", kMaxLowerAngle);
  validate_given(s.given, "given", at);
  validate_given(s.given_fore, "given_fore", at);
  if (s.given_fore.rows() > 0 && s.given.rows() == 0) fail(at, ": given_fore is set without given; expected given first");
  if (!(s.given_mix >= 0 && s.given_mix <= 1)) fail(at, ": given_mix is ", s.given_mix, "; expected a weight from 0 to 1");
  if (!(s.given_smoothing >= 0 && std::isfinite(s.given_smoothing)))
    fail(at, ": given_smoothing is ", s.given_smoothing, "; expected a finite bending penalty >= 0");
  if (std::isinf(s.skeg_bottom)) fail(at, ": skeg_bottom is ", s.skeg_bottom, "; expected a height in metres or NaN (no skeg)");
  if (!(s.skeg_half_thickness > 0 && std::isfinite(s.skeg_half_thickness)))
    fail(at, ": skeg_half_thickness is ", s.skeg_half_thickness, " m; expected > 0");
  if (!(s.skeg_fillet >= 0 && std::isfinite(s.skeg_fillet))) fail(at, ": skeg_fillet is ", s.skeg_fillet, " m; expected >= 0");
  if (std::isinf(s.dome_bottom)) fail(at, ": dome_bottom is ", s.dome_bottom, "; expected a height in metres or NaN (no dome)");
  if (!(s.dome_half_breadth > 0 && std::isfinite(s.dome_half_breadth)))
    fail(at, ": dome_half_breadth is ", s.dome_half_breadth, " m; expected > 0");
  if (!(s.dome_neck > 0 && s.dome_neck < s.dome_half_breadth))
    fail(at, ": dome_neck is ", s.dome_neck, " m; expected 0 < neck < dome_half_breadth = ", s.dome_half_breadth, " m");
}

Section setup(const SectionSpec& s) {
  Section S{s, layout(s.n_control), "section at x = " + fmt(s.x) + " m"};
  validate(s, S.at);
  S.f.D = V2(std::clamp(s.y_deck, 0.0, s.y_max), s.z_deck);
  S.K = V2(0.0, std::min(s.z_keel, s.z_deck));
  const V2 chord = S.K - S.f.D;
  S.f.L = chord.norm();
  S.f.dir = S.f.L > 0 ? V2(chord / S.f.L) : V2(0.0, -1.0);
  S.f.nrm = V2(-S.f.dir.y(), S.f.dir.x());
  S.immersed = !std::isnan(s.draft) && !std::isnan(s.y_dwl) && s.y_dwl > 0 && s.draft > S.K.y();
  if (S.immersed) {
    S.b = std::min(s.y_dwl, s.y_max);
    S.d = s.draft - S.K.y();
    S.Q = V2(S.b, s.draft);
    S.w = smoothstep(std::min(S.b / (kEndBand * s.y_max), S.d / (kEndBand * s.draft)));
    if (S.w < kMinImmersion) {
      S.immersed = false;
      S.w = 0.0;
      return S;
    }
    const double xq = S.f.xi(S.Q);
    if (!(xq > 0 && xq < S.f.L))
      throw InfeasibleFormParameters(S.at + ": the waterline point (" + fmt(S.Q.x()) + ", " + fmt(S.Q.y()) +
                                     ") m does not lie between the deck point and the keel point along the section "
                                     "(design waterline vs deck line and centre profile)");
    S.t_q = xq / S.f.L;
  }
  return S;
}

/// Where the bilge corner heads as the section fines: `character` of the depth below Q, on the
/// line from Q that leans in by the chord's lean b / d -- or less where the top has no room:
/// the top corner Y (at top_corner |D - Q| above Q along the waterline tangent) must stay
/// inside the edge e halfway from the deck's half-breadth to B/2 (kRoomBeyondDeck), so
/// sin(lean) <= (e - b) / (top_corner |D - Q|). With little room the bottom
/// rises (deadrise) under a wall-sided waterline instead of the side leaning in, and the
/// section can still fine down.
/// Least lean of the side below Q (run over depth) that keeps a flared section convex: the
/// side's extension above Q must pass outboard of the deck point D, or the top turns outward
/// against the bilge (hollow flare, an S-shaped section).
double flare_lean(const Section& S) {
  const V2& D = S.f.D;
  const double rise = D.y() - S.Q.y();
  return rise > 0 ? std::max(0.0, kFlareMargin * (D.x() - S.Q.x()) / rise) : 0.0;
}

/// How far smooth_min lowers min(a, c) and smooth_max raises max(a, c) (a, c > 0), as an
/// exponent: a cubic in how deep within e^k their ratio lies, 0 beyond (C2 in log a).
double blend_exponent(double a, double c, double k) {
  const double h = std::max(k - std::abs(std::log(a / c)), 0.0) / k;
  return h * h * h * k / 6.0;
}

/// min(a, c) of a, c >= 0 rounded where their ratio lies within e^k: a cubic blend of their
/// logarithms (C2, below both, the plain minimum beyond; positive where both are).
double smooth_min(double a, double c, double k) {
  if (std::min(a, c) <= 0) return std::min(a, c);
  return std::min(a, c) * std::exp(-blend_exponent(a, c, k));
}

/// max(a, c) for c > 0, rounded where a / c lies within e^k: the mirror of smooth_min (C2,
/// above both by at most the factor e^(k/6), the plain maximum beyond).
double smooth_max(double a, double c, double k) {
  if (a <= 0) return c;
  return std::max(a, c) * std::exp(blend_exponent(a, c, k));
}

/// The leg of an immersed section's top corner (from Q along dir) shortened so the corner lies
/// no further out than the deck point D (see kLeastSideLeg).
double inside_deck_edge(const V2& Q, const V2& dir, double leg, const V2& D) {
  if (!(dir.x() > 0)) return leg;
  const double room = (D.x() - Q.x()) / dir.x();
  return smooth_min(leg, smooth_max(room, kLeastSideLeg * leg, kDeckEdgeBlend), kDeckEdgeBlend);
}

/// The top corner Y = base + leg dir of the topside fillet (deck point D to the waterline point
/// or a dry section's virtual one), its leg shortened where Y would come above kDeckCornerShare
/// of the rise from base to D (a smooth minimum, kCornerBlend; untouched beyond it): a fillet
/// whose corner lies above the deck left D going up, and a wide, dry transom's section rose 1 cm
/// over the deck, which the deck's cap then cut (3.5 % of bench_hull's bulbed hulls composed to a
/// self-intersecting mesh). Below the deck the fillet's polygon, and so the fillet, stays under it.
V2 below_deck(const V2& base, const V2& dir, double leg, const V2& D) {
  const double rise = D.y() - base.y();
  if (dir.y() > 0 && rise > 0) leg = smooth_min(leg, kDeckCornerShare * rise / dir.y(), kCornerBlend);
  return base + leg * dir;
}

/// The sine of the lean a section's side takes below its waterline point (b its half-breadth,
/// reach |D - Q|): the chord's, or less where the top corner has no room (see heading()): the
/// room reaches halfway (kRoomBeyondDeck) from the deck's half-breadth to B/2.
double heading_sine(double sin_chord, double b, double reach, const SectionSpec& s) {
  const double edge = s.y_deck + kRoomBeyondDeck * (s.y_max - s.y_deck);
  const double sin_room = (edge - b) / std::max(s.top_corner * reach, 1e-12);
  return smooth_min(sin_chord, std::max(sin_room, 0.0), kHeadingBlend);
}

/// heading_sine of an immersed section's own chord (its box's breadth b over its depth d: beyond
/// a flat of bottom, the chord from Q to the flat's end); the room is measured from Q.
double chord_heading_sine(const Section& S) {
  const double chord = S.b / S.d;
  return heading_sine(chord / std::sqrt(1.0 + chord * chord), S.Q.x(), (S.f.D - S.Q).norm(), S.s);
}

V2 heading(const Section& S) {
  const SectionSpec& s = S.s;
  // (The flare does not steer the heading: a wide deck over a narrow, shallow waterline would
  // send it across the centre plane and fold the section. The corner C leans for it instead.)
  // The minimum is taken of the sines: the room's sine changes along the ship as the waterline's
  // half-breadth does, where its tangent blows up as the room reaches the whole top (sine 1).
  const double sin_lean = chord_heading_sine(S);
  const double lean = sin_lean / std::sqrt(1.0 - sin_lean * sin_lean);
  return S.Q + s.character * S.d * V2(-lean, -1.0);
}

/// The topside fillet `top` (deck to Q) given the bilge arc's curvature at Q: its third control
/// point from Q moves off the leg. Signed end curvatures: the conic's (1/2) (1/w^2) (X - Q) x
/// (K - X) / |X - Q|^3, the quintic's (4/5) (p4 - p3) x (p5 - p4) / |p5 - p4|^3, which a move
/// of p3 by h along (-u_z, u_y) (u the unit leg p4 -> p5) makes (4/5) h / |p5 - p4|^2.
void match_bilge_curvature(Piece& top, const Piece& bilge) {
  constexpr double conic_end = 0.5, quintic_end = 0.8;  // (n - 1) / n of a degree-n Bezier's end
  const V2 &Q = bilge.p[0], &X = bilge.p[1], &K = bilge.p[2];
  const double leg = (X - Q).norm(), reach = (top.p[3] - top.p[5]).norm(), end = (top.p[5] - top.p[4]).norm();
  if (!(leg > 0 && reach > 0 && end > 0 && bilge.w > 0)) return;
  const double k_q = conic_end / (bilge.w * bilge.w) * cross(X - Q, K - X) / (leg * leg * leg);
  const double r = std::pow(leg / reach, kCurvatureMatchPower);
  const V2 u = (top.p[5] - top.p[4]) / end, n(-u.y(), u.x());
  const double h = r / (1.0 + r) * k_q / quintic_end * end * end;
  // The turn of the polygon at p3, cross(p3 - p2, p4 - p3), is linear in the move: turn + h slope.
  // Whether the move takes turn away is read against the section's bend (the bilge's sign), not
  // the sign of the turn itself: on a wall side the turn is round-off, and its sign would switch
  // the move between none and all of it.
  const V2 a = top.p[3] - top.p[2], b = top.p[4] - top.p[3];
  const double turn = cross(a, b), slope = cross(n, a + b), bend = k_q > 0 ? 1.0 : -1.0;
  const double cap = bend * h * slope < 0 ? kCurvatureMatchShare * std::max(bend * turn, 0.0) / std::abs(slope)
                                          : std::abs(h);
  if (!(cap > 0)) return;
  const double q = std::pow(std::abs(h) / cap, kCurvatureMatchSharpness);
  top.p[3] += h / std::pow(1.0 + q, 1.0 / kCurvatureMatchSharpness) * n;
}

/// The least breadth of the bilge corner C (at height z_keel + rise) a flared section may lean
/// to: kMinCornerBreadth of b, or less where the asked fullness f needs less. The polygon
/// K -> C -> Q holds (c d + b (d - rise)) / 2 of area (c the corner's breadth), the V (chord Q-K)
/// half the box, so c = b (2 (f - 1/2) / kCornerConicShare + rise / d) asks the bilge conic for
/// that share of the polygon's excess over the V.
double least_corner_breadth(const Section& S, double rise) {
  const double floor = kMinCornerBreadth * S.b;
  if (std::isnan(S.s.half_area) || !(S.b > 0 && S.d > 0)) return floor;  // the family's range: the fixed floor
  const double excess = S.s.half_area / (S.b * S.d) - 0.5;
  const double needed = S.b * (2.0 * excess / kCornerConicShare + rise / S.d);
  return smooth_min(smooth_max(needed, kLeastCornerShare * S.b, kCornerBlend), floor, kCornerBlend);
}

/// How far the floor rises at the deadrise over `breadth` from the keel point, at most half the
/// immersed depth.
double floor_rise(const Section& S, double breadth) {
  return std::min(breadth * std::tan(S.s.deadrise * std::numbers::pi / 180.0), 0.5 * S.d);
}

/// The bilge corner X and the arc's middle weight w for shape knob lambda, in the box whose
/// keel point is S.K (the section's, or the flat of bottom's outer end F).
std::pair<V2, double> bilge_corner(const Section& S, double lambda) {
  const SectionSpec& s = S.s;
  const V2& K = S.K;
  const double rise = floor_rise(S, S.b);
  // The flare's corner and the least corner breadth meet in a smooth maximum: a plain one
  // kinked the corner (and the rows of control points) along the hull where they cross.
  const V2 C(K.x() + smooth_max(S.b - flare_lean(S) * (S.d - rise), least_corner_breadth(S, rise), kCornerBlend), K.y() + rise);
  const V2 M = heading(S);
  const double t = std::clamp(lambda / kMaxShapeKnob, 0.0, 1.0);
  const bool given = !std::isnan(s.corner_y);
  const V2 X = given ? V2(K.x() + s.corner_y * S.b, K.y() + s.corner_z * S.d) : V2(C + std::pow(t, kLeanPower) * (M - C));
  return {X, kFullWeight * std::pow((given ? kCornerFineWeight : kFineWeight) / kFullWeight, t)};
}

/// The template's pieces for shape knob lambda (immersed sections), flat_kept of the flat of
/// bottom kept, the top corner drawn inside the deck edge unless `natural_leg` (see
/// knob_template; `leg_shortened`, if given, says whether it was), from the deck to the keel:
/// the topside fillet D -> Y -> Q and the bilge arc Q -> X -> K; with a flat of bottom of
/// half-breadth f the arc is the family's in the box beyond the flat (keel point F = K + (f, rise),
/// its area less the flat's strip) and ends at F1 on its leg X -> F, a fillet rounds the corner at
/// F over kFlatRound of the shorter leg down to F0 on the floor, and the floor runs straight to K.
std::vector<Piece> immersed_template(const Section& S, double lambda, double flat_kept = 1.0, bool natural_leg = false,
                                      bool* leg_shortened = nullptr) {
  const SectionSpec& s = S.s;
  const V2 &D = S.f.D, &K = S.K, &Q = S.Q;
  const double f = flat_kept * s.flat_bottom * S.b;
  std::vector<Piece> floor;  // the flat's pieces, F1 to K
  V2 X, end = K;
  double w = 0;
  if (f > 0) {
    const double rise = floor_rise(S, f);
    const V2 F = K + V2(f, rise);
    SectionSpec beyond = s;  // least_corner_breadth reads the asked area over the box beyond the flat
    if (!std::isnan(beyond.half_area)) beyond.half_area -= f * (S.d - 0.5 * rise);
    const Section inner{beyond, S.l, S.at, S.f, F, Q, S.immersed, S.b - f, S.d - rise, S.w, S.t_q};
    std::tie(X, w) = bilge_corner(inner, lambda);
    const double r = kFlatRound * std::min(f, (X - F).norm());
    const V2 F0 = F + r * (K - F).normalized();
    end = F + r * (X - F).normalized();
    floor = {fillet(end, F, F0), conic(F0, 0.5 * (F0 + K), K, 1.0)};
  } else {
    std::tie(X, w) = bilge_corner(S, lambda);
  }
  const double l1 = (X - Q).norm();
  const V2 tw = l1 > 0 ? V2((X - Q) / l1) : V2((K - Q).normalized());
  const double leg = s.top_corner * (D - Q).norm();
  const double drawn = natural_leg ? leg : inside_deck_edge(Q, -tw, leg, D);
  if (leg_shortened) *leg_shortened = drawn != leg;
  const V2 Y = below_deck(Q, -tw, drawn, D);
  Piece top = fillet(D, Y, Q, kTopFilletFar);
  const Piece bilge = conic(Q, X, end, w);
  match_bilge_curvature(top, bilge);
  std::vector<Piece> pieces{top, bilge};
  pieces.insert(pieces.end(), floor.begin(), floor.end());
  return pieces;
}

/// The area knob t: the shape knob lambda = min(t, hi) with the whole flat of bottom, then (t >
/// hi: a section finer than its finest shape with the whole flat) the flat narrowed to
/// 1 - (t - hi) of itself at that shape. It runs over [0, knob_end(S, hi)].
struct Knob {
  double lambda, flat_kept;
};
Knob knob_at(double t, double hi) { return {std::min(t, hi), 1.0 - std::clamp(t - hi, 0.0, 1.0)}; }
// A given corner's area may rise with lambda (its largest then inside [0, hi]): no narrowing
// stretch after it, or the knob's range would not be one-way.
double knob_end(const Section& S, double hi) { return S.s.flat_bottom > 0 && std::isnan(S.s.corner_y) ? hi + 1.0 : hi; }
/// The template the area knob reads (solve_knob, the fullness bounds) has the top corner's
/// natural leg: the leg shortened inside the deck edge bends the top nearer Q, the spline's
/// samples carry that into its area below T, and a knob meeting the area on it moved the whole
/// bilge over the forefoot (design_section puts that area back near Q instead; see kLeastSideLeg).
std::vector<Piece> knob_template(const Section& S, double t, double hi) {
  const Knob k = knob_at(t, hi);
  return immersed_template(S, k.lambda, k.flat_kept, true);
}

/// Above the water: one rounded corner from the deck point to the keel point, arriving at
/// lower_angle. Beyond a waterline's end it continues the immersed family's fine end (a top
/// corner over a straight leg to the waterline point): the leg runs on from K, at lower_angle,
/// down to a virtual waterline point Q_v at z = T, and the corner is rounded to Q_v and the
/// section cut at K. So sections change at the same rate on both sides of the waterline's end
/// (no knee in the waterlines and buttocks above it); Q_v's distance below K saturates at
/// kVirtualReach of what keeps the corner above K.
std::vector<Piece> above_template(const Section& S) {
  const SectionSpec& s = S.s;
  double a = (std::isnan(s.lower_angle) ? 0.0 : s.lower_angle) * std::numbers::pi / 180.0;
  const double lk = (S.f.D - S.K).norm();
  const bool virtual_q = !std::isnan(s.lower_angle) && !std::isnan(s.draft) && S.K.y() > s.draft;
  auto virtual_point = [&](double angle) {  // Q_v on the leg from K at `angle`, its distance saturating
    const V2 up(std::sin(angle), std::cos(angle));
    const double cap = kVirtualReach * s.top_corner / (1.0 + s.top_corner) * lk;
    const double raw = (S.K.y() - s.draft) / up.y();
    const double e = cap > 0 ? detail::soft_cap(raw, cap, kVirtualSharpness) : 0.0;
    return V2(S.K - e * up);
  };
  // The leg leans as the immersed sections' side does (the chord's lean, less where the top has
  // no room, heading_sine at Q_v): with the chord's lean alone the dry and the immersed sections
  // met with a step where the waterline ends (1 mm at the container ship's 15 m waterline).
  if (!std::isnan(s.lower_angle) && !std::isnan(s.draft)) {  // also at the end itself (Q_v = K)
    const V2 Q0 = virtual_q ? virtual_point(a) : S.K;
    a = std::asin(heading_sine(std::sin(a), Q0.x(), (S.f.D - Q0).norm(), s));
  } else if (std::isnan(s.lower_angle) && S.b > 0 && S.d > 0) {
    // An immersed section too close to the waterline's end to count (setup: w < kMinImmersion,
    // within a millimetre of it) is the end's limit, the top corner over the chord's lean; with
    // no lower angle given it was a vertical leg (the 15 m half-breadth 1.86 m instead of 7.90 m).
    a = std::asin(chord_heading_sine(S));
  }
  const V2 up(std::sin(a), std::cos(a));
  const V2 Qv = virtual_q ? virtual_point(a) : S.K;
  const V2 Y = below_deck(Qv, up, s.top_corner * (S.f.D - Qv).norm(), S.f.D);
  return {fillet(S.f.D, Y, Qv, kTopFilletFar)};
}

/// The template ordinates at the Greville abscissae (the spline's control ordinates). Throws
/// InfeasibleFormParameters when the template is not a graph over its chord.
Eigen::VectorXd sample(const Section& S, const std::vector<Piece>& pieces) {
  const Frame& f = S.f;
  const int n = S.l.n;
  Eigen::VectorXd eta(n);
  std::vector<double> xi_end(pieces.size());
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    double prev = f.xi(pieces[i].at(0.0));
    for (int k = 1; k <= kGraphChecks; ++k) {
      const double cur = f.xi(pieces[i].at(static_cast<double>(k) / kGraphChecks));
      if (cur < prev - 1e-9 * f.L)
        throw InfeasibleFormParameters(S.at + ": the section through the deck point (" + fmt(f.D.x()) + ", " + fmt(f.D.y()) +
                                       "), the waterline point and the keel point (0, " + fmt(S.K.y()) +
                                       ") m turns back on itself (deck line, design waterline and centre profile disagree here)");
      prev = cur;
    }
    xi_end[i] = prev;
  }
  std::size_t piece = 0;
  for (int k = 0; k < n; ++k) {
    const double xi = f.L * S.l.g[k];
    while (piece + 1 < pieces.size() && xi > xi_end[piece]) ++piece;
    const Piece& pc = pieces[piece];
    const double x0 = f.xi(pc.at(0.0)), x1 = f.xi(pc.at(1.0));
    double s = x1 > x0 ? std::clamp((xi - x0) / (x1 - x0), 0.0, 1.0) : 0.0;
    {  // Newton on xi(s) = xi, kept inside a shrinking bracket
      double lo = 0.0, hi = 1.0;
      for (int it = 0; it < 60; ++it) {
        const double r = f.xi(pc.at(s)) - xi;
        if (std::abs(r) <= 1e-14 * f.L) break;
        (r > 0 ? hi : lo) = s;
        const double slope = pc.tangent(s).dot(f.dir);
        double next = slope > 0 ? s - r / slope : 0.5 * (lo + hi);
        if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
        s = next;
      }
    }
    eta[k] = f.eta(pc.at(s));
  }
  eta[0] = 0.0;
  // A template running on past K (a dry section's virtual leg) misses K by a little: take the
  // miss out smoothly, from nothing at the deck to all of it at K.
  const double miss = eta[n - 1] - f.eta(S.K);
  if (std::abs(miss) > kEndMissTol * f.L)
    for (int k = 1; k < n; ++k) eta[k] -= miss * std::pow(S.l.g[k], kEndFixPower);
  eta[n - 1] = f.eta(S.K);
  return eta;
}

/// Area below T as a linear function row . eta + c of the ordinates, for a spline through Q at
/// t_q: Green's theorem along Q -> curve -> K -> (0, T) -> Q; on the curve
/// P x P' = xi' (D x dir) + eta' (D x nrm) + (dir x nrm)(xi eta' - xi' eta), linear in eta.
std::pair<Eigen::RowVectorXd, double> area_row(const Section& S) {
  const Frame& f = S.f;
  const int n = S.l.n;
  const double DxD = cross(f.D, f.dir), DxN = cross(f.D, f.nrm), dxn = cross(f.dir, f.nrm);
  const auto& gr = detail::gauss_rule(kAreaGauss);
  Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(n);
  double c = 0.0;
  std::vector<double> br{S.t_q};
  for (int i = kDegree + 1; i < static_cast<int>(S.l.U.size()) - kDegree - 1; ++i)
    if (S.l.U[i] > br.back()) br.push_back(S.l.U[i]);
  if (br.back() < 1.0) br.push_back(1.0);
  for (std::size_t k = 0; k + 1 < br.size(); ++k) {
    const double h = 0.5 * (br[k + 1] - br[k]), m = 0.5 * (br[k + 1] + br[k]);
    const auto whole = std::find_if(S.l.span_rows.begin(), S.l.span_rows.end(),
                                    [&](const Layout::SpanRows& r) { return r.a == br[k] && r.b == br[k + 1]; });
    Eigen::RowVectorXd Nt, dNt;
    for (std::size_t q = 0; q < gr.x.size(); ++q) {
      const double t = m + h * gr.x[q], wq = gr.w[q] * h;
      if (whole == S.l.span_rows.end()) Nt = basis_row(S.l.U, kDegree, t), dNt = basis_row(S.l.U, kDegree, t, 1);
      const Eigen::RowVectorXd& N = whole == S.l.span_rows.end() ? Nt : whole->N[q];
      const Eigen::RowVectorXd& dN = whole == S.l.span_rows.end() ? dNt : whole->dN[q];
      c += wq * f.L * DxD;
      row += wq * (DxN * dN + dxn * (f.L * t * dN - f.L * N));
    }
  }
  const V2 top(0.0, S.s.draft);
  c += cross(S.K, top) + cross(top, S.Q);
  return {-0.5 * row, -0.5 * c};
}

/// The spline's ordinate row at t (basis functions).
Eigen::RowVectorXd point_row(const Section& S, double t) { return basis_row(S.l.U, kDegree, std::clamp(t, 0.0, 1.0)); }

/// Knob range [0, hi]: the top corner must stay inside B/2 (past it the top would bulge out;
/// the section is clamped to B/2 where a given bilge corner leans its top out).
double knob_limit(const Section& S) {
  if (!std::isnan(S.s.corner_y)) return kMaxShapeKnob;  // a given corner fixes the top: the knob moves the weight only
  auto corner_y = [&](double lam) {  // the top fillet's third control point lies at kTopFilletFar from D toward Y
    const Piece top = immersed_template(S, lam)[0];
    return (top.p[0] + (top.p[2] - top.p[0]) / kTopFilletFar).x();
  };
  const double ymax = S.s.y_max * (1.0 + 1e-12);
  if (corner_y(kMaxShapeKnob) <= ymax) return kMaxShapeKnob;
  if (corner_y(0.0) > ymax) return 0.0;
  double lo = 0.0, hi = kMaxShapeKnob;
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo + hi);
    (corner_y(mid) <= ymax ? lo : hi) = mid;
  }
  return lo;
}

/// Correction delta of the ordinates, least (weighted, smooth), with the ends fixed, the
/// spline through `eta_q` at t_q and the area row changed by `d_area` (m^2). Below Q straight
/// stretches of the spline weigh kFlatGuard times more, so flats stay in their plane; above Q the
/// correction is a near-linear tilt (kTopsideFreedom, kTopsideStiffness).
Eigen::VectorXd correction(const Section& S, const Eigen::VectorXd& eta, double eta_q, const Eigen::RowVectorXd& arow,
                           double d_area) {
  const int n = S.l.n;
  Eigen::MatrixXd Mw = Eigen::MatrixXd::Zero(n, n);
  const double span = 1.0 / (n - kDegree);
  // How much of a topside control point (0 below Q, 1 above) a Greville abscissa g is: a
  // smoothstep over kTopsideBlend knot spans about Q, so the weights change smoothly as Q moves
  // along the section from station to station (a switch at g = t_q jumped the correction).
  auto topside = [&](double g) { return smoothstep((S.t_q - g) / (kTopsideBlend * span) + 0.5); };
  auto mix = [](double a, double b, double tau) { return std::exp(tau * std::log(a) + (1.0 - tau) * std::log(b)); };
  Eigen::VectorXd dd = Eigen::VectorXd::Zero(n);  // the polygon's scaled second differences
  for (int k = 1; k + 1 < n; ++k) dd[k] = (eta[k - 1] - 2.0 * eta[k] + eta[k + 1]) / (kStraightScale * S.f.L);
  for (int k = 0; k < n; ++k) {
    // An inflection is straight at one point only: its neighbours' opposite bends count as
    // curvature, so the guard does not flick on as the inflection passes a control point.
    const double curv2 = k > 0 && k < n - 1 ? dd[k] * dd[k] + std::max(0.0, -dd[k - 1] * dd[k + 1]) : 0.0;
    const double far = (S.l.g[k] - S.t_q) / (kCorrectionReach * span);
    const double below = (1.0 + kFlatGuard / (1.0 + curv2)) * (1.0 + far * far * far * far);
    Mw(k, k) = k > 0 ? mix(kTopsideFreedom, below, topside(S.l.g[k])) : below;
  }
  for (int k = 1; k + 1 < n; ++k) {
    const Eigen::Vector3d c(1.0, -2.0, 1.0);
    Mw.block(k - 1, k - 1, 3, 3) += mix(kTopsideStiffness, kCorrectionSmoothing, topside(S.l.g[k + 1])) * c * c.transpose();
  }
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(4, n);
  C(0, 0) = 1.0;
  C(1, n - 1) = 1.0;
  C.row(2) = point_row(S, S.t_q);
  C.row(3) = arow;
  Eigen::Vector4d r(0.0, 0.0, eta_q - C.row(2).dot(eta), d_area);
  const Eigen::LDLT<Eigen::MatrixXd> M(Mw);
  const Eigen::MatrixXd Y = M.solve(C.transpose());
  const Eigen::Matrix4d Sc = C * Y;
  return Y * Sc.ldlt().solve(r);
}

NurbsCurve assemble(const Section& S, const Eigen::VectorXd& eta) {
  const int n = S.l.n;
  Eigen::MatrixXd P(n, 3);
  for (int k = 0; k < n; ++k) {
    const V2 q = S.f.D + S.f.L * S.l.g[k] * S.f.dir + eta[k] * S.f.nrm;
    P.row(k) << S.s.x, std::clamp(q.x(), 0.0, S.s.y_max), q.y();
  }
  return NurbsCurve(kDegree, S.l.U, P);
}

struct KnobSolve {
  double t = 0, lo_area = 0, hi_area = 0;
  bool met = true;
};

/// The area knob t (knob_at) whose spline holds `target` below T (clamped to [0, knob_end]);
/// area(t) is monotone (falling in the template family, and as the flat narrows; rising too
/// where a given corner lies inside the chord, which has no narrowing stretch).
KnobSolve solve_knob(const Section& S, const Eigen::RowVectorXd& arow, double ac, double target, double hi_shape) {
  auto area = [&](double t) { return arow.dot(sample(S, knob_template(S, t, hi_shape))) + ac; };
  KnobSolve out;
  const double hi = knob_end(S, hi_shape);
  const double area_a = area(0.0), area_b = area(hi);
  out.hi_area = std::max(area_a, area_b), out.lo_area = std::min(area_a, area_b);
  const bool in_range = target >= out.lo_area - kAreaMetTol * S.b * S.d && target <= out.hi_area + kAreaMetTol * S.b * S.d;
  // Near the V the knob follows the asked fullness's excess over 1/2, not over the sampled V's
  // least area: the SAC's excess grows from zero at the waterline's end with zero slope, and the
  // knob with it (it sat on the floor and then left it at once: a convex lobe of 2.04 deg in the
  // container ship's 15 m waterline at x = -1 m). The sampled V may hold less than half the box
  // too (0.491 at the tanker's stern), and the rule is the same. Far above the V the area is the
  // asked one. A given corner has no V (its family may hold a hollow section): no rule there.
  const double box = S.b * S.d, excess = std::max(target - 0.5 * box, 0.0) / box;
  const double surplus = std::isnan(S.s.corner_y) ? out.lo_area - 0.5 * box : 0.0;
  target += surplus * std::exp(-excess / kVeeExcessFade);
  // The least area is approached smoothly (a hard floor would kink the knob along the hull).
  const double soft = kAreaFloorSmoothing * box;
  const double u = (target - out.lo_area) / soft;
  target = out.lo_area + soft * (u > 30.0 ? u : std::log1p(std::exp(u)));
  double a = 0.0, b = hi, fa = area_a - target, fb = area_b - target;
  if (fa * fb >= 0) {  // target outside the range (or at an end): the nearer end
    const bool at_a = std::abs(fa) <= std::abs(fb);
    return out.t = at_a ? 0.0 : hi, out.met = in_range, out;
  }
  out.met = in_range;
  int side = 0;  // Illinois regula falsi
  for (int it = 0; it < kKnobIterations; ++it) {
    const double c = (a * fb - b * fa) / (fb - fa), fc = area(c) - target;
    out.t = c;
    if (std::abs(fc) <= kAreaTol * S.b * S.d || b - a < 1e-15) return out;
    if (fc * fb > 0) {
      b = c, fb = fc;
      if (side == -1) fa *= 0.5;
      side = -1;
    } else {
      a = c, fa = fc;
      if (side == 1) fb *= 0.5;
      side = 1;
    }
  }
  return out;
}

// ---- given shapes (auxiliary sections) -------------------------------------------------

/// Half-breadth where the polyline, from the deck down, first falls below z0 (none if never).
std::optional<double> crossing_y(const Eigen::MatrixXd& P, double z0) {
  for (Eigen::Index i = 0; i + 1 < P.rows(); ++i) {
    const double za = P(i, 1), zb = P(i + 1, 1);
    if (za >= z0 && zb < z0) return P(i, 0) + (za - z0) / (za - zb) * (P(i + 1, 0) - P(i, 0));
  }
  return std::nullopt;
}

/// The given shape's points in this station's frame: its first point onto D, last onto K and,
/// for an immersed station, its crossing of T onto Q; heights stretched linearly between these,
/// half-breadths scaled below T by the waterline's change (its ratio for a shape widest at the
/// waterline) and blended to the deck's ratio above it.
std::vector<V2> map_given(const Section& S, const Eigen::MatrixXd& P) {
  const Eigen::Index m = P.rows();
  const V2 Dg(P(0, 0), P(0, 1));
  const double zk = P(m - 1, 1), T = S.s.draft, tiny = kGivenTiny * S.s.y_max;
  const V2 &D = S.f.D, &K = S.K;
  const double s_deck = Dg.x() > tiny ? D.x() / Dg.x() : 1.0;
  const std::optional<double> yq = S.immersed ? crossing_y(P, T) : std::nullopt;
  std::vector<V2> out(m);
  if (yq && Dg.y() > T && zk < T) {
    // Below T the half-breadths change by the waterline's difference as a share of the shape's
    // widest below T: a shape widest at the waterline scales by the ratio S.b / yq, one far wider
    // below (a bulb's neck under a fine waterline) is not blown up by a millimetre's change of a
    // narrow waterline.
    double widest = *yq;
    for (Eigen::Index i = 0; i < m; ++i)
      if (P(i, 1) < T) widest = std::max(widest, P(i, 0));
    const double s_wl = *yq > tiny ? 1.0 + (S.b - *yq) / widest : s_deck, s_top = Dg.x() > tiny ? s_deck : s_wl;
    for (Eigen::Index i = 0; i < m; ++i) {
      const double z = P(i, 1);
      if (z >= T) {
        const double phi = (z - T) / (Dg.y() - T);
        out[i] = V2(P(i, 0) * (s_wl + phi * (s_top - s_wl)), T + (z - T) * (D.y() - T) / (Dg.y() - T));
      } else {
        out[i] = V2(P(i, 0) * s_wl, K.y() + (z - zk) * (T - K.y()) / (T - zk));
      }
    }
  } else {
    // The deck's difference as a share of the shape's widest: a shape widest at the deck scales
    // by the deck's ratio, a bulb under a stem head (or a web) is not shrunk by the head's few cm.
    double widest = Dg.x();
    for (Eigen::Index i = 0; i < m; ++i) widest = std::max(widest, P(i, 0));
    const double s = widest > tiny ? 1.0 + (D.x() - Dg.x()) / widest : 1.0;
    for (Eigen::Index i = 0; i < m; ++i) out[i] = V2(P(i, 0) * s, K.y() + (P(i, 1) - zk) * (D.y() - K.y()) / (Dg.y() - zk));
  }
  out.front() = D, out.back() = K;
  return out;
}

/// Second differences of n values ((n - 2) by n).
Eigen::MatrixXd second_differences(int n) {
  Eigen::MatrixXd D2 = Eigen::MatrixXd::Zero(n - 2, n);
  for (int k = 0; k + 2 < n; ++k) D2(k, k) = 1.0, D2(k, k + 1) = -2.0, D2(k, k + 2) = 1.0;
  return D2;
}

/// The fit's heights (P's second column) again with the control points whose support lies on
/// the shape's flat of bottom (kGivenFlatTol) held at the keel point's height: A and rhs the
/// fit's normal equations, `t` the points' parameters.
void hold_flat_of_bottom(const Section& S, const std::vector<V2>& pts, const std::vector<double>& t, const Eigen::MatrixXd& A,
                         const Eigen::MatrixX2d& rhs, Eigen::MatrixX2d& P) {
  const int n = S.l.n;
  const double zk = pts.back().y(), tol = kGivenFlatTol * std::max(1.0, std::abs(pts.front().y() - zk));
  std::size_t f = pts.size() - 1;
  while (f > 0 && std::abs(pts[f - 1].y() - zk) <= tol) --f;
  if (!(pts[f].x() > pts.back().x())) return;  // no flat: the keel point alone at its height
  std::vector<char> held(n, 0);
  held[0] = held[n - 1] = 1;
  int any = 0;
  for (int j = 1; j + 1 < n; ++j)
    if (S.l.U[j] >= t[f]) held[j] = 1, P(j, 1) = zk, ++any;
  if (!any) return;
  std::vector<int> free;
  for (int j = 0; j < n; ++j)
    if (!held[j]) free.push_back(j);
  const int m = static_cast<int>(free.size());
  Eigen::MatrixXd Af(m, m);
  Eigen::VectorXd bf(m);
  for (int a = 0; a < m; ++a) {
    bf[a] = rhs(free[a], 1);
    for (int j = 0; j < n; ++j)
      if (held[j]) bf[a] -= A(free[a], j) * P(j, 1);
    for (int c = 0; c < m; ++c) Af(a, c) = A(free[a], free[c]);
  }
  const Eigen::VectorXd z = Af.ldlt().solve(bf);
  for (int a = 0; a < m; ++a) P(free[a], 1) = z[a];
}

/// Control points (n by 2, (y, z)) on the section layout nearest the points: least squares at
/// chord-length parameters weighted by the points' spacing, plus SectionSpec::given_smoothing of bending;
/// the end control points held on the first and last point (D and K), half-breadths clamped to
/// [0, y_max] (a corner's ringing, a few mm, would otherwise leave B/2: the spline stays inside),
/// a flat of bottom held flat (hold_flat_of_bottom).
Eigen::MatrixX2d fit_given(const Section& S, const std::vector<V2>& pts) {
  const int n = S.l.n;
  const std::size_t m = pts.size();
  std::vector<double> arc(m, 0.0);
  for (std::size_t i = 1; i < m; ++i) arc[i] = arc[i - 1] + (pts[i] - pts[i - 1]).norm();
  Eigen::MatrixX2d P = Eigen::MatrixX2d::Zero(n, 2);
  P.row(0) = pts.front().transpose(), P.row(n - 1) = pts.back().transpose();
  if (!(arc.back() > 0) || !(S.f.L > 0)) return P;
  std::vector<double> t(m);  // chord-length parameters (measured shapes may turn back along their chord)
  for (std::size_t i = 0; i < m; ++i) t[i] = arc[i] / arc.back();
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
  Eigen::MatrixX2d rhs = Eigen::MatrixX2d::Zero(n, 2);
  for (std::size_t i = 0; i < m; ++i) {
    const double w = 0.5 * ((i > 0 ? arc[i] - arc[i - 1] : 0.0) + (i + 1 < m ? arc[i + 1] - arc[i] : 0.0)) / arc.back();
    const Eigen::RowVectorXd row = basis_row(S.l.U, kDegree, t[i]);
    A.noalias() += w * row.transpose() * row;
    rhs.noalias() += w * row.transpose() * pts[i].transpose();
  }
  const Eigen::MatrixXd D2 = second_differences(n);
  A.noalias() += S.s.given_smoothing / (n - kDegree) * D2.transpose() * D2;
  const int k = n - 2;  // interior control points; the ends are known
  const Eigen::MatrixX2d b = rhs.middleRows(1, k) - A.block(1, 0, k, 1) * P.row(0) - A.block(1, n - 1, k, 1) * P.row(n - 1);
  P.middleRows(1, k) = A.block(1, 1, k, k).ldlt().solve(b);
  P.col(0) = P.col(0).cwiseMax(0.0).cwiseMin(S.s.y_max);  // the fit's ringing at a corner stays inside B/2
  hold_flat_of_bottom(S, pts, t, A, rhs, P);
  return P;
}

/// The given shape (blended with given_fore) fitted in this station's frame.
Eigen::MatrixX2d given_control_points(const Section& S) {
  Eigen::MatrixX2d P = fit_given(S, map_given(S, S.s.given));
  if (S.s.given_fore.rows() > 0 && S.s.given_mix > 0)
    P = (1.0 - S.s.given_mix) * P + S.s.given_mix * fit_given(S, map_given(S, S.s.given_fore));
  return P;
}

/// Parameter where the spline (control points P) first falls through z = T from the deck down;
/// 1 when it never does.
double waterline_parameter(const Section& S, const Eigen::MatrixX2d& P) {
  const double T = S.s.draft;
  auto z = [&](double t) { return basis_row(S.l.U, kDegree, t).dot(P.col(1)) - T; };
  const int samples = kCrossingSamples * (S.l.n - kDegree);
  double a = 0.0, fa = z(a);
  for (int i = 1; i <= samples; ++i) {
    double b = static_cast<double>(i) / samples, fb = z(b);
    if (fa >= 0 && fb < 0) {
      for (int it = 0; it < 100 && b - a > 1e-15; ++it) {  // bisection: the crossing to round-off
        const double c = 0.5 * (a + b), fc = z(c);
        (fc >= 0 ? a : b) = c;
      }
      return 0.5 * (a + b);
    }
    a = b, fa = fb;
  }
  return 1.0;
}

/// Area below T between the spline and the centre plane (one side) as row . y + 0 for the
/// control half-breadths y, heights held: integral over [t_q, 1] of y(t) (-z'(t)) dt.
Eigen::RowVectorXd given_area_row(const Section& S, const Eigen::MatrixX2d& P, double t_q) {
  const auto& gr = detail::gauss_rule(kAreaGauss);
  Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(S.l.n);
  std::vector<double> br{t_q};
  for (Eigen::Index i = kDegree + 1; i < S.l.U.size() - kDegree - 1; ++i)
    if (S.l.U[i] > br.back()) br.push_back(S.l.U[i]);
  if (br.back() < 1.0) br.push_back(1.0);
  for (std::size_t k = 0; k + 1 < br.size(); ++k) {
    const double h = 0.5 * (br[k + 1] - br[k]), mid = 0.5 * (br[k + 1] + br[k]);
    for (std::size_t q = 0; q < gr.x.size(); ++q) {
      const double t = mid + h * gr.x[q];
      const double dz = basis_row(S.l.U, kDegree, t, 1).dot(P.col(1));
      row.noalias() -= gr.w[q] * h * dz * basis_row(S.l.U, kDegree, t);
    }
  }
  return row;
}

/// Half-breadth shifts of the control points, least in size and bend (the topside's a tilt, as
/// in correction()), with the ends held, that put the spline through Q (unless Q lies on the
/// bound B/2) and to `target` (NaN: area free), each condition asked with the immersion weight w;
/// control points below `hold_below` (m) or before `held_above` (index) are held. A control point within
/// kGivenBoundBand of y_max of the bound 0 or y_max is less mobile (its shift costs more, its
/// mobility falling linearly to kGivenMobility on the bound): a flat side at B/2 stays there.
Eigen::VectorXd given_shifts(const Section& S, const Eigen::MatrixX2d& P, double t_q, double target, double hold_below,
                             int held_above = 0) {
  const int n = S.l.n;
  const Eigen::RowVectorXd arow = given_area_row(S, P, t_q), qrow = point_row(S, t_q);
  const bool area = !std::isnan(target);
  Eigen::MatrixXd Mw = Eigen::MatrixXd::Zero(n, n);
  for (int k = 0; k < n; ++k) {
    const double room = std::min(P(k, 0), S.s.y_max - P(k, 0)) / (kGivenBoundBand * S.s.y_max);
    const double mobility = std::clamp(room, kGivenMobility, 1.0);
    Mw(k, k) = 1.0 / (mobility * mobility);
  }
  const Eigen::MatrixXd D2 = second_differences(n);
  for (int k = 0; k + 2 < n; ++k) {
    const bool topside = S.l.g[k + 2] <= t_q;
    Mw += (topside ? kTopsideStiffness : kGivenShiftSmoothing) * D2.row(k).transpose() * D2.row(k);
  }
  const Eigen::LDLT<Eigen::MatrixXd> M(Mw);
  // A waterline point on the bound B/2 is met by the mapped shape itself (to its fit): asked
  // exactly, the spline would need four control points on B/2, a flat stretch below Q.
  const bool through_q = S.b < (1 - kGivenBoundBand) * S.s.y_max;
  std::vector<std::pair<int, double>> held{{0, 0.0}, {n - 1, 0.0}};  // (control point, its shift)
  for (int k = 1; k + 1 < n; ++k)
    if (P(k, 1) < hold_below || k < held_above) held.emplace_back(k, 0.0);  // a skeg keeps its thickness
  Eigen::VectorXd delta;
  for (int pass = 0; pass < n; ++pass) {  // an active set: shifts past a bound are held on it
    const int h = static_cast<int>(held.size());
    const int rows = h + (through_q ? 1 : 0) + (area ? 1 : 0);
    Eigen::MatrixXd C = Eigen::MatrixXd::Zero(rows, n);
    Eigen::VectorXd r = Eigen::VectorXd::Zero(rows);
    for (int i = 0; i < h; ++i) C(i, held[i].first) = 1.0, r[i] = held[i].second;
    if (through_q) C.row(h) = qrow, r[h] = S.w * (S.b - qrow.dot(P.col(0)));
    if (area) C.row(rows - 1) = arow, r[rows - 1] = S.w * (target - arow.dot(P.col(0)));
    const Eigen::MatrixXd Y = M.solve(C.transpose());
    delta = Y * (C * Y).ldlt().solve(r);
    bool inside = true;
    for (int k = 1; k + 1 < n; ++k) {
      const double y = P(k, 0) + delta[k];
      if (y < -kGivenBoundTol * S.s.y_max || y > (1 + kGivenBoundTol) * S.s.y_max) {
        held.emplace_back(k, std::clamp(y, 0.0, S.s.y_max) - P(k, 0));
        inside = false;
      }
    }
    if (inside || rows + 1 >= n) break;
  }
  return delta;
}

/// The section of control points P (y, z) shifted through Q and to the asked area (control
/// points below `hold_below`, a skeg's, held).
SectionDesign finish_given(const Section& S, Eigen::MatrixX2d P, double hold_below, int held_above = 0) {
  SectionDesign out{NurbsCurve(kDegree, S.l.U, Eigen::MatrixXd::Zero(S.l.n, 3))};
  out.immersion = S.w;
  if (S.immersed) {
    const double t_q = waterline_parameter(S, P);
    P.col(0) += given_shifts(S, P, t_q, S.s.half_area, hold_below, held_above);
    out.fullness = given_area_row(S, P, t_q).dot(P.col(0)) / (S.b * S.d);
  }
  Eigen::MatrixXd Q3(S.l.n, 3);
  for (int k = 0; k < S.l.n; ++k) Q3.row(k) << S.s.x, std::clamp(P(k, 0), 0.0, S.s.y_max), P(k, 1);
  out.curve = NurbsCurve(kDegree, S.l.U, Q3);
  return out;
}

SectionDesign design_given(const Section& S) {
  return finish_given(S, given_control_points(S), -std::numeric_limits<double>::infinity());
}

// ---- skegs --------------------------------------------------------------------------------

/// Where the descending curve (samples deck -> keel) last comes in to half-breadth y0 from
/// outside: the index of the sample at or before it (or -1 when the curve never is that wide).
int last_wider(const Eigen::MatrixXd& yz, double y0) {
  for (Eigen::Index i = yz.rows() - 1; i > 0; --i)
    if (yz(i - 1, 0) >= y0 && yz(i, 0) < y0) return static_cast<int>(i - 1);
  return -1;
}

/// The given shape of a section with a skeg (see SectionSpec::skeg_bottom): the body's section
/// (samples, deck to keel) down to where it comes in to y = t + f, a hollow quadratic fillet
/// from there (along the body's tangent) to the skeg side (heading straight down), the side to
/// the bottom, the bottom to the centre plane; with the height of the side's top (below it the
/// shape is the skeg's, held when the section is shifted to its area). Empty when the body is
/// never that wide.
/// What replaces the tail of a body's section below J (a skeg, a dome).
struct AppendageTail {
  std::vector<V2> pts;     ///< J first, the keel point last
  double t_J = 1.0;        ///< the body's parameter at J
  double side_top = 0.0;   ///< control points below this height are held when Q is met
};

/// J, where the body's section `body` (samples yz at parameters ts) last comes in to y = y0,
/// with its parameter and the body's unit tangent there (heading in); false when it never is
/// that wide. The samples bracket J; J and its tangent are then found on the curve itself, so
/// they move smoothly along the hull: read off the samples' chords they stepped as J crossed
/// from one chord to the next, and the fillet's corner, on the tangent, jumped by centimetres.
bool neck_point(const NurbsCurve& body, const Eigen::VectorXd& ts, const Eigen::MatrixXd& yz, double y0, V2& J,
                double& t_J, V2& tan) {
  const int j = last_wider(yz, y0);
  if (j < 0) return false;
  double lo = ts[j], hi = ts[j + 1];  // y(lo) >= y0 > y(hi)
  double t = lo + (yz(j, 0) - y0) / (yz(j, 0) - yz(j + 1, 0)) * (hi - lo);
  Eigen::MatrixXd d = body.derivatives(t, 1);
  for (int it = 0; it < kNeckIterations; ++it) {  // Newton kept inside a shrinking bracket
    const double r = d(0, 1) - y0;
    if (std::abs(r) <= kNeckTol * std::max(1.0, std::abs(y0))) break;
    (r > 0 ? lo : hi) = t;
    double next = d(1, 1) < 0 ? t - r / d(1, 1) : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    t = next;
    d = body.derivatives(t, 1);
  }
  J = V2(d(0, 1), d(0, 2));
  t_J = t;
  const V2 dj(d(1, 1), d(1, 2));
  tan = dj.norm() > 0 ? V2(dj.normalized()) : V2((yz.row(j + 1) - yz.row(j)).transpose().normalized());
  return true;
}

/// The skeg's tail of a section with a skeg (see SectionSpec::skeg_bottom), from the body's
/// section sampled at parameters ts (yz, deck to keel): from J, where the body last comes in to
/// y = t + f, a hollow quadratic fillet along the body's tangent to the skeg side (heading
/// straight down), the side to the bottom, the bottom to the centre plane.

AppendageTail skeg_tail(const SectionSpec& s, const NurbsCurve& body, const Eigen::VectorXd& ts,
                        const Eigen::MatrixXd& yz) {
  // where it ends the skeg thins and its fillet shrinks (and the fillet is at most
  // kSkegFilletDepth of its depth): the section tends to the body's
  const double share = std::clamp(s.skeg_share, 0.0, 1.0), zb = s.skeg_bottom;
  const double t = std::max(share * s.skeg_half_thickness, kSkegThinnest * s.skeg_half_thickness);
  const double f = std::min(share * s.skeg_fillet, kSkegFilletDepth * (s.z_keel - zb));
  AppendageTail out;
  V2 J, tan;
  if (!neck_point(body, ts, yz, t + f, J, out.t_J, tan)) return out;
  // The fillet's corner C: where the body's tangent at J meets the skeg side y = t, kept no
  // higher than J and leaving the side kSkegBottomRoom of the depth; E: f further down the side.
  const double floor_z = zb + kSkegBottomRoom * (J.y() - zb);
  const double zc = tan.x() < -kGivenTiny ? J.y() + (t - J.x()) / tan.x() * tan.y() : J.y();
  const V2 C(t, std::clamp(zc, floor_z, J.y()));
  const V2 E(t, std::max(C.y() - f, floor_z));
  out.pts.push_back(J);
  for (int k = 1; k <= kSkegFilletPoints; ++k) {  // quadratic Bezier J -> C -> E
    const double u = static_cast<double>(k) / kSkegFilletPoints;
    out.pts.push_back((1 - u) * (1 - u) * J + 2 * u * (1 - u) * C + u * u * E);
  }
  for (int k = 1; k <= kSkegSidePoints; ++k) out.pts.emplace_back(t, E.y() + (zb - E.y()) * k / kSkegSidePoints);
  for (int k = 1; k <= kSkegSidePoints; ++k) out.pts.emplace_back(t * (1.0 - static_cast<double>(k) / kSkegSidePoints), zb);
  out.side_top = E.y();
  return out;
}

/// Control points (y, z) of a section with an appendage: the body's own control points where
/// their support ends above t_s, kAppendageSpans knot spans above J, so its rows run on from the
/// neighbouring sections without one; the rest fitted (least squares, bending weighing
/// `bending`, the keel point held) to the body's curve from the first free span down
/// to J and to the appendage's tail, the body below t_s and the tail sharing [t_s, 1] by arc
/// length. As the appendage vanishes (J -> the keel) the section tends to the body's.
Eigen::MatrixX2d appendage_control_points(const Layout& l, const Eigen::MatrixX2d& body, const NurbsCurve& curve,
                                          const AppendageTail& tail, double bending, int& first_free) {
  const int n = l.n;
  // The last kAppendageSpans spans above J and the tail share [t_s, 1] by arc length: the tail
  // gets room from the body's lowest part, the body above t_s keeps its parameters. The body is
  // sampled afresh between the ends of both stretches (a fixed count each), so the data move
  // smoothly along the hull with J (a fixed sampling let samples hop in and out).
  const double t_s = std::max(0.0, tail.t_J - static_cast<double>(kAppendageSpans) / (n - kDegree));
  int i0 = 1;
  while (i0 < n - 1 && l.U[i0 + kDegree + 1] <= t_s) ++i0;
  std::vector<std::pair<double, V2>> data;  // (parameter, point), weighted by arc spacing
  const Eigen::VectorXd tu = Eigen::VectorXd::LinSpaced(kAppendageUpperSamples + 1, l.U[i0], t_s).head(kAppendageUpperSamples);
  const Eigen::MatrixXd upper = curve.evaluate(tu);
  for (int k = 0; k < kAppendageUpperSamples; ++k)
    if (tu[k] < t_s) data.emplace_back(tu[k], V2(upper(k, 1), upper(k, 2)));
  const Eigen::MatrixXd lower = curve.evaluate(Eigen::VectorXd::LinSpaced(kAppendageLowerSamples + 1, t_s, tail.t_J));
  std::vector<V2> low(kAppendageLowerSamples + 1);  // the body from t_s to J, J last
  std::vector<double> low_run(low.size(), 0.0);
  for (int k = 0; k <= kAppendageLowerSamples; ++k) {
    low[k] = V2(lower(k, 1), lower(k, 2));
    if (k > 0) low_run[k] = low_run[k - 1] + (low[k] - low[k - 1]).norm();
  }
  const double low_arc = low_run.back();
  std::vector<double> arc(tail.pts.size(), 0.0);
  for (std::size_t i = 1; i < tail.pts.size(); ++i) arc[i] = arc[i - 1] + (tail.pts[i] - tail.pts[i - 1]).norm();
  const double t_J = t_s + (1.0 - t_s) * low_arc / std::max(low_arc + arc.back(), 1e-300);
  for (int k = 0; k < kAppendageLowerSamples; ++k)
    data.emplace_back(t_s + (t_J - t_s) * (low_arc > 0 ? low_run[k] / low_arc : 0.0), low[k]);
  for (std::size_t i = 0; i < tail.pts.size(); ++i)
    data.emplace_back(t_J + (1.0 - t_J) * (arc.back() > 0 ? arc[i] / arc.back() : 1.0), tail.pts[i]);
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
  Eigen::MatrixX2d rhs = Eigen::MatrixX2d::Zero(n, 2);
  double total = 0.0;
  for (std::size_t i = 0; i < data.size(); ++i) {
    const double w = 0.5 * ((i > 0 ? (data[i].second - data[i - 1].second).norm() : 0.0) +
                            (i + 1 < data.size() ? (data[i + 1].second - data[i].second).norm() : 0.0));
    const Eigen::RowVectorXd row = basis_row(l.U, kDegree, std::clamp(data[i].first, 0.0, 1.0));
    A.noalias() += w * row.transpose() * row;
    rhs.noalias() += w * row.transpose() * data[i].second.transpose();
    total += w;
  }
  const Eigen::MatrixXd D2 = second_differences(n);
  A.noalias() += bending * total / (n - kDegree) * D2.transpose() * D2;
  Eigen::MatrixX2d P = body;
  P.row(n - 1) = tail.pts.back().transpose();
  const int k = n - 1 - i0;  // free: i0 .. n - 2
  Eigen::MatrixX2d b = rhs.middleRows(i0, k);
  for (int c = 0; c < n; ++c)
    if (c < i0 || c == n - 1) b.noalias() -= A.block(i0, c, k, 1) * P.row(c);
  P.middleRows(i0, k) = A.block(i0, i0, k, k).ldlt().solve(b);
  first_free = i0;
  P.col(0) = P.col(0).cwiseMax(0.0);
  P.col(1) = P.col(1).cwiseMax(tail.pts.back().y());
  return P;
}

/// The dome's tail of a section with a sonar dome (see SectionSpec::dome_bottom): from J, where
/// the body last comes in to the neck's half-width, a hollow quadratic fillet to the point P of
/// the dome's half ellipse (from the body's keel point down to the dome's bottom) at the neck's
/// half-width, then the ellipse down to its bottom on the centre plane.
AppendageTail dome_tail(const SectionSpec& s, const NurbsCurve& body, const Eigen::VectorXd& ts,
                        const Eigen::MatrixXd& yz) {
  AppendageTail out;
  V2 J, tan;
  if (!neck_point(body, ts, yz, s.dome_neck, J, out.t_J, tan)) return out;
  const double b = s.dome_half_breadth, h = 0.5 * (s.z_keel - s.dome_bottom), zc = s.dome_bottom + h;
  auto at = [&](double phi) { return V2(b * std::sin(phi), zc + h * std::cos(phi)); };
  const double phi1 = std::asin(std::clamp(s.dome_neck / b, 0.0, 1.0));
  const V2 P = at(phi1), dir(b * std::cos(phi1), -h * std::sin(phi1));  // the ellipse, heading down and out
  // The fillet's corner: where the body's tangent at J meets the ellipse's at P (their middle
  // when the two lines do not meet ahead of both points).
  const double den = tan.x() * dir.y() - tan.y() * dir.x();
  const V2 d = P - J;
  const double a = std::abs(den) > kGivenTiny ? (d.x() * dir.y() - d.y() * dir.x()) / den : -1.0;
  const double c = std::abs(den) > kGivenTiny ? (d.x() * tan.y() - d.y() * tan.x()) / den : -1.0;
  const V2 C = a > 0 && c > 0 ? V2(J + a * tan) : V2(0.5 * (J + P));
  out.pts.push_back(J);
  for (int k = 1; k <= kSkegFilletPoints; ++k) {
    const double u = static_cast<double>(k) / kSkegFilletPoints;
    out.pts.push_back((1 - u) * (1 - u) * J + 2 * u * (1 - u) * C + u * u * P);
  }
  for (int k = 1; k <= kDomePoints; ++k) out.pts.push_back(at(phi1 + (std::numbers::pi - phi1) * k / kDomePoints));
  out.pts.back().x() = 0.0;
  out.side_top = P.y();
  return out;
}

/// A section with an appendage under its body (a skeg, a dome): the body's section (holding the
/// asked area), its tail below J replaced by the appendage's, which adds its own area (the
/// hull's volume is matched on the surface).
SectionDesign design_with_appendage(const SectionSpec& spec) {
  SectionSpec body = spec;
  body.skeg_bottom = body.dome_bottom = kNaN;
  const SectionDesign b = design_section(body);
  const Eigen::VectorXd ts = Eigen::VectorXd::LinSpaced(kSkegBodySamples, 0.0, 1.0);
  const Eigen::MatrixXd yz = b.curve.evaluate(ts).rightCols(2);
  const bool skeg = !std::isnan(spec.skeg_bottom);
  const AppendageTail tail = skeg ? skeg_tail(spec, b.curve, ts, yz) : dome_tail(spec, b.curve, ts, yz);
  if (tail.pts.empty()) return b;
  SectionSpec with = body;
  with.z_keel = skeg ? spec.skeg_bottom : spec.dome_bottom;
  with.half_area = kNaN;
  const Section S = setup(with);
  int first_free = 0;
  const Eigen::MatrixX2d P = appendage_control_points(S.l, b.curve.control_points().rightCols(2), b.curve, tail,
                                                      skeg ? kSkegSmoothing : kDomeSmoothing, first_free);
  // The body's own control points stay as they are when the section is put through Q (shifted
  // with the rest, the topside tilted by the fit's miss at Q): a skeg's topside is the body's,
  // which a dry transom's run fairs like any other (hull.Hull._section_curves).
  SectionDesign out = finish_given(S, P, tail.side_top, first_free);
  out.shape = b.shape, out.flat_kept = b.flat_kept;  // the body's: the designer reads whether its flat narrowed
  return out;
}

}  // namespace

Eigen::VectorXd section_knot_vector(int n_control) { return layout(n_control).U; }

FullnessBounds section_fullness_bounds(const SectionSpec& spec) {
  const Section S = setup(spec);
  if (!S.immersed || S.f.L <= kPointSection * spec.y_max || spec.given.rows() > 0) return {};
  const auto [arow, ac] = area_row(S);
  const double hi = knob_limit(S);
  auto fullness = [&](double t) { return (arow.dot(sample(S, knob_template(S, t, hi))) + ac) / (S.b * S.d); };
  const double f_0 = fullness(0.0), f_hi = fullness(hi), t_end = knob_end(S, hi);
  const double f_end = t_end > hi ? fullness(t_end) : f_hi;
  return {std::min(f_0, f_hi), std::min({f_0, f_hi, f_end}), std::max({f_0, f_hi, f_end})};
}

std::pair<double, double> section_fullness_range(const SectionSpec& spec) {
  const FullnessBounds f = section_fullness_bounds(spec);
  return {f.least, f.largest};
}

SectionDesign design_section(const SectionSpec& spec) {
  if ((!std::isnan(spec.skeg_bottom) && spec.skeg_bottom < spec.z_keel) ||
      (!std::isnan(spec.dome_bottom) && spec.dome_bottom < spec.z_keel))
    return design_with_appendage(spec);
  const Section S = setup(spec);
  const int n = S.l.n;
  SectionDesign out{NurbsCurve(kDegree, S.l.U, Eigen::MatrixXd::Zero(n, 3))};
  if (S.f.L <= kPointSection * spec.y_max) {  // the stem head: every control point on the deck point
    Eigen::VectorXd eta = Eigen::VectorXd::Zero(n);
    out.curve = assemble(S, eta);
    return out;
  }
  if (spec.given.rows() > 0) return design_given(S);
  if (!S.immersed) {
    out.curve = assemble(S, sample(S, above_template(S)));
    return out;
  }
  const auto [arow, ac] = area_row(S);
  const double box = S.b * S.d;
  const double hi = knob_limit(S);
  Knob knob{std::min(spec.shape, hi), 1.0};
  if (!std::isnan(spec.half_area)) {
    const KnobSolve k = solve_knob(S, arow, ac, spec.half_area, hi);
    out.fullness_min = k.lo_area / box, out.fullness_max = k.hi_area / box;
    knob = knob_at(k.t, hi);
    out.area_met = k.met || S.w < 1.0;
  }
  out.immersion = S.w;
  out.shape = S.w * knob.lambda + (1.0 - S.w) * kMaxShapeKnob;
  out.flat_kept = knob.flat_kept;
  bool shortened = false;
  Eigen::VectorXd eta = sample(S, immersed_template(S, out.shape, knob.flat_kept, false, &shortened));
  // The spline is put through Q in the share w^kThroughQPower (see the constant: with w itself the
  // correction, ill-conditioned as Q nears K, outgrew the fading waterline point).
  const double through_q = std::pow(S.w, kThroughQPower);
  // The area the knob met on its template (knob_template) differs from the drawn one's where the
  // top corner is drawn inside the deck edge: the correction puts it back near Q, in the same
  // share (near the waterline's end Q nears K and the area fades out with the waterline point).
  // A section of given shape (no area asked) is drawn as it is; with the natural leg the two agree.
  const double d_area = std::isnan(spec.half_area) || !shortened
                            ? 0.0
                            : through_q * arow.dot(sample(S, immersed_template(S, out.shape, knob.flat_kept, true)) - eta);
  const double eta_q = through_q * S.f.eta(S.Q) + (1.0 - through_q) * point_row(S, S.t_q).dot(eta);
  eta += correction(S, eta, eta_q, arow, d_area);
  out.fullness = (arow.dot(eta) + ac) / box;
  out.curve = assemble(S, eta);
  return out;
}

std::vector<SectionDesign> design_sections(const std::vector<SectionSpec>& specs) {
  // Sections are independent: contiguous chunks on up to kSectionThreads threads. The first
  // failing section in station order is the one reported (its chunk is the earliest to fail).
  const std::size_t n = specs.size();
  const std::size_t threads = std::min<std::size_t>(
      {kSectionThreads, std::max(1u, std::thread::hardware_concurrency()), std::max<std::size_t>(1, n / kSectionsPerThread)});
  std::vector<std::optional<SectionDesign>> out(n);
  std::vector<std::exception_ptr> failed(threads);
  auto work = [&](std::size_t t) {
    try {
      for (std::size_t i = t * n / threads; i < (t + 1) * n / threads; ++i) out[i] = design_section(specs[i]);
    } catch (...) {
      failed[t] = std::current_exception();
    }
  };
  std::vector<std::thread> pool;
  for (std::size_t t = 1; t < threads; ++t) pool.emplace_back(work, t);
  work(0);
  for (auto& th : pool) th.join();
  for (const auto& e : failed)
    if (e) std::rethrow_exception(e);
  std::vector<SectionDesign> result;
  result.reserve(n);
  for (auto& d : out) result.push_back(std::move(*d));
  return result;
}

}  // namespace fairlines
