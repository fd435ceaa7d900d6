// Hydrostatics by quadrature on the NURBS surface: see fairlines/hydrostatics.hpp.
#include "fairlines/hydrostatics.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Geometry>

#include "fairlines/errors.hpp"
#include "nurbs/checks.hpp"
#include "nurbs/gauss.hpp"

namespace fairlines {

namespace {

using detail::fail;

constexpr int kClipSamples = 8;        // samples per knot span when looking for draft crossings
constexpr long kGridLines = 8;         // u lines per batch of highest_point's grid evaluation
constexpr double kTopFromNet = 1e-12;  // a breakpoint this close (relative) to the net's top z is the highest point
constexpr int kBisection = 60;         // bisection steps (interval shrinks below 1e-16 of the span)
// A waterplane this far (relative) above the surface's sampled top still counts as at the top.
constexpr double kAboveTopTolerance = 1e-9;

/// Distinct knots of a knot vector inside the domain (the span breakpoints).
std::vector<double> breakpoints(const Eigen::VectorXd& U, int degree) {
  const int n = static_cast<int>(U.size()) - degree - 1;
  std::vector<double> b;
  for (int i = degree; i <= n; ++i)
    if (b.empty() || U[i] > b.back()) b.push_back(U[i]);
  return b;
}

/// Sub-intervals of [breaks.front(), breaks.back()] where f(t) <= 0, each split at the breaks.
/// f is sampled kClipSamples times per break interval (all samples at once by
/// sample_all(ts, fs)); sign changes are refined by bisection on f.
template <typename F, typename Fs>
std::vector<std::pair<double, double>> inside_pieces(const std::vector<double>& breaks, F&& f, Fs&& sample_all) {
  std::vector<double> ts;
  for (std::size_t i = 0; i + 1 < breaks.size(); ++i)
    for (int k = 0; k < kClipSamples; ++k)
      ts.push_back(breaks[i] + (breaks[i + 1] - breaks[i]) * k / kClipSamples);
  ts.push_back(breaks.back());
  std::vector<double> fs(ts.size());
  sample_all(ts, fs);
  // Collect boundaries of the inside set.
  std::vector<std::pair<double, double>> ivs;
  bool in = fs[0] <= 0;
  double start = ts[0];
  for (std::size_t i = 0; i + 1 < ts.size(); ++i) {
    const bool in_next = fs[i + 1] <= 0;
    if (in_next == in) continue;
    double a = ts[i], b = ts[i + 1], fa = fs[i];
    for (int it = 0; it < kBisection && b - a > 1e-15 * (1 + std::abs(a)); ++it) {
      const double mid = 0.5 * (a + b), fm = f(mid);
      if ((fm <= 0) == (fa <= 0)) a = mid, fa = fm;
      else b = mid;
    }
    const double root = 0.5 * (a + b);
    if (in) ivs.emplace_back(start, root);
    else start = root;
    in = in_next;
  }
  if (in) ivs.emplace_back(start, ts.back());
  // Split each interval at the breaks.
  std::vector<std::pair<double, double>> pieces;
  for (const auto& [a, b] : ivs) {
    double lo = a;
    for (double br : breaks)
      if (br > lo && br < b) {
        pieces.emplace_back(lo, br);
        lo = br;
      }
    if (b > lo) pieces.emplace_back(lo, b);
  }
  return pieces;
}

/// Longitudinal parameter direction: 1 (v) when the control net's x varies more along j.
int longitudinal_direction(const NurbsSurface& s) {
  const Eigen::MatrixXd& P = s.control_points();
  const int nu = s.nu(), nv = s.nv();
  double du = 0, dv = 0;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      if (i + 1 < nu) du += std::abs(P((i + 1) * nv + j, 0) - P(i * nv + j, 0));
      if (j + 1 < nv) dv += std::abs(P(i * nv + j + 1, 0) - P(i * nv + j, 0));
    }
  return dv >= du ? 1 : 0;
}

/// Direction whose control lines run more steeply: 1 (v) or 0 (u), by the z range of each
/// line over its polygon's length, summed over the lines. The girth of a hull section spans keel
/// to deck within a few times that; a line along the hull spans at most the rise of the keel or
/// sheer, over the whole length. The z range alone is not enough: the keel's and bilge's rows of
/// a hull whose profile climbs to the deck at both ends (a cruiser stern, a raked stem) span the
/// whole depth too, more than its short end sections, and clipping those rows let the waterline
/// run between two Gauss lines along the parallel body.
int vertical_direction(const NurbsSurface& s) {
  const Eigen::MatrixXd& P = s.control_points();
  const int nu = s.nu(), nv = s.nv();
  auto at = [&](int i, int j) { return Eigen::Vector3d(P.row(i * nv + j).transpose()); };
  auto steepness = [&](int lines, int points, auto&& point) {
    double rise = 0.0, length = 0.0;
    for (int l = 0; l < lines; ++l) {
      double lo = point(l, 0).z(), hi = lo;
      for (int k = 1; k < points; ++k) {
        lo = std::min(lo, point(l, k).z()), hi = std::max(hi, point(l, k).z());
        length += (point(l, k) - point(l, k - 1)).norm();
      }
      rise += hi - lo;
    }
    return length > 0 ? rise / length : 0.0;
  };
  const double along_u = steepness(nv, nu, [&](int j, int i) { return at(i, j); });
  const double along_v = steepness(nu, nv, [&](int i, int j) { return at(i, j); });
  return along_v > along_u ? 1 : 0;
}

/// The same surface with u and v exchanged.
NurbsSurface transposed(const NurbsSurface& s) {
  const int nu = s.nu(), nv = s.nv();
  const Eigen::MatrixXd pw = s.homogeneous();
  Eigen::MatrixXd q(pw.rows(), 4);
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) q.row(j * nu + i) = pw.row(i * nv + j);
  return NurbsSurface::from_homogeneous(s.degree_v(), s.degree_u(), s.knots_v(), s.knots_u(), nv, nu, q);
}

/// Surface integrals over the part of a surface below the waterline (see the header): acc =
/// V, Mx, Mz (flux of y); A, Ax, Ayy, Axx (flux of n_z); wetted area. The orientation sums
/// are int |n_y|, int |n_x|, int x n_x and int n_x dS. The extent is that of the Gauss points
/// and piece ends below the waterline.
struct SurfaceSums {
  std::array<double, 8> acc{};
  double abs_ny = 0, abs_nx = 0, x_nx = 0, nx = 0;
  double xmin = std::numeric_limits<double>::infinity(), xmax = -std::numeric_limits<double>::infinity(), ymax = 0;

  void extend(const Eigen::Vector3d& P) {
    xmin = std::min(xmin, P[0]);
    xmax = std::max(xmax, P[0]);
    ymax = std::max(ymax, P[1]);
  }
};

/// Adds the Gauss points of one submerged piece [pa, pb] of the u line at v (weight wv).
void add_piece(const NurbsSurface& s, const detail::GaussRule& g, int gauss, double v, double wv, double pa,
               double pb, SurfaceSums& out) {
  std::array<double, 32> us{}, vs{};
  std::array<double, 9 * 32> d1{};
  const double hu = 0.5 * (pb - pa), mu = 0.5 * (pa + pb);
  for (int ku = 0; ku < gauss; ++ku) us[ku] = mu + hu * g.x[ku], vs[ku] = v;
  s.evaluate_first_derivatives_into(us.data(), vs.data(), gauss, d1.data());
  for (int ku = 0; ku < gauss; ++ku) {
    const double* row = &d1[9 * ku];
    const Eigen::Vector3d P(row[0], row[1], row[2]), Su(row[3], row[4], row[5]), Sv(row[6], row[7], row[8]);
    const Eigen::Vector3d N = Su.cross(Sv);
    const double w = wv * g.w[ku] * hu;
    auto& acc = out.acc;
    acc[0] += w * P[1] * N[1];
    acc[1] += w * P[0] * P[1] * N[1];
    acc[2] += w * P[2] * P[1] * N[1];
    acc[3] += w * N[2];
    acc[4] += w * P[0] * N[2];
    acc[5] += w * P[1] * P[1] * N[2];
    acc[6] += w * P[0] * P[0] * N[2];
    acc[7] += w * N.norm();
    out.abs_ny += w * std::abs(N[1]);
    out.abs_nx += w * std::abs(N[0]);
    out.x_nx += w * P[0] * N[0];
    out.nx += w * N[0];
    out.extend(P);
  }
  // The piece ends are on the surface too: include them in the extent.
  for (double ue : {pa, pb}) out.extend(s.evaluate(ue, v));
}

/// The pieces of the u line at v below waterline_z(x) (inside_pieces over the span breaks bu),
/// its samples evaluated in one batch (`points`, `line_v`: buffers the caller reuses).
template <typename Z>
std::vector<std::pair<double, double>> submerged_pieces(const NurbsSurface& s, const std::vector<double>& bu, double v,
                                                        Z&& waterline_z, std::vector<double>& points,
                                                        std::vector<double>& line_v) {
  auto height = [&](double u) {
    const Eigen::Vector3d P = s.evaluate(u, v);
    return P[2] - waterline_z(P[0]);
  };
  auto heights = [&](const std::vector<double>& ts, std::vector<double>& fs) {
    points.resize(3 * ts.size());
    line_v.assign(ts.size(), v);
    s.evaluate_into(ts.data(), line_v.data(), static_cast<long>(ts.size()), points.data());
    for (std::size_t i = 0; i < ts.size(); ++i) fs[i] = points[3 * i + 2] - waterline_z(points[3 * i]);
  };
  return inside_pieces(bu, height, heights);
}

/// Integrals over the part of `s` (lines of u crossing the waterline) below waterline_z(x).
template <typename Z>
SurfaceSums integrate_below(const NurbsSurface& s, int gauss, Z&& waterline_z) {
  const std::vector<double> bu = breakpoints(s.knots_u(), s.degree_u());
  const std::vector<double> bv = breakpoints(s.knots_v(), s.degree_v());
  const auto& g = detail::gauss_rule(gauss);
  SurfaceSums out;
  std::vector<double> points, line_v;
  for (std::size_t jv = 0; jv + 1 < bv.size(); ++jv) {
    const double hv = 0.5 * (bv[jv + 1] - bv[jv]), mv = 0.5 * (bv[jv + 1] + bv[jv]);
    for (int kv = 0; kv < gauss; ++kv) {
      const double v = mv + hv * g.x[kv];
      for (const auto& [pa, pb] : submerged_pieces(s, bu, v, waterline_z, points, line_v))
        add_piece(s, g, gauss, v, g.w[kv] * hv, pa, pb, out);
    }
  }
  return out;
}

/// The n_z fluxes (acc[3..6]: 1, x, y^2, x^2) through the planar lids that close the ends
/// v = v_min and v = v_max below the waterline, oriented as the surface: a lid in a plane whose
/// normal has no y part (a transom, upright or raked) from the end curve to the centre plane.
/// By Stokes' theorem each is a line integral along the end curve (its counter-clockwise
/// direction in (u, v) reversed), the waterline's chord across the lid (x constant there, x_w)
/// and the centre plane (y = 0) adding nothing: -int (x - x_w) dy, -int (x^2 - x_w^2)/2 dy,
/// int y^3/3 dx, -int (x^3 - x_w^3)/3 dy. All zero for an upright end (x constant) or one on
/// the centre plane.
template <typename Z>
std::array<double, 4> end_lid_fluxes(const NurbsSurface& s, int gauss, Z&& waterline_z) {
  const std::vector<double> bu = breakpoints(s.knots_u(), s.degree_u());
  const std::vector<double> bv = breakpoints(s.knots_v(), s.degree_v());
  const auto& g = detail::gauss_rule(gauss);
  std::array<double, 4> out{};
  std::vector<double> points, line_v;
  for (const double v : {bv.front(), bv.back()}) {
    const double along = v == bv.front() ? 1.0 : -1.0;  // the end's direction of increasing u
    const auto pieces = submerged_pieces(s, bu, v, waterline_z, points, line_v);
    double xw = 0.0, top = -std::numeric_limits<double>::infinity();  // x where the end meets the waterline
    for (const auto& [pa, pb] : pieces)
      for (const double u : {pa, pb}) {
        const Eigen::Vector3d P = s.evaluate(u, v);
        if (const double h = P[2] - waterline_z(P[0]); h > top) top = h, xw = P[0];
      }
    for (const auto& [pa, pb] : pieces) {
      const double hu = 0.5 * (pb - pa), mu = 0.5 * (pa + pb);
      std::array<double, 32> us{}, vs{};
      std::array<double, 9 * 32> d1{};
      for (int k = 0; k < gauss; ++k) us[k] = mu + hu * g.x[k], vs[k] = v;
      s.evaluate_first_derivatives_into(us.data(), vs.data(), gauss, d1.data());
      for (int k = 0; k < gauss; ++k) {
        const double* row = &d1[9 * k];
        const double x = row[0], y = row[1], w = -along * g.w[k] * hu;  // the lid runs the end backwards
        const double dx = w * row[3], dy = w * row[4];
        out[0] += (x - xw) * dy;
        out[1] += 0.5 * (x * x - xw * xw) * dy;
        out[2] -= y * y * y / 3.0 * dx;
        out[3] += (x * x * x - xw * xw * xw) / 3.0 * dy;
      }
    }
  }
  return out;
}

/// `surface` with u the direction along which z varies most, so every line of u that the
/// waterplane cuts is clipped (a draft between two Gauss lines of v would not be).
NurbsSurface vertical_u(const NurbsSurface& surface) {
  return vertical_direction(surface) == 1 ? transposed(surface) : surface;
}

/// The surface's parameters in the plane x = x0: a runs across the hull (the direction of
/// integration), b along it. On each line of a, crossing(a) is the b where x(a, b) = x0: Newton
/// from the last crossing found (consecutive a are close), else a bracketing scan.
class PlaneCrossing {
 public:
  /// S, S_a (across) and S_b (longitudinal) at (a, b).
  struct D1 {
    Eigen::Vector3d S, Sa, Sb;
  };

  PlaneCrossing(const NurbsSurface& s, double x0)
      : s_(s), x0_(x0), lon_(longitudinal_direction(s)),
        across_(breakpoints(lon_ == 1 ? s.knots_u() : s.knots_v(), lon_ == 1 ? s.degree_u() : s.degree_v())),
        along_(breakpoints(lon_ == 1 ? s.knots_v() : s.knots_u(), lon_ == 1 ? s.degree_v() : s.degree_u())) {}

  /// The knot breakpoints of a.
  const std::vector<double>& across_breaks() const { return across_; }

  Eigen::Vector3d point(double a, double b) const { return lon_ == 1 ? s_.evaluate(a, b) : s_.evaluate(b, a); }

  /// Through the allocation-free kernel.
  D1 first_derivs(double a, double b) const {
    double uv[2] = {lon_ == 1 ? a : b, lon_ == 1 ? b : a}, r[9];
    s_.evaluate_first_derivatives_into(&uv[0], &uv[1], 1, r);
    const Eigen::Vector3d S(r[0], r[1], r[2]), Su(r[3], r[4], r[5]), Sv(r[6], r[7], r[8]);
    return lon_ == 1 ? D1{S, Su, Sv} : D1{S, Sv, Su};
  }

  /// b where x(a, b) = x0, or NaN when the plane misses this line.
  double crossing(double a) {
    double b = newton(a);
    if (std::isnan(b)) b = scan(a);
    if (!std::isnan(b)) b_warm_ = b;
    return b;
  }

 private:
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  const NurbsSurface& s_;
  double x0_;
  int lon_;
  std::vector<double> across_, along_;
  double b_warm_ = kNaN;

  double newton(double a) const {
    if (std::isnan(b_warm_)) return kNaN;
    double b = b_warm_;
    const double lo = along_.front(), hi = along_.back();
    for (int it = 0; it < 30; ++it) {
      const D1 D = first_derivs(a, b);
      const double f = D.S[0] - x0_, df = D.Sb[0];
      if (std::abs(f) <= 1e-12 * (1 + std::abs(x0_))) return b;
      if (df == 0) break;
      b -= f / df;
      if (!(b >= lo && b <= hi)) break;
    }
    return kNaN;
  }

  /// A sign change of x - x0 over four samples per knot span of b, bisected.
  double scan(double a) const {
    std::vector<double> bs;
    for (std::size_t i = 0; i + 1 < along_.size(); ++i)
      for (int k = 0; k < 4; ++k) bs.push_back(along_[i] + (along_[i + 1] - along_[i]) * k / 4);
    bs.push_back(along_.back());
    double prev = point(a, bs[0])[0] - x0_;
    if (prev == 0) return bs[0];
    for (std::size_t i = 1; i < bs.size(); ++i) {
      const double cur = point(a, bs[i])[0] - x0_;
      if (cur == 0) return bs[i];
      if ((prev < 0) != (cur < 0)) {
        double lo = bs[i - 1], hi = bs[i], flo = prev;
        for (int it = 0; it < kBisection && hi - lo > 1e-15; ++it) {
          const double mid = 0.5 * (lo + hi), fm = point(a, mid)[0] - x0_;
          if ((fm < 0) == (flo < 0)) lo = mid, flo = fm;
          else hi = mid;
        }
        return 0.5 * (lo + hi);
      }
      prev = cur;
    }
    // Tolerate x0 at the very end of the surface (round-off).
    const double tol = 1e-9 * (1 + std::abs(x0_));
    if (std::abs(point(a, bs.front())[0] - x0_) < tol) return bs.front();
    if (std::abs(point(a, bs.back())[0] - x0_) < tol) return bs.back();
    return kNaN;
  }
};

/// int y dz and int y z dz along the section over the submerged pieces of a (Gauss rule of
/// `gauss` points on each), dz = z_a + z_b db/da with db/da = -x_a / x_b (x stays x0).
std::pair<double, double> section_integrals(PlaneCrossing& cut, const std::vector<std::pair<double, double>>& pieces,
                                            int gauss) {
  const auto& g = detail::gauss_rule(gauss);
  double area = 0, mz = 0;
  for (const auto& [pa, pb] : pieces) {
    const double h = 0.5 * (pb - pa), m = 0.5 * (pa + pb);
    for (int k = 0; k < gauss; ++k) {
      const double a = m + h * g.x[k];
      const double b = cut.crossing(a);
      if (std::isnan(b)) continue;
      const PlaneCrossing::D1 D = cut.first_derivs(a, b);
      const Eigen::Vector3d& Sa = D.Sa;
      const Eigen::Vector3d& Sb = D.Sb;
      if (Sb[0] == 0) continue;
      const double db = -Sa[0] / Sb[0];
      const double dz = Sa[2] + Sb[2] * db;
      const double y = D.S[1], z = D.S[2];
      area += g.w[k] * h * y * dz;
      mz += g.w[k] * h * y * z * dz;
    }
  }
  return {area, mz};
}

}  // namespace

std::pair<double, double> section_area(const NurbsSurface& s, double x0, double draft, bool half_hull,
                                       int gauss) {
  detail::require_finite(x0, "x");
  detail::require_positive(draft, "draft");
  if (gauss < 2 || gauss > 32) fail("gauss is ", gauss, "; expected 2..32 points per knot span");
  PlaneCrossing cut(s, x0);
  auto zfun = [&](double a) {
    const double b = cut.crossing(a);
    if (std::isnan(b)) return 1.0;  // no cut here: outside
    return cut.point(a, b)[2] - draft;
  };
  const auto pieces = inside_pieces(cut.across_breaks(), zfun, [&](const std::vector<double>& ts, std::vector<double>& fs) {
    for (std::size_t i = 0; i < ts.size(); ++i) fs[i] = zfun(ts[i]);
  });
  const auto [area, mz] = section_integrals(cut, pieces, gauss);
  if (area == 0) return {0.0, 0.0};
  const double zc = mz / area;
  return {(half_hull ? 2.0 : 1.0) * std::abs(area), zc};
}

namespace {

/// Highest z of the surface sampled at (us x vs), a few u lines at a time into one small
/// buffer: this runs on every hydrostatics call, and a whole fine grid (~70 000 points) would
/// be megabytes allocated and faulted in each time.
double highest_on_grid(const NurbsSurface& s, const std::vector<double>& us, const std::vector<double>& vs) {
  const long n_u = static_cast<long>(us.size()), n_v = static_cast<long>(vs.size());
  std::vector<double> pts(static_cast<std::size_t>(kGridLines * n_v * 3));
  double top = -std::numeric_limits<double>::infinity();
  for (long a = 0; a < n_u; a += kGridLines) {
    const long lines = std::min(kGridLines, n_u - a);
    s.evaluate_grid_into(us.data() + a, lines, vs.data(), n_v, pts.data());
    for (long k = 0; k < lines * n_v; ++k) top = std::max(top, pts[3 * k + 2]);
  }
  return top;
}

/// Highest z of the surface, sampled kClipSamples times per knot span in each direction
/// (breakpoints included, so a deck edge at constant z is found exactly). The surface lies in
/// its control net's convex hull (positive weights): where a breakpoint already reaches the net's
/// highest z (a deck at constant height), no point is higher and the fine grid is skipped.
double highest_point(const NurbsSurface& s) {
  const std::vector<double> bu = breakpoints(s.knots_u(), s.degree_u());
  const std::vector<double> bv = breakpoints(s.knots_v(), s.degree_v());
  const double net_top = s.control_points().col(2).maxCoeff();
  const double at_breaks = highest_on_grid(s, bu, bv);
  const bool positive = s.weights().size() == 0 || s.weights().minCoeff() > 0.0;  // the convex hull property
  if (positive && at_breaks >= net_top - kTopFromNet * (1.0 + std::abs(net_top)))
    return at_breaks;
  auto refine = [](const std::vector<double>& b) {
    std::vector<double> t;
    for (std::size_t i = 0; i + 1 < b.size(); ++i)
      for (int k = 0; k < kClipSamples; ++k) t.push_back(b[i] + (b[i + 1] - b[i]) * k / kClipSamples);
    t.push_back(b.back());
    return t;
  };
  return highest_on_grid(s, refine(bu), refine(bv));
}

void check_options(const HydrostaticsOptions& o) {
  if (o.gauss < 2 || o.gauss > 32) fail("gauss is ", o.gauss, "; expected 2..32 points per knot span");
  if (o.sac_stations < 2) fail("sac_stations is ", o.sac_stations, "; expected at least 2");
  if (!(o.length >= 0) || !std::isfinite(o.length)) fail("length is ", o.length, "; expected 0 (automatic) or a length > 0 (m)");
  if (!(o.breadth >= 0) || !std::isfinite(o.breadth)) fail("breadth is ", o.breadth, "; expected 0 (automatic) or a breadth > 0 (m)");
  if (!(o.density > 0) || !std::isfinite(o.density)) fail("density is ", o.density, "; expected a density > 0 (t/m^3)");
  if (std::isinf(o.midship_x)) fail("midship_x is ", o.midship_x, "; expected a finite x (m) or NaN (automatic)");
  if (!std::isfinite(o.trim)) fail("trim is ", o.trim, "; expected a finite trim by the stern (m)");
  if (!(o.trim_length >= 0) || !std::isfinite(o.trim_length))
    fail("trim_length is ", o.trim_length, "; expected 0 or the length AP..FP (m)");
  if (o.trim != 0 && !(o.trim_length > 0))
    fail("trim is ", o.trim, " m but trim_length is ", o.trim_length, "; expected the length AP..FP (m) > 0");
}

/// Results from the accumulated surface integrals (see the header for the formulas).
template <typename Z>
void fill_results(Hydrostatics& h, const NurbsSurface& s, double draft, const HydrostaticsOptions& o,
                  const std::array<double, 8>& acc, double xmin, double xmax, double ymax, double slope,
                  Z&& waterline_z) {
  const double sign = acc[0] > 0 ? 1.0 : -1.0;
  const double V = sign * acc[0];
  const double factor = o.half_hull ? 2.0 : 1.0;
  const double cos_t = 1.0 / std::sqrt(1.0 + slope * slope);
  h.draft = draft;
  h.trim = o.trim;
  h.volume = factor * V;
  h.displacement = o.density * h.volume;
  h.lcb = sign * acc[1] / V;
  h.vcb = sign * acc[2] / V;
  const double awp_h = -sign * acc[3];  // half waterplane, projected on z = 0
  h.waterplane_area = factor * awp_h / cos_t;
  h.lcf = awp_h != 0 ? -sign * acc[4] / awp_h : 0.0;
  h.inertia_t = factor * (-sign * acc[5]) / cos_t;
  h.inertia_l = factor * (-sign * acc[6] - awp_h * h.lcf * h.lcf) / (cos_t * cos_t * cos_t);
  h.wetted_surface = factor * acc[7];
  h.x_min = xmin;
  h.x_max = xmax;
  h.length = o.length > 0 ? o.length : xmax - xmin;
  h.breadth = o.breadth > 0 ? o.breadth : 2.0 * ymax;
  h.midship_x = std::isnan(o.midship_x) ? 0.5 * (xmin + xmax) : o.midship_x;
  h.midship_area = section_area(s, h.midship_x, waterline_z(h.midship_x), o.half_hull, o.gauss).first;
  h.cb = h.volume / (h.length * h.breadth * draft);
  h.cm = h.midship_area / (h.breadth * draft);
  h.cp = h.midship_area > 0 ? h.volume / (h.midship_area * h.length) : 0.0;
  h.cwp = h.waterplane_area / (h.length * h.breadth);
  h.bmt = h.inertia_t / h.volume;
  h.bml = h.inertia_l / h.volume;
  h.kmt = h.vcb + h.bmt;
  h.kml = h.vcb + h.bml;
  h.tpc = o.density * h.waterplane_area / 100.0;
  h.mct1cm = h.displacement * h.bml / (100.0 * h.length);
  h.sac_x = Eigen::VectorXd::LinSpaced(o.sac_stations, xmin, xmax);
  h.sac_area.resize(o.sac_stations);
  for (int k = 0; k < o.sac_stations; ++k) {
    const double zl = waterline_z(h.sac_x[k]);
    h.sac_area[k] = zl > 0 ? section_area(s, h.sac_x[k], zl, o.half_hull, o.gauss).first : 0.0;
  }
}

}  // namespace

Hydrostatics hydrostatics(const NurbsSurface& surface, double draft, const HydrostaticsOptions& o) {
  detail::require_positive(draft, "draft");
  check_options(o);
  const NurbsSurface s = vertical_u(surface);
  // Waterplane z = draft + slope (x - x_ref): level when untrimmed.
  const double slope = o.trim != 0 ? -o.trim / o.trim_length : 0.0;
  const double x_ref = 0.5 * o.trim_length;
  auto waterline_z = [&](double x) { return draft + slope * (x - x_ref); };
  SurfaceSums sums = integrate_below(s, o.gauss, waterline_z);
  if (sums.acc[0] == 0) fail("the surface has nothing below draft ", draft, " m; expected a draft above its lowest point");
  // Also sample the domain edges in v so the extent includes the surface ends.
  const std::vector<double> bu = breakpoints(s.knots_u(), s.degree_u());
  const std::vector<double> bv = breakpoints(s.knots_v(), s.degree_v());
  for (double v : {bv.front(), bv.back()})
    for (double u : bu) {
      const Eigen::Vector3d P = s.evaluate(u, v);
      if (P[2] <= waterline_z(P[0])) sums.extend(P);
    }
  const double xmin = sums.xmin, xmax = sums.xmax, ymax = sums.ymax;
  const std::array<double, 4> lids = end_lid_fluxes(s, o.gauss, waterline_z);
  for (int k = 0; k < 4; ++k) sums.acc[3 + k] += lids[k];
  const std::array<double, 8>& acc = sums.acc;
  Hydrostatics h;
  h.z_max = highest_point(s);
  // The body is closed only up to the surface's top: a waterplane above it anywhere along the
  // submerged extent would be an open, meaningless volume.
  const double z_wl_top = std::max(waterline_z(xmin), waterline_z(xmax));
  if (z_wl_top > h.z_max + kAboveTopTolerance * (1 + std::abs(h.z_max)))
    fail("draft ", draft, " m puts the waterplane at z = ", z_wl_top, " m, above the surface's highest point z = ",
         h.z_max, " m (the deck); expected a waterplane at or below it");
  fill_results(h, s, draft, o, acc, xmin, xmax, ymax, slope, waterline_z);
  return h;
}

PatchHydrostatics hydrostatics_of_patches(const std::vector<NurbsSurface>& patches, double draft, double end_x,
                                          bool half_hull, int gauss) {
  if (patches.empty()) fail("patches is empty; expected the NURBS patches that bound the body");
  detail::require_positive(draft, "draft");
  detail::require_finite(end_x, "end_x");
  if (gauss < 2 || gauss > 32) fail("gauss is ", gauss, "; expected 2..32 points per knot span");
  auto level = [draft](double) { return draft; };
  std::array<double, 8> total{};
  for (const NurbsSurface& patch : patches) {
    const SurfaceSums p = integrate_below(vertical_u(patch), gauss, level);
    // Outward by the mesh rule: a side-like patch has int y n_y > 0, an end-like one
    // int (x - end_x) n_x > 0.
    const double flux = p.abs_ny >= p.abs_nx ? p.acc[0] : p.x_nx - end_x * p.nx;
    const double sign = flux < 0 ? -1.0 : 1.0;
    for (std::size_t k = 0; k < total.size(); ++k) total[k] += k == 7 ? p.acc[k] : sign * p.acc[k];
  }
  const double factor = half_hull ? 2.0 : 1.0;
  PatchHydrostatics h;
  h.draft = draft;
  h.volume = factor * total[0];
  h.lcb = total[0] != 0 ? total[1] / total[0] : 0.0;
  h.vcb = total[0] != 0 ? total[2] / total[0] : 0.0;
  h.waterplane_area = -factor * total[3];
  h.lcf = total[3] != 0 ? total[4] / total[3] : 0.0;
  h.wetted_surface = factor * total[7];
  return h;
}

}  // namespace fairlines
