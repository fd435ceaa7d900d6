// Bulbous bow from Kracht coefficients, see fairlines/bulb.hpp.
//
// Notation (Kracht 1978): L_PR, B_B, Z_B the bulb's protrusion, breadth and nose height, H its
// section height; A_BT, A_BL, V_PR its section area at FP, lateral area and volume; m the
// superellipse exponent of the nose outline, n of the sections (kappa(n) their fullness);
// f a section's scale (1 aft of FP, 0 at the nose), theta the angle round a section from the
// bottom; ns, np the sections and points per section sampled; pu, pv their skinning
// parameters, Ku, Kv the knots, p the degree.
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

void require_bulb_options(const BulbOptions& o) {
  detail::require_finite(o.nose_height_shift, "nose_height_shift");
  if (o.aft_length < 0.0 || !std::isfinite(o.aft_length))
    detail::fail("aft_length is ", o.aft_length, "; expected >= 0 metres (0: twice protrusion + breadth)");
  if (o.sections < 8) detail::fail("sections is ", o.sections, "; expected >= 8");
  if (o.section_points < 8) detail::fail("section_points is ", o.section_points, "; expected >= 8");
  if (o.control_u < 4 || o.control_u > o.sections)
    detail::fail("control_u is ", o.control_u, "; expected 4 <= control_u <= sections (", o.sections, ")");
  if (o.control_v < 4 || o.control_v > o.section_points)
    detail::fail("control_v is ", o.control_v, "; expected 4 <= control_v <= section_points (", o.section_points, ")");
}

/// The section exponent n from A_BT = B_B H kappa(n) into s.section_fullness; throws
/// InfeasibleFormParameters when no superellipse section has the requested fullness.
void solve_section_fullness(BulbShape& s) {
  const double kap = s.section_area / (s.breadth * s.height);
  if (bisect(kappa, kSectionExponentMin, kExponentMax, kap, s.section_fullness)) return;
  std::ostringstream os;
  os << "c_abt, c_bb and c_abl conflict: A_BT / (B_B H) = " << kap << " (H = " << s.height
     << " m from c_abl) but a bulb section needs it in [" << kappa(kSectionExponentMin) << ", " << kappa(kExponentMax)
     << "]";
  throw InfeasibleFormParameters(os.str());
}

/// Throws InfeasibleFormParameters when the bulb's body section reaches below the baseline.
void require_above_baseline(const BulbShape& s, const BulbOptions& o) {
  const double zc = s.nose_height + o.nose_height_shift;
  if (zc - 0.5 * s.height >= 0.0) return;
  std::ostringstream os;
  os << "c_zb and c_abl conflict: the bulb (height " << s.height << " m about z = " << zc
     << " m) reaches below the baseline";
  throw InfeasibleFormParameters(os.str());
}

/// The sections' x, scale f and centre height zc, aft to nose.
struct Stations {
  std::vector<double> x, f, zc;
};

/// Sections along x: the aft part uniform in x, the nose part uniform in the angle phi with
/// xi = sin^(2/m) phi, f = cos^(2/m) phi; the section centre moves from the body's height
/// (nose height + shift) to the nose height at the tip.
Stations stations(const BulbShape& s, const BulbOptions& o) {
  const double aft = o.aft_length > 0.0 ? o.aft_length : 2.0 * (s.length + s.breadth);
  const double m = s.nose_shape;
  const int ns = o.sections, n_aft = std::max(3, ns / 4);
  Stations st{std::vector<double>(ns), std::vector<double>(ns), std::vector<double>(ns)};
  for (int i = 0; i < ns; ++i) {
    if (i < n_aft) {
      st.x[i] = s.x_fp - aft * (1.0 - static_cast<double>(i) / n_aft);
      st.f[i] = 1.0;
    } else {
      const double phi = 0.5 * M_PI * (i - n_aft) / (ns - 1 - n_aft);
      const double c = std::cos(phi), sn = std::sin(phi);
      st.x[i] = s.x_fp + s.length * std::pow(sn, 2.0 / m);
      st.f[i] = i == ns - 1 ? 0.0 : std::pow(c, 2.0 / m);
    }
    st.zc[i] = s.nose_height + o.nose_height_shift * st.f[i];
  }
  return st;
}

/// (y, z - zc) of the section at FP at the angle th in [-pi/2, pi/2] (bottom to top).
Eigen::Vector2d section_point(const BulbShape& s, double th) {
  const double n = s.section_fullness, c = std::cos(th), sn = std::sin(th);
  return Eigen::Vector2d(0.5 * s.breadth * std::pow(std::max(0.0, c), 2.0 / n),
                         0.5 * s.height * (sn < 0 ? -1.0 : 1.0) * std::pow(std::abs(sn), 2.0 / n));
}

/// The angles theta at the arc-length fractions pv of the section: every section is a scaled
/// copy of the one at FP, so one spacing serves them all (the superellipse's own angle crowds
/// the centre-line ends).
std::vector<double> arc_length_angles(const BulbShape& s, const Eigen::VectorXd& pv) {
  constexpr int kDense = 4000;
  std::vector<double> arc(kDense + 1, 0.0);
  for (int q = 1; q <= kDense; ++q)
    arc[q] = arc[q - 1] + (section_point(s, -0.5 * M_PI + M_PI * q / kDense) -
                           section_point(s, -0.5 * M_PI + M_PI * (q - 1) / kDense)).norm();
  const int np = static_cast<int>(pv.size());
  std::vector<double> theta(np);
  for (int j = 0, q = 0; j < np; ++j) {
    const double target = arc[kDense] * pv[j];
    while (q < kDense - 1 && arc[q + 1] < target) ++q;
    const double w = std::clamp((target - arc[q]) / (arc[q + 1] - arc[q]), 0.0, 1.0);
    theta[j] = -0.5 * M_PI + M_PI * (q + w) / kDense;
  }
  theta[0] = -0.5 * M_PI;
  theta[np - 1] = 0.5 * M_PI;
  return theta;
}

/// The analytic points, (ns np) by 3, section i's point j in row i np + j (centre-line ends on y = 0).
Eigen::MatrixXd sample_grid(const BulbShape& s, const Stations& st, const std::vector<double>& theta) {
  const int ns = static_cast<int>(st.x.size()), np = static_cast<int>(theta.size());
  const double n = s.section_fullness;
  Eigen::MatrixXd grid(static_cast<Eigen::Index>(ns) * np, 3);
  for (int i = 0; i < ns; ++i)
    for (int j = 0; j < np; ++j) {
      const double th = theta[j];
      const double c = std::cos(th), sn = std::sin(th);
      const double y = 0.5 * s.breadth * st.f[i] * std::pow(std::max(0.0, c), 2.0 / n);
      const double z = st.zc[i] + 0.5 * s.height * st.f[i] * (sn < 0 ? -1.0 : 1.0) * std::pow(std::abs(sn), 2.0 / n);
      grid.row(i * np + j) << st.x[i], (j == 0 || j == np - 1) ? 0.0 : y, z;
    }
  return grid;
}

/// u parameters: chord length along the top profile line and the bottom line, averaged, in [0, 1].
Eigen::VectorXd chord_parameters(const Eigen::MatrixXd& grid, int ns, int np) {
  Eigen::VectorXd pu(ns);
  pu[0] = 0.0;
  for (int i = 1; i < ns; ++i) {
    const double dt = (grid.row(i * np + np - 1) - grid.row((i - 1) * np + np - 1)).norm();
    const double db = (grid.row(i * np) - grid.row((i - 1) * np)).norm();
    pu[i] = pu[i - 1] + 0.5 * (dt + db);
  }
  pu /= pu[ns - 1];
  return pu;
}

/// The bicubic skin of the grid: sections first (common knots), then the control columns
/// along u; every section (and then every control column) shares one collocation matrix, so
/// each direction is one least-squares solve with all coordinates as right-hand sides.
NurbsSurface skin(const Eigen::MatrixXd& grid, const Eigen::VectorXd& pu, const Eigen::VectorXd& pv, const BulbOptions& o) {
  const int ns = static_cast<int>(pu.size()), np = static_cast<int>(pv.size()), p = 3;
  const Eigen::VectorXd Ku = averaged_knots(pu, p, o.control_u);
  const Eigen::VectorXd Kv = averaged_knots(pv, p, o.control_v);
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
  return NurbsSurface(p, p, Ku, Kv, o.control_u, o.control_v, ctrl);
}

}  // namespace

SectionFullness bulb_section_fullness(const KrachtCoefficients& k, const ShipParticulars& ship) {
  require_coefficients(k, ship);
  const BulbShape s = dimensions(k, ship);
  return {s.section_area / (s.breadth * s.height), kappa(kSectionExponentMin), kappa(kExponentMax)};
}

BulbousBow make_bulbous_bow(const KrachtCoefficients& k, const ShipParticulars& ship, const BulbOptions& o) {
  require_coefficients(k, ship);
  require_bulb_options(o);
  BulbShape s = dimensions(k, ship);
  solve_section_fullness(s);
  require_above_baseline(s, o);
  const int ns = o.sections, np = o.section_points;
  Eigen::VectorXd pv(np);
  for (int j = 0; j < np; ++j) pv[j] = static_cast<double>(j) / (np - 1);
  const Eigen::MatrixXd grid = sample_grid(s, stations(s, o), arc_length_angles(s, pv));
  const Eigen::VectorXd pu = chord_parameters(grid, ns, np);
  NurbsSurface surf = skin(grid, pu, pv, o);
  const double dev = (surf.evaluate_grid(pu, pv) - grid).rowwise().norm().maxCoeff();
  return {std::move(surf), s, dev};
}

}  // namespace fairlines
