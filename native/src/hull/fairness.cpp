// Plane cuts of a hull surface with analytic curvature: see fairlines/hull.hpp.
//
// Notation: the cut marches one surface parameter w (u for frames, v otherwise) and solves the
// other, r, so that S(w, r)[axis] = value. (pa, pb) are the in-plane coordinates; c1, c2 the
// cut curve's first and second derivatives with respect to w; k its signed plane curvature.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "fairlines/errors.hpp"
#include "fairlines/hull.hpp"
#include "nurbs/checks.hpp"

namespace fairlines {

namespace {
using detail::fail;
constexpr int kScan = 64;  // samples of the solve parameter when bracketing a crossing

struct CutFrame {
  const NurbsSurface& s;
  int axis;
  double value;
  bool march_u;  // frames march u and solve v; buttocks and waterlines march v and solve u
  int pa, pb;    // in-plane coordinates
  double r0, r1;

  double f(double w, double r) const { return (march_u ? s.evaluate(w, r) : s.evaluate(r, w))[axis] - value; }
};

struct CutSample {
  Eigen::Vector3d point;
  double curvature, speed, acc2, w;
};

// The root of f(w, .) in [lo, hi] by bisection; a sample exactly on the plane is the root (a cut
// along the surface's own edge: bisecting from it would walk to the far end of the bracket).
double bisect(const CutFrame& c, double w, double lo, double hi, double flo) {
  if (flo == 0) hi = lo;
  for (int it = 0; it < 60 && hi - lo > 1e-15; ++it) {
    const double mid = 0.5 * (lo + hi), fm = c.f(w, mid);
    if (fm == 0) return mid;
    if ((fm < 0) == (flo < 0)) lo = mid, flo = fm;
    else hi = mid;
  }
  return 0.5 * (lo + hi);
}

// The crossing of the plane at w: scan r, prefer the crossing nearest the previous solution
// (the first one when there is none); NaN when the plane is not crossed.
double crossing(const CutFrame& c, double w, double r_prev) {
  double best = std::numeric_limits<double>::quiet_NaN();
  double prev_r = c.r0, prev_f = c.f(w, c.r0);
  for (int k = 1; k <= kScan; ++k) {
    const double r = c.r0 + (c.r1 - c.r0) * k / kScan;
    const double f = c.f(w, r);
    if (prev_f == 0 || (prev_f < 0) != (f < 0)) {
      const double root = bisect(c, w, prev_r, r, prev_f);
      if (std::isnan(best) || (!std::isnan(r_prev) && std::abs(root - r_prev) < std::abs(best - r_prev))) best = root;
      if (std::isnan(r_prev)) break;
    }
    prev_r = r, prev_f = f;
  }
  return best;
}

// Point, plane curvature, speed |c1| and |c2|^2 of the cut at (w, r); false where the cut is
// tangent to the solve direction or has zero speed.
bool cut_sample(const CutFrame& c, double w, double r, CutSample& out) {
  const Eigen::MatrixXd D = c.march_u ? c.s.derivatives(w, r, 2) : c.s.derivatives(r, w, 2);
  // D rows k*3+l = d^{k+l}/du^k dv^l. Map to (r, w) derivatives.
  const Eigen::Vector3d Su = D.row(3), Sv = D.row(1), Suu = D.row(6), Svv = D.row(2), Suv = D.row(4);
  const Eigen::Vector3d Sr = c.march_u ? Sv : Su, Sw = c.march_u ? Su : Sv;
  const Eigen::Vector3d Srr = c.march_u ? Svv : Suu, Sww = c.march_u ? Suu : Svv, Srw = Suv;
  const int a = c.axis;
  if (Sr[a] == 0) return false;
  const double r1d = -Sw[a] / Sr[a];
  const double r2d = -(Srr[a] * r1d * r1d + 2 * Srw[a] * r1d + Sww[a]) / Sr[a];
  const Eigen::Vector3d c1 = Sr * r1d + Sw;
  const Eigen::Vector3d c2 = Srr * r1d * r1d + 2 * Srw * r1d + Sww + Sr * r2d;
  const double p1 = c1[c.pa], q1 = c1[c.pb], p2 = c2[c.pa], q2 = c2[c.pb];
  const double sp = std::hypot(p1, q1);
  if (!(sp > 0)) return false;
  out = {D.row(0).transpose(), (p1 * q2 - q1 * p2) / (sp * sp * sp), sp, c2.squaredNorm(), w};
  return true;
}

// Bending energy (int k^2 ds) and E2 (int |c''|^2 over w rescaled to [0, 1]) by trapezoids.
void add_energies(const std::vector<CutSample>& q, PlaneCut& cut) {
  const double span = q.back().w - q.front().w;
  for (std::size_t i = 0; i + 1 < q.size(); ++i) {
    const double dw = q[i + 1].w - q[i].w;
    const double k0 = q[i].curvature, k1 = q[i + 1].curvature;
    cut.bending_energy += 0.5 * dw * (k0 * k0 * q[i].speed + k1 * k1 * q[i + 1].speed);
    // c'' with respect to w rescaled to [0, 1]: multiply by span^2, and dw by 1/span.
    if (span > 0) cut.e2 += 0.5 * (dw / span) * (q[i].acc2 + q[i + 1].acc2) * span * span * span * span;
  }
}

// Sign changes of the curvature above the cut's threshold, each placed midway between the
// two samples either side of it.
void add_inflections(const std::vector<CutSample>& q, PlaneCut& cut) {
  int last_sign = 0, last_idx = -1;
  std::vector<Eigen::RowVector3d> infl;
  for (int i = 0; i < static_cast<int>(q.size()); ++i) {
    const double k = q[i].curvature;
    if (std::abs(k) <= cut.threshold) continue;
    const int sg = k > 0 ? 1 : -1;
    if (last_sign != 0 && sg != last_sign) {
      ++cut.sign_changes;
      infl.push_back(0.5 * (q[i].point + q[last_idx].point).transpose());
    }
    last_sign = sg;
    last_idx = i;
  }
  cut.inflections.resize(static_cast<Eigen::Index>(infl.size()), 3);
  for (std::size_t i = 0; i < infl.size(); ++i) cut.inflections.row(static_cast<Eigen::Index>(i)) = infl[i];
}
}  // namespace

PlaneCut plane_cut(const NurbsSurface& s, int axis, double value, int samples) {
  if (axis < 0 || axis > 2) fail("axis is ", axis, "; expected 0 (frame), 1 (buttock) or 2 (waterline)");
  detail::require_finite(value, "value");
  if (samples < 10) fail("samples is ", samples, "; expected at least 10");
  PlaneCut cut;
  cut.axis = axis;
  cut.value = value;
  const bool march_u = axis == 0;
  const auto [m0, m1] = march_u ? s.domain_u() : s.domain_v();
  const auto [r0, r1] = march_u ? s.domain_v() : s.domain_u();
  const CutFrame frame{s, axis, value, march_u, axis == 0 ? 1 : 0, axis == 2 ? 1 : 2, r0, r1};
  std::vector<CutSample> q;
  double r_prev = std::numeric_limits<double>::quiet_NaN();
  for (int i = 0; i < samples; ++i) {
    const double w = m0 + (m1 - m0) * i / (samples - 1);
    const double r = crossing(frame, w, r_prev);
    if (std::isnan(r)) continue;
    r_prev = r;
    CutSample sample;
    if (cut_sample(frame, w, r, sample)) q.push_back(sample);
  }
  const int m = static_cast<int>(q.size());
  if (m < 3) return cut;
  cut.points.resize(m, 3);
  cut.curvature.resize(m);
  double kmax = 0;
  for (int i = 0; i < m; ++i) {
    cut.points.row(i) = q[i].point.transpose();
    cut.curvature[i] = q[i].curvature;
    kmax = std::max(kmax, std::abs(q[i].curvature));
  }
  add_energies(q, cut);
  cut.threshold = 1e-6 * kmax + 1e-9;
  add_inflections(q, cut);
  return cut;
}

}  // namespace fairlines
