// Bare-hull sections on one shared knot vector: see fairlines/sections.hpp.
#include "fairlines/sections.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include <Eigen/Dense>

#include "fairlines/basis.hpp"
#include "fairlines/errors.hpp"
#include "fairlines/knots.hpp"
#include "nurbs/checks.hpp"
#include "nurbs/gauss.hpp"
#include "nurbs/gram.hpp"

namespace fairlines {

namespace {

using detail::fail;
using V2 = Eigen::Vector2d;

constexpr int kDegree = 3;
constexpr double kBottomAngleSlack = 5.0;  // deg: a bottom angle this far below -90 (noise of measured data) is -90
constexpr double kFeasibleTol = 1e-9;    // relative residual above which the conditions contradict each other
constexpr int kCheckSamples = 12;        // samples per knot span when checking the designed section
constexpr int kCentroidIterations = 30;  // Newton steps for the (cubic) centroid condition
constexpr double kCentroidTol = 1e-12;   // relative residual of the centroid condition

std::string fmt(double v) {
  std::ostringstream os;
  os.precision(6);
  os << v;
  return os.str();
}

double cross(const V2& a, const V2& b) { return a.x() * b.y() - a.y() * b.x(); }

/// C2 step from 0 (r <= 0) to 1 (r >= 1).
double smoothstep(double r) {
  r = std::clamp(r, 0.0, 1.0);
  return r * r * r * (10.0 - 15.0 * r + 6.0 * r * r);
}

/// Zone length from the flat's length L (may be negative: no flat) and the floor f: a soft
/// maximum, ~L + f^2 / L where the flat is long, f where there is none, smooth in between.
double zone_length(double L, double f) { return f + 0.5 * ((L - f) + std::sqrt((L - f) * (L - f) + 4.0 * f * f)); }

/// Unit tangent going down the section for an angle in degrees from the downward vertical
/// toward +y; exactly vertical / horizontal at 0 and -90 so flats are exact.
V2 tangent(double alpha_deg) {
  if (alpha_deg == 0.0) return V2(0.0, -1.0);
  if (alpha_deg == -90.0) return V2(-1.0, 0.0);
  const double a = alpha_deg * std::numbers::pi / 180.0;
  return V2(std::sin(a), -std::cos(a));
}

/// Equality-constrained least E2: min eta' G eta subject to rows eta = rhs. The rows are
/// normalised; conflicting rows show as a residual (returned in `bad`, by name).
struct Constraints {
  std::vector<Eigen::RowVectorXd> rows;
  std::vector<double> rhs;
  std::vector<std::string> names;
  void add(Eigen::RowVectorXd r, double b, std::string name) {
    const double s = r.norm();
    if (s > 0) r /= s, b /= s;
    rows.push_back(std::move(r));
    rhs.push_back(b);
    names.push_back(std::move(name));
  }
};

Eigen::VectorXd kkt_solve(const Eigen::MatrixXd& G, const Constraints& c, const std::string& at) {
  const int n = static_cast<int>(G.rows()), m = static_cast<int>(c.rows.size());
  if (m > n) fail(at, ": ", m, " conditions on a curved part with ", n, " control points; expected more control points (sections.n_control)");
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n + m, n + m);
  const double gs = std::max(1e-300, (2.0 * G).cwiseAbs().maxCoeff());
  K.topLeftCorner(n, n) = 2.0 * G / gs;
  Eigen::VectorXd b = Eigen::VectorXd::Zero(n + m);
  for (int i = 0; i < m; ++i) {
    K.block(n + i, 0, 1, n) = c.rows[i];
    K.block(0, n + i, n, 1) = c.rows[i].transpose();
    b[n + i] = c.rhs[i];
  }
  const Eigen::VectorXd sol = Eigen::FullPivLU<Eigen::MatrixXd>(K).solve(b);
  const Eigen::VectorXd eta = sol.head(n);
  double scale = 1e-300;
  for (int i = 0; i < m; ++i) scale = std::max(scale, std::abs(c.rhs[i]) + c.rows[i].cwiseAbs().sum() * eta.cwiseAbs().maxCoeff());
  for (int i = 0; i < m; ++i)
    if (!std::isfinite(c.rows[i].dot(eta)) || std::abs(c.rows[i].dot(eta) - c.rhs[i]) > kFeasibleTol * scale) {
      std::string list;
      for (const auto& s : c.names) list += (list.empty() ? "" : ", ") + s;
      throw InfeasibleFormParameters(at + ": the section conditions " + list + " contradict each other on a curved part with " +
                                     std::to_string(n) + " control points (not met: " + c.names[i] + ")");
    }
  return eta;
}

}  // namespace

Eigen::VectorXd section_knot_vector(int n_control) {
  if (n_control < 8) fail("sections.n_control is ", n_control, "; expected at least 8 (six control points make the G2 legs)");
  const int spans = n_control - kDegree;
  Eigen::VectorXd U(n_control + 10);
  int k = 0;
  for (int i = 0; i <= kDegree; ++i) U[k++] = 0.0;
  for (int i = 0; i < kDegree; ++i) U[k++] = kTopZoneEnd;
  for (int i = 1; i < spans; ++i) U[k++] = kTopZoneEnd + (kBottomZoneStart - kTopZoneEnd) * i / spans;
  for (int i = 0; i < kDegree; ++i) U[k++] = kBottomZoneStart;
  for (int i = 0; i <= kDegree; ++i) U[k++] = 1.0;
  return U;
}

std::vector<std::pair<int, int>> section_straight_groups(int n_control) {
  section_knot_vector(n_control);  // validates n_control
  const int n = n_control + 6;
  // Rows 0..3: the top zone, from the deck point to A at fractions 0, 1/3, 2/3, 1 in every
  // section; rows n-4..n-1 the bottom zone from E to the keel point likewise.
  return {{0, 3}, {n - 4, n - 1}};
}

NurbsCurve design_section(const SectionSpec& s, double y_max) {
  const std::string at = "section at x = " + fmt(s.x) + " m";
  auto finite = [&](double v, const char* field) {
    if (!std::isfinite(v)) fail(at, ": ", field, " is ", v, "; expected a finite number");
  };
  finite(s.x, "x");
  finite(s.z_deck, "z_deck");
  finite(s.y_deck, "y_deck");
  finite(s.draft, "draft");
  finite(s.y_dwl, "y_dwl");
  finite(s.z_keel, "z_keel");
  finite(s.half_area, "half_area");
  finite(s.y_fob, "y_fob");
  finite(s.alpha_deck, "alpha_deck");
  finite(s.alpha_bottom, "alpha_bottom");
  if (std::isinf(s.z_fos)) fail(at, ": z_fos is ", s.z_fos, "; expected a height or NaN (no flat side)");
  if (std::isinf(s.z_centroid)) fail(at, ": z_centroid is ", s.z_centroid, "; expected a height or NaN (free)");
  if (std::isinf(s.flat_departure)) fail(at, ": flat_departure is ", s.flat_departure, "; expected a rate (1/m^2) or NaN");
  if (!(y_max > 0) || !std::isfinite(y_max)) fail("y_max is ", y_max, "; expected a half-breadth > 0 (m)");
  if (s.degree != kDegree) fail(at, ": degree is ", s.degree, "; expected 3 (sections are cubic)");
  const int nc = s.n_control;
  const Eigen::VectorXd U = section_knot_vector(nc);
  if (!(s.z_keel < s.draft)) fail(at, ": keel height ", s.z_keel, " m is not below the DWL ", s.draft, " m (centre profile)");
  if (!(s.draft < s.z_deck)) fail(at, ": DWL ", s.draft, " m is not below the deck ", s.z_deck, " m");
  if (!(std::abs(s.alpha_deck) < 90.0)) fail(at, ": alpha_deck is ", s.alpha_deck, " deg; expected an angle between -90 and 90");
  if (!(s.alpha_bottom >= -90.0 - kBottomAngleSlack && s.alpha_bottom < 90.0))
    fail(at, ": alpha_bottom is ", s.alpha_bottom, " deg; expected an angle from -90 (horizontal) to 90");
  const double alpha_bottom = std::max(s.alpha_bottom, -90.0);
  const double tol = 1e-9 * (y_max + std::abs(s.z_deck));
  for (auto [v, field] : {std::pair{s.y_deck, "y_deck (deck curve)"}, std::pair{s.y_dwl, "y_dwl (design waterline)"}})
    if (v < -tol || v > y_max + tol) fail(at, ": ", field, " is ", v, " m; expected 0 <= y <= ", y_max, " m (B/2)");
  if (s.y_fob > y_max + tol) fail(at, ": y_fob (flat of bottom) is ", s.y_fob, " m; expected at most B/2 = ", y_max, " m");
  if (s.half_area < 0) fail(at, ": half area is ", s.half_area, " m^2; expected >= 0 (sectional area curve)");
  const double depth_dwl = s.draft - s.z_keel;
  if (s.half_area > y_max * depth_dwl * (1 + 1e-12))
    throw InfeasibleFormParameters(at + ": half area " + fmt(s.half_area) + " m^2 exceeds the rectangle B/2 x (T - z_keel) = " +
                                   fmt(y_max * depth_dwl) + " m^2 (sectional area curve vs breadth and centre profile)");

  const double D = s.z_deck, T = s.draft;
  const double y_deck = std::clamp(s.y_deck, 0.0, y_max), y_dwl = std::clamp(s.y_dwl, 0.0, y_max);
  const double breadth = std::max({y_deck, y_dwl, s.y_fob, 0.0});
  const bool stem = breadth <= tol;
  if (stem && s.half_area > tol * y_max)
    throw InfeasibleFormParameters(at + ": half area " + fmt(s.half_area) +
                                   " m^2 with zero breadth at deck, DWL and bottom (sectional area curve vs design waterline and deck)");
  const double floor_len = kZoneFloor * (D - s.z_keel);
  const double floor_eff = std::max(0.1 * floor_len, std::min(floor_len, breadth / 4.0));

  // Zones. A flat of side needs the deck at B/2 with a vertical tangent; a flat of bottom a
  // horizontal tangent at the keel.
  const double L_top = std::isnan(s.z_fos) ? -(D - s.z_keel) : D - s.z_fos;
  const double L_bot = s.y_fob;
  const bool flat_side = L_top > tol && !stem, flat_bottom = L_bot > tol && !stem;
  // Under a flat the zone is exactly vertical / horizontal whatever the angle curves say (they
  // apply where there is no flat; consistent curves are 0 / -90 there, and measured ones
  // carry noise).
  const double fade = smoothstep(breadth / (kAngleFadeBreadth * y_max));
  const V2 Tt = stem ? V2(0.0, -1.0) : tangent(flat_side ? 0.0 : s.alpha_deck * fade);
  const V2 Tb = stem ? V2(0.0, -1.0) : tangent(flat_bottom ? -90.0 : alpha_bottom * fade);
  const double lt = stem ? floor_eff : zone_length(L_top, floor_eff);
  const double lb = stem ? floor_eff : zone_length(L_bot, floor_eff);
  const V2 P_deck(y_deck, D), K(0.0, s.z_keel);
  const V2 A = P_deck + lt * Tt, E = K - lb * Tb;
  if (!(E.y() < T))
    throw InfeasibleFormParameters(at + ": the keel (z = " + fmt(s.z_keel) + " m) leaves no room below the DWL for the bottom zone");
  if (!(A.y() > E.y()))
    throw InfeasibleFormParameters(at + ": the flat of side reaches down to the bottom (z = " + fmt(A.y()) +
                                   " m); expected the fos curve above the keel");

  // The curved part: a graph over the chord A -> E.
  const V2 chord = E - A;
  const double Lc = chord.norm();
  const V2 d = chord / Lc, n(-d.y(), d.x());
  const Eigen::VectorXd Uc = clamped_uniform_knots(nc, kDegree);
  const Eigen::VectorXd g = greville_abscissae(Uc, kDegree);  // xi(t) = Lc t exactly
  const double td = Tt.dot(d), bd = Tb.dot(d);
  if (!stem && (td < kMinTangentChordCos || bd < kMinTangentChordCos))
    throw InfeasibleFormParameters(at + ": the " + std::string(td < kMinTangentChordCos ? "deck" : "bottom") +
                                   " tangent (" + fmt(td < kMinTangentChordCos ? s.alpha_deck : s.alpha_bottom) +
                                   " deg) points across the section instead of toward the " +
                                   std::string(td < kMinTangentChordCos ? "keel" : "deck") +
                                   " (deck_angle / bottom_angle curves vs the section's breadth and depth)");
  // Legs: the first and last three control points on the zones' lines (G2 joints with flats;
  // the third ones are released where there is no flat, see wt / wb below).
  std::vector<V2> P(nc);
  // At a stem (zero breadth) the whole section is the centre-line segment A -> E.
  if (stem)
    for (int k = 0; k < nc; ++k) P[k] = A + Lc * g[k] * d;
  for (int k : {0, 1, 2}) {
    P[k] = stem ? V2(A + Lc * g[k] * d) : V2(A + (Lc * g[k] / td) * Tt);
  }
  for (int k : {nc - 1, nc - 2, nc - 3}) {
    P[k] = stem ? V2(A + Lc * g[k] * d) : V2(E - (Lc * (1.0 - g[k]) / bd) * Tb);
  }
  P[0] = A, P[nc - 1] = E;

  Eigen::VectorXd eta = Eigen::VectorXd::Zero(nc);
  if (!stem) {
    Constraints base;
    auto unit = [&](int k) {
      Eigen::RowVectorXd r = Eigen::RowVectorXd::Zero(nc);
      r[k] = 1.0;
      return r;
    };
    // P0, P1 (and E, P_n-2) on the zones' lines always: tangent continuity. P2 (and P_n-3) too
    // where the zone is a flat: zero curvature there, G2 with the flat (see g2 below).
    for (int k : {0, 1, nc - 2, nc - 1}) base.add(unit(k), (P[k] - A).dot(n), "end tangents");
    const Eigen::RowVectorXd g2_top_row = unit(2), g2_bot_row = unit(nc - 3);
    const double g2_top_val = (P[2] - A).dot(n), g2_bot_val = (P[nc - 3] - A).dot(n);
    // E2 of the ordinates (the abscissae are linear in t).
    const Eigen::MatrixXd G = detail::derivative_gram(Uc, kDegree, 2);
    // The DWL: on the top zone (then its half-breadth must be the zone's) or a point of the
    // curved part at t_Q = xi_Q / Lc.
    const bool dwl_on_top = T >= A.y();
    double t_from = 0.0;
    V2 Q(y_dwl, T);
    if (dwl_on_top) {
      const V2 Qz = P_deck + ((D - T) / -Tt.y()) * Tt;
      if (std::abs(Qz.x() - y_dwl) > kSectionBoundTol * y_max + 1e-9)
        throw InfeasibleFormParameters(at + ": the DWL half-breadth " + fmt(s.y_dwl) + " m differs from the " +
                                       (flat_side ? "flat of side's " : "deck leg's ") + fmt(Qz.x()) +
                                       " m at z = T (the design waterline leaves B/2 where the fos curve is still below the DWL)");
      Q = Qz;
    } else {
      const double xq = (Q - A).dot(d);
      if (!(xq > 0 && xq < Lc))
        throw InfeasibleFormParameters(at + ": the DWL point (" + fmt(y_dwl) + ", " + fmt(T) +
                                       ") m lies outside the section's curved part (design waterline vs deck and keel)");
      t_from = xq / Lc;
    }
    // Half area below the DWL by Green's theorem along Q -> curve -> E -> K -> (0, T) -> Q
    // (clockwise, so the area is minus half the sum of P x dP). On the curved part
    // P x P' = Lc (A x d) + (A x n) eta' + (d x n) Lc (t eta' - eta): linear in eta.
    // Knot spans of the curved part below the DWL point (quadrature pieces).
    std::vector<double> br{t_from};
    for (int i = kDegree + 1; i < nc; ++i)
      if (Uc[i] > t_from) br.push_back(Uc[i]);
    br.push_back(1.0);
    // Gauss-Legendre with `points` nodes on each piece: f(t, weight, N(t), N'(t)).
    auto integrate = [&](int points, auto&& f) {
      const auto& gr = detail::gauss_rule(points);
      for (std::size_t k = 0; k + 1 < br.size(); ++k) {
        const double h = 0.5 * (br[k + 1] - br[k]), m = 0.5 * (br[k + 1] + br[k]);
        if (!(h > 0)) continue;
        for (std::size_t q = 0; q < gr.x.size(); ++q) {
          const double t = m + h * gr.x[q];
          f(t, gr.w[q] * h, basis_row(Uc, kDegree, t), basis_row(Uc, kDegree, t, 1));
        }
      }
    };
    Eigen::RowVectorXd area_row = Eigen::RowVectorXd::Zero(nc);
    double area_const = 0.0;
    {
      const double Axd = cross(A, d), Axn = cross(A, n), dxn = cross(d, n);
      integrate(3, [&](double t, double w, const Eigen::RowVectorXd& N, const Eigen::RowVectorXd& dN) {
        area_const += 0.5 * w * Lc * Axd;
        area_row += 0.5 * w * (Axn * dN + dxn * Lc * (t * dN - N));
      });
      area_const += 0.5 * cross(E, K) + 0.5 * cross(V2(0.0, T), Q);
      if (dwl_on_top) area_const += 0.5 * cross(Q, A);
    }
    base.add(-area_row, s.half_area + area_const, "Area");
    Eigen::RowVectorXd dwl_row;
    if (!dwl_on_top) dwl_row = basis_row(Uc, kDegree, t_from);
    const double eta_Q = (Q - A).dot(n);

    // Centroid height (optional): int z dA = sum of (z^2 / 2) dy along the clockwise boundary,
    // cubic in eta on the curved part; met by Newton steps on its linearisation (at the fixed
    // point the KKT conditions of the nonlinear problem hold).
    const bool want_zc = std::isfinite(s.z_centroid);
    auto moment = [&](const Eigen::VectorXd& e, Eigen::RowVectorXd* grad) {
      double M = 0.0;
      if (grad) *grad = Eigen::RowVectorXd::Zero(nc);
      integrate(6, [&](double t, double w, const Eigen::RowVectorXd& N, const Eigen::RowVectorXd& dN) {
        const double et = N.dot(e), det = dN.dot(e);
        const double z = A.y() + Lc * t * d.y() + et * n.y(), dy = Lc * d.x() + det * n.x();
        M += w * 0.5 * z * z * dy;
        if (grad) *grad += w * (z * n.y() * dy * N + 0.5 * z * z * n.x() * dN);
      });
      auto seg = [](const V2& p1, const V2& p2) { return (p2.x() - p1.x()) * (p1.y() * p1.y() + p1.y() * p2.y() + p2.y() * p2.y()) / 6.0; };
      M += seg(E, K) + seg(K, V2(0.0, T)) + seg(V2(0.0, T), Q);
      if (dwl_on_top) M += seg(Q, A);
      return M;
    };
    // The fairest curve meeting the conditions, with its control polygon kept inside
    // 0 <= y <= B/2 (then so is the curve): control points that leave it are pinned to the
    // bound one at a time, the most violated first. Consistent basic curves never get here; it
    // keeps a slider that asks for a little too much area from failing (the section flattens
    // against B/2 there, as a real flat of side would).
    auto bounded = [&](Constraints c) {
      const double ytol = kSectionBoundTol * y_max;
      for (int it = 0; it < nc; ++it) {
        const Eigen::VectorXd e = kkt_solve(G, c, at);
        int worst = -1;
        double excess = ytol, target = 0.0;
        for (int k = 2; k < nc - 2; ++k) {
          const double y = A.x() + Lc * g[k] * d.x() + e[k] * n.x();
          if (y - y_max > excess) worst = k, excess = y - y_max, target = y_max;
          if (-y > excess) worst = k, excess = -y, target = 0.0;
        }
        if (worst < 0) return e;
        if (!(std::abs(n.x()) > 1e-9))
          throw InfeasibleFormParameters(at + ": the section leaves 0 <= y <= B/2 and its chord is horizontal (no room to keep it in)");
        c.add(unit(worst) * n.x(), target - A.x() - Lc * g[worst] * d.x(), "0 <= y <= B/2");
      }
      return kkt_solve(G, c, at);
    };
    auto solve = [&](const Constraints& c) {
      if (!want_zc) return bounded(c);
      const double target = s.z_centroid * s.half_area;
      Eigen::VectorXd e = bounded(c);
      const double scale = std::max(1e-300, std::abs(target) + s.half_area * std::max(std::abs(T), std::abs(s.z_keel)));
      for (int it = 0; it < kCentroidIterations; ++it) {
        Eigen::RowVectorXd gradM;
        const double M = moment(e, &gradM);
        if (std::abs(M - target) <= kCentroidTol * scale) return e;
        Constraints cc = c;
        cc.add(gradM, target - M + gradM.dot(e), "z_centroid");
        e = bounded(cc);
      }
      const double M = moment(e, nullptr);
      if (std::abs(M - target) <= 1e3 * kCentroidTol * scale) return e;
      throw ConvergenceError(at + ": the section's centroid height " + fmt(s.z_centroid) + " m was not met after " +
                             std::to_string(kCentroidIterations) + " Newton steps (residual " + fmt(M - target) + " m^3)");
    };
    auto with = [](Constraints c, const Eigen::RowVectorXd& r, double b, const char* name) {
      c.add(r, b, name);
      return c;
    };

    // Departure from a flat of side near the DWL crossing (see SectionSpec::flat_departure):
    // in the first span only P_3 leaves the flat's line, so the breadth lost at depth
    // depth(t) = 3 t lambda_1 / u4 + ... is off_3 N_3(t) = off_3 t^3 / (u4 u5 u6): the rate K
    // fixes off_3 = K 27 lambda_1^3 u5 u6 / u4^2.
    const bool departure = flat_side && std::isfinite(s.flat_departure) && s.flat_departure >= 0;
    Eigen::RowVectorXd off_row = Eigen::RowVectorXd::Zero(nc);
    double off_const = 0.0, off_T = 0.0;
    if (departure) {
      const V2 m_in(Tt.y(), -Tt.x());  // inward normal of the flat (away from B/2)
      off_row[3] = n.dot(m_in);
      off_const = Lc * g[3] * d.dot(m_in);
      const double lambda1 = Lc * g[1] / td, u4 = Uc[4], u5 = Uc[5], u6 = Uc[6];
      off_T = s.flat_departure * 27.0 * lambda1 * lambda1 * lambda1 * u5 * u6 / (u4 * u4);
    }
    const double band = kDepartureBand * T, near = kDwlNearBand * T;
    const double below = T - A.y();  // > 0: the flat ends below the DWL
    auto design = [&](bool g2_top, bool g2_bot) -> Eigen::VectorXd {
      Constraints c = base;
      if (g2_top) c.add(g2_top_row, g2_top_val, "zero curvature leaving the flat of side");
      if (g2_bot) c.add(g2_bot_row, g2_bot_val, "zero curvature meeting the flat of bottom");
      if (g2_top && departure && below >= 0 && below < band) {
        // Aft of the crossing: blend the free departure toward the DWL's rate.
        const Eigen::VectorXd free = solve(c);
        const double w = smoothstep(1.0 - below / band);
        const double target = (1.0 - w) * (off_row.dot(free) + off_const) + w * off_T;
        return solve(with(c, off_row, target - off_const, "departure from the flat of side"));
      }
      if (g2_top && departure && below < 0 && -below < near) {
        // Just forward of the crossing the DWL point sits millimetres below the flat's end:
        // blend from the departure condition (its limit) to the exact DWL point.
        const double sw = smoothstep(-below / near);
        const Eigen::VectorXd e_dep = solve(with(c, off_row, off_T - off_const, "departure from the flat of side"));
        return sw > 0 ? Eigen::VectorXd((1.0 - sw) * e_dep + sw * solve(with(c, dwl_row, eta_Q, "DWL point"))) : e_dep;
      }
      if (!dwl_on_top) return solve(with(c, dwl_row, eta_Q, "DWL point"));
      return solve(c);
    };
    // Zero end curvature (G2) is what a flat asks for; where there is none the end curvature is
    // left to the fairness, so cuts near the deck and keel keep a definite curvature. In between
    // the two designs blend with the flat's length (over kG2Blend of the depth): nothing jumps.
    const double g2_len = kG2Blend * (D - s.z_keel);
    const double wt = smoothstep(L_top / g2_len), wb = smoothstep(L_bot / g2_len);
    eta.setZero();
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b) {
        const double w = (a ? wt : 1.0 - wt) * (b ? wb : 1.0 - wb);
        if (w > 0) eta += w * design(a == 1, b == 1);
      }
    for (int k = 1; k < nc - 1; ++k) {
      const bool exact = k == 1 || k == nc - 2 || (k == 2 && wt == 1.0) || (k == nc - 3 && wb == 1.0);
      if (!exact) P[k] = A + (Lc * g[k]) * d + eta[k] * n;
    }
  }

  // Assemble: top zone, curved part, bottom zone.
  const int np = nc + 6;
  Eigen::MatrixXd C(np, 3);
  int r = 0;
  for (int k = 0; k < 3; ++k, ++r) {
    const V2 p = P_deck + (lt * k / 3.0) * Tt;
    C.row(r) << s.x, p.x(), p.y();
  }
  for (int k = 0; k < nc; ++k, ++r) C.row(r) << s.x, P[k].x(), P[k].y();
  for (int k = 1; k <= 3; ++k, ++r) {
    const V2 p = k == 3 ? K : E + (lb * k / 3.0) * Tb;
    C.row(r) << s.x, p.x(), p.y();
  }
  NurbsCurve curve(kDegree, U, C);

  // Checks: inside 0 <= y <= B/2 and going down all the way (plane cuts need sections that do not fold).
  if (!stem) {
    const double ytol = kSectionBoundTol * y_max;
    double z_prev = std::numeric_limits<double>::infinity();
    for (int sp = 0; sp + 1 < U.size(); ++sp) {
      if (!(U[sp + 1] > U[sp])) continue;
      for (int q = 0; q <= kCheckSamples; ++q) {
        const Eigen::VectorXd p = curve.evaluate(U[sp] + (U[sp + 1] - U[sp]) * q / kCheckSamples);
        if (p[1] > y_max + ytol)
          throw InfeasibleFormParameters(at + ": the section reaches y = " + fmt(p[1]) + " m at z = " + fmt(p[2]) +
                                         " m, beyond B/2 = " + fmt(y_max) +
                                         " m (the sectional area curve asks more area than the design waterline, flat of side and keel leave room for)");
        if (p[1] < -ytol)
          throw InfeasibleFormParameters(at + ": the section crosses the centre plane (y = " + fmt(p[1]) + " m at z = " + fmt(p[2]) +
                                         " m; the sectional area curve asks less area than the design waterline, deck and end angles make)");
        if (p[2] > z_prev + ytol)
          throw InfeasibleFormParameters(at + ": the section turns upward at z = " + fmt(p[2]) +
                                         " m (the deck_angle / bottom_angle curves or the area fold it back)");
        z_prev = std::min(z_prev, p[2]);
      }
    }
  }
  return curve;
}

std::vector<NurbsCurve> design_sections(const std::vector<SectionSpec>& specs, double y_max) {
  std::vector<NurbsCurve> out;
  out.reserve(specs.size());
  for (const SectionSpec& s : specs) out.push_back(design_section(s, y_max));
  return out;
}

}  // namespace fairlines
