// Lagrange-Newton (SQP) solver with a log barrier on the linear section conditions
// and continuation in the requested form parameters.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <cstdlib>
#include <sstream>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <Eigen/QR>
#include <Eigen/SVD>

#include "fairlines/errors.hpp"
#include "problem.hpp"
#include "solver.hpp"

namespace fairlines::form_curve_impl {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kDeg = std::numbers::pi / 180.0;
// Relative rounding level of a constraint value c_i = value - target: residuals below
// kMeritRoundoff * (|target| + scale) are noise, not violation. The l1 merit ignores
// them: with penalty weights nu ~ 1e5 that noise otherwise swamps the decrease of a
// near-converged Newton step and the line search creeps with tiny steps.
constexpr double kMeritRoundoff = 1e-14;
// A step shorter than this (relative to |z|) changes nothing representable: the line
// search has stalled and the iterate is as converged as the merit can resolve.
constexpr double kStallStep = 1e-13;
}  // namespace

Solver::Solver(Problem& problem, int iteration_budget) : pb(problem), max_total(iteration_budget) {
  m = static_cast<int>(pb.cons.size());
  // Linear equality system L z = b
  std::vector<int> lin;
  for (int i = 0; i < m; ++i)
    if (pb.cons[i].kind == ConKind::Linear) lin.push_back(i);
  L.resize(static_cast<int>(lin.size()), pb.nv);
  b.resize(static_cast<int>(lin.size()));
  for (size_t r = 0; r < lin.size(); ++r) {
    L.row(static_cast<int>(r)) = pb.cons[lin[r]].row.transpose();
    b[static_cast<int>(r)] = pb.cons[lin[r]].target;
  }
  lin_index = lin;
  // Drop inequalities fixed by the linear equalities; report those they contradict.
  std::vector<int> keep;
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod;
  if (L.rows() > 0) cod.compute(L.transpose());
  for (int r = 0; r < pb.G.rows(); ++r) {
    const Eigen::VectorXd g = pb.G.row(r).transpose();
    if (L.rows() > 0) {
      const Eigen::VectorXd y = cod.solve(g);
      if ((L.transpose() * y - g).norm() <= 1e-10 * g.norm()) {
        const double value = y.dot(b) - pb.h[r];
        const double tol = 1e-12 * (1 + y.cwiseAbs().dot(b.cwiseAbs()));
        if (value < -tol) {
          std::ostringstream os;
          os << "form parameters {";
          bool first = true;
          for (int k = 0; k < y.size(); ++k)
            if (std::abs(y[k]) > 1e-12) {
              os << (first ? "" : ", ") << pb.cons[lin[k]].name;
              first = false;
            }
          os << "} contradict the bound '" << pb.ineq_names[r] << "' (violated by " << -value << ")";
          throw InfeasibleFormParameters(os.str());
        }
        continue;  // always satisfied (or exactly active): no barrier needed
      }
    }
    keep.push_back(r);
  }
  G.resize(static_cast<int>(keep.size()), pb.nv);
  h.resize(static_cast<int>(keep.size()));
  for (size_t k = 0; k < keep.size(); ++k) {
    G.row(static_cast<int>(k)) = pb.G.row(keep[k]);
    h[static_cast<int>(k)] = pb.h[keep[k]];
    ineq_names.push_back(pb.ineq_names[keep[k]]);
  }
}

double Solver::merit(const Eigen::VectorXd& z, double mu, double nu, Eigen::VectorXd& c) const {
  const Eigen::VectorXd s = G * z - h;
  if (s.size() > 0 && !(s.minCoeff() > 0)) return kInf;
  pb.constraints(z, c, nullptr, nullptr, nullptr);
  return merit_of(pb.objective(z, nullptr, nullptr), c, s, mu, nu);
}

double Solver::merit_of(double f, const Eigen::VectorXd& c, const Eigen::VectorXd& s, double mu, double nu) const {
  double l1 = 0;
  for (int i = 0; i < c.size(); ++i) {
    const double noise = kMeritRoundoff * (std::abs(pb.cons[i].target) + pb.cons[i].scale);
    l1 += std::max(0.0, std::abs(c[i]) - noise);
  }
  double val = f + nu * l1;
  for (int i = 0; i < s.size(); ++i) val -= mu * std::log(s[i]);
  return std::isfinite(val) ? val : kInf;
}

namespace {
/// LLT of A + delta I with the smallest delta of 0, 1e-10 scale, x10, ... that factors
/// (inertia correction); false when none of 40 shifts does.
bool factor_shifted(const Eigen::MatrixXd& A, Eigen::LLT<Eigen::MatrixXd>& llt) {
  double delta = 0;
  const double hs = std::max(1e-12, A.diagonal().cwiseAbs().maxCoeff());
  for (int k = 0; k < 40; ++k) {
    llt.compute(A + delta * Eigen::MatrixXd::Identity(A.rows(), A.cols()));
    if (llt.info() == Eigen::Success) return true;
    delta = delta == 0 ? 1e-10 * hs : delta * 10;
  }
  return false;
}
}  // namespace

bool Solver::model_at(const Eigen::VectorXd& z, const Eigen::VectorXd& lam, double mu, NewtonModel& md) {
  md.f = pb.objective(z, &md.g, &md.H);
  pb.constraints(z, md.c, &md.J, &lam, &md.HL);
  if (!std::isfinite(md.f) || !md.c.allFinite() || !md.J.allFinite()) return false;
  md.s = G * z - h;
  md.gt = md.g;
  md.Ht = md.H + md.HL;
  if (md.s.size() > 0) {
    // primal-dual barrier: the Hessian term uses the dual estimates v (v_i s_i -> mu)
    if (vdual.size() != md.s.size()) vdual = mu * md.s.cwiseInverse();
    for (int r = 0; r < md.s.size(); ++r)
      vdual[r] = std::clamp(vdual[r], mu / (1e10 * md.s[r]), 1e10 * mu / md.s[r]);
    const Eigen::VectorXd inv = md.s.cwiseInverse();
    md.gt.noalias() -= mu * (G.transpose() * inv);
    md.Ht.noalias() += G.transpose() * vdual.cwiseProduct(inv).asDiagonal() * G;
  }
  return true;
}

bool Solver::null_space_step(const NewtonModel& md, Eigen::VectorXd& d, Eigen::VectorXd& lam_new) {
  const int nv = pb.nv;
  Eigen::HouseholderQR<Eigen::MatrixXd> qr(md.J.transpose());
  const Eigen::MatrixXd R = qr.matrixQR().topRows(m).triangularView<Eigen::Upper>();
  const double rmax = R.diagonal().cwiseAbs().maxCoeff();
  if (!(R.diagonal().cwiseAbs().minCoeff() > 1e-11 * std::max(rmax, 1e-300))) return false;
  const Eigen::MatrixXd Q = qr.householderQ();
  const auto Y = Q.leftCols(m);
  const auto Z = Q.rightCols(nv - m);
  const Eigen::VectorXd py = R.transpose().triangularView<Eigen::Lower>().solve(-md.c);
  d = Y * py;
  if (nv > m) {
    const Eigen::MatrixXd Hr = Z.transpose() * md.Ht * Z;
    const Eigen::VectorXd rhs = -(Z.transpose() * (md.gt + md.Ht * d));
    Eigen::LLT<Eigen::MatrixXd> llt;
    if (!factor_shifted(Hr, llt)) {
      d.resize(0);  // the reduced Hessian cannot be corrected: no step
      return true;
    }
    d.noalias() += Z * llt.solve(rhs);
  }
  lam_new = R.triangularView<Eigen::Upper>().solve(-(Y.transpose() * (md.gt + md.Ht * d)));
  soc_Y = Y;
  soc_R = R;
  return true;
}

bool Solver::regularised_step(const NewtonModel& md, Eigen::VectorXd& d, Eigen::VectorXd& lam_new) const {
  const int nv = pb.nv;
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(nv + m, nv + m);
  const double hs = std::max(1e-12, md.Ht.diagonal().cwiseAbs().maxCoeff());
  K.topLeftCorner(nv, nv) = md.Ht + 1e-8 * hs * Eigen::MatrixXd::Identity(nv, nv);
  K.topRightCorner(nv, m) = md.J.transpose();
  K.bottomLeftCorner(m, nv) = md.J;
  K.bottomRightCorner(m, m) = -1e-10 * Eigen::MatrixXd::Identity(m, m);
  Eigen::VectorXd rhs(nv + m);
  rhs << -md.gt, -md.c;
  const Eigen::VectorXd sol = K.partialPivLu().solve(rhs);
  if (!sol.allFinite()) return false;
  d = sol.head(nv);
  lam_new = sol.tail(m);
  return true;
}

bool Solver::kkt_step(const NewtonModel& md, Eigen::VectorXd& d, Eigen::VectorXd& lam_new, bool& regular) {
  regular = true;
  if (m == 0) {
    Eigen::LLT<Eigen::MatrixXd> llt;
    if (!factor_shifted(md.Ht, llt)) return false;
    d = llt.solve(-md.gt);
    lam_new.resize(0);
  } else if (null_space_step(md, d, lam_new)) {
    if (d.size() == 0) return false;
  } else {
    // dependent constraint gradients: regularised KKT, LU with partial pivoting
    regular = false;
    if (!regularised_step(md, d, lam_new)) return false;
  }
  return d.allFinite();
}

bool Solver::line_search(Eigen::VectorXd& z, const Eigen::VectorXd& d, const NewtonModel& md, double mu, double nu,
                         bool regular, double& alpha) {
  double amax = 1;
  if (md.s.size() > 0) {
    const Eigen::VectorXd Gd = G * d;
    for (int r = 0; r < md.s.size(); ++r)
      if (Gd[r] < 0) amax = std::min(amax, -0.995 * md.s[r] / Gd[r]);
  }
  // z is interior (s > 0) and f, c are its values: no re-evaluation needed
  const double phi0 = merit_of(md.f, md.c, md.s, mu, nu);
  const double dphi = md.gt.dot(d) - nu * md.c.lpNorm<1>();
  Eigen::VectorXd ctrial;
  alpha = amax;
  for (int k = 0; k < 40; ++k) {
    Eigen::VectorXd zt = z + alpha * d;
    double phi = merit(zt, mu, nu, ctrial);
    if (!(phi <= phi0 + 1e-4 * alpha * std::min(dphi, 0.0)) && m > 0 && regular && std::isfinite(phi)) {
      // second-order corrections: pull the trial point back onto the constraint
      // manifold with the current factorization (curved constraints, Maratos effect)
      for (int corr = 0; corr < 3; ++corr) {
        const Eigen::VectorXd py = soc_R.transpose().triangularView<Eigen::Lower>().solve(-ctrial);
        const Eigen::VectorXd zs = zt + soc_Y * py;
        const double phis = merit(zs, mu, nu, ctrial);
        if (!std::isfinite(phis)) break;
        zt = zs;
        phi = phis;
        if (phi <= phi0 + 1e-4 * alpha * std::min(dphi, 0.0)) break;
      }
    }
    if (phi <= phi0 + 1e-4 * alpha * std::min(dphi, 0.0)) {
      // a step below representable size is a stall, not progress
      const bool accepted = (zt - z).norm() > kStallStep * (1 + z.norm());
      if (accepted) z = zt;
      return accepted;
    }
    alpha *= 0.5;
    if (alpha < 1e-14) break;
  }
  return false;
}

void Solver::dual_step(const NewtonModel& md, const Eigen::VectorXd& d, double mu) {
  // dv = mu/s - v - (v/s) G d, fraction-to-boundary on v
  const Eigen::VectorXd Gd = G * d;
  Eigen::VectorXd dv(md.s.size());
  double av = 1;
  for (int r = 0; r < md.s.size(); ++r) {
    dv[r] = mu / md.s[r] - vdual[r] - vdual[r] / md.s[r] * Gd[r];
    if (dv[r] < 0) av = std::min(av, -0.995 * vdual[r] / dv[r]);
  }
  vdual += av * dv;
}

bool Solver::newton(Eigen::VectorXd& z, Eigen::VectorXd& lam, double mu, double tol_c, double tol_g, int maxit) {
  NewtonModel md;
  Eigen::VectorXd d, lam_new;
  double nu = 0;
  for (int it = 0; it < maxit; ++it) {
    if (total_iterations >= max_total) return false;
    if (!model_at(z, lam, mu, md)) return false;
    const double viol = pb.scaled_violation(md.c);
    const double gscale = 1 + md.g.lpNorm<Eigen::Infinity>();
    const double stat = (md.gt + md.J.transpose() * lam).lpNorm<Eigen::Infinity>();
    last_violation = viol;
    last_stationarity = stat / gscale;
    if (viol <= tol_c && stat <= tol_g * gscale) return true;
    ++total_iterations;
    bool regular = true;
    if (!kkt_step(md, d, lam_new, regular)) return false;
    if (m > 0) nu = std::max(nu, 1.1 * lam_new.lpNorm<Eigen::Infinity>() + 1e-8);
    double alpha = 0;
    // No decrease possible: converged to the accuracy the merit can resolve?
    if (!line_search(z, d, md, mu, nu, regular, alpha)) return viol <= tol_c && stat <= 1e3 * tol_g * gscale;
    if (m > 0) lam += std::min(alpha, 1.0) * (lam_new - lam);
    if (md.s.size() > 0) dual_step(md, d, mu);
  }
  return false;
}

void Solver::set_targets(double tau) {
  for (auto& k : pb.cons)
    if (k.kind != ConKind::Linear) k.target = k.start + tau * (k.requested - k.start);
}

void Solver::set_starts(const Eigen::VectorXd& z) {
  double A = 0, My = 0, Mx = 0;
  if (pb.need_area) area_moments(pb.tab, z, A, My, Mx);
  const bool areaok = std::abs(A) > 1e-9 * pb.Ls * pb.Ls;
  Eigen::MatrixXd C, ders;
  for (auto& k : pb.cons) {
    switch (k.kind) {
      case ConKind::Linear: k.start = k.requested = k.target; break;
      case ConKind::Area: k.start = A; break;
      case ConKind::MomentXC: k.start = areaok ? My / A : k.requested; break;
      case ConKind::MomentYC: k.start = areaok ? Mx / A : k.requested; break;
      case ConKind::Curvature: {
        const Eigen::MatrixXd& R = pb.tab.end_rows[k.end];
        const double x1 = R.row(1).dot(z.segment(0, pb.n)), y1 = R.row(1).dot(z.segment(pb.n, pb.n));
        const double x2 = R.row(2).dot(z.segment(0, pb.n)), y2 = R.row(2).dot(z.segment(pb.n, pb.n));
        k.start = (x1 * y2 - y1 * x2) / std::pow(x1 * x1 + y1 * y1, 1.5);
        if (!std::isfinite(k.start)) k.start = k.requested;
        break;
      }
      case ConKind::Point: {
        int f = 0;
        pb.point_derivs(z, z[pb.tvar(k.point)], C, ders, f);
        k.start = C(0, k.coord);
        break;
      }
    }
  }
}

namespace {

// End points of the straight start curve: the requested ones, else those of the first / last
// point to pass, else a unit chord along x; a curve given only its area gets height Area / chord.
void start_end_points(const Problem& pb, Eigen::VectorXd& S, Eigen::VectorXd& E) {
  const auto& req = pb.req;
  const auto& P = req.params;
  const int dim = pb.dim, npts = pb.npts;
  auto get = [&](const char* k, double dflt) { return P.count(k) ? P.at(k) : dflt; };
  const char* bnames[3] = {"xB", "yB", "zB"};
  const char* enames[3] = {"xE", "yE", "zE"};
  S.resize(dim);
  E.resize(dim);
  for (int c = 0; c < dim; ++c) {
    double s0 = 0, e0 = c == 0 ? 1.0 : 0.0;
    if (npts > 0) {
      s0 = req.points.front().position[c];
      e0 = req.points.back().position[c];
    }
    if (c == 0 && !P.count("xB") && !P.count("xE") && npts == 0) s0 = 0, e0 = 1;
    S[c] = get(bnames[c], P.count(enames[c]) && !P.count(bnames[c]) && npts == 0 ? P.at(enames[c]) - (c == 0) : s0);
    E[c] = get(enames[c], P.count(bnames[c]) && !P.count(enames[c]) && npts == 0 ? P.at(bnames[c]) + (c == 0) : e0);
  }
  if (dim >= 2 && !P.count("yB") && !P.count("yE") && npts == 0 && P.count("Area")) {
    const double Lx = E[0] - S[0];
    if (std::abs(Lx) > 1e-12) S[1] = E[1] = P.at("Area") / Lx;
  }
}

// Control polygon on the chord S..E at the abscissae xi; with rng (a multistart) the interior
// points are scattered, monotone along the bounded axis; held above the floor when y >= 0.
Eigen::MatrixXd start_polygon(const Problem& pb, const Eigen::VectorXd& S, const Eigen::VectorXd& E,
                              const Eigen::VectorXd& xi, std::mt19937* rng) {
  const auto& P = pb.req.params;
  const int n = pb.n, dim = pb.dim, ax = pb.req.bounds.monotone_axis;
  Eigen::MatrixXd Pm(n, dim);
  for (int i = 0; i < n; ++i) Pm.row(i) = (S + xi[i] * (E - S)).transpose();
  if (rng) {
    std::normal_distribution<double> nd(0.0, 0.25 * pb.Ls);
    std::uniform_real_distribution<double> ud(0.0, 1.0);
    std::vector<double> u(n - 2);
    for (auto& v : u) v = ud(*rng);
    std::sort(u.begin(), u.end());
    for (int i = 1; i + 1 < n; ++i)
      for (int c = 0; c < dim; ++c) {
        if (c == ax) Pm(i, c) = S[c] + (0.1 + 0.8 * u[i - 1]) * (E[c] - S[c]);
        else Pm(i, c) += nd(*rng);
      }
  }
  if (pb.req.bounds.y_nonnegative && dim >= 2) {
    const double floor = 0.05 * pb.Ls;
    for (int i = 1; i + 1 < n; ++i) Pm(i, 1) = std::max(Pm(i, 1), std::max(floor, 0.5 * std::min(S[1], E[1])));
    if (!P.count("yB")) Pm(0, 1) = std::max(Pm(0, 1), floor);
    if (!P.count("yE")) Pm(n - 1, 1) = std::max(Pm(n - 1, 1), floor);
  }
  return Pm;
}

// The second (next-to-last) control point moved along a requested end angle or 3-D tangent,
// short enough to keep the monotone axis and y >= 0.
void aim_end_tangents(const Problem& pb, const Eigen::VectorXd& S, const Eigen::VectorXd& E,
                      const Eigen::VectorXd& xi, Eigen::MatrixXd& Pm) {
  const auto& req = pb.req;
  const auto& P = req.params;
  const int n = pb.n, dim = pb.dim, ax = req.bounds.monotone_axis;
  const bool ynn = req.bounds.y_nonnegative && dim >= 2;
  const char* an[2] = {"alphaB", "alphaE"};
  const Eigen::VectorXd* tg[2] = {&req.tangent_start, &req.tangent_end};
  for (int e = 0; e < 2; ++e) {
    Eigen::VectorXd dir;
    if (P.count(an[e]) && dim >= 2) {
      dir = Eigen::VectorXd::Zero(dim);
      dir[0] = std::cos(P.at(an[e]) * kDeg);
      dir[1] = std::sin(P.at(an[e]) * kDeg);
      if (dim == 3 && tg[e]->size() == 3) dir[2] = 0;
    } else if (dim == 3 && tg[e]->size() == 3) {
      dir = tg[e]->normalized();
    } else {
      continue;
    }
    const int i0 = e == 0 ? 0 : n - 1, i1 = e == 0 ? 1 : n - 2;
    const double sgn = e == 0 ? 1.0 : -1.0;
    double ell = std::abs(xi[1] - xi[0]) * std::max((E - S).norm(), 0.2 * pb.Ls);
    if (ax >= 0 && std::abs(dir[ax]) > 1e-12)
      ell = std::min(ell, 0.5 * std::abs(xi[2] - xi[0]) * std::abs(E[ax] - S[ax]) / std::abs(dir[ax]));
    if (ynn && sgn * dir[1] < 0 && Pm(i0, 1) > 0) ell = std::min(ell, 0.5 * Pm(i0, 1) / std::abs(dir[1]));
    Pm.row(i1) = Pm.row(i0) + sgn * ell * dir.transpose();
  }
}

// Each point's curve parameter: the nearest of kStartSamples samples of the start curve,
// kept increasing and inside (0.02, 0.98).
void start_point_parameters(Problem& pb, Eigen::VectorXd& z) {
  constexpr int kStartSamples = 400;
  const int npts = pb.npts;
  Eigen::MatrixXd C, ders;
  std::vector<Eigen::VectorXd> samples(kStartSamples + 1);
  for (int k = 0; k <= kStartSamples; ++k) {
    int f = 0;
    pb.point_derivs(z, double(k) / kStartSamples, C, ders, f);
    samples[k] = C.row(0).transpose();
  }
  double last = 0.0;
  for (int j = 0; j < npts; ++j) {
    int best = 0;
    double bd = kInf;
    for (int k = 0; k <= kStartSamples; ++k) {
      const double dd = (samples[k] - pb.req.points[j].position).squaredNorm();
      if (dd < bd) bd = dd, best = k;
    }
    double t = std::clamp(double(best) / kStartSamples, 0.02, 0.98);
    if (t <= last) t = std::min(0.98, last + 0.5 / (npts + 1));
    last = t;
    z[pb.tvar(j)] = t;
  }
}

}  // namespace

Eigen::VectorXd Solver::start_curve(std::mt19937* rng) const {
  const int n = pb.n, dim = pb.dim;
  Eigen::VectorXd S, E;
  start_end_points(pb, S, E);
  Eigen::VectorXd xi(n);
  for (int i = 0; i < n; ++i) xi[i] = pb.tab.knots.segment(i + 1, pb.p).mean();
  Eigen::MatrixXd Pm = start_polygon(pb, S, E, xi, rng);
  aim_end_tangents(pb, S, E, xi, Pm);
  Eigen::VectorXd z(pb.nv);
  for (int c = 0; c < dim; ++c) z.segment(c * n, n) = Pm.col(c);
  if (pb.npts > 0) start_point_parameters(pb, z);
  return z;
}

Eigen::VectorXd Solver::fair_linear_start(const Eigen::VectorXd& zc) const {
  // fairest curve meeting only the linear form parameters (one KKT solve), with a
  // small pull towards zc for directions the fairness does not see
  const int nv = pb.nv;
  Eigen::VectorXd g;
  Eigen::MatrixXd H;
  pb.objective(zc, &g, &H);
  const double reg = 1e-8 * std::max(1e-12, H.diagonal().cwiseAbs().maxCoeff());
  const int ml = static_cast<int>(L.rows());
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(nv + ml, nv + ml);
  K.topLeftCorner(nv, nv) = H + reg * Eigen::MatrixXd::Identity(nv, nv);
  K.topRightCorner(nv, ml) = L.transpose();
  K.bottomLeftCorner(ml, nv) = L;
  Eigen::VectorXd rhs(nv + ml);
  rhs.head(nv) = H * zc - g + reg * zc;
  rhs.tail(ml) = b;
  const Eigen::VectorXd sol = K.partialPivLu().solve(rhs);
  Eigen::VectorXd z = sol.head(nv);
  z.tail(pb.npts) = zc.tail(pb.npts);
  return z.allFinite() ? z : zc;
}

Eigen::VectorXd Solver::project_linear(const Eigen::VectorXd& z) const {
  if (L.rows() == 0) return z;
  const Eigen::VectorXd r = L * z - b;
  return z - L.transpose() * (L * L.transpose()).ldlt().solve(r);
}

bool Solver::interior(const Eigen::VectorXd& z) const {
  if (G.rows() == 0) return true;
  return (G * z - h).minCoeff() > 0;
}

double Solver::restoration_merit(const Eigen::VectorXd& z, const Eigen::VectorXd& sinv, double mu,
                                 Eigen::VectorXd& c) const {
  const Eigen::VectorXd s = G * z - h;
  if (s.size() > 0 && !(s.minCoeff() > 0)) return kInf;
  pb.constraints(z, c, nullptr, nullptr, nullptr);
  double v = 0.5 * c.cwiseProduct(sinv).squaredNorm();
  for (int r = 0; r < s.size(); ++r) v -= mu * std::log(s[r]);
  return std::isfinite(v) ? v : kInf;
}

void Solver::restoration_model(const Eigen::MatrixXd& Js, const Eigen::VectorXd& sc, const Eigen::VectorXd& s,
                               double mu, Eigen::MatrixXd& A, Eigen::VectorXd& g) const {
  A = Js.transpose() * Js;
  g = Js.transpose() * sc;
  if (s.size() > 0) {
    const Eigen::VectorXd inv = s.cwiseInverse();
    A.noalias() += mu * (G.transpose() * inv.cwiseAbs2().asDiagonal() * G);
    g.noalias() -= mu * (G.transpose() * inv);
  }
}

Eigen::VectorXd Solver::restoration_step(const Eigen::MatrixXd& A, const Eigen::VectorXd& g, const Eigen::VectorXd& s,
                                         double lm, double diag) const {
  const int nv = pb.nv;
  Eigen::MatrixXd Ab = A + lm * diag * Eigen::MatrixXd::Identity(nv, nv);
  Eigen::VectorXd d = Ab.llt().solve(-g);
  // rows of inequalities the step would nearly cross are held fixed (heavy weight)
  for (int pass = 0; pass < 3 && s.size() > 0; ++pass) {
    const Eigen::VectorXd Gd = G * d;
    bool added = false;
    for (int r = 0; r < s.size(); ++r)
      if (Gd[r] < -0.5 * s[r]) {
        const double wgt = 1e4 * diag / std::max(1e-300, G.row(r).squaredNorm());
        Ab.noalias() += wgt * G.row(r).transpose() * G.row(r);
        added = true;
      }
    if (!added) break;
    d = Ab.llt().solve(-g);
  }
  return d;
}

double Solver::fraction_to_boundary(const Eigen::VectorXd& d, const Eigen::VectorXd& s) const {
  double amax = 1;
  if (s.size() > 0) {
    const Eigen::VectorXd Gd = G * d;
    for (int r = 0; r < s.size(); ++r)
      if (Gd[r] < 0) amax = std::min(amax, -0.99 * s[r] / Gd[r]);
  }
  return amax;
}

bool Solver::restore(Eigen::VectorXd& z, int maxit) {
  // Levenberg-Marquardt on 1/2 |S c(z)|^2 (S = 1/scale) with a small log barrier on the
  // linear inequalities: finds a point meeting the requested values without tracking
  // the optimum along a path.
  Eigen::VectorXd c, ct, sinv(m);
  Eigen::MatrixXd J;
  for (int i = 0; i < m; ++i) sinv[i] = 1.0 / pb.cons[i].scale;
  double lm = 1e-6, prev_res = kInf;
  int stall = 0;
  for (int it = 0; it < maxit; ++it) {
    if (total_iterations >= max_total) return false;
    pb.constraints(z, c, &J, nullptr, nullptr);
    if (!c.allFinite() || !J.allFinite()) return false;
    const Eigen::VectorXd sc = c.cwiseProduct(sinv);
    const double res = sc.lpNorm<Eigen::Infinity>();
    if (res <= restore_tol) return true;
    stall = res > 0.98 * prev_res ? stall + 1 : 0;
    prev_res = res;
    if (stall >= 3) return res <= 1e-2;  // stagnating: let Lagrange-Newton try from here
    ++total_iterations;
    const Eigen::MatrixXd Js = sinv.asDiagonal() * J;
    const double mu = 1e-3 * std::min(1.0, sc.squaredNorm());
    const Eigen::VectorXd s = G * z - h;
    Eigen::MatrixXd A;
    Eigen::VectorXd g;
    restoration_model(Js, sc, s, mu, A, g);
    const double phi0 = restoration_merit(z, sinv, mu, ct);
    const double diag = std::max(1e-12, A.diagonal().maxCoeff());
    bool accepted = false;
    for (int k = 0; k < 12 && !accepted; ++k) {
      const Eigen::VectorXd d = restoration_step(A, g, s, lm, diag);
      const Eigen::VectorXd zt = z + fraction_to_boundary(d, s) * d;
      if (restoration_merit(zt, sinv, mu, ct) < phi0) {
        z = zt;
        accepted = true;
        lm = std::max(1e-12, lm / 5);
      } else {
        lm *= 10;
      }
    }
    if (!accepted) return false;
  }
  return false;
}

bool Solver::direct_solve(RunOutcome& out, double mu0) {
  set_targets(1.0);
  Eigen::VectorXd z = out.z, lam = Eigen::VectorXd::Zero(m);
  if (restore(z, 60) && newton(z, lam, mu0, 1e-10, 1e-5, 30)) {
    out.z = z;
    out.lam = lam;
    out.steps = 1;
    return true;
  }
  vdual.resize(0);
  return false;
}

double Solver::continue_to_targets(RunOutcome& out, double mu0, bool continuation) {
  double tau = 0, dtau = 0.5;
  while (tau < 1) {
    const double tn = std::min(1.0, tau + dtau);
    set_targets(tn);
    Eigen::VectorXd z = out.z, lam = out.lam;
    const bool ok = newton(z, lam, mu0, tn < 1 ? 1e-8 : 1e-10, 1e-5, 15);
    if (ok) {
      out.z = z;
      out.lam = lam;
      tau = tn;
      ++out.steps;
      dtau = std::min(1.0, 2 * dtau);
    } else {
      if (!continuation || total_iterations >= max_total) break;
      dtau *= 0.5;
      if (dtau < 1e-6) break;
    }
  }
  return tau;
}

void Solver::polish(RunOutcome& out, double mu0, double mu_min) {
  // drive the barrier weight down
  for (double mu = mu0 * 0.01; mu > mu_min; mu *= 0.01) {
    Eigen::VectorXd z = out.z, lam = out.lam;
    if (!newton(z, lam, mu, 1e-11, 1e-7, 15)) break;
    out.z = z;
    out.lam = lam;
  }
  Eigen::VectorXd z = out.z, lam = out.lam;
  const bool ok = newton(z, lam, mu_min, pb.req.options.tolerance, 1e-9, 40);
  const double final_stationarity = last_stationarity;
  if (ok || last_violation <= pb.req.options.tolerance) {
    out.z = z;
    out.lam = lam;
  }
  Eigen::VectorXd c;
  pb.constraints(out.z, c, nullptr, nullptr, nullptr);
  out.violation = pb.scaled_violation(c);
  out.feasible = out.violation <= std::max(pb.req.options.tolerance, 1e-11) && interior(out.z);
  out.converged = out.feasible && (ok || final_stationarity <= 1e-6);
  out.objective = pb.objective(out.z, nullptr, nullptr);
}

RunOutcome Solver::run(const Eigen::VectorXd& z0, bool continuation) {
  total_iterations = 0;
  RunOutcome out;
  out.z = z0;
  out.lam = Eigen::VectorXd::Zero(m);
  vdual.resize(0);
  set_starts(z0);
  for (const auto& k : pb.cons) out.starts.push_back(k.start);
  const double f0 = pb.objective(z0, nullptr, nullptr);
  const double fscale = std::max(f0, 1e-6 * pb.Ls * pb.Ls);
  const double mu0 = 1e-4 * fscale, mu_min = 1e-12 * fscale;
  // Reach the requested values directly (LM restoration, then Lagrange-Newton from that
  // feasible point); continuation in the targets is the fallback.
  const double tau = direct_solve(out, mu0) ? 1.0 : continue_to_targets(out, mu0, continuation);
  out.tau = tau;
  if (tau < 1) {
    set_targets(tau);
    return out;
  }
  polish(out, mu0, mu_min);
  return out;
}

}  // namespace fairlines::form_curve_impl
