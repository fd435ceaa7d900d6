// One face inside one loop of fixed boundary nodes, see patch.hpp.
//
// Notation: (u, v) face parameters; (U, V) integer dyadic coordinates of the subdivision,
// 2^kDepth units per root cell; h the target element size (m); S_u, S_v first partials;
// "scaled" (u, v) are the parameters times the mean parametric speeds, in which the planar
// Delaunay triangulation is built.
#include "meshing/patch.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <span>
#include <tuple>
#include <unordered_map>

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include "fairlines/errors.hpp"
#include "meshing/triangulation.hpp"
#include "nurbs/checks.hpp"

namespace fairlines::meshing {

namespace {

constexpr int kDepth = 16;                 ///< subdivision levels available per root cell
constexpr double kClearance = 0.55;        ///< interior nodes keep this x h from the boundary
constexpr double kCurvatureSafety = 0.8;   ///< size from curvature times this (element diagonals)
constexpr double kCurvatureStep = 1e-4;    ///< curvature_sum's difference step / the parameter range
constexpr double kDefaultTolerance = 0.01; ///< chordal tolerance / size when not given
constexpr double kDefaultMinSize = 0.05;   ///< minimum size / size when not given
constexpr int kSwapPasses = 8;             ///< sweeps of 3-D edge swaps
constexpr int kAugmentVisits = 4000;       ///< triangles one augmenting-path search may reach
constexpr double kLeafQuality = 0.8;       ///< leaves scoring less are not taken whole (the blend's sheared ones)
constexpr int kRerouteDepth = 12;          ///< leaf pairs this many sides from an unpaired triangle may be re-paired
constexpr double kRelaxedPair = -0.5;      ///< pairs whose quad scores at least this (in space) may be matched at last
constexpr double kGrading = 0.6;           ///< size may grow by this x the distance from the boundary
constexpr double kInteriorGrading = 0.3;   ///< and by this x the distance from a finer curvature size inside
                                           ///< the face (GradedGrid): the subdivision's 2:1 steps 3 or more
                                           ///< elements apart (bare hull's mean 0.934; at 0.6 0.924, 0.919 ungraded)
constexpr double kGridStep = 0.25;         ///< GradedGrid's spacing / the largest size (at 0.35 the bare hull's
                                           ///< mean 0.932 and its sag 29 mm of 30; finer costs curvature samples)
constexpr double kGridMost = 1 << 20;      ///< GradedGrid's samples at most (40 MB; a face at the element cap,
                                           ///< 2 million, would ask 32 million): the spacing grows to fit
constexpr double kFlat = 1e-2;             ///< a triangle with |2 area| below this x its longest side^2 is flat
constexpr int kFlatPasses = 8;             ///< flat triangles' flip passes at most (a row of them needs one each)
constexpr double kPoleZone = 2.0;          ///< interior nodes within this x h of a pole are thinned
constexpr double kPoleSpacing = 0.4;       ///< to this x h apart
constexpr double kFanSpread = 4.0;         ///< iso-line length ratio from which a face is a fan
constexpr double kPi = 3.14159265358979323846;
constexpr double kImproveBelow = 0.6;      ///< nodes of elements scoring below this are optimised one by one
                                           ///< (0.75 took most of the time on the bare hull, where leaf
                                           ///< quads score 0.6-0.75; corners are improve_corners's)
constexpr double kCornerSlack = 40.0;      ///< quad corners further than this from 90 deg (deg) are penalised
constexpr double kSmoothSettle = 0.02;     ///< a smoothing move shorter than this x the node's reach is not made
constexpr double kPolishBand = 0.02;       ///< polish searches the elements this close to the worst
constexpr double kPolishMinStep = 0.003;   ///< down to this step / the node's mean edge length
constexpr int kImprovePasses = 4;          ///< sweeps of that node optimisation
constexpr double kPairFlipBelow = 0.3;     ///< a triangle scoring below this after the node passes is
                                           ///< re-paired with its neighbour (flip_sliver_pairs) ...
constexpr double kPairFlipGain = 1e-3;     ///< ... where that raises the pair's worst by more than this
constexpr double kImproveStep = 0.25;      ///< its first trial step / the node's mean edge length
constexpr double kImproveMinStep = 0.04;   ///< and its last
constexpr double kImproveShortest = 0.3;   ///< no trial shortens a node's edges below this x their mean
constexpr double kTrialMiss = 0.03;        ///< a linear step onto the face may land this x its length from
                                           ///< its target (else Newton, Work::toward); at 0.1 the least
                                           ///< scaled Jacobian fell at 2 m (0.339 -> 0.328, the bulb's nose)
constexpr double kSplitSkew = 0.1;         ///< an all-quad split node this x its edge off the middle along
                                           ///< the surface is put at the middle (split_point)
constexpr double kCornerLimit = 45.0;      ///< the goal: quad corners within kCornerLimit of 0 and 180 deg are out
constexpr double kCornerTrade = 0.5;       ///< improve_corners may lower a node's worst element to this
                                           ///< (corners within 30-150 deg) for corners nearer 90 deg
constexpr double kMeanBelow = 1.0;         ///< improve_mean moves the free nodes of elements scoring below this
                                           ///< (all but perfect ones; 0.85 left the bare hull under gmsh's mean)
constexpr int kMeanPasses = 3;             ///< its sweeps (the third raises the bare hull's mean 0.001 for 10-20 % time)
constexpr double kHexBelow = 0.75;         ///< remove_valence3_nodes looks at valence-3 nodes whose quads score below this
constexpr double kHexReach = 0.1;          ///< splits scoring more than this below them before the search are not tried
constexpr double kHexGain = 0.02;          ///< and makes two quads of three where that raises their worst this much
constexpr double kCollapseRatio = 2.5;     ///< a quad whose mean side is this many times under a neighbour's is
                                           ///< collapsed across a diagonal (a 0.59 m quad among 1.95 m ones, ratio
                                           ///< 3.30, at the example's forefoot; the subdivision's 2:1 steps give 2)
constexpr double kCollapseFloor = 0.5;     ///< ... where the elements about it then score at least this (strict)
constexpr double kCollapseTrade = 0.15;    ///< ... and their worst falls by no more than this
constexpr int kCollapsePasses = 3;         ///< passes of it: a pass leaves the quads next to a collapse for the next
constexpr std::array<int, 4> kDeadElement{-2, -2, -2, -2};  ///< an element an edit pass removed
constexpr int kMeanTries = 2;              ///< moves toward the ideal position tried per visit: all the way, half
constexpr double kMeanScoreSlack = 1e-12;  ///< a mean move may lower its elements' worst score by round-off
constexpr double kMeanMinGain = 1e-9;      ///< and must lower the sum of their deficits by more than this

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;

/// The smallest angle of triangle abc (0 if a side has no length): the arc cosine of its
/// corners' largest cosine, one acos instead of three (acos decreases, so the value is the same).
double min_angle(const Vec3& a, const Vec3& b, const Vec3& c) {
  double most = -1.0;
  for (const auto& [x, y, z] : {std::tie(a, b, c), std::tie(b, c, a), std::tie(c, a, b)}) {
    const Vec3 e1 = y - x, e2 = z - x;
    const double n1 = e1.norm(), n2 = e2.norm();
    if (n1 <= 0 || n2 <= 0) return 0.0;
    most = std::max(most, std::clamp(e1.dot(e2) / (n1 * n2), -1.0, 1.0));
  }
  return std::acos(most);
}

double cross2(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

double segment_distance(const Vec3& q, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double l2 = ab.squaredNorm();
  const double t = l2 > 0 ? std::clamp((q - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
  return (a + t * ab - q).norm();
}

// ---- binary subdivision of the parameter rectangle (Yoon & Kim's node generation) ----------

struct Cell {
  long long U0, U1, V0, V1;
  int child = -1;  // first of two children
  bool split_u = false;
};

/// `SizeAt`: size_at(q, p, below) is the target size at (u, v) = q and its point p; any value
/// below `below` where the size is below it (the split test needs no more, and a bound is
/// cheaper than the curvature).
template <typename SizeAt>
class Subdivision {
 public:
  Subdivision(const FaceGeometry& g, const MeshOptions& o, std::vector<double> ru, std::vector<double> rv,
              double size_scale, const SizeAt& size_at)
      : g_(g), o_(o), ru_(std::move(ru)), rv_(std::move(rv)), scale_(size_scale), size_at_(size_at) {
    const long long one = 1LL << kDepth;
    for (size_t i = 0; i + 1 < ru_.size(); ++i)
      for (size_t j = 0; j + 1 < rv_.size(); ++j)
        cells_.push_back({static_cast<long long>(i) * one, static_cast<long long>(i + 1) * one,
                          static_cast<long long>(j) * one, static_cast<long long>(j + 1) * one});
    roots_ = static_cast<int>(cells_.size());
    std::vector<std::pair<int, Samples>> work;
    for (int c = roots_ - 1; c >= 0; --c) work.push_back({c, samples(cells_[c])});
    while (!work.empty()) {
      const auto [c, P] = work.back();
      work.pop_back();
      const int d = wanted_split(cells_[c], P);
      if (d < 0) continue;
      split(c, d == 0);
      // each child shares two of its three sample lines with the parent (its ends), so only
      // its middle line is evaluated: 3 points instead of 9
      work.push_back({cells_[c].child + 1, child_samples(cells_[cells_[c].child + 1], P, d == 0, true)});
      work.push_back({cells_[c].child, child_samples(cells_[cells_[c].child], P, d == 0, false)});
    }
    balance();
  }

  double u(long long U) const { return coord(ru_, U); }
  double v(long long V) const { return coord(rv_, V); }

  /// Corners of every leaf, each once: (U, V) pairs.
  std::vector<std::pair<long long, long long>> corners() const {
    std::vector<std::pair<long long, long long>> out;
    for (const Cell& c : cells_)
      if (c.child < 0)
        for (long long U : {c.U0, c.U1})
          for (long long V : {c.V0, c.V1}) out.push_back({U, V});
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }
  /// The leaves: (U0, U1, V0, V1) of each.
  std::vector<std::array<long long, 4>> leaves() const {
    std::vector<std::array<long long, 4>> out;
    for (const Cell& c : cells_)
      if (c.child < 0) out.push_back({c.U0, c.U1, c.V0, c.V1});
    return out;
  }

 private:
  /// The face at a cell's corners, side middles and middle: P[a][b] at (us[a], vs[b]) with
  /// us = {u(U0), middle, u(U1)} (likewise vs).
  using Samples = std::array<std::array<Vec3, 3>, 3>;

  static double coord(const std::vector<double>& r, long long X) {
    const long long one = 1LL << kDepth;
    const long long i = std::min<long long>(X >> kDepth, static_cast<long long>(r.size()) - 2);
    const double f = static_cast<double>(X - i * one) / static_cast<double>(one);
    return f >= 1.0 ? r[i + 1] : r[i] + (r[i + 1] - r[i]) * f;
  }
  std::array<double, 3> us(const Cell& c) const { return {u(c.U0), 0.5 * (u(c.U0) + u(c.U1)), u(c.U1)}; }
  std::array<double, 3> vs(const Cell& c) const { return {v(c.V0), 0.5 * (v(c.V0) + v(c.V1)), v(c.V1)}; }

  Samples samples(const Cell& c) const {
    const auto U = us(c), V = vs(c);
    Samples P;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) P[a][b] = g_.point({U[a], V[b]});
    return P;
  }
  /// A child's samples: its end lines are the parent's lines 0 and 1 (first child) or 1 and
  /// 2 (second), split in u (lines of constant u) or in v.
  Samples child_samples(const Cell& c, const Samples& parent, bool in_u, bool second) const {
    const auto U = us(c), V = vs(c);
    const int lo = second ? 1 : 0;
    Samples P;
    for (int k = 0; k < 3; ++k) {
      if (in_u) {
        P[0][k] = parent[lo][k];
        P[2][k] = parent[lo + 1][k];
        P[1][k] = g_.point({U[1], V[k]});
      } else {
        P[k][0] = parent[k][lo];
        P[k][2] = parent[k][lo + 1];
        P[k][1] = g_.point({U[k], V[1]});
      }
    }
    return P;
  }

  /// -1: keep; 0: split in u; 1: split in v.
  int wanted_split(const Cell& c, const Samples& P) const {
    const bool can_u = c.U1 - c.U0 > 1, can_v = c.V1 - c.V0 > 1;
    if (!can_u && !can_v) return -1;
    double Lu = 0, Lv = 0;
    for (int k = 0; k < 3; ++k) {
      Lu = std::max(Lu, (P[1][k] - P[0][k]).norm() + (P[2][k] - P[1][k]).norm());
      Lv = std::max(Lv, (P[k][1] - P[k][0]).norm() + (P[k][2] - P[k][1]).norm());
    }
    // chordal deviation: the normal distance of the middle from the corners' bilinear middle
    // (a parametrisation whose speed jumps moves the middle along the surface, not off it)
    Vec3 n = (P[2][1] - P[0][1]).cross(P[1][2] - P[1][0]);
    const double nn = n.norm();
    const Vec3 off = P[1][1] - 0.25 * (P[0][0] + P[2][0] + P[0][2] + P[2][2]);
    const double dev = nn > 0 ? std::abs(off.dot(n / nn)) : off.norm();
    const bool too_curved = dev > o_.chordal_tolerance && std::max(Lu, Lv) > scale_ * o_.min_size;
    // the size (its curvature term is the costly part) only where the deviation does not decide
    const bool too_big =
        !too_curved && std::max(Lu, Lv) > size_at_({us(c)[1], vs(c)[1]}, P[1][1], std::max(Lu, Lv));
    if (!too_big && !too_curved) return -1;
    if (Lu >= Lv) return can_u ? 0 : 1;
    return can_v ? 1 : 0;
  }

  void split(int ci, bool in_u) {
    const int first = static_cast<int>(cells_.size());
    Cell a = cells_[ci], b = cells_[ci];
    a.child = b.child = -1;
    if (in_u) {
      a.U1 = b.U0 = (a.U0 + a.U1) / 2;
    } else {
      a.V1 = b.V0 = (a.V0 + a.V1) / 2;
    }
    cells_.push_back(a);
    cells_.push_back(b);
    cells_[ci].child = first;
    cells_[ci].split_u = in_u;
  }

  int find(long long U, long long V) const {
    const long long one = 1LL << kDepth;
    const long long nu = static_cast<long long>(ru_.size()) - 1, nv = static_cast<long long>(rv_.size()) - 1;
    if (U < 0 || V < 0 || U >= nu * one || V >= nv * one) return -1;
    int c = static_cast<int>((U >> kDepth) * nv + (V >> kDepth));
    while (cells_[c].child >= 0) {
      const Cell& x = cells_[c];
      const bool second = x.split_u ? U >= (x.U0 + x.U1) / 2 : V >= (x.V0 + x.V1) / 2;
      c = x.child + (second ? 1 : 0);
    }
    return c;
  }

  /// 2:1 balance: no leaf is more than twice as long as a side neighbour in either direction.
  /// A leaf found balanced stays so until a cell it samples splits, and such a cell touches
  /// it across a side, so a pass re-checks only the leaves unsettled by a split next to them
  /// (the same splits in the same order as re-checking every leaf: most passes split few).
  void balance() {
    std::vector<char> settled(cells_.size(), 0);
    for (bool changed = true; changed;) {
      changed = false;
      const int n = static_cast<int>(cells_.size());
      for (int ci = 0; ci < n; ++ci) {
        if (cells_[ci].child >= 0 || settled[ci]) continue;
        const int want = balance_split(cells_[ci]);
        if (want < 0) {
          settled[ci] = 1;
          continue;
        }
        split(ci, want == 0);
        settled.resize(cells_.size(), 0);
        unsettle_neighbours(cells_[ci], settled);
        changed = true;
      }
    }
  }

  /// -1: leaf c is balanced; 0 / 1: it is to be split in u / v for a shorter side neighbour.
  int balance_split(const Cell& c) const {
    const long long du = c.U1 - c.U0, dv = c.V1 - c.V0;
    int want = -1;
    auto check = [&](long long U, long long V) {
      if (want >= 0) return;
      const int nb = find(U, V);
      if (nb < 0) return;
      const Cell& x = cells_[nb];
      if (2 * (x.U1 - x.U0) < du && du > 1) want = 0;
      else if (2 * (x.V1 - x.V0) < dv && dv > 1) want = 1;
    };
    for (int k = 0; k < 4; ++k) {
      const long long V = c.V0 + std::max<long long>(dv * (2 * k + 1) / 8, 0);
      const long long U = c.U0 + std::max<long long>(du * (2 * k + 1) / 8, 0);
      check(c.U0 - 1, V);
      check(c.U1, V);
      check(U, c.V0 - 1);
      check(U, c.V1);
    }
    return want;
  }

  /// The leaves across each side of cell s (which just split) are checked again.
  void unsettle_neighbours(const Cell& s, std::vector<char>& settled) const {
    for (long long V = s.V0; V < s.V1;) {  // across the sides of constant u
      for (long long U : {s.U0 - 1, s.U1})
        if (const int nb = find(U, V); nb >= 0) settled[nb] = 0;
      V = next_along(V, s.V1, {s.U0 - 1, s.U1}, false);
    }
    for (long long U = s.U0; U < s.U1;) {  // across the sides of constant v
      for (long long V : {s.V0 - 1, s.V1})
        if (const int nb = find(U, V); nb >= 0) settled[nb] = 0;
      U = next_along(U, s.U1, {s.V0 - 1, s.V1}, true);
    }
  }

  /// The next position along a side (in v, or in u if `in_u`) from X where a leaf across
  /// either line `across` may begin: the nearer end of the two leaves there, at most `end`.
  long long next_along(long long X, long long end, std::array<long long, 2> across, bool in_u) const {
    long long next = end;
    for (long long Y : across) {
      const int nb = in_u ? find(X, Y) : find(Y, X);
      if (nb >= 0) next = std::min(next, in_u ? cells_[nb].U1 : cells_[nb].V1);
    }
    return std::max(next, X + 1);
  }

  const FaceGeometry& g_;
  const MeshOptions& o_;
  std::vector<double> ru_, rv_;
  double scale_;
  const SizeAt& size_at_;
  std::vector<Cell> cells_;
  int roots_ = 0;
};

/// Cumulative chord length (m) at n + 1 points of an iso-line: the parameter that varies
/// (u if `vary_u`) runs from a to b, the other is held at `fixed`.
std::vector<double> iso_line_arc(const FaceGeometry& g, bool vary_u, double fixed, double a, double b, int n) {
  auto at = [&](double t) { return g.point(vary_u ? Vec2(t, fixed) : Vec2(fixed, t)); };
  std::vector<double> s(n + 1, 0.0);
  Vec3 prev = at(a);
  for (int k = 1; k <= n; ++k) {
    const Vec3 p = at(a + (b - a) * k / n);
    s[k] = s[k - 1] + (p - prev).norm();
    prev = p;
  }
  return s;
}

/// Root lines in one direction: equal arc length along the face's middle iso-line, as many
/// as the longest of three iso-lines needs at the maximum size.
std::vector<double> root_lines(const FaceGeometry& g, double a, double b, double c0, double c1, bool along_u,
                               double h) {
  constexpr int kSamples = 64;
  double longest = 0.0;
  std::vector<double> s(kSamples + 1, 0.0);
  for (double f : {0.0, 0.5, 1.0}) {
    const std::vector<double> cum = iso_line_arc(g, along_u, c0 + (c1 - c0) * f, a, b, kSamples);
    longest = std::max(longest, cum.back());
    if (f == 0.5) s = cum;
  }
  const int n = std::max(1, static_cast<int>(std::ceil(longest / h - 1e-9)));
  std::vector<double> out(n + 1);
  out[0] = a;
  out[n] = b;
  const double total = s.back();
  for (int i = 1; i < n; ++i) {
    if (!(total > 0)) {
      out[i] = a + (b - a) * i / n;
      continue;
    }
    const double target = total * i / n;
    int k = 1;
    while (k < kSamples && s[k] < target) ++k;
    const double w = s[k] > s[k - 1] ? (target - s[k - 1]) / (s[k] - s[k - 1]) : 0.0;
    out[i] = a + (b - a) * (k - 1 + w) / kSamples;
  }
  return out;
}

/// Monotone map of one parameter to the mean arc length (m) along three iso-lines of the other.
class ArcMap {
 public:
  ArcMap(const FaceGeometry& g, double a, double b, double c0, double c1, bool along_u) : a_(a), b_(b) {
    s_.assign(kSamples + 1, 0.0);
    for (double f : {0.25, 0.5, 0.75}) {
      const std::vector<double> arc = iso_line_arc(g, along_u, c0 + (c1 - c0) * f, a, b, kSamples);
      for (int k = 1; k <= kSamples; ++k) s_[k] += arc[k] / 3.0;
    }
    const double total = std::max(s_.back(), 1e-300);
    for (int k = 1; k <= kSamples; ++k)  // strictly increasing, even across a pole
      s_[k] = std::max(s_[k], s_[k - 1] + 1e-9 * total / kSamples);
  }
  double operator()(double t) const {
    const double f = b_ > a_ ? (t - a_) / (b_ - a_) * kSamples : 0.0;
    const int k = std::clamp(static_cast<int>(std::floor(f)), 0, kSamples - 1);
    return s_[k] + (s_[k + 1] - s_[k]) * (f - k);
  }
  /// d(arc length) / d(parameter) at t.
  double speed(double t) const {
    const double f = b_ > a_ ? (t - a_) / (b_ - a_) * kSamples : 0.0;
    const int k = std::clamp(static_cast<int>(std::floor(f)), 0, kSamples - 1);
    return b_ > a_ ? (s_[k + 1] - s_[k]) * kSamples / (b_ - a_) : 1.0;
  }

 private:
  static constexpr int kSamples = 256;
  double a_, b_;
  std::vector<double> s_;
};

/// Length of the iso-lines across one direction relative to their mean, as a function of the
/// other parameter: r(t) = |iso-line at t| / mean. Scaling the cross coordinate by r makes a
/// face whose iso-lines shrink to a pole (a stem top, a bulb's nose) a fan in the planar
/// coordinates, as it is in 3-D, instead of a rectangle of slivers.
class IsoWidth {
 public:
  IsoWidth(const FaceGeometry& g, double a, double b, double c0, double c1, bool along_u) : a_(a), b_(b) {
    r_.assign(kSamples + 1, 1.0);
    double mean = 0.0;
    for (int k = 0; k <= kSamples; ++k) {
      r_[k] = iso_line_arc(g, !along_u, a + (b - a) * k / kSamples, c0, c1, kAcross).back();
      mean += r_[k] / (kSamples + 1);
    }
    lo_ = 1e300;
    hi_ = 0.0;
    for (double& x : r_) {
      x = mean > 0 ? std::max(x / mean, kFloor) : 1.0;
      lo_ = std::min(lo_, x);
      hi_ = std::max(hi_, x);
    }
  }
  double operator()(double t) const {
    const double f = b_ > a_ ? std::clamp((t - a_) / (b_ - a_), 0.0, 1.0) * kSamples : 0.0;
    const int k = std::min(static_cast<int>(std::floor(f)), kSamples - 1);
    return r_[k] + (r_[k + 1] - r_[k]) * (f - k);
  }
  /// max r / min r: how far the iso-lines are from equal length.
  double spread() const { return hi_ / lo_; }

 private:
  static constexpr int kSamples = 128;    ///< iso-lines tabulated
  static constexpr int kAcross = 32;      ///< chords along each iso-line
  static constexpr double kFloor = 1e-3;  ///< r never below this: the pole's copies stay apart
  double a_, b_, lo_ = 1, hi_ = 1;
  std::vector<double> r_;
};

// ---- elements ---------------------------------------------------------------------------

/// A position on the face with the partials there.
struct Place {
  Vec2 uv;
  Vec3 p, su, sv;
};

struct Work {
  const FaceGeometry& g;
  const MeshOptions& o;
  std::vector<Vec3> xyz;
  std::vector<Vec2> uv;
  std::vector<Vec3> normal;  // surface normal at each node (S_u x S_v direction)
  int fixed = 0;             // nodes 0 .. fixed-1 do not move
  std::vector<std::array<int, 4>> el;

  Vec3 surface_normal(const Vec2& q) const {
    Vec3 p, su, sv;
    g.first(q, p, su, sv);
    return unit_normal(su, sv);
  }
  /// S_u x S_v normalised, zero where the surface is singular.
  static Vec3 unit_normal(const Vec3& su, const Vec3& sv) {
    const Vec3 n = su.cross(sv);
    const double len = n.norm();
    return len > 1e-300 ? Vec3(n / len) : Vec3::Zero();
  }
  Vec3 element_normal(const std::array<int, 4>& e) const {
    const int k = e[3] < 0 ? 3 : 4;
    Vec3 n = Vec3::Zero();
    for (int i = 0; i < k; ++i) n += normal[e[i]];
    const double len = n.norm();
    if (len >= 1e-12) return n / len;  // normalized(), its norm taken once
    // singular corners (a pole): the element's own normal
    n = k == 4 ? Vec3((xyz[e[2]] - xyz[e[0]]).cross(xyz[e[3]] - xyz[e[1]]))
               : Vec3((xyz[e[1]] - xyz[e[0]]).cross(xyz[e[2]] - xyz[e[0]]));
    return n.normalized();
  }
  /// Scaled Jacobian about the surface normals at the element's nodes (3-D only).
  double spatial_quality(const std::array<int, 4>& e) const {
    const int k = e[3] < 0 ? 3 : 4;
    Vec3 p[4];
    for (int i = 0; i < k; ++i) p[i] = xyz[e[i]];
    return element_quality(p, k, element_normal(e));
  }
  double quality(const std::array<int, 4>& e) const {
    const double q = spatial_quality(e);
    // folded in the parameter plane: as bad as inverted
    return (e[3] < 0 ? folded<3>(e) : folded<4>(e)) ? std::min(q, -1.0) : q;
  }
  /// A corner of the K-corner element e turns the wrong way in the parameter plane (its sides
  /// of some length: a pole's collapsed side does not count).
  template <int K>
  bool folded(const std::array<int, 4>& e) const {
    for (int i = 0; i < K; ++i)
      if (cross2(uv[e[i]], uv[e[(i + 1) % K]], uv[e[(i + K - 1) % K]]) <= 0 &&
          (xyz[e[i]] - xyz[e[(i + 1) % K]]).norm() > 0 && (xyz[e[i]] - xyz[e[(i + K - 1) % K]]).norm() > 0)
        return true;
    return false;
  }
  /// The worse of spatial_quality() and, for a quad, the scaled Jacobian about its own normal
  /// (its diagonal cross product, the census's measure), so neither sees it folded.
  double strict_quality(const std::array<int, 4>& e) const {
    if (e[3] < 0) return spatial_quality(e);
    Vec3 p[4];
    for (int i = 0; i < 4; ++i) p[i] = xyz[e[i]];
    const Vec3 n = (p[2] - p[0]).cross(p[3] - p[1]);
    const double len = n.norm();
    if (!(len > 0)) return std::min(spatial_quality(e), 0.0);
    const Vec3 ns = element_normal(e), nd = n / len;
    // side i runs from corner i to i + 1; corner i's second side is side i - 1 reversed, of
    // the same norm bit for bit (its components negated), so each side's norm is taken once
    double side[4];
    for (int i = 0; i < 4; ++i) side[i] = (p[(i + 1) % 4] - p[i]).norm();
    double q = 1e9;  // both normals' corner terms from one cross product per corner
    for (int i = 0; i < 4; ++i) {
      const Vec3 e1 = p[(i + 1) % 4] - p[i], e2 = p[(i + 3) % 4] - p[i];
      const double l = side[i] * side[(i + 3) % 4];
      const Vec3 c = e1.cross(e2);
      // one division: dividing by l > 0 keeps the order, so min(a, b) / l = min(a / l, b / l)
      q = std::min(q, l > 0 ? std::min(c.dot(ns), c.dot(nd)) / l : 0.0);
    }
    return q;
  }
  /// Normal distance of an element's centroid from the surface point at its mean (u, v).
  double chordal(const std::array<int, 4>& e) const {
    if (!g.surface) return 0.0;
    const int k = e[3] < 0 ? 3 : 4;
    Vec3 c = Vec3::Zero();
    Vec2 m = Vec2::Zero();
    for (int i = 0; i < k; ++i) c += xyz[e[i]], m += uv[e[i]];
    return std::abs((c / k - g.point(m / k)).dot(element_normal(e)));
  }
  Place place_at(const Vec2& q) const {
    Place x{q, Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
    g.first(q, x.p, x.su, x.sv);
    return x;
  }
  /// The face's point near `target` (a point on the tangent plane at `from`): the first
  /// Gauss-Newton step of FaceGeometry::locate from `from`, one evaluation; only where that
  /// lands more than kTrialMiss x the distance from the target (the clamped or ruled ends of a
  /// blend, near a pole) Newton to convergence.
  Place toward(const Place& from, const Vec3& target) const {
    const double E = from.su.dot(from.su), F = from.su.dot(from.sv), G = from.sv.dot(from.sv), det = E * G - F * F;
    const Vec3 r = target - from.p;
    const double a = from.su.dot(r), b = from.sv.dot(r);
    const Vec2 d((G * a - F * b) / det, (E * b - F * a) / det);  // the 2 x 2 normal equations
    if (det > 0 && d.allFinite()) {
      const Place x = place_at(g.clamp(from.uv + d));
      if ((x.p - target).norm() <= kTrialMiss * r.norm()) return x;
    }
    return place_at(g.locate(target, from.uv));
  }
  /// Node i to x.
  void put(int i, const Place& x) {
    uv[i] = x.uv;
    xyz[i] = x.p;
    normal[i] = unit_normal(x.su, x.sv);
  }
  int add(const Vec2& q) {
    uv.push_back(q);
    xyz.push_back(g.point(q));
    normal.push_back(surface_normal(q));
    return static_cast<int>(xyz.size()) - 1;
  }
};

/// Augmenting-path search of Edmonds' (1965) blossom algorithm on the triangles' adjacency
/// graph: odd cycles of triangles (blossoms) are contracted, so the paths a search without
/// them misses (a triangle mesh's dual graph is full of odd cycles) are found too. The state
/// of one search is reset only where it touched it.
class BlossomSearch {
 public:
  BlossomSearch(const std::vector<std::vector<int>>& adj, std::vector<int>& mate)
      : adj_(adj), mate_(mate), parent_(adj.size(), -1), base_(adj.size()), order_(adj.size(), 0),
        in_tree_(adj.size(), 0), mark_(adj.size(), 0), seen_(adj.size(), 0), members_(adj.size()) {
    for (size_t i = 0; i < adj.size(); ++i) base_[i] = static_cast<int>(i);
  }

  /// Augments the matching along a path from the free vertex `root` found within `limit`
  /// vertices of the search; false if there is none.
  bool augment(int root, int limit) {
    const bool found = search(root, limit);
    for (int v : touched_) parent_[v] = -1, base_[v] = v, in_tree_[v] = 0;
    touched_.clear();
    return found;
  }

 private:
  void touch(int v) {
    if (!in_tree_[v] && parent_[v] < 0 && base_[v] == v) {
      order_[v] = static_cast<int>(touched_.size());
      touched_.push_back(v);
      members_[v].assign(1, v);
    }
  }
  int lca(int a, int b) {  // the base of the blossom an edge a-b between two even vertices closes
    ++stamp_;
    for (;;) {
      a = base_[a];
      seen_[a] = stamp_;
      if (mate_[a] < 0) break;
      a = parent_[mate_[a]];
    }
    for (;;) {
      b = base_[b];
      if (seen_[b] == stamp_) return b;
      b = parent_[mate_[b]];
    }
  }
  void mark_path(int v, int b, int child) {
    while (base_[v] != b) {
      mark_[base_[v]] = mark_[base_[mate_[v]]] = stamp_;
      marked_.push_back(base_[v]);
      marked_.push_back(base_[mate_[v]]);
      parent_[v] = child;
      child = mate_[v];
      v = parent_[mate_[v]];
    }
  }
  bool search(int root, int limit) {
    std::vector<int> queue{root};
    touch(root);
    in_tree_[root] = 1;
    for (size_t head = 0; head < queue.size() && static_cast<int>(touched_.size()) < limit; ++head) {
      const int v = queue[head];
      for (int to : adj_[v]) {
        if (base_[v] == base_[to] || mate_[v] == to) continue;
        if (to == root || (mate_[to] >= 0 && parent_[mate_[to]] >= 0)) {  // an odd cycle: contract it
          const int b = lca(v, to);
          ++stamp_;
          marked_.clear();
          mark_path(v, b, to);
          mark_path(to, b, v);
          contract(b, queue);
        } else if (parent_[to] < 0) {
          touch(to);
          parent_[to] = v;
          if (mate_[to] < 0) {
            flip(to);
            return true;
          }
          touch(mate_[to]);
          in_tree_[mate_[to]] = 1;
          queue.push_back(mate_[to]);
        }
      }
    }
    return false;
  }
  /// Every vertex whose base mark_path marked now has base b; those not yet in the tree join
  /// the queue, in the order they were touched (the order of a scan of all touched vertices,
  /// which cost O(touched) per blossom; the bases' member lists cost O(blossom)).
  void contract(int b, std::vector<int>& queue) {
    inside_.clear();
    bool b_marked = false;
    for (int m : marked_) {
      if (mark_[m] != stamp_) continue;  // listed twice
      mark_[m] = 0;
      b_marked = b_marked || m == b;
      inside_.insert(inside_.end(), members_[m].begin(), members_[m].end());
      if (m != b) members_[m].clear();
    }
    std::sort(inside_.begin(), inside_.end(), [&](int x, int y) { return order_[x] < order_[y]; });
    for (int i : inside_) {
      base_[i] = b;
      if (!in_tree_[i]) in_tree_[i] = 1, queue.push_back(i);
    }
    if (b_marked) return;  // its members were listed with the rest
    members_[b].insert(members_[b].end(), inside_.begin(), inside_.end());
  }
  void flip(int v) {  // the path root .. v alternates: swap its matched and unmatched edges
    while (v >= 0) {
      const int pv = parent_[v], next = mate_[pv];
      mate_[v] = pv;
      mate_[pv] = v;
      v = next;
    }
  }

  const std::vector<std::vector<int>>& adj_;
  std::vector<int>& mate_;
  std::vector<int> parent_, base_, order_, touched_;  // order_: index in touched_
  std::vector<char> in_tree_;
  std::vector<int> mark_, seen_, marked_, inside_;
  std::vector<std::vector<int>> members_;  // the touched vertices with this base
  int stamp_ = 0;
};

/// The triangles at each node, in triangle order (compressed rows: at[start[i] .. start[i + 1])).
struct TrianglesAtNodes {
  std::vector<int> start, at;
  TrianglesAtNodes(const std::vector<std::array<int, 3>>& tri, size_t nodes) : start(nodes + 1, 0), at(3 * tri.size()) {
    for (const auto& t : tri)
      for (int v : t) ++start[v + 1];
    for (size_t i = 0; i < nodes; ++i) start[i + 1] += start[i];
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (int t = 0; t < static_cast<int>(tri.size()); ++t)
      for (int v : tri[t]) at[fill[v]++] = t;
  }
  /// The last triangle (in triangle order) holding the directed edge a -> b, and the index of
  /// a in it; (-1, -1) if none.
  std::pair<int, int> holding(const std::vector<std::array<int, 3>>& tri, int a, int b) const {
    std::pair<int, int> found{-1, -1};
    for (int i = start[a]; i < start[a + 1]; ++i)
      for (int k = 0; k < 3; ++k)
        if (tri[at[i]][k] == a && tri[at[i]][(k + 1) % 3] == b) found = {at[i], k};
    return found;
  }
};

/// The subdivision's corners, sorted, and the node each became (-1: none, outside the face or
/// too close to its boundary).
struct CornerNodes {
  std::vector<std::pair<long long, long long>> corner;
  std::vector<int> node;
  int at(long long U, long long V) const {
    const auto it = std::lower_bound(corner.begin(), corner.end(), std::make_pair(U, V));
    return it != corner.end() && *it == std::make_pair(U, V) ? node[it - corner.begin()] : -1;
  }
};

/// The leaves of the subdivision whose four corners are nodes and whose quad the matching
/// would take (it scores min_quad_quality, and sags within the tolerance): node ids
/// counter-clockwise from (U0, V0). Where the triangulation holds such a leaf as two
/// triangles, the pair is matched in advance and kept from the swaps (a structured interior:
/// the leaves are the cells the subdivision made for the size, and the matching took nearly
/// all of them anyway).
std::vector<std::array<int, 4>> leaf_quads(const Work& w, const std::vector<std::array<long long, 4>>& leaves,
                                           const CornerNodes& nodes) {
  std::vector<std::array<int, 4>> out;
  for (const auto& [U0, U1, V0, V1] : leaves) {
    const std::array<int, 4> q{nodes.at(U0, V0), nodes.at(U1, V0), nodes.at(U1, V1), nodes.at(U0, V1)};
    if (q[0] < 0 || q[1] < 0 || q[2] < 0 || q[3] < 0) continue;
    // a node in the middle of a side (a finer neighbour's corner; 2:1 balance puts none
    // elsewhere) makes the leaf a pentagon
    const long long Um = (U0 + U1) / 2, Vm = (V0 + V1) / 2;
    if (nodes.at(Um, V0) >= 0 || nodes.at(U1, Vm) >= 0 || nodes.at(Um, V1) >= 0 || nodes.at(U0, Vm) >= 0) continue;
    if (!w.o.all_quad && w.chordal(q) > w.o.chordal_tolerance) continue;
    if (w.strict_quality(q) >= kLeafQuality && w.quality(q) >= kLeafQuality) out.push_back(q);
  }
  return out;
}

/// For each quad of `quads` (a, b, c, d counter-clockwise) the pair of triangles of `tri` that
/// make it up, split along either diagonal: (a, b, c) + (a, c, d) or (a, b, d) + (b, c, d);
/// (-1, -1) where `tri` does not hold it.
std::vector<std::pair<int, int>> held_pairs(const std::vector<std::array<int, 3>>& tri, const TrianglesAtNodes& around,
                                            const std::vector<std::array<int, 4>>& quads) {
  std::vector<std::pair<int, int>> out;
  auto third = [&](int t, int k) { return tri[t][(k + 2) % 3]; };
  for (const auto& [a, b, c, d] : quads) {
    out.push_back({-1, -1});
    const auto [t1, k1] = around.holding(tri, a, b);
    if (t1 < 0) continue;
    const int x = third(t1, k1);
    const auto [t2, k2] = x == c ? around.holding(tri, c, d) : x == d ? around.holding(tri, b, c) : std::make_pair(-1, -1);
    if (t2 >= 0 && third(t2, k2) == (x == c ? a : d)) out.back() = {t1, t2};
  }
  return out;
}

/// Pairs of neighbouring triangles the matching may take: strong ones (their quad scores at
/// least min_quad_quality) with that score, and weak ones (only not folded in space).
struct PairCandidates {
  std::vector<std::tuple<double, int, int>> strong;
  std::vector<std::pair<int, int>> weak;

  /// Triangle t and its neighbour across its side k (nbr), t < that neighbour.
  void consider(const Work& w, const std::vector<std::array<int, 3>>& tri, const std::vector<std::array<int, 3>>& nbr,
                int t, int k) {
    const int u = nbr[t][k], a = tri[t][k], b = tri[t][(k + 1) % 3], c = tri[t][(k + 2) % 3];
    int d = -1;
    for (int j = 0; j < 3; ++j)
      if (tri[u][j] != a && tri[u][j] != b) d = tri[u][j];
    // a pair across a cell side spans two cells: its quad may sag more than its triangles (the
    // all-quad split halves every element, so its quads sag a quarter as much)
    if (!w.o.all_quad && w.chordal({a, d, b, c}) > w.o.chordal_tolerance) return;
    const double q = w.quality({a, d, b, c});
    if (q >= w.o.min_quad_quality) strong.push_back({q, t, u});
    else if (!w.o.all_quad && w.spatial_quality({a, d, b, c}) >= kRelaxedPair) weak.push_back({t, u});
  }
};

/// Augmenting paths from every free triangle (BlossomSearch) over the edges of `adj`, after
/// adding the strong candidates, then again after adding the weak ones.
void augment_all(std::vector<std::vector<int>>& adj, std::vector<int>& mate, const PairCandidates& c) {
  BlossomSearch search(adj, mate);
  auto sweep = [&] {
    for (int f = 0; f < static_cast<int>(mate.size()); ++f)
      if (mate[f] < 0 && !adj[f].empty()) search.augment(f, kAugmentVisits);
  };
  for (const auto& [q, t, u] : c.strong) adj[t].push_back(u), adj[u].push_back(t);
  sweep();
  for (const auto& [t, u] : c.weak) adj[t].push_back(u), adj[u].push_back(t);
  sweep();
}

/// Triangles within `depth` steps across sides of a triangle that `free` marks.
std::vector<char> near_free(const std::vector<std::array<int, 3>>& nbr, const std::vector<int>& mate, int depth) {
  std::vector<char> in(nbr.size(), 0);
  std::vector<int> front;
  for (int t = 0; t < static_cast<int>(nbr.size()); ++t)
    if (mate[t] < 0) in[t] = 1, front.push_back(t);
  for (int step = 0; step < depth && !front.empty(); ++step) {
    std::vector<int> next;
    for (int t : front)
      for (int u : nbr[t])
        if (u >= 0 && !in[u]) in[u] = 1, next.push_back(u);
    front.swap(next);
  }
  return in;
}

/// Greedy matching by quad quality, then augmenting paths (BlossomSearch) so that as few
/// triangles as possible stay unpaired: first among the pairs whose quad scores at least
/// min_quad_quality, then also among those that are only not folded in space (kRelaxedPair:
/// the quads across a 2:1 step of the subdivision, with a straight corner at its middle node,
/// which merge_weak_pairs bends where it can). The pairs that make up a leaf quad
/// (leaf_quads) are matched first and left out of the candidates; where triangles are left
/// unpaired, the pairs of leaf triangles within kRerouteDepth of them become candidates too,
/// so a path may run through leaf quads (re-pairing their triangles) as it could before.
/// `leaf`: per triangle, whether it ends up in its leaf quad.
std::vector<int> match_triangles(const Work& w, const std::vector<std::array<int, 3>>& tri,
                                 const std::vector<std::array<int, 4>>& leaves, std::vector<std::array<int, 3>>& nbr,
                                 std::vector<char>& leaf) {
  const int n = static_cast<int>(tri.size());
  const TrianglesAtNodes around(tri, w.xyz.size());
  std::vector<int> mate(n, -1), leaf_mate(n, -1);
  for (const auto& [t, u] : held_pairs(tri, around, leaves))
    if (t >= 0) mate[t] = leaf_mate[t] = u, mate[u] = leaf_mate[u] = t;
  nbr.assign(n, {-1, -1, -1});
  for (int t = 0; t < n; ++t)
    for (int k = 0; k < 3; ++k) nbr[t][k] = around.holding(tri, tri[t][(k + 1) % 3], tri[t][k]).first;
  PairCandidates free_pairs;
  for (int t = 0; t < n; ++t)
    for (int k = 0; k < 3; ++k)
      if (nbr[t][k] > t && leaf_mate[t] < 0 && leaf_mate[nbr[t][k]] < 0) free_pairs.consider(w, tri, nbr, t, k);
  std::sort(free_pairs.strong.begin(), free_pairs.strong.end(),
            [](const auto& x, const auto& y) { return std::get<0>(x) > std::get<0>(y); });
  std::vector<std::vector<int>> adj(n);
  for (const auto& [q, t, u] : free_pairs.strong)
    if (mate[t] < 0 && mate[u] < 0) mate[t] = u, mate[u] = t;
  augment_all(adj, mate, free_pairs);
  const std::vector<char> near = near_free(nbr, mate, w.o.all_quad ? 0 : kRerouteDepth);
  PairCandidates leaf_pairs;
  for (int t = 0; t < n; ++t)
    for (int k = 0; k < 3; ++k) {
      const int u = nbr[t][k];
      if (u > t && near[t] && near[u] && (leaf_mate[t] >= 0 || leaf_mate[u] >= 0) && !w.o.all_quad)
        leaf_pairs.consider(w, tri, nbr, t, k);
    }
  if (!leaf_pairs.strong.empty() || !leaf_pairs.weak.empty()) augment_all(adj, mate, leaf_pairs);
  leaf.assign(n, 0);
  for (int t = 0; t < n; ++t) leaf[t] = leaf_mate[t] >= 0 && mate[t] == leaf_mate[t];
  return mate;
}

/// The elements at each node, in element order (compressed rows: one allocation, not one per
/// node).
class ElementsAtNodes {
 public:
  explicit ElementsAtNodes(const Work& w) : start_(w.xyz.size() + 1, 0) {
    for (const auto& e : w.el)
      for (int k = 0; k < (e[3] < 0 ? 3 : 4); ++k) ++start_[e[k] + 1];
    for (size_t i = 0; i + 1 < start_.size(); ++i) start_[i + 1] += start_[i];
    at_.resize(start_.back());
    std::vector<int> fill(start_.begin(), start_.end() - 1);
    for (int e = 0; e < static_cast<int>(w.el.size()); ++e)
      for (int k = 0; k < (w.el[e][3] < 0 ? 3 : 4); ++k) at_[fill[w.el[e][k]]++] = e;
  }
  std::span<const int> operator[](int i) const { return {at_.data() + start_[i], at_.data() + start_[i + 1]}; }

 private:
  std::vector<int> start_, at_;
};

/// The elements at each node as lists (merge_weak_pairs adds to them).
std::vector<std::vector<int>> elements_at_nodes(const Work& w) {
  const ElementsAtNodes at(w);
  std::vector<std::vector<int>> around(w.xyz.size());
  for (int i = 0; i < static_cast<int>(w.xyz.size()); ++i) around[i].assign(at[i].begin(), at[i].end());
  return around;
}

/// Nodes whose last visit by a pass moved nothing and about which nothing has moved since. A
/// visit (smooth, optimise_node) is a function of the positions of the nodes of the elements
/// about the node alone, so visiting such a node again would move nothing: the passes skip it.
class Settled {
 public:
  Settled(const Work& w, const ElementsAtNodes& around) : w_(w), around_(around), flag_(w.xyz.size(), 0) {}
  bool operator[](int i) const { return flag_[i] != 0; }
  /// After a visit of node i: settled if it did not move, else its neighbours are no longer.
  void visited(int i, bool moved) {
    if (!moved) {
      flag_[i] = 1;
      return;
    }
    for (int e : around_[i])
      for (int k = 0; k < (w_.el[e][3] < 0 ? 3 : 4); ++k) flag_[w_.el[e][k]] = 0;
  }

 private:
  const Work& w_;
  const ElementsAtNodes& around_;
  std::vector<char> flag_;
};

/// The mean of the centroids of the elements `around` node i; `worst`: the lowest of their
/// qualities q, `reach`: the sum of the centroids' distances from the node (m).
Vec3 smoothing_target(const Work& w, std::span<const int> around, int i, const std::vector<double>& q, double& worst,
                      double& reach) {
  Vec3 target = Vec3::Zero();
  for (int e : around) {
    worst = std::min(worst, q[e]);
    const int k = w.el[e][3] < 0 ? 3 : 4;
    Vec3 c = Vec3::Zero();
    for (int j = 0; j < k; ++j) c += w.xyz[w.el[e][j]];
    target += c / k;
    reach += (c / k - w.xyz[i]).norm();
  }
  return target / static_cast<double>(around.size());
}

/// Whether a smoothing move (node already moved) leaves every element `around` it at or above
/// `worst`, the lowest of their qualities q before; then `now_q` holds their new qualities.
/// The element that was worst is scored first: it rejects most moves that are rejected, and
/// one element below the worst rejects the move, so no more are needed.
bool smoothing_keeps(const Work& w, std::span<const int> around, const std::vector<double>& q, double worst,
                     std::vector<double>& now_q) {
  size_t first = 0;
  for (size_t k = 1; k < around.size(); ++k)
    if (q[around[k]] < q[around[first]]) first = k;
  now_q.assign(around.size(), 0.0);
  now_q[first] = w.quality(w.el[around[first]]);
  if (now_q[first] + 1e-12 < worst) return false;
  for (size_t k = 0; k < around.size(); ++k) {
    if (k == first) continue;
    now_q[k] = w.quality(w.el[around[k]]);
    if (now_q[k] + 1e-12 < worst) return false;
  }
  return true;
}

/// Moves each free node toward the mean of its elements' centroids, back onto the face,
/// when the worst of its elements does not get worse; `structured` nodes stay (see
/// structured_nodes).
void smooth(Work& w, int passes, const std::vector<char>& structured) {
  const int n = static_cast<int>(w.xyz.size());
  const ElementsAtNodes around(w);
  Settled settled(w, around);
  std::vector<double> q(w.el.size()), now_q;  // each element's quality(), kept current
  for (size_t e = 0; e < w.el.size(); ++e) q[e] = w.quality(w.el[e]);
  // each node's place_at(uv) once: only a kept move changes it, and toward's result is it
  std::vector<Place> place(n);
  std::vector<char> placed(n, 0);
  for (int pass = 0; pass < passes; ++pass) {
    int moved = 0;
    for (int i = w.fixed; i < n; ++i) {
      if (around[i].empty() || settled[i] || structured[i]) continue;
      double worst = 1e9, reach = 0.0;
      const Vec3 target = smoothing_target(w, around[i], i, q, worst, reach);
      // a move this short changes no element's score noticeably, yet it would unsettle every
      // neighbour: the node counts as settled
      if ((target - w.xyz[i]).norm() < kSmoothSettle * reach / static_cast<double>(around[i].size())) {
        settled.visited(i, false);
        continue;
      }
      const Vec2 old_uv = w.uv[i];
      const Vec3 old_p = w.xyz[i], old_n = w.normal[i];
      // onto the face by the linear step from the node toward the target's foot on its tangent
      // plane (Work::toward: Newton only where that misses, at a clamped or ruled end): two
      // evaluations where Newton to the foot point took five or six
      if (!placed[i]) place[i] = w.place_at(old_uv), placed[i] = 1;
      const Place& here = place[i];
      const Vec3 n = Work::unit_normal(here.su, here.sv);
      const Place x = w.toward(here, target - (target - here.p).dot(n) * n);
      if ((x.uv - old_uv).squaredNorm() == 0.0) {
        settled.visited(i, false);
        continue;
      }
      w.put(i, x);
      const bool keep = smoothing_keeps(w, around[i], q, worst, now_q);
      if (keep) {
        for (size_t k = 0; k < around[i].size(); ++k) q[around[i][k]] = now_q[k];
        place[i] = x;  // toward's Place is place_at(x.uv), bit for bit
      } else {
        w.uv[i] = old_uv, w.xyz[i] = old_p, w.normal[i] = old_n;
      }
      moved += keep;
      settled.visited(i, keep);
    }
    if (!moved) break;
  }
}

/// Calls f(j) for the far node j of each edge at node i of the elements `around` (an edge two
/// elements share, twice).
template <class F>
void for_each_edge_at(const Work& w, std::span<const int> around, int i, F&& f) {
  for (int e : around) {
    const int k = w.el[e][3] < 0 ? 3 : 4;
    for (int c = 0; c < k; ++c)
      if (w.el[e][c] == i) {
        f(w.el[e][(c + 1) % k]);
        f(w.el[e][(c + k - 1) % k]);
      }
  }
}

/// The mean and shortest length of the edges at node i (`around`: the elements at each node).
void edge_lengths(const Work& w, std::span<const int> around, int i, double& mean, double& shortest) {
  mean = 0.0, shortest = 1e300;
  int edges = 0;
  for_each_edge_at(w, around, i, [&](int j) {
    const double l = (w.xyz[j] - w.xyz[i]).norm();
    mean += l, shortest = std::min(shortest, l), ++edges;
  });
  mean /= std::max(edges, 1);
}

/// |cos| of quad e's corner c (1 for a corner with a zero-length side): 0 for a right angle.
double corner_cos(const Work& w, const std::array<int, 4>& e, int c) {
  const Vec3& x = w.xyz[e[c]];
  const Vec3 a = w.xyz[e[(c + 1) % 4]] - x, b = w.xyz[e[(c + 3) % 4]] - x;
  const double l = a.norm() * b.norm();
  return l > 0 ? std::abs(a.dot(b)) / l : 1.0;
}

/// The second objective of optimise_node: the squared excess of |cos| over sin kCornerSlack
/// summed over the quad corners at node i that move with it (at i and at its two neighbours
/// in each quad; the opposite corner keeps its sides), so a node whose worst element cannot
/// rise still moves quad corners back toward 45-135 deg. A corner within the slack costs no
/// square root (its squared cosine is compared). Any value above `above` once the sum passes
/// it (the terms are not negative: the rest cannot bring it back).
double corner_excess(const Work& w, std::span<const int> around, int i, double above = 1e300) {
  static const double slack = std::sin(kCornerSlack * kPi / 180.0), slack2 = slack * slack;
  double sum = 0.0;
  for (int e : around) {
    const std::array<int, 4>& q = w.el[e];
    if (q[3] < 0) continue;
    int c = 0;
    while (c < 3 && q[c] != i) ++c;
    // the quad's sides once: corner k's sides are side k and side k - 1 reversed, whose
    // negated components change the dot product's sign only, and no squared norm
    Vec3 side[4];
    double len2[4];
    for (int k = 0; k < 4; ++k) side[k] = w.xyz[q[(k + 1) % 4]] - w.xyz[q[k]], len2[k] = side[k].squaredNorm();
    for (int k : {c, (c + 1) % 4, (c + 3) % 4}) {
      const int before = (k + 3) % 4;
      const double d = side[k].dot(side[before]), l2 = len2[k] * len2[before];
      if (l2 > 0 && d * d <= slack2 * l2) continue;
      const double over = (l2 > 0 ? std::abs(d) / std::sqrt(l2) : 1.0) - slack;
      sum += over * over;
    }
    if (sum > above) return sum;
  }
  return sum;
}

/// The shortest edge (m) at node i of the elements `around` (no square root per edge: hot).
double shortest_edge(const Work& w, std::span<const int> around, int i) {
  double shortest2 = 1e300;
  for_each_edge_at(w, around, i, [&](int j) { shortest2 = std::min(shortest2, (w.xyz[j] - w.xyz[i]).squaredNorm()); });
  return std::sqrt(shortest2);
}

/// The largest chordal deviation (m) of the elements `around`.
double largest_sag(const Work& w, std::span<const int> around) {
  double d = 0.0;
  for (int e : around) d = std::max(d, w.chordal(w.el[e]));
  return d;
}

/// (cos, sin) of the compass directions k x 45 deg.
const std::array<std::array<double, 2>, 8>& compass() {
  static const std::array<std::array<double, 2>, 8> c = [] {
    std::array<std::array<double, 2>, 8> out;
    for (int k = 0; k < 8; ++k) out[k] = {std::cos(k * kPi / 4), std::sin(k * kPi / 4)};
    return out;
  }();
  return c;
}

/// optimise_node's search at node i: its elements worst first, its limits, and the two
/// objectives' best values so far (the worst element's strict quality, corner_excess).
struct NodeSearch {
  /// A trial that beat the best so far, with its objectives.
  struct Better {
    Place x;
    double now, excess;
  };

  Work& w;
  std::span<const int> around;
  int i;
  double trade_above;
  double floor = 0.0, sag_limit = 0.0, best = 1e9, best_excess = 0.0;
  std::vector<std::pair<double, int>> order;  // (strict quality, element), worst first

  NodeSearch(Work& work, std::span<const int> elements, int node, double trade) : w(work), around(elements), i(node), trade_above(trade) {
    // the elements worst first: a trial is mostly rejected by the one that was worst
    for (int e : around) order.push_back({w.strict_quality(w.el[e]), e});
    std::sort(order.begin(), order.end());
    if (!order.empty()) best = order.front().first;
    best_excess = corner_excess(w, around, i);
  }

  /// The worst element's strict quality; the count stops at the first element below `limit`
  /// (the trial is rejected whatever the rest).
  double worst(double limit) const {
    double q = 1e9;
    for (const auto& [q0, e] : order)
      if ((q = std::min(q, w.strict_quality(w.el[e]))) < limit) break;
    return q;
  }

  /// The compass trials about `at` at `step` (m) in the tangent frame (t1, t2) that beat the
  /// best so far, in turn (each beats the one before); best and best_excess follow them.
  int trials(const Place& at, double step, const Vec3& t1, const Vec3& t2, std::array<Better, 8>& better) {
    int nb = 0;
    for (const auto& [c, s] : compass()) {
      const Place x = w.toward(at, at.p + step * (c * t1 + s * t2));
      if ((x.uv - at.uv).squaredNorm() == 0.0) continue;
      // the node's normal (a square root and three divisions) only once a trial gets past the
      // corners: their excess needs the point alone
      w.uv[i] = x.uv, w.xyz[i] = x.p;
      // at or above trade_above the worst cannot make a trial better, only the corners can:
      // they are counted first, the cheaper test
      double excess = best >= trade_above ? corner_excess(w, around, i, best_excess) : -1.0;
      if (excess > best_excess) continue;
      w.normal[i] = Work::unit_normal(x.su, x.sv);
      const double best_capped = std::min(best, trade_above), now = worst(best_capped);
      const double capped = std::min(now, trade_above);
      if (capped < best_capped) continue;  // worse whatever the corners
      if (shortest_edge(w, around, i) < floor) continue;
      if (excess < 0) excess = corner_excess(w, around, i);
      if (capped > best_capped + 1e-12 || excess < best_excess - 1e-9 || (excess <= best_excess && now > best + 1e-12)) {
        best = now, best_excess = excess;
        better[nb++] = {x, now, excess};
      }
    }
    return nb;
  }
};

/// Compass search for node i (see improve_worst); true when it moved. A trial is better when
/// it raises the worst of the node's elements, or keeps it and lowers corner_excess; with
/// `trade_above` (see improve_corners) the worst counts only up to that level, so above it a
/// trial that lowers corner_excess wins even if it lowers the worst (never below the level).
bool optimise_node(Work& w, std::span<const int> around, int i, double trade_above = 1e300,
                   double first_step = kImproveStep, double min_step = kImproveMinStep) {
  constexpr int kMaxSteps = 40;  // trial rounds
  NodeSearch search(w, around, i, trade_above);
  double len, shortest;
  edge_lengths(w, around, i, len, shortest);
  // the scaled Jacobian does not see size: a search for it alone can collapse an edge
  search.floor = std::min(kImproveShortest * len, shortest);
  // no move takes an element further from the surface than the tolerance (or than it was)
  search.sag_limit = std::max(largest_sag(w, around), w.o.chordal_tolerance);
  double step = first_step * len;
  Place at = w.place_at(w.uv[i]);
  at.p = w.xyz[i];  // as stored (a loop node's may differ by round-off)
  const Vec3 start_normal = w.normal[i];
  bool moved = false;
  for (int round = 0; round < kMaxSteps && step >= min_step * len; ++round) {
    const Vec3 nn = at.su.cross(at.sv);
    if (nn.norm() <= 0 || at.su.norm() <= 0) break;
    const Vec3 t1 = at.su.normalized(), t2 = nn.normalized().cross(t1);
    // the sag (a surface evaluation per element) is checked after the trials, from the last
    // better one back, so mostly once
    std::array<NodeSearch::Better, 8> better;
    const double round_best = search.best, round_excess = search.best_excess;
    const int nb = search.trials(at, step, t1, t2, better);
    Place to = at;
    search.best = round_best, search.best_excess = round_excess;
    for (int b = nb - 1; b >= 0; --b) {
      w.put(i, better[b].x);
      if (largest_sag(w, around) > search.sag_limit) continue;
      to = better[b].x, search.best = better[b].now, search.best_excess = better[b].excess;
      break;
    }
    if ((to.uv - at.uv).squaredNorm() > 0) {
      moved = true;
      at = to;
    } else {
      step *= 0.5;
    }
    w.put(i, at);
    if (!moved) w.normal[i] = start_normal;  // bit for bit where it was
  }
  return moved;
}

/// Max-min node optimisation (after Freitag & Plassmann 2000): each free node of an element
/// scoring below kImproveBelow (strict_quality in space) moves by a compass search in its
/// tangent plane, every trial put back onto the face, to where the worst of its elements
/// scores highest. A move is kept only when it raises that worst (and keeps the node's edges
/// above kImproveShortest x their mean), so no element gets worse than its neighbourhood's
/// worst; it untangles the folded elements the Laplacian step cannot.
std::vector<double> strict_qualities(const Work& w) {
  std::vector<double> q(w.el.size());
  for (size_t e = 0; e < w.el.size(); ++e) q[e] = w.strict_quality(w.el[e]);
  return q;
}

/// Flags the nodes of every element whose score (q, per element) is below `below`.
std::vector<char> nodes_scoring_below(const Work& w, const std::vector<double>& q, double below) {
  std::vector<char> poor(w.xyz.size(), 0);
  for (size_t e = 0; e < w.el.size(); ++e)
    if (q[e] < below)
      for (int k = 0; k < (w.el[e][3] < 0 ? 3 : 4); ++k) poor[w.el[e][k]] = 1;
  return poor;
}

/// `q`: each element's strict_quality if the caller has them (else computed here), kept
/// current: only a moved node's elements change (a search that does not move its node leaves
/// it bit for bit where it was).
void improve_worst(Work& w, double below = kImproveBelow, double first_step = kImproveStep,
                   double min_step = kImproveMinStep, std::vector<double> q = {}) {
  const int n = static_cast<int>(w.xyz.size());
  const ElementsAtNodes around(w);
  Settled settled(w, around);
  if (q.size() != w.el.size()) q = strict_qualities(w);
  for (int pass = 0; pass < kImprovePasses; ++pass) {
    const std::vector<char> poor = nodes_scoring_below(w, q, below);
    int moved = 0;
    for (int i = w.fixed; i < n; ++i) {
      if (!poor[i] || around[i].empty() || settled[i]) continue;
      const bool m = optimise_node(w, around[i], i, 1e300, first_step, min_step);
      if (m)
        for (int e : around[i]) q[e] = w.strict_quality(w.el[e]);
      moved += m;
      settled.visited(i, m);
    }
    if (!moved) break;
  }
}

/// The last pass: the nodes of the worst elements (within kPolishBand of the worst) searched
/// again, from twice the searches' last step down to a finer one, kPolishMinStep: that last
/// step leaves a node up to 0.04 of an edge from where its worst element peaks, and the worst
/// search does not look at elements above kImproveBelow.
void polish(Work& w) {
  std::vector<double> q = strict_qualities(w);
  double worst = 1e9;
  for (double x : q) worst = std::min(worst, x);
  improve_worst(w, worst + kPolishBand, 2 * kImproveMinStep, kPolishMinStep, std::move(q));
}

/// Triangles the node passes left as slivers (w.quality below kPairFlipBelow): the pair (a, b, c)
/// + (b, a, d) across a side ab is re-paired across cd, (a, d, c) + (d, b, c), where that raises
/// the pair's worst quality (valid in space and in the parameters: w.quality). The triangulation's
/// swaps judged the nodes where they were first placed; the passes moved them since (the example
/// ship's blend at 1.5 m kept a 155-deg triangle, scaled Jacobian 0.19, on the centre plane above
/// the bulb). Returns whether any pair was flipped.
bool flip_sliver_pairs(Work& w) {
  const long long n = static_cast<long long>(w.xyz.size());
  std::unordered_map<long long, int> side;  // directed side a -> b of a triangle -> its element
  auto sides = [&](int e, bool add) {
    for (int j = 0; j < 3; ++j) {
      const long long key = w.el[e][j] * n + w.el[e][(j + 1) % 3];
      if (add) side[key] = e;
      else side.erase(key);
    }
  };
  for (int e = 0; e < static_cast<int>(w.el.size()); ++e)
    if (w.el[e][3] < 0) sides(e, true);
  bool any = false;
  for (int t = 0; t < static_cast<int>(w.el.size()); ++t) {
    if (w.el[t][3] >= 0 || w.quality(w.el[t]) >= kPairFlipBelow) continue;
    for (int k = 0; k < 3; ++k) {
      const int a = w.el[t][k], b = w.el[t][(k + 1) % 3], c = w.el[t][(k + 2) % 3];
      const auto it = side.find(b * n + a);
      if (it == side.end()) continue;  // no triangle across: a quad, or the face's boundary
      const int u = it->second;
      int d = -1;
      for (int j = 0; j < 3; ++j)
        if (w.el[u][j] != a && w.el[u][j] != b) d = w.el[u][j];
      if (side.count(c * n + d) || side.count(d * n + c)) continue;  // cd is a side already
      const std::array<int, 4> t1{a, d, c, -1}, u1{d, b, c, -1};
      const double before = std::min(w.quality(w.el[t]), w.quality(w.el[u]));
      if (!(std::min(w.quality(t1), w.quality(u1)) > before + kPairFlipGain)) continue;
      sides(t, false), sides(u, false);
      w.el[t] = t1, w.el[u] = u1;
      sides(t, true), sides(u, true);
      any = true;
      break;
    }
  }
  return any;
}

/// The corner pass, after the weak pairs are merged (their quads' corners at the 2:1 steps lie
/// near 135-160 deg, and the search for the worst element stops once nothing about a node can
/// rise): each free node of a quad with a corner outside kCornerLimit..180 - kCornerLimit deg
/// moves by optimise_node with trade_above = kCornerTrade, so above that level its quads'
/// corners move toward 90 deg even where a neighbour's score drops a little; no element about
/// the node drops below the lower of kCornerTrade and the worst there before. Without the
/// trade, a valence-3 node at a step (two fine quads and a merged one) cannot spread its
/// corners to about 120 deg each: the fine quads' corners there get worse as it moves.
void improve_corners(Work& w) {
  const int n = static_cast<int>(w.xyz.size());
  const ElementsAtNodes around(w);
  const double out = std::cos(kCornerLimit * kPi / 180.0);
  Settled settled(w, around);
  for (int pass = 0; pass < kImprovePasses; ++pass) {
    std::vector<char> poor(n, 0);
    for (const auto& e : w.el) {
      if (e[3] < 0) continue;
      bool bad = false;
      for (int c = 0; c < 4; ++c) bad = bad || corner_cos(w, e, c) > out;
      if (bad)
        for (int k = 0; k < 4; ++k) poor[e[k]] = 1;
    }
    int moved = 0;
    for (int i = w.fixed; i < n; ++i) {
      if (!poor[i] || around[i].empty() || settled[i]) continue;
      const bool m = optimise_node(w, around[i], i, kCornerTrade);
      moved += m;
      settled.visited(i, m);
    }
    if (!moved) break;
  }
}

/// Where node i would make each of its elements ideal, averaged: a quad (i, a, o, b) a
/// rectangle, i on the circle with diameter ab across from o (a right corner at i, the
/// diagonals io and ab of one length); a triangle (i, a, b) equilateral, i on its side of ab
/// in the plane normal to n. (The parallelogram a + b - o kept the sheared quads as they were.)
Vec3 ideal_position(const Work& w, std::span<const int> around, int i, const Vec3& n) {
  Vec3 sum = Vec3::Zero();
  for (int e : around) {
    const auto& q = w.el[e];
    const int k = q[3] < 0 ? 3 : 4;
    int c = 0;
    while (c < k - 1 && q[c] != i) ++c;
    const Vec3 &a = w.xyz[q[(c + 1) % k]], &b = w.xyz[q[(c + k - 1) % k]];
    const Vec3 m = 0.5 * (a + b);
    const Vec3 d = k == 4 ? Vec3(m - w.xyz[q[(c + 2) % 4]]) : Vec3(n.cross(b - a));
    const double len = d.norm(), reach = (k == 4 ? 0.5 : 0.5 * std::sqrt(3.0)) * (b - a).norm();
    if (!(len > 0)) {
      sum += w.xyz[i];
      continue;
    }
    // a triangle's apex on the node's side of ab
    const double side = k == 3 && d.dot(w.xyz[i] - m) < 0 ? -1.0 : 1.0;
    sum += m + (side * reach / len) * d;
  }
  return sum / static_cast<double>(around.size());
}

/// Whether the elements `around` node i (just moved from old_uv, old_p, old_n) sag within the
/// chordal tolerance, or no more than before the move (evaluated only then: rarely needed).
bool sags_within(Work& w, std::span<const int> around, int i, const Vec2& old_uv, const Vec3& old_p, const Vec3& old_n) {
  const double now = largest_sag(w, around);
  if (now <= w.o.chordal_tolerance) return true;
  const Vec2 uv = w.uv[i];
  const Vec3 p = w.xyz[i], n = w.normal[i];
  w.uv[i] = old_uv, w.xyz[i] = old_p, w.normal[i] = old_n;
  const double before = largest_sag(w, around);
  w.uv[i] = uv, w.xyz[i] = p, w.normal[i] = n;
  return now <= before;
}

/// Moves node i toward `target` (on its tangent plane), all the way or by kMeanTries halvings,
/// onto the face where that lowers the sum of its elements' deficits (1 - strict quality)
/// without lowering their worst, shortening an edge below `floor` or sagging an element beyond
/// the tolerance (or than before). `q`: the elements' scores, kept current; true if it moved.
bool move_for_mean(Work& w, std::span<const int> around, int i, const Place& here, const Vec3& target, double floor,
                   std::vector<double>& q) {
  double worst = 1e9, deficit = 0.0;
  for (int e : around) worst = std::min(worst, q[e]), deficit += 1.0 - q[e];
  const Vec2 old_uv = w.uv[i];
  const Vec3 old_p = w.xyz[i], old_n = w.normal[i];
  std::array<double, 16> now;  // a node of more elements is not moved
  if (around.size() > now.size()) return false;
  double f = 1.0;
  for (int t = 0; t < kMeanTries; ++t, f *= 0.5) {
    const Place x = w.toward(here, old_p + f * (target - old_p));
    if ((x.uv - old_uv).squaredNorm() == 0.0) return false;
    w.put(i, x);
    double sum = 0.0;
    bool ok = true;
    for (size_t k = 0; k < around.size() && ok; ++k) {
      now[k] = w.strict_quality(w.el[around[k]]);
      sum += 1.0 - now[k];
      ok = now[k] + kMeanScoreSlack >= worst;
    }
    if (ok && sum < deficit - kMeanMinGain && shortest_edge(w, around, i) >= floor && sags_within(w, around, i, old_uv, old_p, old_n)) {
      for (size_t k = 0; k < around.size(); ++k) q[around[k]] = now[k];
      return true;
    }
    w.uv[i] = old_uv, w.xyz[i] = old_p, w.normal[i] = old_n;
  }
  return false;
}

/// The mean pass, before the corner pass: each free node of an element scoring below
/// kMeanBelow moves toward ideal_position where that raises the sum of its elements' scores
/// (move_for_mean). The searches raise the worst element and the corners outside 45-135 deg
/// only; the quads about the 2:1 steps of the subdivision (valence 3 and 5 nodes, 2:1 sides)
/// were left sheared at 0.7-0.9, most of what the bare hull's mean lost. One surface
/// evaluation per try, not a compass search's dozens (that raised the mean as far at 2.5 x the
/// time).
void improve_mean(Work& w) {
  const int n = static_cast<int>(w.xyz.size());
  const ElementsAtNodes around(w);
  Settled settled(w, around);
  std::vector<double> q = strict_qualities(w);
  for (int pass = 0; pass < kMeanPasses; ++pass) {
    const std::vector<char> poor = nodes_scoring_below(w, q, kMeanBelow);
    int moved = 0;
    for (int i = w.fixed; i < n; ++i) {
      if (!poor[i] || around[i].empty() || settled[i]) continue;
      double len, shortest;
      edge_lengths(w, around[i], i, len, shortest);
      const Place here = w.place_at(w.uv[i]);
      const Vec3 nn = Work::unit_normal(here.su, here.sv);
      Vec3 target = ideal_position(w, around[i], i, nn);
      target -= (target - w.xyz[i]).dot(nn) * nn;
      const bool m = move_for_mean(w, around[i], i, here, target, std::min(kImproveShortest * len, shortest), q);
      moved += m;
      settled.visited(i, m);
    }
    if (!moved) break;
  }
}

/// The hexagon about free node c whose three elements `at` are quads (c, s, f, s'), chained
/// s' = the next one's s: s f s' f' ... counter-clockwise as the quads are; false if not so.
bool hexagon_about(const Work& w, const std::vector<int>& at, int c, std::array<int, 6>& hex) {
  std::array<std::array<int, 3>, 3> sfs;
  for (int k = 0; k < 3; ++k) {
    const auto& q = w.el[at[k]];
    if (q[3] < 0) return false;
    int j = 0;
    while (j < 3 && q[j] != c) ++j;
    sfs[k] = {q[(j + 1) % 4], q[(j + 2) % 4], q[(j + 3) % 4]};
  }
  int k = 0;
  for (int m = 0; m < 3; ++m) {
    hex[2 * m] = sfs[k][0], hex[2 * m + 1] = sfs[k][1];
    int next = -1;
    for (int x = 0; x < 3; ++x)
      if (sfs[x][0] == sfs[k][2]) next = x;
    if (next < 0 || (m < 2 ? next == 0 : next != 0)) return false;
    k = next;
  }
  return true;
}

/// Whether an element of `at` (the elements at node a) has the side a-b.
bool joined(const Work& w, const std::vector<int>& at, int a, int b) {
  for (int e : at) {
    const auto& q = w.el[e];
    const int k = q[3] < 0 ? 3 : 4;
    for (int c = 0; c < k; ++c)
      if (q[c] == a && (q[(c + 1) % k] == b || q[(c + k - 1) % k] == b)) return true;
  }
  return false;
}

/// A trial edit about some nodes: the live elements about them (to judge the worst there) and
/// the free nodes' positions (to put back if the edit is undone).
struct LocalEdit {
  std::vector<int> touched;
  std::vector<std::tuple<int, Vec2, Vec3, Vec3>> saved;  // (node, uv, xyz, normal)
  template <class Nodes, class Live>
  LocalEdit(const Work& w, const Nodes& nodes, const Live& live) {
    for (int x : nodes)
      for (int e : live(x)) touched.push_back(e);
    std::sort(touched.begin(), touched.end());
    touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
    for (int x : nodes)
      if (x >= w.fixed) saved.push_back({x, w.uv[x], w.xyz[x], w.normal[x]});
  }
  /// The worst strict quality of the touched elements still alive.
  double worst(const Work& w) const {
    double q = 1e9;
    for (int e : touched)
      if (w.el[e][0] != -2) q = std::min(q, w.strict_quality(w.el[e]));
    return q;
  }
  void restore(Work& w) const {
    for (const auto& [x, uv, xyz, nn] : saved) w.uv[x] = uv, w.xyz[x] = xyz, w.normal[x] = nn;
  }
};

/// The elements at each node while a pass edits them: the lists only grow (an edit's elements
/// are added to their nodes), and an element counts at a node while it holds it.
class EditedElementsAtNodes {
 public:
  explicit EditedElementsAtNodes(const Work& w) : w_(w), around_(elements_at_nodes(w)) {}
  std::vector<int> live(int node) const {
    std::vector<int> r;
    for (int e : around_[node])
      if (std::find(w_.el[e].begin(), w_.el[e].end(), node) != w_.el[e].end()) r.push_back(e);
    return r;
  }
  void add(int node, int e) {
    if (std::find(around_[node].begin(), around_[node].end(), e) == around_[node].end()) around_[node].push_back(e);
  }

 private:
  const Work& w_;
  std::vector<std::vector<int>> around_;
};

/// Free nodes with exactly three elements, all quads, scoring below kHexBelow are removed
/// where two quads do better: the three quads about such a node c are a hexagon, split here
/// along the diagonal (a spoke to the far corner across) whose quads score best; the hexagon's
/// free nodes are then searched (optimise_node), and the split kept where its quads' worst beats
/// the three's by kHexGain and no element about the hexagon falls below the worst there before.
/// At a corner of the face's boundary the matching can leave the corner node with two quads
/// meeting at c, each with half the corner's angle (the bilge patch's 86 deg corner: two 43 deg
/// corners, scaled Jacobian 0.68 at most wherever c is); one quad takes the corner then.
/// Returns whether a node was removed (the caller compacts the nodes).
bool remove_valence3_nodes(Work& w) {
  const int n = static_cast<int>(w.xyz.size());
  EditedElementsAtNodes at_nodes(w);  // a split's quads are added to their nodes
  auto live = [&](int node) { return at_nodes.live(node); };
  auto add = [&](int node, int e) { at_nodes.add(node, e); };
  bool removed = false;
  for (int c = w.fixed; c < n; ++c) {
    const std::vector<int> at = live(c);
    std::array<int, 6> hex;
    if (at.size() != 3 || !hexagon_about(w, at, c, hex)) continue;
    double before3 = 1e9;
    for (int e : at) before3 = std::min(before3, w.strict_quality(w.el[e]));
    // only next to the boundary (a spoke on it): inside, the valence-3 nodes are the 2:1 steps'
    // middle nodes, which the corner pass spreads (removing them there cost 22 % more time on
    // the bare hull for a mean 0.0017 higher)
    if (before3 >= kHexBelow || (hex[0] >= w.fixed && hex[2] >= w.fixed && hex[4] >= w.fixed)) continue;
    int best = -1;
    double best_q = -1e9;
    std::array<std::array<int, 4>, 2> split[3];
    for (int d = 0; d < 3; ++d) {
      const auto h = [&](int x) { return hex[(d + x) % 6]; };
      split[d] = {{{h(0), h(1), h(2), h(3)}, {h(3), h(4), h(5), h(0)}}};
      if (joined(w, live(h(0)), h(0), h(3))) continue;
      const double q = std::min(w.quality(split[d][0]), w.quality(split[d][1]));
      if (q > 0 && q > best_q) best = d, best_q = q;
    }
    if (best < 0 || best_q < before3 - kHexReach) continue;
    const LocalEdit edit(w, hex, live);
    const double before = edit.worst(w);
    const std::array<std::array<int, 4>, 3> old{w.el[at[0]], w.el[at[1]], w.el[at[2]]};
    w.el[at[0]] = split[best][0], w.el[at[1]] = split[best][1], w.el[at[2]] = kDeadElement;
    for (int x : split[best][0]) add(x, at[0]);
    for (int x : split[best][1]) add(x, at[1]);
    auto good = [&] {
      return std::min(w.strict_quality(w.el[at[0]]), w.strict_quality(w.el[at[1]])) >= before3 + kHexGain &&
             edit.worst(w) >= before;
    };
    for (const auto& sv : edit.saved) optimise_node(w, live(std::get<0>(sv)), std::get<0>(sv));
    if (good()) {
      removed = true;
      continue;
    }
    // undone: the three quads and the positions back
    for (int k = 0; k < 3; ++k) w.el[at[k]] = old[k];
    edit.restore(w);
  }
  w.el.erase(std::remove(w.el.begin(), w.el.end(), kDeadElement), w.el.end());
  return removed;
}

/// Mean side length (m) of element e.
double mean_side(const Work& w, const std::array<int, 4>& e) {
  const int k = e[3] < 0 ? 3 : 4;
  double sum = 0.0;
  for (int i = 0; i < k; ++i) sum += (w.xyz[e[(i + 1) % k]] - w.xyz[e[i]]).norm();
  return sum / k;
}

/// Elements (quads and triangles) whose mean side is under 1 / kCollapseRatio of a neighbour's
/// (an element sharing a side) in ratio order, the largest first: (ratio, element).
std::vector<std::pair<double, int>> small_elements(const Work& w) {
  std::unordered_map<long long, std::array<int, 2>> sides;  // side (a < b) -> its two elements
  const long long n = static_cast<long long>(w.xyz.size());
  std::vector<double> h(w.el.size());
  for (size_t e = 0; e < w.el.size(); ++e) {
    const auto& q = w.el[e];
    const int k = q[3] < 0 ? 3 : 4;
    h[e] = mean_side(w, q);
    for (int i = 0; i < k; ++i) {
      const long long a = std::min(q[i], q[(i + 1) % k]), b = std::max(q[i], q[(i + 1) % k]);
      auto [it, fresh] = sides.try_emplace(a * n + b, std::array<int, 2>{static_cast<int>(e), -1});
      if (!fresh) it->second[1] = static_cast<int>(e);
    }
  }
  std::vector<double> largest(w.el.size(), 0.0);
  for (const auto& [key, pair] : sides)
    if (pair[1] >= 0) {
      largest[pair[0]] = std::max(largest[pair[0]], h[pair[1]]);
      largest[pair[1]] = std::max(largest[pair[1]], h[pair[0]]);
    }
  std::vector<std::pair<double, int>> out;
  for (size_t e = 0; e < w.el.size(); ++e)
    if (h[e] > 0 && largest[e] > kCollapseRatio * h[e])
      out.push_back({largest[e] / h[e], static_cast<int>(e)});
  std::sort(out.begin(), out.end(), std::greater<>());
  return out;
}

/// The free nodes of the elements at nodes a and b (sorted, each once).
std::vector<int> nodes_about(const Work& w, const EditedElementsAtNodes& at, int a, int b) {
  std::vector<int> out;
  for (int node : {a, b})
    for (int x : at.live(node))
      for (int k = 0; k < 4; ++k)
        if (w.el[x][k] >= 0) out.push_back(w.el[x][k]);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

/// The quad over the outer corners of quads q and r that share the two sides at node x (a
/// doublet: x lies in them alone), oriented as they are; none where they are not such a pair.
std::optional<std::array<int, 4>> doublet_quad(std::array<int, 4> q, std::array<int, 4> r, int x) {
  if (q[3] < 0 || r[3] < 0) return std::nullopt;
  auto from_x = [x](std::array<int, 4>& e) {
    const auto at = std::find(e.begin(), e.end(), x);
    if (at == e.end()) return false;
    std::rotate(e.begin(), at, e.end());
    return true;
  };
  if (!from_x(q) || !from_x(r) || r[1] != q[3] || r[3] != q[1] || r[2] == q[2]) return std::nullopt;
  return std::array<int, 4>{q[1], q[2], q[3], r[2]};
}

/// Whether keep and gone are neighbouring corners of element q.
bool side_of(const std::array<int, 4>& q, int keep, int gone) {
  const int k = q[3] < 0 ? 3 : 4;
  for (int i = 0; i < k; ++i)
    if ((q[i] == keep && q[(i + 1) % k] == gone) || (q[i] == gone && q[(i + 1) % k] == keep)) return true;
  return false;
}

/// Element q without its corner `gone` (a quad becomes a triangle of the same orientation).
std::array<int, 4> without(const std::array<int, 4>& q, int gone) {
  std::array<int, 4> out{-1, -1, -1, -1};
  int k = 0;
  for (int x : q)
    if (x >= 0 && x != gone) out[k++] = x;
  return out;
}

/// One trial of collapse_small_elements: element e's corners `gone` onto `keep` (a quad's
/// diagonal, or a triangle's side, whose other element becomes a triangle or, a triangle,
/// goes too), kept when it scores as the pass asks; else undone. Returns the nodes about it
/// when kept, else none.
std::vector<int> try_collapse(Work& w, EditedElementsAtNodes& at, int e, int keep, int gone, double mesh_worst) {
  auto live = [&](int node) { return at.live(node); };
  const std::vector<int> at_gone = live(gone);
  const bool side = w.el[e][3] < 0;
  for (int x : at_gone)  // another element holding both would fold, unless across a triangle's side
    if (x != e && std::find(w.el[x].begin(), w.el[x].end(), keep) != w.el[x].end() && !(side && side_of(w.el[x], keep, gone)))
      return {};
  const std::vector<int> nodes = nodes_about(w, at, keep, gone);
  const LocalEdit edit(w, nodes, live);
  const double before = edit.worst(w);
  std::vector<std::pair<int, std::array<int, 4>>> old;
  for (int x : at_gone) old.push_back({x, w.el[x]});
  w.el[e] = kDeadElement;
  for (int x : at_gone) {
    if (x == e) continue;
    if (std::find(w.el[x].begin(), w.el[x].end(), keep) != w.el[x].end()) {  // across the side
      w.el[x] = w.el[x][3] < 0 ? kDeadElement : without(w.el[x], gone);
      continue;
    }
    std::replace(w.el[x].begin(), w.el[x].end(), gone, keep);
    at.add(keep, x);
  }
  if (keep >= w.fixed) {
    const Vec3 mid = 0.5 * (w.xyz[keep] + w.xyz[gone]);
    w.put(keep, w.place_at(w.g.locate(mid, 0.5 * (w.uv[keep] + w.uv[gone]))));
  }
  // A free node the collapse leaves in two quads goes with them: they become one quad.
  std::vector<std::pair<int, std::array<int, 4>>> merged;
  for (int x : nodes) {
    const std::vector<int> two = x != gone && x >= w.fixed ? live(x) : std::vector<int>{};
    if (two.size() != 2) continue;
    if (const auto quad = doublet_quad(w.el[two[0]], w.el[two[1]], x)) {
      merged.push_back({two[0], w.el[two[0]]}), merged.push_back({two[1], w.el[two[1]]});
      w.el[two[0]] = *quad, w.el[two[1]] = kDeadElement;
      for (int n : *quad) at.add(n, two[0]);
    }
  }
  bool ok = std::none_of(nodes.begin(), nodes.end(), [&](int x) {
    const size_t n = live(x).size();
    return x != gone && x >= w.fixed && n > 0 && n < 3;
  });
  if (ok) {
    for (const auto& sv : edit.saved) {
      const int node = std::get<0>(sv);
      const std::vector<int> around = node != gone ? live(node) : std::vector<int>{};
      if (!around.empty()) optimise_node(w, around, node);  // a merged doublet's node has none
    }
    ok = edit.worst(w) >= std::max({kCollapseFloor, before - kCollapseTrade, mesh_worst});
  }
  if (ok) return nodes;
  for (auto it = merged.rbegin(); it != merged.rend(); ++it) w.el[it->first] = it->second;
  for (const auto& [x, el] : old) w.el[x] = el;
  edit.restore(w);
  return {};
}

/// Elements much smaller than a neighbour (small_elements) are collapsed: a quad across a
/// diagonal, its two ends a, c becoming one node (at their middle on the face, or at the fixed
/// one); a triangle along a side, shortest first, the element across it losing that corner (a
/// 0.17 m triangle beside a 0.68 m quad where a designed coaster's keel leaves the water). The
/// element goes, and the free nodes about it are searched (optimise_node); a free node left in
/// two quads goes with them, which become one quad (doublet_quad: refusing that collapse left a
/// 0.17 m quad among 0.6 m ones). Kept where no free node is left in one or two elements and the
/// elements about it score at least kCollapseFloor, their worst before less kCollapseTrade, and
/// the face's worst before the pass; else undone. The quad's diagonal whose ends have fewer
/// elements is tried first (two valence-3 corners make one regular node). Returns whether an
/// element went (the caller compacts the nodes).
bool collapse_small_elements(Work& w) {
  EditedElementsAtNodes at(w);  // the kept node takes its partner's elements
  std::vector<char> touched(w.xyz.size(), 0);
  bool collapsed = false;
  double mesh_worst = 1e9;  // no collapse makes the face's worst element worse
  for (const auto& e : w.el) mesh_worst = std::min(mesh_worst, w.strict_quality(e));
  for (const auto& [ratio, e] : small_elements(w)) {
    const std::array<int, 4> el = w.el[e];
    if (el == kDeadElement || std::any_of(el.begin(), el.end(), [&](int x) { return x >= 0 && touched[x] != 0; }))
      continue;
    std::vector<std::pair<int, int>> pairs;  // (keep, gone) candidates in the order tried
    if (el[3] >= 0) {  // a quad: across a diagonal
      auto valence = [&](int d) { return at.live(el[d]).size() + at.live(el[d + 2]).size(); };
      for (int d : valence(1) < valence(0) ? std::array<int, 2>{1, 0} : std::array<int, 2>{0, 1})
        pairs.push_back({el[d], el[d + 2]});
    } else {  // a triangle: along a side, the shortest first
      for (int i = 0; i < 3; ++i) pairs.push_back({el[i], el[(i + 1) % 3]});
      auto length = [&](const std::pair<int, int>& p) { return (w.xyz[p.first] - w.xyz[p.second]).squaredNorm(); };
      std::sort(pairs.begin(), pairs.end(), [&](const auto& a, const auto& b) { return length(a) < length(b); });
    }
    for (auto [keep, gone] : pairs) {
      if (keep < w.fixed && gone < w.fixed) continue;
      if (gone < w.fixed) std::swap(keep, gone);
      const std::vector<int> nodes = try_collapse(w, at, e, keep, gone, mesh_worst);
      if (nodes.empty()) continue;
      for (int x : nodes) touched[x] = 1;
      collapsed = true;
      break;
    }
  }
  w.el.erase(std::remove(w.el.begin(), w.el.end(), kDeadElement), w.el.end());
  return collapsed;
}

/// Drops the free nodes no element uses (removed by remove_valence3_nodes, collapse_small_elements),
/// renumbering the rest.
void compact_nodes(Work& w) {
  std::vector<int> to(w.xyz.size(), -1);
  for (const auto& e : w.el)
    for (int k = 0; k < (e[3] < 0 ? 3 : 4); ++k) to[e[k]] = 0;
  for (int i = 0; i < w.fixed; ++i) to[i] = i;
  int next = w.fixed;
  for (size_t i = w.fixed; i < to.size(); ++i)
    if (to[i] >= 0) {
      to[i] = next;
      w.xyz[next] = w.xyz[i], w.uv[next] = w.uv[i], w.normal[next] = w.normal[i];
      ++next;
    }
  w.xyz.resize(next), w.uv.resize(next), w.normal.resize(next);
  for (auto& e : w.el)
    for (int k = 0; k < (e[3] < 0 ? 3 : 4); ++k) e[k] = to[e[k]];
}

/// Canonical local id of every node: a pole's copies along its parameter edge (consecutive
/// loop nodes with one global id) map to the first copy.
std::vector<int> pole_canon(const std::vector<LoopNode>& loop, size_t nodes) {
  const int nb = static_cast<int>(loop.size());
  std::vector<int> canon(nodes);
  for (size_t i = 0; i < nodes; ++i) canon[i] = static_cast<int>(i);
  int start = 0;  // a run of copies may wrap round the loop's start
  while (start < nb && loop[start].id == loop[(start + nb - 1) % nb].id) ++start;
  if (start == nb) return canon;
  for (int k = 1; k < nb; ++k) {
    const int i = (start + k) % nb, prev = (start + k - 1) % nb;
    if (loop[i].id == loop[prev].id) canon[i] = canon[prev];
  }
  return canon;
}

/// The longest side (corner k to k + 1) of triangle t, and whether t is flat (kFlat).
bool flat_triangle(const std::vector<Vec3>& xyz, const std::array<int, 3>& t, int& k) {
  double longest = 0.0;
  k = 0;
  for (int j = 0; j < 3; ++j) {
    const double l = (xyz[t[(j + 1) % 3]] - xyz[t[j]]).squaredNorm();
    if (l > longest) longest = l, k = j;
  }
  return (xyz[t[1]] - xyz[t[0]]).cross(xyz[t[2]] - xyz[t[0]]).norm() <= kFlat * longest;
}

/// Directed edge a -> b of triangles indexed by their N nodes -> the triangle holding it.
struct HalfEdges {
  long long n;
  std::unordered_map<long long, int> at;
  void set(const std::array<int, 3>& t, int i) {
    for (int j = 0; j < 3; ++j) at[t[j] * n + t[(j + 1) % 3]] = i;
  }
};

/// Flips the longest side p -> q of flat triangle t = (p, q, m) with the triangle u = (q, p, x)
/// across it, (p, q, m) + (q, p, x) -> (p, x, m) + (x, q, m) (the orientation kept, as in
/// Triangulation's flips), where that raises the pair's least angle and both new triangles
/// turn the way u does (valid in space). Returns whether it flipped.
bool flip_flat(const std::vector<Vec3>& xyz, std::vector<std::array<int, 3>>& tri, HalfEdges& half, int t) {
  int k = 0;
  if (!flat_triangle(xyz, tri[t], k)) return false;
  const int p = tri[t][k], q = tri[t][(k + 1) % 3], m = tri[t][(k + 2) % 3];
  const auto it = half.at.find(q * half.n + p);
  if (it == half.at.end()) return false;  // no triangle across: the face's boundary
  const int u = it->second;
  int x = -1;
  for (int j = 0; j < 3; ++j)
    if (tri[u][j] != p && tri[u][j] != q) x = tri[u][j];
  if (half.at.count(m * half.n + x) || half.at.count(x * half.n + m)) return false;  // m-x is an edge already
  const Vec3 &P = xyz[p], &Q = xyz[q], &M = xyz[m], &X = xyz[x];
  const double before = std::min(min_angle(P, Q, M), min_angle(Q, P, X));
  const double after = std::min(min_angle(P, X, M), min_angle(X, Q, M));
  const Vec3 n = (P - Q).cross(X - Q);  // u's turn
  if (!(after > before) || (X - P).cross(M - P).dot(n) <= 0 || (Q - X).cross(M - X).dot(n) <= 0) return false;
  half.at.erase(p * half.n + q);  // the flipped side is no triangle's any more
  half.at.erase(q * half.n + p);
  tri[t] = {p, x, m};
  tri[u] = {x, q, m};
  half.set(tri[t], t);
  half.set(tri[u], u);
  return true;
}

}  // namespace

std::vector<std::array<int, 3>> merged_triangles(const std::vector<Vec3>& xyz, const std::vector<std::array<int, 3>>& in,
                                                 const std::vector<int>& canon) {
  std::vector<std::array<int, 3>> tri;
  for (const auto& t : in) {
    const std::array<int, 3> r{canon[t[0]], canon[t[1]], canon[t[2]]};
    if (r[0] != r[1] && r[1] != r[2] && r[2] != r[0]) tri.push_back(r);
  }
  int k = 0;
  bool any = false;
  for (const auto& t : tri) any = any || flat_triangle(xyz, t, k);
  if (!any) return tri;  // none (no pole): nothing to flip
  HalfEdges half{static_cast<long long>(xyz.size()), {}};
  for (int t = 0; t < static_cast<int>(tri.size()); ++t) half.set(tri[t], t);
  // a flat triangle's neighbour may be flat too (a row of straight stem nodes at the pole):
  // flipping the outer one makes the inner one's neighbour a proper triangle, so repeat
  for (int pass = 0; pass < kFlatPasses; ++pass) {
    bool flipped = false;
    for (int t = 0; t < static_cast<int>(tri.size()); ++t) flipped = flip_flat(xyz, tri, half, t) || flipped;
    if (!flipped) break;
  }
  return tri;
}

namespace {

/// A quad left folded (strict_quality in space <= 0: about the surface's normals or its own
/// diagonal one, the census's measure) is cut into two triangles along the diagonal that gives
/// the better pair. Judged in space: where the parametrisation shears across a knot a convex
/// quad on the surface can have a reflex corner in (u, v).
void split_folded_quads(Work& w) {
  std::vector<std::array<int, 4>> out;
  for (const auto& e : w.el) {
    if (e[3] < 0 || w.strict_quality(e) > 0) {
      out.push_back(e);
      continue;
    }
    const std::array<int, 4> a{e[0], e[1], e[2], -1}, b{e[0], e[2], e[3], -1}, c{e[0], e[1], e[3], -1}, d{e[1], e[2], e[3], -1};
    const bool first = std::min(w.quality(a), w.quality(b)) >= std::min(w.quality(c), w.quality(d));
    out.push_back(first ? a : c);
    out.push_back(first ? b : d);
  }
  w.el = std::move(out);
}

/// Scaled Jacobian of quad e's corner at node i (about the quad's diagonal normal).
double corner_quality(const Work& w, const std::array<int, 4>& e, int i) {
  int c = 0;
  while (c < 3 && e[c] != i) ++c;
  const Vec3 n = (w.xyz[e[2]] - w.xyz[e[0]]).cross(w.xyz[e[3]] - w.xyz[e[1]]);
  const Vec3 a = w.xyz[e[(c + 1) % 4]] - w.xyz[i], b = w.xyz[e[(c + 3) % 4]] - w.xyz[i];
  const double l = a.norm() * b.norm() * n.norm();
  return l > 0 ? a.cross(b).dot(n) / l : -1.0;
}

/// A triangle pair matched only below min_quad_quality: its two elements and its quad.
struct WeakPair {
  int t1, t2;
  std::array<int, 4> quad;
};

/// Each weak pair (a quad across a 2:1 step of the subdivision, with a straight corner at the
/// step's middle node) is merged into its quad where a max-min search of the quad's free nodes
/// (optimise_node) raises it to min_quad_quality and leaves every element about its nodes at
/// least as good as the worst there before (or at min_quad_quality); else it stays two triangles.
void merge_weak_pairs(Work& w, const std::vector<WeakPair>& pairs) {
  std::vector<std::vector<int>> around = elements_at_nodes(w);
  auto live = [&](int node) {
    std::vector<int> r;
    for (int e : around[node])
      if (w.el[e][0] != -2) r.push_back(e);
    return r;
  };
  for (const WeakPair& p : pairs) {
    LocalEdit edit(w, p.quad, live);
    const double before = edit.worst(w);
    auto& saved = edit.saved;
    const std::array<int, 4> e1 = w.el[p.t1], e2 = w.el[p.t2];
    w.el[p.t1] = p.quad;
    w.el[p.t2] = kDeadElement;
    for (int node : p.quad) around[node].push_back(p.t1);
    // the quad's free nodes, its worst corner's first (the step's middle node), until it is good
    std::sort(saved.begin(), saved.end(), [&](const auto& a, const auto& b) {
      return corner_quality(w, p.quad, std::get<0>(a)) < corner_quality(w, p.quad, std::get<0>(b));
    });
    auto good = [&] {
      return w.strict_quality(p.quad) >= w.o.min_quad_quality && edit.worst(w) >= std::min(before, w.o.min_quad_quality);
    };
    bool merged = false;
    for (int sweep = 0; sweep < 2 && !merged; ++sweep)
      for (size_t k = 0; k < saved.size() && !merged; ++k) {
        optimise_node(w, live(std::get<0>(saved[k])), std::get<0>(saved[k]));
        merged = good();
      }
    if (merged) continue;
    w.el[p.t1] = e1;
    w.el[p.t2] = e2;
    edit.restore(w);
  }
  w.el.erase(std::remove(w.el.begin(), w.el.end(), kDeadElement), w.el.end());
}

/// point_in_polygon against the sides that span q's v only: the polygon's v range is cut into
/// slabs and each side listed in the slabs its v range touches, so a query tests a few sides
/// instead of all (the crossing test and so the answer are point_in_polygon's).
class PolygonSlabs {
 public:
  explicit PolygonSlabs(const std::vector<Vec2>& poly) : poly_(poly) {
    const int n = static_cast<int>(poly.size());
    lo_ = hi_ = poly[0].y();
    for (const Vec2& q : poly) lo_ = std::min(lo_, q.y()), hi_ = std::max(hi_, q.y());
    count_ = std::max(1, n / 2);
    width_ = (hi_ - lo_) / count_;
    slab_.resize(count_);
    for (int i = 0, j = n - 1; i < n; j = i++)
      for (int k = slab(std::min(poly[i].y(), poly[j].y())); k <= slab(std::max(poly[i].y(), poly[j].y())); ++k)
        slab_[k].push_back({i, j});
  }
  bool inside(const Vec2& q) const {
    if (!(q.y() >= lo_ && q.y() <= hi_)) return false;  // no side spans it: an even count
    bool in = false;
    for (const auto& [i, j] : slab_[slab(q.y())]) {
      const Vec2 &a = poly_[i], &c = poly_[j];
      if ((a.y() > q.y()) != (c.y() > q.y()) && q.x() < (c.x() - a.x()) * (q.y() - a.y()) / (c.y() - a.y()) + a.x())
        in = !in;
    }
    return in;
  }

 private:
  int slab(double y) const {
    return width_ > 0 ? std::clamp(static_cast<int>(std::floor((y - lo_) / width_)), 0, count_ - 1) : 0;
  }
  const std::vector<Vec2>& poly_;
  double lo_, hi_, width_;
  int count_;
  std::vector<std::vector<std::pair<int, int>>> slab_;
};

/// min(h, hb_i + kGrading |p - x_i|) over the loop nodes x_i (hb_i > 0: the node's longer
/// side), the size graded from the boundary. The nodes are bucketed in cubes of `reach`: with
/// h <= kGrading x reach (the largest size), a node farther than that cannot lower h, so only
/// the 27 cubes about p are searched (the same minimum as over all nodes).
class GradedSize {
 public:
  GradedSize(const std::vector<Vec3>& x, const std::vector<double>& hb, double reach)
      : x_(x), hb_(hb), reach_(reach) {
    for (size_t i = 0; i < hb.size(); ++i)
      if (hb[i] > 0) cells_[key(cell(x[i]))].push_back(static_cast<int>(i));
  }
  double operator()(const Vec3& p, double h) const {
    const std::array<long long, 3> c = cell(p);
    if (!near_valid_ || c != near_cell_) gather(c);
    for (int i : near_) h = std::min(h, hb_[i] + kGrading * (p - x_[i]).norm());
    return h;
  }

 private:
  std::array<long long, 3> cell(const Vec3& p) const {
    return {static_cast<long long>(std::floor(p.x() / reach_)), static_cast<long long>(std::floor(p.y() / reach_)),
            static_cast<long long>(std::floor(p.z() / reach_))};
  }
  // a hash of the cell: two cells that share one share the bucket, which only adds nodes
  static long long key(const std::array<long long, 3>& c) {
    return (c[0] * 73856093LL) ^ (c[1] * 19349663LL) ^ (c[2] * 83492791LL);
  }
  /// The nodes of the 27 buckets about cell c, in order. The callers' queries come in
  /// neighbourhoods (the subdivision's cells, the nodes as placed), so most queries reuse
  /// the last cell's list instead of looking up 27 buckets.
  void gather(const std::array<long long, 3>& c) const {
    near_.clear();
    for (long long dx = -1; dx <= 1; ++dx)
      for (long long dy = -1; dy <= 1; ++dy)
        for (long long dz = -1; dz <= 1; ++dz) {
          const auto it = cells_.find(key({c[0] + dx, c[1] + dy, c[2] + dz}));
          if (it != cells_.end()) near_.insert(near_.end(), it->second.begin(), it->second.end());
        }
    near_cell_ = c, near_valid_ = true;
  }
  const std::vector<Vec3>& x_;
  const std::vector<double>& hb_;
  double reach_;
  std::unordered_map<long long, std::vector<int>> cells_;
  mutable std::vector<int> near_;  ///< gather's list, for near_cell_
  mutable std::array<long long, 3> near_cell_{};
  mutable bool near_valid_ = false;
};

/// Where the all-quad split puts a new node: the face's point at `uv`, the parameters' mean of
/// the nodes it lies between, while that lies within kSplitSkew x `length` of their spatial
/// mean `target` along the surface (the normal offset is the sag); else the face's point
/// nearest `target` (Newton from `uv`) if it is nearer than that. Where the parameter's speed
/// changes across an element the parameters' mean is not its middle: an edge across a blend's
/// ruled end strip, 0.1 m wide in space and 0.06 of u next to a NURBS 15 m per unit of u, got
/// its midpoint at a tenth of its length, and the split quads there were inverted (scaled
/// Jacobian down to -0.59, four left folded, cut into triangles, in the all-quad cut at 8 m).
Vec2 split_point(const Work& w, const Vec2& uv, const Vec3& target, double length) {
  const Place x = w.place_at(uv);
  const Vec3 n = Work::unit_normal(x.su, x.sv), off = x.p - target;
  if ((off - off.dot(n) * n).norm() <= kSplitSkew * length) return uv;
  // Newton across the strip's speed jump can run off along the other parameter: a centre
  // node 1.6 m from its target, 1.3 edges off, two quads folded, in the all-quad cut at 8 m
  // (fair4's hull). A point further from the target than the mean's is not taken.
  const Vec2 nearest = w.g.locate(target, uv);
  return (w.g.point(nearest) - target).norm() < off.norm() ? nearest : uv;
}

/// Each quad into four and each triangle into three quads (edge midpoints and centre), at
/// split_point.
/// `canon`: canonical local id of each node (pole copies merged).
void split_all_quad(Work& w, const std::vector<int>& canon, int loop_size, const LoopMidpoint& midpoint,
                    std::vector<int>& global) {
  std::unordered_map<long long, int> mid;
  const long long N = static_cast<long long>(w.xyz.size()) + 1;
  std::unordered_map<long long, int> loop_edge;  // canonical end pair -> loop edge index
  for (int i = 0; i < loop_size; ++i) {
    const int a = canon[i], b = canon[(i + 1) % loop_size];
    if (a != b) loop_edge[std::min(a, b) * N + std::max(a, b)] = i;
  }
  auto edge_mid = [&](int a, int b) {
    const long long key = std::min(a, b) * N + std::max(a, b);
    auto it = mid.find(key);
    if (it != mid.end()) return it->second;
    int id;
    const auto on_loop = loop_edge.find(key);
    if (on_loop != loop_edge.end()) {
      const int i = on_loop->second;
      const LoopNode m = midpoint(i);
      w.uv.push_back(m.uv);
      w.xyz.push_back(m.xyz);
      w.normal.push_back(w.surface_normal(m.uv));
      id = static_cast<int>(w.xyz.size()) - 1;
      global.resize(w.xyz.size(), -1);
      global[id] = m.id;
    } else {
      id = w.add(split_point(w, 0.5 * (w.uv[a] + w.uv[b]), 0.5 * (w.xyz[a] + w.xyz[b]), (w.xyz[b] - w.xyz[a]).norm()));
    }
    mid[key] = id;
    return id;
  };
  std::vector<std::array<int, 4>> out;
  std::vector<std::array<int, 4>> el = w.el;
  for (const auto& e : el) {
    const int k = e[3] < 0 ? 3 : 4;
    Vec2 c = Vec2::Zero();
    Vec3 x = Vec3::Zero();
    double longest = 0.0;
    for (int i = 0; i < k; ++i)
      c += w.uv[e[i]], x += w.xyz[e[i]], longest = std::max(longest, (w.xyz[e[(i + 1) % k]] - w.xyz[e[i]]).norm());
    const int centre = w.add(split_point(w, c / k, x / k, longest));
    int m[4];
    for (int i = 0; i < k; ++i) m[i] = edge_mid(e[i], e[(i + 1) % k]);
    for (int i = 0; i < k; ++i) out.push_back({e[i], m[i], centre, m[(i + k - 1) % k]});
  }
  w.el = std::move(out);
  global.resize(w.xyz.size(), -1);
}

}  // namespace

bool point_in_polygon(const Vec2& q, const std::vector<Vec2>& poly) {
  bool in = false;
  const size_t n = poly.size();
  for (size_t i = 0, j = n - 1; i < n; j = i++) {
    const Vec2& a = poly[i];
    const Vec2& c = poly[j];
    if ((a.y() > q.y()) != (c.y() > q.y()) && q.x() < (c.x() - a.x()) * (q.y() - a.y()) / (c.y() - a.y()) + a.x())
      in = !in;
  }
  return in;
}

// ---- FaceGeometry ------------------------------------------------------------------------

Vec3 FaceGeometry::point(const Vec2& q) const {
  if (!surface) return origin + q.x() * ax + q.y() * ay;
  Vec3 p;
  if (const RuledStrip* r = ruled(q.x())) {
    const double t = (q.x() - r->a) / (r->b - r->a);
    p = (1 - t) * surface->evaluate(r->a, q.y()) + t * surface->evaluate(r->b, q.y());
  } else {
    p = surface->evaluate(q.x(), q.y());
  }
  if (clamp_y) p.y() = std::max(p.y(), 0.0);
  return p;
}

void FaceGeometry::first(const Vec2& q, Vec3& p, Vec3& su, Vec3& sv) const {
  if (!surface) {
    p = point(q);
    su = ax;
    sv = ay;
    return;
  }
  double out[9];
  if (const RuledStrip* r = ruled(q.x())) {  // (1 - t) S(u0, v) + t S(u1, v)
    const double t = (q.x() - r->a) / (r->b - r->a);
    double a[9], b[9];
    const double u0 = r->a, u1 = r->b;
    surface->evaluate_first_derivatives_into(&u0, &q.y(), 1, a);
    surface->evaluate_first_derivatives_into(&u1, &q.y(), 1, b);
    for (int k = 0; k < 3; ++k) {
      out[k] = (1 - t) * a[k] + t * b[k];
      out[3 + k] = (b[k] - a[k]) / (u1 - u0);
      out[6 + k] = (1 - t) * a[6 + k] + t * b[6 + k];
    }
  } else {
    surface->evaluate_first_derivatives_into(&q.x(), &q.y(), 1, out);
  }
  p = Vec3(out[0], clamp_y ? std::max(out[1], 0.0) : out[1], out[2]);
  su = Vec3(out[3], out[4], out[5]);
  sv = Vec3(out[6], out[7], out[8]);
}

const FaceGeometry::RuledStrip* FaceGeometry::ruled(double u) const {
  for (const RuledStrip& r : ruled_strips)
    // its outer edge too (the folded end's NURBS normal is wrong there), not the inner one
    if (surface && (u > r.a || (u == r.a && r.a != r.inner)) && (u < r.b || (u == r.b && r.b != r.inner))) return &r;
  return nullptr;
}

double FaceGeometry::curvature_sum(const Vec2& q) const {
  if (!surface) return 0.0;
  // in a ruled strip: the curvature of the surface where the strip joins it
  const RuledStrip* r = ruled(q.x());
  const double u = r ? r->inner : q.x(), v = q.y();
  // second partials by central differences of the first at four points about (u, v), one
  // call for all five and no allocation (NurbsSurface::derivatives allocates and cost about
  // 7 000 instructions, most of the subdivision's time); the stencil stays in the domain
  const auto [u0, u1] = surface->domain_u();
  const auto [v0, v1] = surface->domain_v();
  const double ua = std::max(u0, u - kCurvatureStep * (u1 - u0)), ub = std::min(u1, u + kCurvatureStep * (u1 - u0));
  const double va = std::max(v0, v - kCurvatureStep * (v1 - v0)), vb = std::min(v1, v + kCurvatureStep * (v1 - v0));
  const double us[5] = {u, ua, ub, u, u}, vs[5] = {v, v, v, va, vb};
  double d[45];  // row k: S, S_u, S_v at (us[k], vs[k])
  surface->evaluate_first_derivatives_into(us, vs, 5, d);
  auto at = [&](int k, int part) { return Vec3(d[9 * k + 3 * part], d[9 * k + 3 * part + 1], d[9 * k + 3 * part + 2]); };
  const Vec3 su = at(0, 1), sv = at(0, 2);
  const Vec3 suu = (at(2, 1) - at(1, 1)) / (ub - ua), svv = (at(4, 2) - at(3, 2)) / (vb - va);
  const Vec3 suv = 0.5 * ((at(2, 2) - at(1, 2)) / (ub - ua) + (at(4, 1) - at(3, 1)) / (vb - va));
  Vec3 n = su.cross(sv);
  const double len = n.norm();
  const double E = su.dot(su), F = su.dot(sv), G = sv.dot(sv);
  const double det = E * G - F * F;
  if (len < 1e-12 * std::max(E, G) || det <= 0) return 0.0;
  n /= len;
  const double L = suu.dot(n), M = suv.dot(n), N = svv.dot(n);
  const double K = (L * N - M * M) / det, H = (E * N - 2 * F * M + G * L) / (2 * det);
  return K >= 0 ? 2 * std::abs(H) : 2 * std::sqrt(H * H - K);
}

Vec2 FaceGeometry::clamp(const Vec2& q) const {
  if (!surface) return q;
  const auto [u0, u1] = surface->domain_u();
  const auto [v0, v1] = surface->domain_v();
  return {std::clamp(q.x(), u0, u1), std::clamp(q.y(), v0, v1)};
}

Vec2 FaceGeometry::locate(const Vec3& p, const Vec2& start) const {
  if (!surface) return {(p - origin).dot(ax), (p - origin).dot(ay)};
  Vec2 q = start;
  for (int it = 0; it < 8; ++it) {
    Vec3 s, su, sv;
    first(q, s, su, sv);
    Eigen::Matrix2d A;
    A << su.dot(su), su.dot(sv), su.dot(sv), sv.dot(sv);
    const Vec2 rhs(su.dot(p - s), sv.dot(p - s));
    const Vec2 d = A.ldlt().solve(rhs);
    if (!d.allFinite()) break;
    const Vec2 next = clamp(q + d);
    const double step = (next - q).norm();
    q = next;
    if (step < 1e-13) break;
  }
  return q;
}

// ---- public (internal) functions --------------------------------------------------------

MeshOptions resolved(const MeshOptions& o) {
  if (!(o.size > 0) || !std::isfinite(o.size)) detail::fail("size is ", o.size, "; expected a length > 0 (m)");
  if (!(o.chordal_tolerance >= 0) || !std::isfinite(o.chordal_tolerance))
    detail::fail("chordal_tolerance is ", o.chordal_tolerance, "; expected >= 0 (m; 0: size / 100)");
  if (!(o.min_size >= 0) || !std::isfinite(o.min_size) || o.min_size > o.size)
    detail::fail("min_size is ", o.min_size, "; expected 0 <= min_size <= size (m; 0: size / 20)");
  if (o.smoothing_passes < 0) detail::fail("smoothing_passes is ", o.smoothing_passes, "; expected >= 0");
  if (!(o.min_quad_quality >= 0 && o.min_quad_quality < 1))
    detail::fail("min_quad_quality is ", o.min_quad_quality, "; expected a scaled Jacobian in [0, 1)");
  MeshOptions r = o;
  if (r.chordal_tolerance == 0) r.chordal_tolerance = kDefaultTolerance * r.size;
  if (r.min_size == 0) r.min_size = kDefaultMinSize * r.size;
  return r;
}

double target_size(const FaceGeometry& g, const Vec2& uv, const MeshOptions& o) {
  const double k = g.curvature_sum(uv);
  double h = o.size;
  if (k > 0) h = std::min(h, kCurvatureSafety * std::sqrt(8.0 * o.chordal_tolerance / k));
  return std::max(h, o.min_size);
}

namespace {

/// The least corner term of element_quality over K corners (K a constant: the corner indices
/// unrolled, no integer division per corner).
template <int K>
double least_corner(const Vec3* p, const Vec3& n) {
  double side[K];  // each side's norm once (a corner's second side is the side before, reversed)
  for (int i = 0; i < K; ++i) side[i] = (p[(i + 1) % K] - p[i]).norm();
  double q = 1e9;
  for (int i = 0; i < K; ++i) {
    const Vec3 e1 = p[(i + 1) % K] - p[i], e2 = p[(i + K - 1) % K] - p[i];
    const double l = side[i] * side[(i + K - 1) % K];
    const double s = l > 0 ? e1.cross(e2).dot(n) / l : 0.0;
    q = std::min(q, s);
  }
  return q;
}

}  // namespace

double element_quality(const Vec3* p, int k, const Vec3& n) {
  if (k == 4) return least_corner<4>(p, n);
  return std::min(1.0, least_corner<3>(p, n) * 2.0 / std::sqrt(3.0));
}

namespace {

/// The planar coordinates the triangulation works in: each parameter mapped by the mean arc
/// length along three iso-lines (monotone, so orientation is kept), which evens out
/// parametrisations whose speed jumps (a hull's flat-of-side zone between triple knots); on a
/// face whose iso-lines shrink toward a pole (a fan), the cross coordinate of the direction
/// whose iso-lines vary most in length is scaled by their length (one direction only, so the
/// map stays one-to-one).
class PlanarMap {
 public:
  PlanarMap(const FaceGeometry& g, const Vec2& lo, const Vec2& hi)
      : amap_u_(g, lo.x(), hi.x(), lo.y(), hi.y(), true), amap_v_(g, lo.y(), hi.y(), lo.x(), hi.x(), false),
        width_v_(g, lo.x(), hi.x(), lo.y(), hi.y(), true),    // iso-u lines: lengths along v
        width_u_(g, lo.y(), hi.y(), lo.x(), hi.x(), false) {  // iso-v lines: lengths along u
    scale_v_ = width_v_.spread() >= width_u_.spread();
    fan_ = std::max(width_v_.spread(), width_u_.spread()) > kFanSpread;
  }
  Vec2 operator()(const Vec2& q) const {
    if (!fan_) return {amap_u_(q.x()), amap_v_(q.y())};
    return scale_v_ ? Vec2(amap_u_(q.x()), amap_v_(q.y()) * width_v_(q.x()))
                    : Vec2(amap_u_(q.x()) * width_u_(q.y()), amap_v_(q.y()));
  }
  /// d(planar) / d(u) and d(planar) / d(v) along the axes.
  double speed_u(const Vec2& q) const { return amap_u_.speed(q.x()) * (fan_ && !scale_v_ ? width_u_(q.y()) : 1.0); }
  double speed_v(const Vec2& q) const { return amap_v_.speed(q.y()) * (fan_ && scale_v_ ? width_v_(q.x()) : 1.0); }

 private:
  ArcMap amap_u_, amap_v_;
  IsoWidth width_v_, width_u_;
  bool scale_v_ = true, fan_ = false;
};

/// The curvature's size graded across the face: scale x target_size sampled on a grid of
/// iso-lines (equal arc length along the middle ones, kGridStep x the largest size apart;
/// samples outside the loop count as the largest size), each sample lowered to the least
/// h_j + kInteriorGrading x (the shortest grid path's length to sample j) over the grid's
/// 8-neighbour graph (3-D chords; grade), and interpolated bilinearly in (u, v). The pointwise size
/// alone jumped from 0.3 to 2.3 m within a few metres at the example bare hull's forefoot.
class GradedGrid {
 public:
  GradedGrid(const FaceGeometry& g, const MeshOptions& o, const std::vector<Vec2>& poly, const Vec2& lo,
             const Vec2& hi, double scale) {
    if (!g.surface) return;  // a plane: no curvature, nothing to grade
    double step = kGridStep * scale * o.size;
    for (int fit = 0; fit < 2; ++fit) {  // the second time at a spacing that fits kGridMost
      us_ = root_lines(g, lo.x(), hi.x(), lo.y(), hi.y(), true, step);
      vs_ = root_lines(g, lo.y(), hi.y(), lo.x(), hi.x(), false, step);
      const double n = static_cast<double>(us_.size()) * static_cast<double>(vs_.size());
      if (n <= kGridMost) break;
      step *= std::sqrt(n / kGridMost) * 1.01;
    }
    const PolygonSlabs inside(poly);
    const int nu = static_cast<int>(us_.size()), nv = static_cast<int>(vs_.size());
    std::vector<Vec3> p(nu * nv);
    h_.assign(nu * nv, scale * o.size);
    for (int i = 0; i < nu; ++i)
      for (int j = 0; j < nv; ++j) {
        const Vec2 q(us_[i], vs_[j]);
        p[i * nv + j] = g.point(q);
        if (inside.inside(q)) h_[i * nv + j] = scale * target_size(g, q, o);
      }
    grade(p, nu, nv);
  }
  /// The graded size at q (the largest size where there is no grid).
  double operator()(const Vec2& q) const {
    if (h_.empty()) return std::numeric_limits<double>::infinity();
    const int nv = static_cast<int>(vs_.size());
    const auto [i, a] = cell(us_, q.x());
    const auto [j, b] = cell(vs_, q.y());
    auto at = [&](int di, int dj) { return h_[(i + di) * nv + j + dj]; };
    return (1 - a) * ((1 - b) * at(0, 0) + b * at(0, 1)) + a * ((1 - b) * at(1, 0) + b * at(1, 1));
  }

 private:
  /// h_k = min over samples j of h_j + kInteriorGrading x (the shortest grid path's length):
  /// raster sweeps forward and back, each sample lowered from its four neighbours already
  /// swept, repeated until a round lowers none (the shortest paths' fixed point, as Dijkstra
  /// would give; two or three rounds, without the heap that took as long as the sampling).
  void grade(const std::vector<Vec3>& p, int nu, int nv) {
    constexpr int kBefore[4][2] = {{-1, -1}, {-1, 0}, {-1, 1}, {0, -1}};
    const int n = nu * nv;
    for (bool lowered = true; lowered;) {
      lowered = false;
      for (int dir : {1, -1})
        for (int s = 0; s < n; ++s) {
          const int k = dir > 0 ? s : n - 1 - s, i = k / nv, j = k % nv;
          for (const auto& [di, dj] : kBefore) {
            const int a = i + dir * di, b = j + dir * dj;
            if (a < 0 || b < 0 || a >= nu || b >= nv) continue;
            const int m = a * nv + b;
            const double t = h_[m] + kInteriorGrading * (p[m] - p[k]).norm();
            if (t < h_[k]) h_[k] = t, lowered = true;
          }
        }
    }
  }
  /// The grid interval holding x (clamped) and x's fraction of it.
  static std::pair<int, double> cell(const std::vector<double>& r, double x) {
    const int n = static_cast<int>(r.size());
    const int i = std::clamp(static_cast<int>(std::upper_bound(r.begin(), r.end(), x) - r.begin()) - 1, 0, n - 2);
    const double w = r[i + 1] > r[i] ? std::clamp((x - r[i]) / (r[i + 1] - r[i]), 0.0, 1.0) : 0.0;
    return {i, w};
  }
  std::vector<double> us_, vs_, h_;  ///< the grid lines; the graded sizes, u major
};

/// The target size at a point of the face: the curvature's (target_size), graded across the
/// face (GradedGrid) and from the boundary's own spacing, times `scale` (2 for the all-quad
/// split's coarse pass).
class PatchSize {
 public:
  PatchSize(const Work& w, int nb, const std::vector<Vec2>& poly, const Vec2& lo, const Vec2& hi, double scale)
      : w_(w), scale_(scale), hb_(longer_sides(w, nb)), graded_(w.xyz, hb_, scale * w.o.size / kGrading),
        grid_(w.g, w.o, poly, lo, hi, scale) {}
  /// The size at (q, p); any value below `below` where the size is below it: the size without
  /// the pointwise curvature bounds it, and where that is below `below` the curvature is not
  /// needed (graded(p, h) = min(h, its value at the largest size) for h up to the largest size).
  double operator()(const Vec2& q, const Vec3& p, double below) const {
    const double at_largest = std::min(graded_(p, scale_ * w_.o.size), grid_(q));
    const double bound = std::max(at_largest, scale_ * w_.o.min_size);
    if (bound < below) return bound;
    return std::max(std::min(scale_ * target_size(w_.g, q, w_.o), at_largest), scale_ * w_.o.min_size);
  }

 private:
  /// The longer of the two loop sides at each of the nb loop nodes.
  static std::vector<double> longer_sides(const Work& w, int nb) {
    std::vector<double> hb(nb);
    for (int i = 0; i < nb; ++i)
      hb[i] = std::max((w.xyz[(i + 1) % nb] - w.xyz[i]).norm(), (w.xyz[(i + nb - 1) % nb] - w.xyz[i]).norm());
    return hb;
  }
  const Work& w_;
  double scale_;
  std::vector<double> hb_;
  GradedSize graded_;
  GradedGrid grid_;
};

/// The boundary sides of a face bucketed in planar coordinates, for the clearance test of
/// place_nodes: is p (at q) within `clear` of a side, or within kClearance x the side's own
/// length (a node close to a long side, a boundary coarser than the curvature inside wants,
/// would be joined to its ends by slivers)?
class SideBuckets {
 public:
  SideBuckets(const Work& w, const std::vector<Vec2>& planar, int nb, double bucket) : w_(w), nb_(nb), bucket_(bucket) {
    longest_ = 0.0;
    for (int i = 0; i < nb; ++i) {
      const Vec2 &a = planar[i], &b = planar[(i + 1) % nb];
      for (long long x = cell(std::min(a.x(), b.x())); x <= cell(std::max(a.x(), b.x())); ++x)
        for (long long y = cell(std::min(a.y(), b.y())); y <= cell(std::max(a.y(), b.y())); ++y) buckets_[key(x, y)].push_back(i);
      longest_ = std::max(longest_, (w.xyz[(i + 1) % nb] - w.xyz[i]).norm());
    }
  }
  /// `slow`: the least metres per planar unit at q (the search radius in planar units).
  bool near(const Vec3& p, const Vec2& s, double clear, double slow) const {
    const double reach = std::min(kClearance * std::max(clear / kClearance, longest_) / slow, 50.0 * bucket_);
    for (long long x = cell(s.x() - reach); x <= cell(s.x() + reach); ++x)
      for (long long y = cell(s.y() - reach); y <= cell(s.y() + reach); ++y) {
        auto it = buckets_.find(key(x, y));
        if (it == buckets_.end()) continue;
        for (int i : it->second) {
          const Vec3 &a = w_.xyz[i], &b = w_.xyz[(i + 1) % nb_];
          if (segment_distance(p, a, b) < std::max(clear, kClearance * (b - a).norm())) return true;
        }
      }
    return false;
  }

 private:
  long long cell(double t) const { return static_cast<long long>(std::floor(t / bucket_)); }
  static long long key(long long i, long long j) { return i * 1000003LL + j; }
  const Work& w_;
  int nb_;
  double bucket_, longest_;
  std::unordered_map<long long, std::vector<int>> buckets_;
};

/// Interior nodes: the corners of the balanced subdivision inside the loop and clear of its
/// sides (kClearance x the size); near a pole, where the subdivision's lines converge and
/// their corners crowd, also kPoleSpacing x the size from the nodes already taken (not in the
/// all-quad coarse pass: on the bulb's nose its split quads then fold, 9 inverted at 1.5 m
/// instead of 3). Appends them to w and their planar points to `planar`.
CornerNodes place_nodes(Work& w, const Subdivision<PatchSize>& sub, const std::vector<LoopNode>& loop, const std::vector<Vec2>& poly,
                        const PlanarMap& map, const PatchSize& size, double bucket, std::vector<Vec2>& planar) {
  const int nb = static_cast<int>(loop.size());
  const SideBuckets sides(w, planar, nb, bucket);
  std::vector<Vec3> poles;
  for (int i = 0; i < nb && !w.o.all_quad; ++i)
    if (loop[i].id == loop[(i + 1) % nb].id) poles.push_back(w.xyz[i]);
  auto crowded_at_pole = [&](const Vec3& p, double h) {
    bool close = false;
    for (const Vec3& c : poles) close = close || (p - c).norm() < kPoleZone * h;
    if (!close) return false;
    for (size_t i = nb; i < w.xyz.size(); ++i)
      if ((w.xyz[i] - p).norm() < kPoleSpacing * h) return true;
    return false;
  };
  const PolygonSlabs inside(poly);
  CornerNodes out;
  out.corner = sub.corners();
  out.node.assign(out.corner.size(), -1);
  for (size_t c = 0; c < out.corner.size(); ++c) {
    const Vec2 q(sub.u(out.corner[c].first), sub.v(out.corner[c].second));
    if (!inside.inside(q)) continue;
    Vec3 p, su, sv;
    w.g.first(q, p, su, sv);
    const double slow = std::max(1e-300, std::min(su.norm() / map.speed_u(q), sv.norm() / map.speed_v(q)));
    const Vec2 s = map(q);
    // both tests reject more the larger the size: a node clear by the size's bound without
    // the curvature (most of them, away from the boundary) is clear by the size
    auto rejected = [&](double h) { return sides.near(p, s, kClearance * h, slow) || crowded_at_pole(p, h); };
    if (rejected(size(q, p, std::numeric_limits<double>::infinity())) && rejected(size(q, p, 0.0))) continue;
    out.node[c] = static_cast<int>(w.xyz.size());
    w.uv.push_back(q);
    w.xyz.push_back(p);
    w.normal.push_back(Work::unit_normal(su, sv));
    planar.push_back(s);
  }
  return out;
}

/// Whether the flip of edge ab (triangles abc and bad) into adc and dbc leaves both turning
/// counter-clockwise about the surface normal at their nodes: the swap is judged valid in space,
/// as it is judged better. The planar coordinates only model the face's metric (per direction,
/// not its shear): on a face whose iso-lines cross far from square (the blend: |cos| 0.62 at the
/// median) a quad convex on the surface is often reflex in them, and a planar convexity test kept
/// the Delaunay triangulation's 3-D slivers (a fan of four from one keel-end boundary node).
bool convex_in_space(const Work& w, int a, int b, int c, int d) {
  const Vec3 n = w.normal[a] + w.normal[b] + w.normal[c] + w.normal[d];
  const Vec3 &pa = w.xyz[a], &pb = w.xyz[b], &pc = w.xyz[c], &pd = w.xyz[d];
  return (pd - pa).cross(pc - pa).dot(n) > 0 && (pb - pd).cross(pc - pd).dot(n) > 0;
}

/// Constrained Delaunay triangulation of the nodes in planar coordinates, then edge swaps by
/// the 3-D max-min angle except in the leaf quads it holds (their pairs are matched as they
/// are), then the pole copies merged (merged_triangles).
std::vector<std::array<int, 3>> triangulate(const Work& w, const std::vector<Vec2>& planar, const std::vector<LoopNode>& loop,
                                            const std::vector<std::array<int, 4>>& leaves) {
  const int nb = static_cast<int>(loop.size());
  std::vector<int> order(nb);
  for (int i = 0; i < nb; ++i) order[i] = i;
  Triangulation tr(planar, order);
  for (int i = nb; i < static_cast<int>(planar.size()); ++i) tr.insert(i);
  // a leaf the Delaunay triangulation cut across (in fan coordinates a leaf is a trapezoid) is
  // made two triangles by flipping the edges across its sides
  const auto before = held_pairs(tr.triangles(), TrianglesAtNodes(tr.triangles(), planar.size()), leaves);
  for (size_t l = 0; l < leaves.size(); ++l)
    if (before[l].first < 0)
      for (int k = 0; k < 4; ++k) tr.enforce(leaves[l][k], leaves[l][(k + 1) % 4]);
  std::vector<char> keep(tr.triangles().size(), 0);
  for (const auto& [t, u] : held_pairs(tr.triangles(), TrianglesAtNodes(tr.triangles(), planar.size()), leaves))
    if (t >= 0) keep[t] = keep[u] = 1;
  tr.flip_while(
      [&](int a, int b, int c, int d) {
        const double now = std::min(min_angle(w.xyz[a], w.xyz[b], w.xyz[c]), min_angle(w.xyz[b], w.xyz[a], w.xyz[d]));
        const double then = std::min(min_angle(w.xyz[a], w.xyz[d], w.xyz[c]), min_angle(w.xyz[d], w.xyz[b], w.xyz[c]));
        return then > now + 1e-9;
      },
      kSwapPasses, keep, [&](int a, int b, int c, int d) { return convex_in_space(w, a, b, c, d); });
  return merged_triangles(w.xyz, tr.triangles(), pole_canon(loop, w.xyz.size()));
}

/// The matched triangles as elements of w: quads, unpaired triangles, and the weak pairs
/// (their quad below min_quad_quality) as two triangles each, listed in `weak`. Returns, per
/// element, whether it is a leaf quad.
std::vector<char> assemble(Work& w, const std::vector<std::array<int, 3>>& tri, const std::vector<int>& mate,
                           const std::vector<char>& leaf, const std::vector<std::array<int, 3>>& nbr,
                           std::vector<WeakPair>& weak) {
  std::vector<char> is_leaf;
  auto push = [&](const std::array<int, 4>& e, bool l) { w.el.push_back(e), is_leaf.push_back(l); };
  for (int t = 0; t < static_cast<int>(tri.size()); ++t) {
    if (mate[t] < 0) {
      push({tri[t][0], tri[t][1], tri[t][2], -1}, false);
      continue;
    }
    if (mate[t] < t) continue;
    const int u = mate[t];
    for (int k = 0; k < 3; ++k) {
      if (nbr[t][k] != u) continue;
      const int a = tri[t][k], b = tri[t][(k + 1) % 3], c = tri[t][(k + 2) % 3];
      int d = -1;
      for (int j = 0; j < 3; ++j)
        if (tri[u][j] != a && tri[u][j] != b) d = tri[u][j];
      const std::array<int, 4> quad{a, d, b, c};
      if (w.o.all_quad || leaf[t] || w.quality(quad) >= w.o.min_quad_quality) {
        push(quad, leaf[t]);
        continue;
      }
      const int first = static_cast<int>(w.el.size());
      push({tri[t][0], tri[t][1], tri[t][2], -1}, false);
      push({tri[u][0], tri[u][1], tri[u][2], -1}, false);
      weak.push_back({first, first + 1, quad});
    }
  }
  return is_leaf;
}

/// Nodes every element of which is a leaf quad (the structured interior): smoothing leaves
/// them where the subdivision put them (on the face, in cells the size asked for); the
/// searches still move them where an element about them scores low.
std::vector<char> structured_nodes(const Work& w, const std::vector<char>& is_leaf) {
  std::vector<char> out(w.xyz.size(), 1);
  for (int i = 0; i < w.fixed; ++i) out[i] = 0;
  for (size_t e = 0; e < w.el.size(); ++e)
    if (!is_leaf[e])
      for (int k = 0; k < (w.el[e][3] < 0 ? 3 : 4); ++k) out[w.el[e][k]] = 0;
  std::vector<char> used(w.xyz.size(), 0);
  for (const auto& e : w.el)
    for (int k = 0; k < (e[3] < 0 ? 3 : 4); ++k) used[e[k]] = 1;
  for (size_t i = 0; i < out.size(); ++i) out[i] = out[i] && used[i];
  return out;
}

/// The all-quad mesh: the coarse mesh in w (smoothed) split into quads (split_all_quad), its
/// loop midpoints moved before the free nodes, smoothed and searched.
PatchMesh all_quad_patch(Work& w, const std::vector<int>& canon, int nb, const LoopMidpoint& midpoint,
                         std::vector<int> global, const std::vector<char>& is_leaf) {
  std::vector<char> leaf_child;  // per fine element: whether its coarse parent was a leaf quad
  for (size_t e = 0; e < w.el.size(); ++e) leaf_child.insert(leaf_child.end(), w.el[e][3] < 0 ? 3 : 4, is_leaf[e]);
  split_all_quad(w, canon, nb, midpoint, global);
  // split-off boundary midpoints stay where the edge put them: renumbered before the free nodes
  const int n = static_cast<int>(w.xyz.size());
  std::vector<int> perm, rest;
  for (int i = 0; i < n; ++i) (i < nb || global[i] >= 0 ? perm : rest).push_back(i);
  const int fixed = static_cast<int>(perm.size());
  perm.insert(perm.end(), rest.begin(), rest.end());
  std::vector<int> inv(n);
  for (int i = 0; i < n; ++i) inv[perm[i]] = i;
  Work r{w.g, w.o, {}, {}, {}, fixed, {}};
  std::vector<int> g2(n);
  for (int i = 0; i < n; ++i) {
    r.xyz.push_back(w.xyz[perm[i]]);
    r.uv.push_back(w.uv[perm[i]]);
    r.normal.push_back(w.normal[perm[i]]);
    g2[i] = global[perm[i]];
  }
  for (auto e : w.el) {
    for (int k = 0; k < 4; ++k)
      if (e[k] >= 0) e[k] = inv[e[k]];
    r.el.push_back(e);
  }
  smooth(r, r.o.smoothing_passes, structured_nodes(r, leaf_child));
  if (r.o.smoothing_passes > 0) {
    improve_worst(r);
    improve_corners(r);  // the split's corners lie near 60, 90 and 120 deg, some beyond 45-135
  }
  if (r.o.smoothing_passes > 0) polish(r);
  split_folded_quads(r);  // the last resort: none on the composed ship at 3 and 1.5 m
  return {std::move(r.xyz), std::move(r.uv), std::move(r.el), std::move(g2)};
}

}  // namespace

PatchMesh mesh_patch(const FaceGeometry& g, const std::vector<LoopNode>& loop, const MeshOptions& o,
                     const LoopMidpoint& midpoint) {
  const int nb = static_cast<int>(loop.size());
  if (nb < 3) throw InvalidInput("mesh: a face boundary has fewer than 3 nodes; expected a smaller element size");
  Work w{g, o, {}, {}, {}, nb, {}};
  std::vector<Vec2> poly(nb);
  Vec2 lo = loop[0].uv, hi = lo;
  for (int i = 0; i < nb; ++i) {
    w.uv.push_back(loop[i].uv);
    w.xyz.push_back(loop[i].xyz);
    w.normal.push_back(w.surface_normal(loop[i].uv));
    poly[i] = loop[i].uv;
    lo = lo.cwiseMin(poly[i]);
    hi = hi.cwiseMax(poly[i]);
  }
  const PlanarMap map(g, lo, hi);
  const double scale = o.all_quad ? 2.0 : 1.0;
  const PatchSize size(w, nb, poly, lo, hi, scale);
  const Subdivision<PatchSize> sub(g, o, root_lines(g, lo.x(), hi.x(), lo.y(), hi.y(), true, scale * o.size),
                                   root_lines(g, lo.y(), hi.y(), lo.x(), hi.x(), false, scale * o.size), scale, size);
  std::vector<Vec2> planar;
  for (const Vec2& q : poly) planar.push_back(map(q));
  const CornerNodes nodes = place_nodes(w, sub, loop, poly, map, size, scale * o.size, planar);
  const std::vector<std::array<int, 4>> leaves = leaf_quads(w, sub.leaves(), nodes);
  const std::vector<std::array<int, 3>> tri = triangulate(w, planar, loop, leaves);
  std::vector<std::array<int, 3>> nbr;
  std::vector<char> leaf;
  const std::vector<int> mate = match_triangles(w, tri, leaves, nbr, leaf);
  std::vector<WeakPair> weak;
  const std::vector<char> is_leaf = assemble(w, tri, mate, leaf, nbr, weak);
  std::vector<int> global(w.xyz.size(), -1);
  for (int i = 0; i < nb; ++i) global[i] = loop[i].id;
  smooth(w, o.smoothing_passes, structured_nodes(w, is_leaf));
  if (o.all_quad)  // the triangles were merged on the pole copies' canonical ids
    return all_quad_patch(w, pole_canon(loop, w.xyz.size()), nb, midpoint, std::move(global), is_leaf);
  if (o.smoothing_passes > 0) improve_worst(w);
  merge_weak_pairs(w, weak);
  if (o.smoothing_passes > 0 && remove_valence3_nodes(w)) compact_nodes(w);
  if (o.smoothing_passes > 0) improve_mean(w);
  if (o.smoothing_passes > 0) improve_corners(w);
  if (o.smoothing_passes > 0) improve_mean(w);
  // after the quality passes, which make the size jumps (on the example's bare hull none before
  // improve_corners, three quads past kCollapseRatio after it)
  for (int pass = 0; o.smoothing_passes > 0 && pass < kCollapsePasses && collapse_small_elements(w); ++pass) compact_nodes(w);
  if (o.smoothing_passes > 0) polish(w);
  if (o.smoothing_passes > 0 && flip_sliver_pairs(w)) polish(w);
  split_folded_quads(w);
  global.resize(w.xyz.size(), -1);
  return {std::move(w.xyz), std::move(w.uv), std::move(w.el), std::move(global)};
}

}  // namespace fairlines::meshing
