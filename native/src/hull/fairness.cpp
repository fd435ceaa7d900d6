// Plane cuts of a hull surface with analytic curvature: see fairlines/hull.hpp.
#include <algorithm>
#include <cmath>
#include <vector>

#include "fairlines/errors.hpp"
#include "fairlines/hull.hpp"
#include "nurbs/checks.hpp"

namespace fairlines {

namespace {
using detail::fail;
constexpr int kScan = 64;  // samples of the solve parameter when bracketing a crossing
}  // namespace

PlaneCut plane_cut(const NurbsSurface& s, int axis, double value, int samples) {
  if (axis < 0 || axis > 2) fail("axis is ", axis, "; expected 0 (frame), 1 (buttock) or 2 (waterline)");
  detail::require_finite(value, "value");
  if (samples < 10) fail("samples is ", samples, "; expected at least 10");
  PlaneCut cut;
  cut.axis = axis;
  cut.value = value;
  // Frames: march u, solve v. Others: march v, solve u.
  const bool march_u = axis == 0;
  const auto [m0, m1] = march_u ? s.domain_u() : s.domain_v();
  const auto [r0, r1] = march_u ? s.domain_v() : s.domain_u();
  auto eval = [&](double w, double r) { return march_u ? s.evaluate(w, r) : s.evaluate(r, w); };
  const int pa = axis == 0 ? 1 : 0, pb = axis == 2 ? 1 : 2;  // in-plane coordinates
  std::vector<Eigen::Vector3d> pts;
  std::vector<double> ks, speed, acc2, ws;
  double r_prev = std::numeric_limits<double>::quiet_NaN();
  for (int i = 0; i < samples; ++i) {
    const double w = m0 + (m1 - m0) * i / (samples - 1);
    // Bracket a crossing: scan r; prefer the one nearest the previous solution.
    double best = std::numeric_limits<double>::quiet_NaN();
    double prev_r = r0, prev_f = eval(w, r0)[axis] - value;
    for (int k = 1; k <= kScan; ++k) {
      const double r = r0 + (r1 - r0) * k / kScan;
      const double f = eval(w, r)[axis] - value;
      if (prev_f == 0 || (prev_f < 0) != (f < 0)) {
        // A sample exactly on the plane is the root (a cut along the surface's own edge):
        // bisecting from it would walk to the far end of the bracket.
        double lo = prev_r, hi = prev_f == 0 ? prev_r : r, flo = prev_f;
        for (int it = 0; it < 60 && hi - lo > 1e-15; ++it) {
          const double mid = 0.5 * (lo + hi), fm = eval(w, mid)[axis] - value;
          if (fm == 0) {
            lo = hi = mid;
            break;
          }
          if ((fm < 0) == (flo < 0)) lo = mid, flo = fm;
          else hi = mid;
        }
        const double root = 0.5 * (lo + hi);
        if (std::isnan(best) || (!std::isnan(r_prev) && std::abs(root - r_prev) < std::abs(best - r_prev))) best = root;
        if (std::isnan(r_prev)) break;
      }
      prev_r = r, prev_f = f;
    }
    if (std::isnan(best)) continue;
    r_prev = best;
    const Eigen::MatrixXd D = march_u ? s.derivatives(w, best, 2) : s.derivatives(best, w, 2);
    // D rows k*3+l = d^{k+l}/du^k dv^l. Map to (r, w) derivatives.
    Eigen::Vector3d S = D.row(0), Sr, Sw, Srr, Sww, Srw;
    const Eigen::Vector3d Su = D.row(3), Sv = D.row(1), Suu = D.row(6), Svv = D.row(2), Suv = D.row(4);
    if (march_u) Sr = Sv, Sw = Su, Srr = Svv, Sww = Suu, Srw = Suv;
    else Sr = Su, Sw = Sv, Srr = Suu, Sww = Svv, Srw = Suv;
    if (Sr[axis] == 0) continue;
    const double r1d = -Sw[axis] / Sr[axis];
    const double r2d = -(Srr[axis] * r1d * r1d + 2 * Srw[axis] * r1d + Sww[axis]) / Sr[axis];
    const Eigen::Vector3d c1 = Sr * r1d + Sw;
    const Eigen::Vector3d c2 = Srr * r1d * r1d + 2 * Srw * r1d + Sww + Sr * r2d;
    const double p1 = c1[pa], q1 = c1[pb], p2 = c2[pa], q2 = c2[pb];
    const double sp = std::hypot(p1, q1);
    if (!(sp > 0)) continue;
    pts.push_back(S);
    ks.push_back((p1 * q2 - q1 * p2) / (sp * sp * sp));
    speed.push_back(sp);
    acc2.push_back(c2.squaredNorm());
    ws.push_back(w);
  }
  const int m = static_cast<int>(pts.size());
  if (m < 3) return cut;
  cut.points.resize(m, 3);
  cut.curvature.resize(m);
  double kmax = 0;
  for (int i = 0; i < m; ++i) {
    cut.points.row(i) = pts[i].transpose();
    cut.curvature[i] = ks[i];
    kmax = std::max(kmax, std::abs(ks[i]));
  }
  const double span = ws.back() - ws.front();
  for (int i = 0; i + 1 < m; ++i) {
    const double dw = ws[i + 1] - ws[i];
    cut.bending_energy += 0.5 * dw * (ks[i] * ks[i] * speed[i] + ks[i + 1] * ks[i + 1] * speed[i + 1]);
    // c'' with respect to w rescaled to [0, 1]: multiply by span^2, and dw by 1/span.
    if (span > 0) cut.e2 += 0.5 * (dw / span) * (acc2[i] + acc2[i + 1]) * span * span * span * span;
  }
  cut.threshold = 1e-6 * kmax + 1e-9;
  int last_sign = 0, last_idx = -1;
  std::vector<Eigen::RowVector3d> infl;
  for (int i = 0; i < m; ++i) {
    if (std::abs(ks[i]) <= cut.threshold) continue;
    const int sg = ks[i] > 0 ? 1 : -1;
    if (last_sign != 0 && sg != last_sign) {
      ++cut.sign_changes;
      infl.push_back(0.5 * (pts[i] + pts[last_idx]).transpose());
    }
    last_sign = sg;
    last_idx = i;
  }
  cut.inflections.resize(static_cast<Eigen::Index>(infl.size()), 3);
  for (std::size_t i = 0; i < infl.size(); ++i) cut.inflections.row(static_cast<Eigen::Index>(i)) = infl[i];
  return cut;
}

}  // namespace fairlines
