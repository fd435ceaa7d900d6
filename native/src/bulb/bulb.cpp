// Bulbous bow from Kracht coefficients, see fairlines/bulb.hpp.
#include "fairlines/bulb.hpp"

#include <algorithm>
#include <cmath>
#include <vector>
#include <functional>
#include <sstream>

#include "fairlines/errors.hpp"
#include "fairlines/fitting.hpp"
#include "fairlines/knots.hpp"
#include "nurbs/checks.hpp"

namespace fairlines {

namespace {

/// int_0^1 (1 - xi^m)^(p/m) dxi by composite 5-point Gauss-Legendre on graded panels
/// (the integrand's derivative is singular at xi = 1, so panels shrink toward it).
double outline_integral(double m, double p) {
  static const double gx[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                               0.9061798459386640};
  static const double gw[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                               0.4786286704993665, 0.2369268850561891};
  constexpr int kPanels = 60;
  double sum = 0.0;
  for (int k = 0; k < kPanels; ++k) {
    // graded: s in [0,1] -> xi = 1 - (1 - s)^3 clusters panels near xi = 1
    const double s0 = static_cast<double>(k) / kPanels, s1 = static_cast<double>(k + 1) / kPanels;
    const double a = 1.0 - std::pow(1.0 - s0, 3), b = 1.0 - std::pow(1.0 - s1, 3);
    for (int g = 0; g < 5; ++g) {
      const double xi = 0.5 * (a + b) + 0.5 * (b - a) * gx[g];
      sum += 0.5 * (b - a) * gw[g] * std::pow(std::max(0.0, 1.0 - std::pow(xi, m)), p / m);
    }
  }
  return sum;
}

double kappa(double n) {  // area of the superellipse |x|^n + |y|^n <= 1 over 4
  return std::exp(2.0 * std::lgamma(1.0 + 1.0 / n) - std::lgamma(1.0 + 2.0 / n));
}

/// Bisection of an increasing function g on [lo, hi] for g = target; false when outside.
bool bisect(const std::function<double(double)>& g, double lo, double hi, double target, double& out) {
  double glo = g(lo), ghi = g(hi);
  if (target < glo || target > ghi) return false;
  for (int it = 0; it < 200 && hi - lo > 1e-13 * hi; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (g(mid) < target) lo = mid;
    else hi = mid;
  }
  out = 0.5 * (lo + hi);
  (void)glo;
  (void)ghi;
  return true;
}

constexpr double kExponentMin = 1.0;         // nose outline: below, a pointed (concave) nose
constexpr double kExponentMax = 12.0;        // above: practically a box
constexpr double kSectionExponentMin = 1.6;  // sections: below, a diamond a fair skin cannot follow

}  // namespace

namespace {

void require_coefficients(const KrachtCoefficients& k, const ShipParticulars& ship) {
  detail::require_positive({{ship.lpp, "lpp"}, {ship.beam, "beam"}, {ship.draft_fp, "draft_fp"},
                            {ship.midship_area, "midship_area"}, {ship.displacement_volume, "displacement_volume"}});
  detail::require_positive({{k.c_lpr, "c_lpr"}, {k.c_bb, "c_bb"}, {k.c_zb, "c_zb"}, {k.c_abt, "c_abt"},
                            {k.c_abl, "c_abl"}, {k.c_vpr, "c_vpr"}});
}

/// The requested dimensions, the nose exponent m from the volume and the section height H from
/// the lateral area (the section exponent is left to the caller).
BulbShape dimensions(const KrachtCoefficients& k, const ShipParticulars& ship) {
  BulbShape s{};
  s.x_fp = fp_x(ship);
  s.length = k.c_lpr * ship.lpp;
  s.breadth = k.c_bb * ship.beam;
  s.nose_height = k.c_zb * ship.draft_fp;
  s.section_area = k.c_abt * ship.midship_area;
  s.lateral_area = k.c_abl * ship.midship_area;
  s.volume = k.c_vpr * ship.displacement_volume;

  // V_PR = A_BT L_PR phi2(m): the nose exponent m from the volume.
  const double phi2 = s.volume / (s.section_area * s.length);
  if (!bisect([](double m) { return outline_integral(m, 2.0); }, kExponentMin, kExponentMax, phi2, s.nose_shape)) {
    std::ostringstream os;
    os << "c_vpr, c_abt and c_lpr conflict: V_PR / (A_BT L_PR) = " << phi2 << " but a bulb nose needs it in ["
       << outline_integral(kExponentMin, 2.0) << ", " << outline_integral(kExponentMax, 2.0) << "]";
    throw InfeasibleFormParameters(os.str());
  }
  // A_BL = H L_PR phi1(m): the section height.
  s.height = s.lateral_area / (s.length * outline_integral(s.nose_shape, 1.0));
  return s;
}

}  // namespace

SectionFullness bulb_section_fullness(const KrachtCoefficients& k, const ShipParticulars& ship) {
  require_coefficients(k, ship);
  const BulbShape s = dimensions(k, ship);
  return {s.section_area / (s.breadth * s.height), kappa(kSectionExponentMin), kappa(kExponentMax)};
}

BulbousBow make_bulbous_bow(const KrachtCoefficients& k, const ShipParticulars& ship, const BulbOptions& o) {
  require_coefficients(k, ship);
  detail::require_finite(o.nose_height_shift, "nose_height_shift");
  if (o.aft_length < 0.0 || !std::isfinite(o.aft_length))
    detail::fail("aft_length is ", o.aft_length, "; expected >= 0 metres (0: twice protrusion + breadth)");
  if (o.sections < 8) detail::fail("sections is ", o.sections, "; expected >= 8");
  if (o.section_points < 8) detail::fail("section_points is ", o.section_points, "; expected >= 8");
  if (o.control_u < 4 || o.control_u > o.sections)
    detail::fail("control_u is ", o.control_u, "; expected 4 <= control_u <= sections (", o.sections, ")");
  if (o.control_v < 4 || o.control_v > o.section_points)
    detail::fail("control_v is ", o.control_v, "; expected 4 <= control_v <= section_points (", o.section_points, ")");

  BulbShape s = dimensions(k, ship);
  // A_BT = B_B H kappa(n): the section fullness.
  const double kap = s.section_area / (s.breadth * s.height);
  if (!bisect(kappa, kSectionExponentMin, kExponentMax, kap, s.section_fullness)) {
    std::ostringstream os;
    os << "c_abt, c_bb and c_abl conflict: A_BT / (B_B H) = " << kap << " (H = " << s.height
       << " m from c_abl) but a bulb section needs it in [" << kappa(kSectionExponentMin) << ", " << kappa(kExponentMax)
       << "]";
    throw InfeasibleFormParameters(os.str());
  }
  const double zc = s.nose_height + o.nose_height_shift;
  if (zc - 0.5 * s.height < 0.0) {
    std::ostringstream os;
    os << "c_zb and c_abl conflict: the bulb (height " << s.height << " m about z = " << zc
       << " m) reaches below the baseline";
    throw InfeasibleFormParameters(os.str());
  }
  const double aft = o.aft_length > 0.0 ? o.aft_length : 2.0 * (s.length + s.breadth);
  const double m = s.nose_shape, n = s.section_fullness;

  // Sample: sections along (aft part uniform in x, nose part uniform in the angle phi with
  // xi = sin^(2/m) phi, f = cos^(2/m) phi), points around uniform in theta.
  const int ns = o.sections, np = o.section_points;
  const int n_aft = std::max(3, ns / 4);
  std::vector<double> xs(ns), fs(ns), zcs(ns);
  for (int i = 0; i < ns; ++i) {
    if (i < n_aft) {
      xs[i] = s.x_fp - aft * (1.0 - static_cast<double>(i) / n_aft);
      fs[i] = 1.0;
    } else {
      const double phi = 0.5 * M_PI * (i - n_aft) / (ns - 1 - n_aft);
      const double c = std::cos(phi), sn = std::sin(phi);
      xs[i] = s.x_fp + s.length * std::pow(sn, 2.0 / m);
      fs[i] = i == ns - 1 ? 0.0 : std::pow(c, 2.0 / m);
    }
    // the section centre moves from zc (body) to the nose height at the tip
    zcs[i] = s.nose_height + o.nose_height_shift * fs[i];
  }
  Eigen::MatrixXd grid(static_cast<Eigen::Index>(ns) * np, 3);
  Eigen::VectorXd pv(np);
  for (int j = 0; j < np; ++j) pv[j] = static_cast<double>(j) / (np - 1);
  // Every section is a scaled copy of the one at FP, so one arc-length spacing of the angle
  // theta serves them all (the superellipse's own angle crowds the centre-line ends).
  auto sec_point = [&](double th) {
    const double c = std::cos(th), sn = std::sin(th);
    return Eigen::Vector2d(0.5 * s.breadth * std::pow(std::max(0.0, c), 2.0 / n),
                           0.5 * s.height * (sn < 0 ? -1.0 : 1.0) * std::pow(std::abs(sn), 2.0 / n));
  };
  constexpr int kDense = 4000;
  std::vector<double> arc(kDense + 1, 0.0);
  for (int q = 1; q <= kDense; ++q)
    arc[q] = arc[q - 1] + (sec_point(-0.5 * M_PI + M_PI * q / kDense) - sec_point(-0.5 * M_PI + M_PI * (q - 1) / kDense)).norm();
  std::vector<double> theta(np);
  for (int j = 0, q = 0; j < np; ++j) {
    const double target = arc[kDense] * pv[j];
    while (q < kDense - 1 && arc[q + 1] < target) ++q;
    const double w = std::clamp((target - arc[q]) / (arc[q + 1] - arc[q]), 0.0, 1.0);
    theta[j] = -0.5 * M_PI + M_PI * (q + w) / kDense;
  }
  theta[0] = -0.5 * M_PI;
  theta[np - 1] = 0.5 * M_PI;
  for (int i = 0; i < ns; ++i)
    for (int j = 0; j < np; ++j) {
      const double th = theta[j];
      const double c = std::cos(th), sn = std::sin(th);
      const double y = 0.5 * s.breadth * fs[i] * std::pow(std::max(0.0, c), 2.0 / n);
      const double z = zcs[i] + 0.5 * s.height * fs[i] * (sn < 0 ? -1.0 : 1.0) * std::pow(std::abs(sn), 2.0 / n);
      grid.row(i * np + j) << xs[i], (j == 0 || j == np - 1) ? 0.0 : y, z;
    }
  // u parameters: chord length along the top profile line and the bottom line, averaged
  Eigen::VectorXd pu(ns);
  pu[0] = 0.0;
  for (int i = 1; i < ns; ++i) {
    const double dt = (grid.row(i * np + np - 1) - grid.row((i - 1) * np + np - 1)).norm();
    const double db = (grid.row(i * np) - grid.row((i - 1) * np)).norm();
    pu[i] = pu[i - 1] + 0.5 * (dt + db);
  }
  pu /= pu[ns - 1];
  const int p = 3;
  const Eigen::VectorXd Ku = averaged_knots(pu, p, o.control_u);
  const Eigen::VectorXd Kv = averaged_knots(pv, p, o.control_v);
  // sections first (common knots), then the control columns along u; every section (and
  // then every control column) shares one collocation matrix, so each direction is one
  // least-squares solve with all coordinates as right-hand sides
  Eigen::MatrixXd sections(np, 3 * ns);
  for (int i = 0; i < ns; ++i)
    for (int j = 0; j < np; ++j) sections.block<1, 3>(j, 3 * i) = grid.row(i * np + j);
  const Eigen::MatrixXd sec_ctrl = fit_curve_with(sections, pv, Kv, p).curve.control_points();  // (cv, 3 ns)
  Eigen::MatrixXd columns(ns, 3 * o.control_v);
  for (int i = 0; i < ns; ++i)
    for (int j = 0; j < o.control_v; ++j) columns.block<1, 3>(i, 3 * j) = sec_ctrl.block<1, 3>(j, 3 * i);
  const Eigen::MatrixXd col_ctrl = fit_curve_with(columns, pu, Ku, p).curve.control_points();  // (cu, 3 cv)
  Eigen::MatrixXd ctrl(static_cast<Eigen::Index>(o.control_u) * o.control_v, 3);
  for (int i = 0; i < o.control_u; ++i)
    for (int j = 0; j < o.control_v; ++j) ctrl.row(i * o.control_v + j) = col_ctrl.block<1, 3>(i, 3 * j);
  NurbsSurface surf(p, p, Ku, Kv, o.control_u, o.control_v, ctrl);
  const double dev = (surf.evaluate_grid(pu, pv) - grid).rowwise().norm().maxCoeff();
  return {std::move(surf), s, dev};
}

}  // namespace fairlines
