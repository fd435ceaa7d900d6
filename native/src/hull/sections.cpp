// Hull sections as fairest graphs over one frame: see fairlines/sections.hpp.
//
// Notation (section plane x = const, coordinates (y, z), metres):
//   P_D, Q, K     deck, DWL and keel points; d, n the frame's direction and outward normal
//   xi, eta       coordinates along d and n from P_D; a control point is P_D + xi_k d + eta_k n
//   t             curve parameter in [0, 1]; t_j the joint (a triple knot): the top piece runs
//                 over [0, t_j], the bottom piece over [t_j, 1]
//   x(t)          abscissa along d, linear on each piece with slope a_top / a_bot (x' below)
//   S             the split: where a flared top turns into the convex bottom (the DWL, or
//                 higher on a counter); the joint sits at it, so the sign pattern of the
//                 curvature never slides across the knots as the sections change along a hull
// A graph's curvature has the sign of eta_xixi = eta_tt / x'^2, so sign conditions on the
// knot values of eta_tt are exact; every condition is linear in eta.
#include "fairlines/sections.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>

#include "fairlines/basis.hpp"
#include "fairlines/errors.hpp"
#include "fairlines/knots.hpp"
#include "fairlines/qp.hpp"
#include "nurbs/checks.hpp"
#include "nurbs/gauss.hpp"

namespace fairlines {

namespace {

using detail::fail;
using V2 = Eigen::Vector2d;

constexpr int kDegree = 3;
/// A tangent must make an angle below acos(kMinTangentChordCos) (87 deg) with the frame's
/// direction; one pointing across or away from it cannot carry a graph.
constexpr double kMinTangentChordCos = 0.05;
/// Share of the knot spans given to the top piece (deck to split).
constexpr double kTopShare = 0.25;
/// The joint keeps at least this fraction of the chord from either end (a piece never vanishes).
constexpr double kMinPiece = 0.06;
/// Weight of the fairness term when the area range is sought (a near-LP).
constexpr double kRangeFairness = 1e-7;
/// An immersed part shorter than this many knot spans (a sliver next to the stem, or where a
/// counter leaves the water) cannot be shaped at will: its DWL point and area blend in from what
/// the section without them has, by a smooth step over these spans, so nothing jumps there.
constexpr double kBlendSpans = 3.0;
/// Weight of the DWL-angle penalty at alpha_dwl_weight 1, per unit squared slope and relative to
/// the bending energy: 1e3 holds the angle to about half a degree against the other conditions.
constexpr double kDwlAngleWeight = 1e3;
/// Curvature (1/m) of the wrong sign a section may have before its shape condition binds: far
/// below what a lines plan shows, it spares conditions where the fairest section is straight.
constexpr double kShapeTolerance = 2e-3;
/// Curvature (1/m) no section has: a sign condition with this much room is in effect free.
constexpr double kFreeCurvature = 10.0;
/// Height (fraction of the section's) over which the bottom's convexity fades in as the split
/// rises off the keel.
constexpr double kSplitFade = 0.1;
/// Reweighted solves toward the least bending energy.
constexpr int kBendingIterations = 2;
/// How far (fraction of the chord) the central point may pass a bound: room for bounds the
/// equalities pin (a wall between two points on B/2).
constexpr double kBoundRelax = 1e-6;
/// Length (fraction of the chord) over which the central point rounds a bound off.
constexpr double kBarrierLength = 5e-3;
/// Points per knot span at which the section is kept inside its bounds and going down.
constexpr int kBoundSamples = 2;
/// Gauss points per knot span of the bending energy (its weight is not a polynomial).
constexpr int kGaussBending = 6;
/// Weight of the deck-keel chord in the frame's direction (see chord_frame).
constexpr double kFrameBlend = 0.1;
/// Degrees a keel angle may lie below -90 (round-off of an angle curve) and still count as -90.
constexpr double kAngleSlack = 1e-6;

double cross(const V2& a, const V2& b) { return a.x() * b.y() - a.y() * b.x(); }

std::string fmt(double v) {
  std::ostringstream os;
  os.precision(6);
  os << v;
  return os.str();
}

/// Unit tangent going down the section for an angle in degrees from the downward vertical
/// toward +y; exactly vertical / horizontal at 0 and -90 so flats are exact.
V2 tangent(double alpha_deg) {
  if (alpha_deg == 0.0) return V2(0.0, -1.0);
  if (alpha_deg == -90.0) return V2(-1.0, 0.0);
  const double a = alpha_deg * std::numbers::pi / 180.0;
  return V2(std::sin(a), -std::cos(a));
}

/// Angle of a downward direction in degrees from the downward vertical toward +y.
double alpha_of(const V2& t) { return std::atan2(t.x(), -t.y()) * 180.0 / std::numbers::pi; }

/// C2 step from 0 (r <= 0) to 1 (r >= 1).
double smoothstep(double r) {
  r = std::clamp(r, 0.0, 1.0);
  return r * r * r * (10.0 - 15.0 * r + 6.0 * r * r);
}

/// The knot vector shared by every section with n control points: a top piece of s_top spans
/// on [0, t_j], a triple knot at t_j, a bottom piece of s_bot spans on [t_j, 1].
/// The nonzero basis functions (and first two derivatives) at one parameter: columns first ..
/// first + 3.
struct BasisAt {
  double t = 0, w = 0;  // parameter, quadrature weight (0 for samples)
  int first = 0;
  Eigen::Matrix<double, 3, 4> d;  // row r: r-th derivatives
};

struct Layout {
  int n = 0, s_top = 0, s_bot = 0, j = 0;  // j: index of the control point at the joint
  double tj = 0;
  Eigen::VectorXd U, g;                    // knots, Greville abscissae
  std::vector<BasisAt> gauss;              // kGaussBending points per span (bending energy)
  std::vector<BasisAt> samples;            // kBoundSamples points per span (bounds)
};

BasisAt basis_at(const Eigen::VectorXd& U, double t, double w) {
  BasisAt b;
  b.t = t, b.w = w;
  const int span = find_span(kDegree, U, t);
  Eigen::MatrixXd ders(3, kDegree + 1);
  basis_derivatives(span, t, kDegree, 2, U, ders);
  b.first = span - kDegree;
  b.d = ders;
  return b;
}

Layout layout(int n) {
  if (n < kMinSectionControls || n > kMaxSectionControls)
    fail("sections.n_control is ", n, "; expected ", kMinSectionControls, " to ", kMaxSectionControls);
  Layout l;
  l.n = n;
  const int spans = n - 5;
  l.s_top = std::max(1, static_cast<int>(std::lround(kTopShare * spans)));
  l.s_bot = spans - l.s_top;
  l.j = l.s_top + 2;
  l.tj = static_cast<double>(l.s_top) / spans;
  std::vector<double> u(4, 0.0);
  for (int k = 1; k < l.s_top; ++k) u.push_back(l.tj * k / l.s_top);
  for (int k = 0; k < 3; ++k) u.push_back(l.tj);
  for (int k = 1; k < l.s_bot; ++k) u.push_back(l.tj + (1.0 - l.tj) * k / l.s_bot);
  for (int k = 0; k < 4; ++k) u.push_back(1.0);
  l.U = Eigen::Map<Eigen::VectorXd>(u.data(), static_cast<Eigen::Index>(u.size()));
  l.g = greville_abscissae(l.U, kDegree);
  const auto& gr = detail::gauss_rule(kGaussBending);
  for (int sp = kDegree; sp < static_cast<int>(l.U.size()) - kDegree - 1; ++sp) {
    const double a = l.U[sp], b = l.U[sp + 1];
    if (!(b > a)) continue;
    for (std::size_t q = 0; q < gr.x.size(); ++q)
      l.gauss.push_back(basis_at(l.U, 0.5 * (a + b) + 0.5 * (b - a) * gr.x[q], 0.5 * (b - a) * gr.w[q]));
    for (int q = 0; q < kBoundSamples; ++q) l.samples.push_back(basis_at(l.U, a + (b - a) * (q + 0.5) / kBoundSamples, 0.0));
  }
  return l;
}

/// Layouts are the same for every section of a hull: built once per count (per thread).
const Layout& cached_layout(int n) {
  thread_local std::vector<std::pair<int, Layout>> cache;
  for (const auto& [k, l] : cache)
    if (k == n) return l;
  cache.emplace_back(n, layout(n));
  return cache.back().second;
}

/// Row vector (n) of a BasisAt's r-th derivatives.
Eigen::RowVectorXd row_of(const BasisAt& b, int r, int n) {
  Eigen::RowVectorXd e = Eigen::RowVectorXd::Zero(n);
  e.segment(b.first, kDegree + 1) = b.d.row(r);
  return e;
}

struct Frame {
  V2 P, K, d, n;
  double L = 0;      // xi of the keel point
  double eta_k = 0;  // eta of the keel point
  V2 at(double xi, double eta) const { return P + xi * d + eta * n; }
  double xi(const V2& q) const { return (q - P).dot(d); }
  double eta(const V2& q) const { return (q - P).dot(n); }
};

/// Rows of the QP with the name of the condition each encodes.
struct Rows {
  std::vector<Eigen::RowVectorXd> rows;
  std::vector<double> rhs;
  std::vector<std::string> names;
  void add(const Eigen::RowVectorXd& r, double b, const std::string& name) {
    rows.push_back(r);
    rhs.push_back(b);
    names.push_back(name);
  }
  void fill(Eigen::MatrixXd& M, Eigen::VectorXd& v, int n) const {
    M.resize(static_cast<Eigen::Index>(rows.size()), n);
    v.resize(static_cast<Eigen::Index>(rows.size()));
    for (std::size_t i = 0; i < rows.size(); ++i) M.row(static_cast<Eigen::Index>(i)) = rows[i], v[static_cast<Eigen::Index>(i)] = rhs[i];
  }
};

struct Section {
  const SectionSpec& s;
  std::string at;
  const Layout& l;
  Frame f;
  double xj = 0;              // abscissa of the joint
  Eigen::VectorXd xi;         // abscissae of the control points
  bool has_dwl = false, wants_area = false;
  double alpha_deck = kNaN;   // deck tangent in use (given, or from the flare)
  int above = 0;              // sign of the top's curvature: -1 convex, +1 flare, 0 free
  double t_q = 0, eta_q = 0;
  V2 Q;
  Rows eq, in;
  Eigen::RowVectorXd area_row;
  double area_rhs = 0;
  int area_eq = -1, dwl_eq = -1;  // indices of the area and DWL-point rows in eq
  int n() const { return l.n; }
  double slope_x(double t) const { return t < l.tj ? xj / l.tj : (f.L - xj) / (1.0 - l.tj); }  // x'(t)
  double x_of(double t) const { return t < l.tj ? xj * t / l.tj : xj + (f.L - xj) * (t - l.tj) / (1.0 - l.tj); }
  double t_of(double x) const { return x < xj ? l.tj * x / xj : l.tj + (1.0 - l.tj) * (x - xj) / (f.L - xj); }
};

Eigen::RowVectorXd unit(int n, int k) {
  Eigen::RowVectorXd e = Eigen::RowVectorXd::Zero(n);
  e[k] = 1.0;
  return e;
}

/// Basis row of the order-th derivative at t, taken inside the piece `side` (-1 top, +1
/// bottom) when t is the joint (where the derivatives jump between the pieces).
Eigen::RowVectorXd row_at(const Layout& l, double t, int order, int side = 0) {
  constexpr double kInside = 1e-12;
  if (side < 0 && t >= l.tj) t = l.tj * (1.0 - kInside);
  if (side > 0 && t <= l.tj) t = l.tj + (1.0 - l.tj) * kInside;
  return basis_row(l.U, kDegree, std::clamp(t, 0.0, 1.0), order);
}

void validate(const SectionSpec& s, const std::string& at) {
  auto finite = [&](double v, const char* field) {
    if (!std::isfinite(v)) fail(at, ": ", field, " is ", v, "; expected a finite number");
  };
  finite(s.x, "x"), finite(s.y_deck, "y_deck"), finite(s.z_deck, "z_deck"), finite(s.z_keel, "z_keel"), finite(s.y_max, "y_max");
  for (auto [v, field] : {std::pair{s.alpha_deck, "alpha_deck"}, {s.alpha_keel, "alpha_keel"}, {s.flare, "flare"}, {s.draft, "draft"},
                          {s.y_dwl, "y_dwl"}, {s.half_area, "half_area"}, {s.alpha_dwl, "alpha_dwl"}, {s.z_fos, "z_fos"},
                          {s.y_fob, "y_fob"}, {s.skeg_half_thickness, "skeg_half_thickness"}, {s.skeg_bottom, "skeg_bottom"},
                          {s.skeg_top, "skeg_top"}, {s.points_weight, "points_weight"}, {s.z_inflection, "z_inflection"}})
    if (std::isinf(v)) fail(at, ": ", field, " is ", v, "; expected a number or NaN (not given)");
  if (!(s.y_max > 0)) fail(at, ": y_max is ", s.y_max, "; expected a half-breadth bound B/2 > 0 (m)");
  const double tol = kSectionTol * (s.y_max + std::abs(s.z_deck));
  if (s.y_deck < -tol || s.y_deck > s.y_max + tol) fail(at, ": y_deck (deck line) is ", s.y_deck, " m; expected 0 <= y <= B/2 = ", s.y_max, " m");
  if (!(s.z_keel < s.z_deck) && !(s.z_keel == s.z_deck && s.y_deck <= tol))
    fail(at, ": keel height ", s.z_keel, " m is not below the deck ", s.z_deck, " m (centre profile vs depth)");
  if (!std::isnan(s.alpha_deck) && !(std::abs(s.alpha_deck) < 90.0)) fail(at, ": alpha_deck is ", s.alpha_deck, " deg; expected -90 < angle < 90");
  if (!std::isnan(s.flare) && !(s.flare > -1.0 && s.flare < 3.0)) fail(at, ": flare is ", s.flare, "; expected -1 < flare < 3 (a fraction of the top's lean)");
  if (!std::isnan(s.alpha_keel) && !(s.alpha_keel >= -90.0 - kAngleSlack && s.alpha_keel < 90.0))
    fail(at, ": alpha_keel is ", s.alpha_keel, " deg; expected -90 (horizontal) <= angle < 90");
  if (!std::isnan(s.y_dwl) && (s.y_dwl < -tol || s.y_dwl > s.y_max + tol))
    fail(at, ": y_dwl (design waterline) is ", s.y_dwl, " m; expected 0 <= y <= B/2 = ", s.y_max, " m");
  if (!std::isnan(s.half_area) && s.half_area < -tol * s.y_max) fail(at, ": half_area is ", s.half_area, " m^2; expected >= 0 (sectional area curve)");
  if (!std::isnan(s.draft) && !(s.draft < s.z_deck)) fail(at, ": DWL ", s.draft, " m is not below the deck ", s.z_deck, " m");
  if (!(s.points_weight >= 0)) fail(at, ": points_weight is ", s.points_weight, "; expected >= 0");
  if (!(s.alpha_dwl_weight >= 0 && s.alpha_dwl_weight <= 1)) fail(at, ": alpha_dwl_weight is ", s.alpha_dwl_weight, "; expected 0 to 1");
  if (!std::isnan(s.alpha_dwl) && !(std::abs(s.alpha_dwl) < 80.0)) fail(at, ": alpha_dwl is ", s.alpha_dwl, " deg; expected -80 < angle < 80");
  if (!(s.e2 >= 0 && s.e3 >= 0 && s.e2 + s.e3 > 0)) fail(at, ": e2 / e3 are ", s.e2, " / ", s.e3, "; expected weights >= 0, not both 0");
}

/// The frame: from the deck point along d, the direction from the DWL point to the keel
/// (blended with the deck-keel chord by kFrameBlend, which takes over as the immersed part
/// vanishes), so the part below the water gets most of the abscissa. Without a DWL, d is the
/// deck-keel chord.
Frame chord_frame(const SectionSpec& s) {
  Frame f;
  f.P = V2(std::clamp(s.y_deck, 0.0, s.y_max), s.z_deck);
  f.K = V2(0.0, s.z_keel);
  V2 dir = f.K - f.P;
  if (!std::isnan(s.draft) && !std::isnan(s.y_dwl) && s.draft > s.z_keel) {
    const V2 q(std::clamp(s.y_dwl, 0.0, s.y_max), s.draft);
    const V2 blended = (f.K - q) + kFrameBlend * (f.K - f.P);
    if (blended.dot(f.K - f.P) > 0) dir = blended;
  }
  f.d = dir.norm() > 0 ? V2(dir.normalized()) : V2(0.0, -1.0);
  f.n = V2(-f.d.y(), f.d.x());
  f.L = (f.K - f.P).dot(f.d);
  f.eta_k = (f.K - f.P).dot(f.n);
  return f;
}

/// The split height and the joint's abscissa: the split's parameter is interpolated between the
/// deck, DWL and keel points (through which the section passes), kept kMinPiece off the ends.
void place_joint(Section& S) {
  const SectionSpec& s = S.s;
  const double D = s.z_deck, zk = s.z_keel;
  double z = !std::isnan(s.z_inflection) ? s.z_inflection : S.has_dwl ? s.draft : 0.5 * (D + zk);
  z = std::clamp(z, zk, D);
  double x = S.f.L * (D - z) / std::max(D - zk, 1e-300);
  if (S.has_dwl) {
    const double xq = S.f.xi(S.Q);
    x = z >= s.draft ? xq * (D - z) / (D - s.draft) : xq + (S.f.L - xq) * (s.draft - z) / (s.draft - zk);
  }
  S.xj = std::clamp(x, kMinPiece * S.f.L, (1.0 - kMinPiece) * S.f.L);
  S.xi.resize(S.n());
  for (int k = 0; k < S.n(); ++k) S.xi[k] = S.x_of(S.l.g[k]);
}

/// Slope d eta / d xi of a tangent direction in the frame; the tangent must head along d.
double frame_slope(const Section& S, const V2& t, const char* which, double alpha) {
  const double td = t.dot(S.f.d);
  if (td < kMinTangentChordCos)
    throw InfeasibleFormParameters(S.at + ": the " + which + " tangent (" + fmt(alpha) + " deg) points across the section instead of along it "
                                   "(deck / keel angle curves vs the section's breadth and depth)");
  return t.dot(S.f.n) / td;
}

void find_dwl(Section& S) {
  const SectionSpec& s = S.s;
  S.has_dwl = !std::isnan(s.draft) && !std::isnan(s.y_dwl) && s.draft > s.z_keel;
  if (!S.has_dwl) {
    if (!std::isnan(s.half_area) && s.half_area > kSectionTol * s.y_max * s.y_max)
      throw InfeasibleFormParameters(S.at + ": half area " + fmt(s.half_area) + " m^2 but the keel (z = " + fmt(s.z_keel) +
                                     " m) is not below the DWL (sectional area curve vs centre profile)");
    return;
  }
  S.Q = V2(std::clamp(s.y_dwl, 0.0, s.y_max), s.draft);
  const double xq = S.f.xi(S.Q);
  if (!(xq > 0 && xq < S.f.L))
    throw InfeasibleFormParameters(S.at + ": the DWL point (" + fmt(S.Q.x()) + ", " + fmt(S.Q.y()) +
                                   ") m is not between the deck and keel points along the section (design waterline vs deck and profile)");
  S.eta_q = S.f.eta(S.Q);
}

/// The deck tangent in use and the sign of the top's curvature. A DWL point inward of the
/// deck-keel chord can only be reached with a flare; otherwise the deck tangent decides:
/// leaning out of the deck -> DWL line it makes a convex top, leaning in a flare. A tangent on
/// the wrong side for the shape asked would need a second inflection and is refused.
void choose_top(Section& S) {
  const SectionSpec& s = S.s;
  const V2 target = S.has_dwl ? S.Q : S.f.K;
  const V2 c = (target - S.f.P).norm() > 0 ? V2((target - S.f.P).normalized()) : S.f.d;
  const double alpha_chord = alpha_of(c);
  S.alpha_deck = !std::isnan(s.alpha_deck) ? s.alpha_deck : std::isnan(s.flare) ? kNaN : alpha_chord * (1.0 + s.flare);
  const bool inside = S.has_dwl && cross(S.f.K - S.f.P, S.Q - S.f.P) < 0;
  switch (s.above) {
    case SectionAbove::Convex: S.above = -1; break;
    case SectionAbove::Flare: S.above = 1; break;
    case SectionAbove::Free: S.above = 0; break;
    case SectionAbove::Auto: S.above = inside ? 1 : std::isnan(S.alpha_deck) ? 0 : (S.alpha_deck >= alpha_chord ? -1 : 1);
  }
  if (std::isnan(S.alpha_deck) || S.above == 0 || !S.has_dwl) return;
  const double lean = S.alpha_deck - alpha_chord;  // > 0: out of the chord (convex), < 0: in (flare)
  if ((S.above > 0 && lean > 1e-9) || (S.above < 0 && lean < -1e-9))
    throw InfeasibleFormParameters(S.at + ": the deck angle " + fmt(S.alpha_deck) + " deg leans " + (lean > 0 ? "out of" : "into") +
                                   " the line from the deck point to the DWL point (" + fmt(alpha_chord) + " deg): the section would need a second inflection; " +
                                   (S.above > 0 ? "a flared top needs a deck angle below " : "a convex top needs a deck angle above ") + fmt(alpha_chord) +
                                   " deg here (deck angle vs deck line and design waterline)");
}

/// End points, end tangents, and C2 continuity across the joint (G1: the legs on either side
/// in one line; G2: equal eta_xixi, as eta_xi is equal there).
void add_ends(Section& S) {
  const int n = S.n(), j = S.l.j;
  const Eigen::VectorXd& x = S.xi;
  S.eq.add(unit(n, 0), 0.0, "deck point");
  S.eq.add(unit(n, n - 1), S.f.eta_k, "keel point");
  if (!std::isnan(S.alpha_deck)) S.eq.add(unit(n, 1), (x[1] - x[0]) * frame_slope(S, tangent(S.alpha_deck), "deck", S.alpha_deck), "deck angle");
  if (!std::isnan(S.s.alpha_keel)) {
    const double alpha = std::max(S.s.alpha_keel, -90.0);
    S.eq.add(unit(n, n - 2), S.f.eta_k - (x[n - 1] - x[n - 2]) * frame_slope(S, tangent(alpha), "keel", alpha), "keel angle");
  }
  const double r = (x[j + 1] - x[j]) / (x[j] - x[j - 1]);
  Eigen::RowVectorXd g1 = Eigen::RowVectorXd::Zero(n);
  g1[j + 1] = 1.0, g1[j] = -1.0 - r, g1[j - 1] = r;
  S.eq.add(g1, 0.0, "tangent continuity at the joint");
  const double at = S.slope_x(0.0), ab = S.slope_x(1.0);
  S.eq.add(row_at(S.l, S.l.tj, 2, -1) / (at * at) - row_at(S.l, S.l.tj, 2, 1) / (ab * ab), 0.0, "curvature continuity at the joint");
}

/// The DWL point and the area below it (Green's theorem along Q -> curve -> K -> (0, T) -> Q,
/// clockwise: area = -1/2 of the sum of P x dP; on the curve P x P' = x' (P_D x d) +
/// eta' (P_D x n) + (d x n)(x eta' - x' eta), linear in eta).
void add_dwl(Section& S) {
  if (!S.has_dwl) return;
  const SectionSpec& s = S.s;
  const int n = S.n();
  S.t_q = S.t_of(S.f.xi(S.Q));
  S.dwl_eq = static_cast<int>(S.eq.rows.size());
  S.eq.add(row_at(S.l, S.t_q, 0, 1), S.eta_q, "DWL point");
  if (std::isnan(s.half_area)) return;
  const Frame& f = S.f;
  const double PxD = cross(f.P, f.d), PxN = cross(f.P, f.n), DxN = cross(f.d, f.n);
  std::vector<double> br{S.t_q};
  for (int i = kDegree + 1; i < static_cast<int>(S.l.U.size()) - kDegree - 1; ++i)
    if (S.l.U[i] > S.t_q && S.l.U[i] > br.back()) br.push_back(S.l.U[i]);
  br.push_back(1.0);
  const auto& gr = detail::gauss_rule(3);
  Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(n);
  double c = 0.0;
  for (std::size_t k = 0; k + 1 < br.size(); ++k) {
    const double h = 0.5 * (br[k + 1] - br[k]), m = 0.5 * (br[k + 1] + br[k]);
    if (!(h > 0)) continue;
    for (std::size_t q = 0; q < gr.x.size(); ++q) {
      const double t = m + h * gr.x[q], w = gr.w[q] * h, xp = S.slope_x(t), xt = S.x_of(t);
      const Eigen::RowVectorXd N = basis_row(S.l.U, kDegree, t), dN = basis_row(S.l.U, kDegree, t, 1);
      c += w * xp * PxD;
      row += w * (PxN * dN + DxN * (xt * dN - xp * N));
    }
  }
  const V2 top(0.0, s.draft);
  c += cross(f.K, top) + cross(top, S.Q);
  S.area_row = -0.5 * row;
  S.area_rhs = s.half_area + 0.5 * c;
  S.wants_area = true;
  S.area_eq = static_cast<int>(S.eq.rows.size());
  S.eq.add(S.area_row, S.area_rhs, "area below the DWL");
}

/// Control points whose support lies in [a, b] of the parameter put on the line through
/// `point` with direction `dir` (explicit flats and the skeg side).
void add_on_line(Section& S, double a, double b, const V2& point, const V2& dir, const std::string& name) {
  const V2 nrm(-dir.y(), dir.x());
  const double nn = S.f.n.dot(nrm);
  if (std::abs(nn) < 1e-12) return;
  for (int k = 1; k < S.n() - 1; ++k)
    if (S.l.U[k] >= a - 1e-12 && S.l.U[k + kDegree + 1] <= b + 1e-12)
      S.eq.add(unit(S.n(), k) * nn, (point - S.f.P - S.xi[k] * S.f.d).dot(nrm), name);
}

void add_flats(Section& S) {
  const SectionSpec& s = S.s;
  if (!std::isnan(s.z_fos) && s.z_fos < s.z_deck)
    add_on_line(S, 0.0, S.t_of(S.f.xi(V2(s.y_max, s.z_fos))), V2(s.y_max, s.z_deck), V2(0.0, -1.0), "flat of side");
  if (!std::isnan(s.y_fob) && s.y_fob > 0) add_on_line(S, S.t_of(S.f.xi(V2(s.y_fob, s.z_keel))), 1.0, S.f.K, V2(-1.0, 0.0), "flat of bottom");
  if (!std::isnan(s.skeg_half_thickness) && !std::isnan(s.skeg_bottom) && !std::isnan(s.skeg_top)) {
    const V2 lo(s.skeg_half_thickness, s.skeg_bottom), hi(s.skeg_half_thickness, s.skeg_top);
    add_on_line(S, S.t_of(S.f.xi(hi)), S.t_of(S.f.xi(lo)), hi, V2(0.0, -1.0), "skeg side");
  }
}

/// Bounds and the downward march on the curve itself, kBoundSamples points per span (on the
/// control polygon they would keep a curve that touches B/2 tangentially off it); and the sign
/// of the curvature at every knot of each piece (the top's sign on the top piece, convex on the
/// bottom one), with kShapeTolerance of room.
void add_inequalities(Section& S) {
  const SectionSpec& s = S.s;
  const Frame& f = S.f;
  const Eigen::VectorXd& U = S.l.U;
  for (const BasisAt& b : S.l.samples) {
    const Eigen::RowVectorXd N = row_of(b, 0, S.n()), dN = row_of(b, 1, S.n());
    const double xt = S.x_of(b.t), y0 = f.P.x() + xt * f.d.x();
    // (z >= keel and z <= deck follow from going down between the deck and keel points.)
    S.in.add(N * f.n.x(), s.y_max - y0, "y <= B/2");
    S.in.add(-N * f.n.x(), y0, "y >= 0");
    S.in.add(dN * f.n.y(), -S.slope_x(b.t) * f.d.y(), "section going down");
  }
  const int below = s.convex_below ? -1 : 0;
  // A split at the keel (a flare running down to a stem head above the water) leaves no bottom
  // to be convex: the bottom piece's condition fades out as the split nears the keel.
  const double z_split = std::isnan(s.z_inflection) ? (S.has_dwl ? s.draft : 0.5 * (s.z_deck + s.z_keel)) : s.z_inflection;
  const double bottom_free = 1.0 - smoothstep((z_split - s.z_keel) / (kSplitFade * (s.z_deck - s.z_keel)));
  for (int side : {-1, 1}) {
    const int sign = side < 0 ? S.above : below;
    if (sign == 0) continue;
    const double a = S.slope_x(side < 0 ? 0.0 : 1.0);
    const double room = (kShapeTolerance + (side > 0 ? kFreeCurvature * bottom_free : 0.0)) * a * a;
    const char* name = side > 0 ? "convex below the DWL" : sign < 0 ? "convex above the DWL" : "flare above the DWL";
    std::vector<double> knots;
    for (int i = kDegree; i < static_cast<int>(U.size()) - kDegree; ++i)
      if ((side < 0 && U[i] <= S.l.tj) || (side > 0 && U[i] >= S.l.tj))
        if (knots.empty() || U[i] > knots.back()) knots.push_back(U[i]);
    for (double t : knots) S.in.add(-sign * row_at(S.l, t, 2, side), room, name);
  }
}

Section build(const SectionSpec& s) {
  Section S{s, "section at x = " + fmt(s.x) + " m", cached_layout(s.n_control)};
  validate(s, S.at);
  S.f = chord_frame(s);
  find_dwl(S);
  place_joint(S);
  choose_top(S);
  add_ends(S);
  add_dwl(S);
  add_flats(S);
  add_inequalities(S);
  return S;
}

/// Gram matrix of the bending energy int k^2 ds (up to a constant factor) for a curve with the
/// slopes of eta_prev (identity slopes when null): over the frame k^2 ds = eta_xixi^2
/// (1 + eta_xi^2)^(-5/2) dxi, and with x linear on each piece, eta_xixi = eta_tt / x'^2 and
/// dxi = x' dt. Gauss with 6 points per span (the weight is not a polynomial).
Eigen::MatrixXd bending_gram(const Section& S, const Eigen::VectorXd* eta_prev) {
  const int n = S.n();
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(n, n);
  for (const BasisAt& b : S.l.gauss) {
    const double xp = S.slope_x(b.t);
    const double slope = eta_prev ? b.d.row(1).dot(eta_prev->segment(b.first, kDegree + 1)) / xp : 0.0;
    const double w = b.w * std::pow(1.0 + slope * slope, -2.5) / (xp * xp * xp);
    G.block(b.first, b.first, kDegree + 1, kDegree + 1).noalias() += w * b.d.row(2).transpose() * b.d.row(2);
  }
  return G * S.f.L * S.f.L * S.f.L;  // scaled like int eta_tt^2 dt of a single-piece graph
}

/// The objective: e2 times the bending energy, plus the data points, the DWL angle penalty.
QuadraticProgram objective(const Section& S, double fairness) {
  QuadraticProgram qp;
  const int n = S.n();
  qp.H = 2.0 * fairness * S.s.e2 * bending_gram(S, nullptr);
  if (S.s.e3 > 0) {
    Eigen::MatrixXd G3 = Eigen::MatrixXd::Zero(n, n);
    const auto& gr = detail::gauss_rule(3);
    for (int sp = kDegree; sp < static_cast<int>(S.l.U.size()) - kDegree - 1; ++sp) {
      const double a = S.l.U[sp], b = S.l.U[sp + 1];
      if (!(b > a)) continue;
      for (std::size_t q = 0; q < gr.x.size(); ++q) {
        const double t = 0.5 * (a + b) + 0.5 * (b - a) * gr.x[q];
        const Eigen::RowVectorXd d3 = basis_row(S.l.U, kDegree, t, 3);
        G3 += gr.w[q] * 0.5 * (b - a) * d3.transpose() * d3;
      }
    }
    qp.H += 2.0 * fairness * S.s.e3 * G3;
  }
  qp.g = Eigen::VectorXd::Zero(n);
  if (!S.s.points.empty() && S.s.points_weight > 0) {
    const double w = S.s.points_weight / static_cast<double>(S.s.points.size());
    for (const V2& p : S.s.points) {
      const Eigen::RowVectorXd N = basis_row(S.l.U, kDegree, std::clamp(S.t_of(S.f.xi(p)), 0.0, 1.0));
      qp.H += 2.0 * w * N.transpose() * N;
      qp.g -= 2.0 * w * S.f.eta(p) * N.transpose();
    }
  }
  if (S.has_dwl && !std::isnan(S.s.alpha_dwl) && S.s.alpha_dwl_weight > 0) {
    const V2 t = tangent(S.s.alpha_dwl);
    const double m = t.dot(S.f.n) / std::max(t.dot(S.f.d), kMinTangentChordCos);
    const Eigen::RowVectorXd r = row_at(S.l, S.t_q, 1, 1) / S.slope_x(S.t_q);
    const double w = fairness * S.s.alpha_dwl_weight * kDwlAngleWeight * S.f.L * S.f.L * S.f.L;
    qp.H += 2.0 * w * r.transpose() * r;
    qp.g -= 2.0 * w * m * r.transpose();
  }
  S.eq.fill(qp.E, qp.e, n);
  S.in.fill(qp.A, qp.b, n);
  return qp;
}

NurbsCurve assemble(const Section& S, const Eigen::VectorXd& eta) {
  Eigen::MatrixXd C(S.n(), 3);
  for (int k = 0; k < S.n(); ++k) {
    const V2 p = S.f.at(S.xi[k], eta[k]);
    C.row(k) << S.s.x, std::max(0.0, p.x()), p.y();
  }
  return NurbsCurve(kDegree, S.l.U, C);
}

/// The section as the centre-line segment (stem, cruiser-stern end) or a point.
bool degenerate(const Section& S) {
  const SectionSpec& s = S.s;
  const double narrow = kStemBreadth * s.y_max;
  return (S.f.K - S.f.P).norm() <= narrow || (s.y_deck <= narrow && (std::isnan(s.y_dwl) || s.y_dwl <= narrow));
}

std::string conflict_names(const Section& S, const QuadraticProgram& qp, const QpSolution& sol) {
  std::set<std::string> names;
  for (int k : sol.conflict) names.insert(k < qp.E.rows() ? S.eq.names[k] : S.in.names[k - qp.E.rows()]);
  std::string list;
  for (const auto& nm : names) list += (list.empty() ? "" : ", ") + nm;
  return list;
}

/// Barrier weight of the section's central point: mu = h (kBarrierLength L)^2, h the mean
/// diagonal of H. A bound the fairest section would cross by v metres is kept about
/// (kBarrierLength L)^2 / v inside it: a flat the area pushes hard against lies within a
/// millimetre of its plane, while one only just touched is rounded off smoothly.
double barrier_weight(const Section& S, const QuadraticProgram& qp) {
  const double ell = kBarrierLength * S.f.L;
  return qp.H.diagonal().mean() * ell * ell;
}

/// Where the immersed part spans fewer than kBlendSpans knot spans, move the DWL point's and
/// the area's targets from what the section without them has to the asked ones by a smooth
/// step in its length (one extra solve, at the waterline's ends only).
void blend_immersed_part(const Section& S, QuadraticProgram& qp) {
  if (!S.has_dwl) return;
  const double w = smoothstep((1.0 - S.t_q) * S.l.s_bot / (1.0 - S.l.tj) / kBlendSpans);
  if (w >= 1.0) return;
  QuadraticProgram free = qp;
  std::vector<int> keep;
  for (int i = 0; i < static_cast<int>(qp.E.rows()); ++i)
    if (i != S.dwl_eq && i != S.area_eq) keep.push_back(i);
  free.E = qp.E(keep, Eigen::all);
  free.e = qp.e(keep);
  const QpSolution nat = solve_qp(free);
  if (nat.status != QpStatus::Optimal)
    throw InfeasibleFormParameters(S.at + ": the conditions " + conflict_names(S, free, nat) + " contradict each other");
  qp.e[S.dwl_eq] = (1.0 - w) * qp.E.row(S.dwl_eq).dot(nat.x) + w * qp.e[S.dwl_eq];
  if (S.area_eq >= 0) qp.e[S.area_eq] = (1.0 - w) * qp.E.row(S.area_eq).dot(nat.x) + w * qp.e[S.area_eq];
}

/// The smooth central point (its active set would change from one section to the next and kink
/// the surface's rows) of the geometric fairness, a batten's least bending energy: the bending
/// Gram reweighted with the slopes of the previous solution a few times.
std::optional<Eigen::VectorXd> central_fairest(const Section& S, QuadraticProgram& qp, CentralState& state) {
  const Eigen::MatrixXd H_rest = qp.H - 2.0 * S.s.e2 * bending_gram(S, nullptr);
  const double mu = barrier_weight(S, qp);
  for (int it = 0; it <= kBendingIterations; ++it) {
    if (it > 0 && S.s.e2 > 0) qp.H = H_rest + 2.0 * S.s.e2 * bending_gram(S, &state.x);
    const QpSolution c = solve_qp_central(qp, mu, kBoundRelax * S.f.L, &state);
    if (c.status != QpStatus::Optimal) return it > 0 ? std::optional<Eigen::VectorXd>(state.x) : std::nullopt;
  }
  return state.x;
}

}  // namespace

static SectionDesign design_section_warm(const SectionSpec& spec, const std::vector<int>& warm, CentralState* central);

Eigen::VectorXd section_knot_vector(int n_control) { return cached_layout(n_control).U; }

std::pair<double, double> section_area_range(const SectionSpec& spec) {
  SectionSpec s0 = spec;
  s0.half_area = 0.0;  // the area row as it would be added: its constant part at zero area
  const Section S0 = build(s0);
  if (!S0.has_dwl || degenerate(S0) || !S0.wants_area) return {kNaN, kNaN};
  QuadraticProgram qp = objective(S0, kRangeFairness);
  std::vector<int> keep;
  for (int i = 0; i < static_cast<int>(qp.E.rows()); ++i)
    if (i != S0.area_eq) keep.push_back(i);
  qp.E = Eigen::MatrixXd(qp.E(keep, Eigen::all));
  qp.e = Eigen::VectorXd(qp.e(keep));
  const double scale = S0.f.L * S0.f.L;
  double out[2];
  for (int side = 0; side < 2; ++side) {
    qp.g = (side == 0 ? 1.0 : -1.0) * S0.area_row.transpose() / scale;
    const QpSolution sol = solve_qp(qp);
    out[side] = sol.status == QpStatus::Optimal ? S0.area_row.dot(sol.x) - S0.area_rhs : kNaN;
  }
  return {out[0], out[1]};
}

Eigen::MatrixXd section_fullness_bands(const std::vector<SectionSpec>& specs) {
  Eigen::MatrixXd out(static_cast<Eigen::Index>(specs.size()), 2);
  for (std::size_t i = 0; i < specs.size(); ++i) {
    const SectionSpec& s = specs[i];
    const auto [lo, hi] = section_area_range(s);
    const double box = std::clamp(s.y_dwl, 0.0, s.y_max) * (s.draft - s.z_keel);
    out.row(static_cast<Eigen::Index>(i)) << (box > 0 ? lo / box : kNaN), (box > 0 ? hi / box : kNaN);
  }
  return out;
}

SectionDesign design_section(const SectionSpec& spec, const std::vector<int>& warm) { return design_section_warm(spec, warm, nullptr); }

static SectionDesign design_section_warm(const SectionSpec& spec, const std::vector<int>& warm, CentralState* central) {
  const Section S = build(spec);
  SectionDesign out{NurbsCurve(kDegree, S.l.U, Eigen::MatrixXd::Zero(S.n(), 3)), {}, kNaN};
  if (S.has_dwl && S.wants_area && S.Q.x() > 0) out.fullness = spec.half_area / (S.Q.x() * (spec.draft - spec.z_keel));
  if (degenerate(S)) {
    if (S.wants_area && spec.half_area > kSectionTol * spec.y_max * spec.y_max)
      throw InfeasibleFormParameters(S.at + ": half area " + fmt(spec.half_area) +
                                     " m^2 with zero breadth at deck and DWL (sectional area curve vs design waterline and deck)");
    out.curve = assemble(S, S.xi / std::max(S.f.L, 1e-300) * S.f.eta_k);  // the straight line from deck to keel
    return out;
  }
  QuadraticProgram qp = objective(S, 1.0);
  blend_immersed_part(S, qp);
  CentralState local;
  CentralState& state = central ? *central : local;
  const std::optional<Eigen::VectorXd> eta = central_fairest(S, qp, state);
  if (eta) {
    out.curve = assemble(S, *eta);
    return out;
  }
  // No strictly feasible section: the active-set solver names what is in conflict.
  const QpSolution sol = solve_qp(qp, warm);
  if (sol.status != QpStatus::Optimal) {
    if (S.wants_area) {
      const auto [lo, hi] = section_area_range(spec);
      const double box = S.Q.x() * (spec.draft - spec.z_keel);
      if (std::isnan(lo) || spec.half_area < lo || spec.half_area > hi)
        throw InfeasibleFormParameters(S.at + ": the sectional area curve asks a half area of " + fmt(spec.half_area) + " m^2 (fullness " +
                                       fmt(out.fullness) + "); a fair section through this DWL point, deck and keel holds " +
                                       (std::isnan(lo) ? std::string("none") : fmt(lo) + " to " + fmt(hi) + " m^2 (fullness " + fmt(lo / box) +
                                                                                    " to " + fmt(hi / box) + ")") + " here");
    }
    throw InfeasibleFormParameters(S.at + ": the conditions " + conflict_names(S, qp, sol) + " contradict each other");
  }
  out.curve = assemble(S, sol.x);  // feasible but not strictly: the minimiser itself
  out.active = sol.active;
  return out;
}

std::vector<NurbsCurve> design_sections(const std::vector<SectionSpec>& specs) {
  std::vector<NurbsCurve> out;
  out.reserve(specs.size());
  std::vector<int> warm;
  CentralState central;  // the neighbouring section's central point starts the next one
  int n_prev = -1;
  for (const SectionSpec& s : specs) {
    if (s.n_control != n_prev) central = CentralState{};
    SectionDesign d = design_section_warm(s, s.n_control == n_prev ? warm : std::vector<int>{}, &central);
    warm = std::move(d.active);
    n_prev = s.n_control;
    out.push_back(std::move(d.curve));
  }
  return out;
}

}  // namespace fairlines
