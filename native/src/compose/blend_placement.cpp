// Blend boundaries around a hull/bulb seam, see fairlines/blend_placement.hpp.
//
// Notation (parameter space of the oriented hull H):
//   u0, u1     aft cut and stem edges; v0, v1 keel and deck edges
//   vz         end of the straight keel zone (a C0 knot in the first tenth of v), else v0
//   (u_j, v_j) seam points on H; the boundary is an ellipse arc of semi-axes du (along u) and
//              R (along v) about (u1, tc) -- the stem edge -- or about (uc, vz) over the keel
//   scale      the least factor by which the ellipse through the seam's extreme points must
//              grow to hold every seam point; the clearances are added after scaling
//   kappa      shear of the fore quarter over the keel, so that it leaves the centre edge
//              square to it in metres (square_to_centre_edge)
#include "fairlines/blend_placement.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "../nurbs/checks.hpp"

namespace fairlines {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kEdgeTolerance = 1e-6;  ///< a seam end within this fraction of the domain is on an edge
constexpr double kKeelZoneReach = 0.1;   ///< a keel zone ends within this fraction of the v range
/// Of the stem above the seam's fore end (in u), the fraction the boundary may take: the blend's
/// top end then meets the stem 3-4 m above the bulb on the example (half the stem gave a
/// 5 m strip; 0.4 put a 0.15 element into its 3 m mesh).
constexpr double kForeRoom = 0.35;

[[noreturn]] void no_blend_fits(const std::string& why) {
  throw NoBlendFits("no blend fits between hull and bulb: " + why);
}

/// v where a straight keel zone ends: the first knot of full multiplicity (a C0 joint) in the
/// first tenth of the v range above the keel edge, or the keel edge itself.
double keel_zone_end(const NurbsSurface& H) {
  const Eigen::VectorXd& kv = H.knots_v();
  const double v0 = kv(0), v1 = kv(kv.size() - 1);
  for (Eigen::Index i = 0; i < kv.size();) {
    Eigen::Index j = i;
    while (j < kv.size() && kv(j) == kv(i)) ++j;
    if (v0 < kv(i) && kv(i) < v0 + kKeelZoneReach * (v1 - v0) && j - i >= H.degree_v()) return kv(i);
    i = j;
  }
  return v0;
}

/// n equally spaced angles over [0, end], the last exactly end.
std::vector<double> angles(double end, int n) {
  std::vector<double> phi(n);
  const double step = end / (n - 1);
  for (int i = 0; i < n; ++i) phi[i] = i * step;
  phi[n - 1] = end;
  return phi;
}

Eigen::MatrixXd with_keel_ends(const Eigen::MatrixXd& arc, double v0, bool before, bool after) {
  Eigen::MatrixXd out(arc.rows() + before + after, 2);
  if (before) out.row(0) << arc(0, 0), v0;
  out.middleRows(before, arc.rows()) = arc;
  if (after) out.row(out.rows() - 1) << arc(arc.rows() - 1, 0), v0;
  return out;
}

/// Half ellipse from the stem edge below the seam to the stem edge above it.
Eigen::MatrixXd around_seam_on_stem(const NurbsSurface& H, const Eigen::MatrixXd& uv, const BlendPlacementOptions& o) {
  const double u0 = H.knots_u()(0), u1 = H.knots_u()(H.knots_u().size() - 1);
  const double v0 = H.knots_v()(0), v1 = H.knots_v()(H.knots_v().size() - 1);
  const double lo = uv.col(1).minCoeff(), hi = uv.col(1).maxCoeff();
  const double tc = 0.5 * (lo + hi), R = 0.5 * (hi - lo) + o.clearance_v;
  const double du = u1 - uv.col(0).minCoeff() + o.clearance_u;
  if (tc - R <= v0 || tc + R >= v1)
    no_blend_fits("a blend boundary clear of the seam would leave the hull between keel and deck");
  if (u1 - du <= u0) no_blend_fits("a blend boundary clear of the seam would reach the aft cut");
  const std::vector<double> phi = angles(kPi, o.points);
  Eigen::MatrixXd arc(o.points, 2);
  for (int i = 0; i < o.points; ++i) arc.row(i) << u1 - du * std::sin(phi[i]), tc - R * std::cos(phi[i]);
  return arc;
}

/// Quarter ellipse about the forefoot corner (u1, vz), from the keel edge to the stem edge.
Eigen::MatrixXd around_forefoot(const NurbsSurface& H, const Eigen::MatrixXd& uv, const BlendPlacementOptions& o) {
  const double u0 = H.knots_u()(0), u1 = H.knots_u()(H.knots_u().size() - 1);
  const double v0 = H.knots_v()(0), v1 = H.knots_v()(H.knots_v().size() - 1);
  const double vz = keel_zone_end(H);
  const double a0 = u1 - uv.col(0).minCoeff(), b0 = uv.col(1).maxCoeff() - vz;
  if (!(b0 > 0)) no_blend_fits("the seam does not rise above the keel zone");
  double scale = 0.0;
  for (Eigen::Index j = 0; j < uv.rows(); ++j)
    scale = std::max(scale, std::hypot((u1 - uv(j, 0)) / a0, std::max(uv(j, 1) - vz, 0.0) / b0));
  const double du = scale * a0 + o.clearance_u, R = scale * b0 + o.clearance_v;
  if (vz + R >= v1) no_blend_fits("a blend boundary clear of the seam would reach the deck");
  if (u1 - du <= u0) no_blend_fits("a blend boundary clear of the seam would reach the aft cut");
  const std::vector<double> phi = angles(0.5 * kPi, o.points);
  Eigen::MatrixXd arc(o.points, 2);
  for (int i = 0; i < o.points; ++i) arc.row(i) << u1 - du * std::sin(phi[i] + 0.5 * kPi), vz + R * std::sin(phi[i]);
  // Across the keel zone along v: the zone is a few centimetres of a straight leg, so the
  // boundary enters the curved part along the section without a kink.
  return with_keel_ends(arc, v0, vz > v0, false);
}

/// u of the fore quarter over the keel at s = sin phi = (v - vz) / R, c = -cos phi: the
/// ellipse's uc + a c plus the shear kappa R (1 - s).
double fore_quarter_u(double uc, double a, double kappa, double R, double c, double s) {
  return uc + a * c + kappa * R * (1.0 - s);
}

/// Shear kappa of the fore quarter (u = uc - a cos phi + kappa R (1 - sin phi)) that makes it
/// leave the centre edge at (u_end, v0) square to the edge in metres, S_u . S_v / |S_u|^2
/// there: a raked stem's sections meet it at 20-30 deg, and an arc along them made the
/// blend's top end a strip a few decimetres wide up the stem. Held to half of each fore seam
/// point's clearance (the shear draws the arc's middle aft) and to half of u_end - uc.
double square_to_centre_edge(const NurbsSurface& H, const Eigen::MatrixXd& uv, double uc, double u_end, double vz,
                             double R) {
  const Eigen::MatrixXd d = H.derivatives(u_end, H.knots_v()(0), 1);  // rows: S, S_v, S_u
  const double su2 = d.row(2).squaredNorm();
  double kappa = su2 > 0.0 ? std::max(0.0, d.row(1).dot(d.row(2)) / su2) : 0.0;
  kappa = std::min(kappa, 0.5 * (u_end - uc) / R);
  for (Eigen::Index j = 0; j < uv.rows(); ++j) {
    if (uv(j, 0) <= uc) continue;
    const double s = std::min(std::max(uv(j, 1) - vz, 0.0) / R, 1.0), c = std::sqrt(1.0 - s * s);
    const double gap = fore_quarter_u(uc, u_end - uc, 0.0, R, c, s) - uv(j, 0), pull = R * (s + c - 1.0);
    if (pull > 0.0) kappa = std::min(kappa, std::max(0.0, 0.5 * gap / pull));
  }
  return kappa;
}

/// Throws NoBlendFits unless every seam point lies between the arc over the keel and the centre
/// edge: the arc's fore end is held to kForeRoom of the stem, and a seam that runs on up the
/// stem past it would cross the boundary.
void require_inside(const Eigen::MatrixXd& uv, double uc, double a_aft, double a_fore, double kappa, double vz,
                    double R) {
  for (Eigen::Index j = 0; j < uv.rows(); ++j) {
    const double s = std::max(uv(j, 1) - vz, 0.0) / R;
    const double c = s < 1.0 ? std::sqrt(1.0 - s * s) : 0.0;
    if (!(s < 1.0 && uc - a_aft * c < uv(j, 0) && uv(j, 0) < fore_quarter_u(uc, a_fore, kappa, R, c, s)))
      no_blend_fits("the seam runs too far up the stem for a boundary around it; a lower or shorter bulb fits");
  }
}

/// Two quarter ellipses meeting over the seam's highest point, from the keel-and-stem edge of a
/// whole-ship hull aft of the seam to the same edge between the seam and the stem head.
Eigen::MatrixXd over_centre_edge(const NurbsSurface& H, const Eigen::MatrixXd& uv, const BlendPlacementOptions& o) {
  const double u0 = H.knots_u()(0), u1 = H.knots_u()(H.knots_u().size() - 1);
  const double v0 = H.knots_v()(0), v1 = H.knots_v()(H.knots_v().size() - 1);
  const double vz = keel_zone_end(H);
  Eigen::Index top;
  uv.col(1).maxCoeff(&top);
  const double uc = uv(top, 0), b0 = uv(top, 1) - vz;
  const double u_min = uv.col(0).minCoeff(), u_max = uv.col(0).maxCoeff();
  double a_aft = uc - u_min, a_fore = u_max - uc;
  if (!(b0 > 0 && a_aft > 0 && a_fore > 0)) no_blend_fits("the seam does not rise above the keel zone");
  double scale = 0.0;
  for (Eigen::Index j = 0; j < uv.rows(); ++j) {
    const double side = uv(j, 0) < uc ? a_aft : a_fore;
    scale = std::max(scale, std::hypot((uv(j, 0) - uc) / side, std::max(uv(j, 1) - vz, 0.0) / b0));
  }
  const double R = scale * b0 + o.clearance_v;
  a_aft = scale * a_aft + o.clearance_u;
  const double u_end = std::min(uc + scale * a_fore + o.clearance_u, u_max + kForeRoom * (u1 - u_max));
  const double kappa = square_to_centre_edge(H, uv, uc, u_end, vz, R);
  a_fore = u_end - uc - kappa * R;
  require_inside(uv, uc, a_aft, a_fore, kappa, vz, R);
  if (vz + R >= v1) no_blend_fits("a blend boundary clear of the seam would reach the deck");
  if (uc - a_aft <= u0) no_blend_fits("a blend boundary clear of the seam would reach the aft end");
  const std::vector<double> phi = angles(kPi, o.points);
  Eigen::MatrixXd arc(o.points, 2);
  for (int i = 0; i < o.points; ++i)
    arc.row(i) << (phi[i] <= 0.5 * kPi ? uc - a_aft * std::cos(phi[i]) : fore_quarter_u(uc, a_fore, kappa, R, -std::cos(phi[i]), std::sin(phi[i]))),
        vz + R * std::sin(phi[i]);
  return with_keel_ends(arc, v0, vz > v0, vz > v0);
}

void validate(const Eigen::MatrixXd& uv_h, const Eigen::MatrixXd& uv_b, const BlendPlacementOptions& o) {
  if (uv_h.cols() != 2 || uv_h.rows() < 2)
    detail::fail("seam_uv_hull has shape (", uv_h.rows(), ", ", uv_h.cols(), "); expected (k, 2) with k >= 2");
  if (uv_b.cols() != 2 || uv_b.rows() != uv_h.rows())
    detail::fail("seam_uv_bulb has shape (", uv_b.rows(), ", ", uv_b.cols(), "); expected (", uv_h.rows(), ", 2)");
  detail::require_finite(uv_h, "seam_uv_hull");
  detail::require_finite(uv_b, "seam_uv_bulb");
  if (!(o.clearance_u >= 0.0) || !std::isfinite(o.clearance_u))
    detail::fail("clearance_u is ", o.clearance_u, "; expected a finite parameter distance >= 0");
  if (!(o.clearance_v >= 0.0) || !std::isfinite(o.clearance_v))
    detail::fail("clearance_v is ", o.clearance_v, "; expected a finite parameter distance >= 0");
  if (!(o.bulb_clearance >= 0.0) || !std::isfinite(o.bulb_clearance))
    detail::fail("bulb_clearance is ", o.bulb_clearance, "; expected a finite parameter distance >= 0");
  if (!(o.tension > 0.0) || !std::isfinite(o.tension)) detail::fail("tension is ", o.tension, "; expected a finite number > 0");
  if (o.points < 3) detail::fail("points is ", o.points, "; expected an integer >= 3");
}

}  // namespace

BlendSpec blend_boundaries_around_seam(const NurbsSurface& H, const Eigen::MatrixXd& uv,
                                       const Eigen::MatrixXd& uv_b, const BlendPlacementOptions& o) {
  validate(uv, uv_b, o);
  const double u0 = H.knots_u()(0), u1 = H.knots_u()(H.knots_u().size() - 1);
  const double v0 = H.knots_v()(0), v1 = H.knots_v()(H.knots_v().size() - 1);
  const double tol = kEdgeTolerance * (u1 - u0), tol_v = tol * (v1 - v0) / (u1 - u0);
  const Eigen::Index last = uv.rows() - 1;
  const bool stem0 = std::abs(uv(0, 0) - u1) < tol, stem1 = std::abs(uv(last, 0) - u1) < tol;
  const bool keel0 = std::abs(uv(0, 1) - v0) < tol_v, keel1 = std::abs(uv(last, 1) - v0) < tol_v;
  BlendSpec spec;
  if (stem0 && stem1)
    spec.hull_uv = around_seam_on_stem(H, uv, o);
  else if ((keel0 && stem1) || (keel1 && stem0))
    spec.hull_uv = around_forefoot(H, uv, o);
  else if (keel0 && keel1)
    spec.hull_uv = over_centre_edge(H, uv, o);
  else
    no_blend_fits("the seam does not run from the keel or stem edge to the stem edge");
  spec.bulb_u = uv_b.col(0).maxCoeff() + o.bulb_clearance;
  spec.tension = o.tension;
  return spec;
}

std::pair<NurbsSurface, BlendSpec> seam_blend_placement(const NurbsSurface& hull, const NurbsSurface& bulb,
                                                        const ComposeOptions& compose_options,
                                                        const BlendPlacementOptions& options) {
  HullBulbSeam s = hull_bulb_seam(hull, bulb, compose_options);
  const auto& pts = s.seam.points;
  Eigen::MatrixXd uv_h(pts.size(), 2), uv_b(pts.size(), 2);
  for (size_t j = 0; j < pts.size(); ++j) {
    uv_h.row(j) = pts[j].uv_a.transpose();
    uv_b.row(j) = pts[j].uv_b.transpose();
  }
  BlendSpec spec = blend_boundaries_around_seam(s.hull, uv_h, uv_b, options);
  return {std::move(s.hull), std::move(spec)};
}

}  // namespace fairlines
