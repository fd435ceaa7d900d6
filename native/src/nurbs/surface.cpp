#include "fairlines/surface.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

#include "checks.hpp"
#include "fairlines/basis.hpp"
#include "fairlines/knots.hpp"

namespace fairlines {

using detail::fail;

Direction parse_direction(const std::string& name) {
  if (name == "u" || name == "U") return Direction::U;
  if (name == "v" || name == "V") return Direction::V;
  fail("direction is '", name, "'; expected 'u' or 'v'");
}

namespace {

double binomial(int n, int k) {
  double r = 1.0;
  for (int i = 1; i <= k; ++i) r = r * (n - k + i) / i;
  return r;
}

// Cox-de Boor with the degree known at compile time, so loops unroll (hot path).
template <int P>
inline void basis_fixed(int span, double t, const double* U, double* N) {
  double left[P + 1], right[P + 1];
  N[0] = 1.0;
  for (int j = 1; j <= P; ++j) {
    left[j] = t - U[span + 1 - j];
    right[j] = U[span + j] - t;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      const double temp = N[r] / (right[r + 1] + left[j - r]);
      N[r] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    N[j] = saved;
  }
}

inline void basis_dyn(int p, int span, double t, const double* U, double* N) {
  switch (p) {
    case 1: basis_fixed<1>(span, t, U, N); return;
    case 2: basis_fixed<2>(span, t, U, N); return;
    case 3: basis_fixed<3>(span, t, U, N); return;
    default: basis_functions(span, t, p, U, N);
  }
}

struct Layout {
  const double* ku;
  const double* kv;
  int nku, nkv, nv;
  double ua, ub, va, vb;
  const double* pw;
  bool rational;
};

// Scattered evaluation kernel; P, Q > 0 fixes the degrees at compile time, 0 means runtime.
template <int P, int Q>
void scatter_kernel(const Layout& L, int pd, int qd, const double* u, const double* v, long m, double* out) {
  const int p = P > 0 ? P : pd, q = Q > 0 ? Q : qd;
  double Nu[kMaxFastDegree + 1], Nv[kMaxFastDegree + 1];
  for (long k = 0; k < m; ++k) {
    const double uk = std::clamp(u[k], L.ua, L.ub), vk = std::clamp(v[k], L.va, L.vb);
    const int su = find_span(p, L.ku, L.nku, uk), sv = find_span(q, L.kv, L.nkv, vk);
    if constexpr (P > 0) basis_fixed<P>(su, uk, L.ku, Nu); else basis_dyn(p, su, uk, L.ku, Nu);
    if constexpr (Q > 0) basis_fixed<Q>(sv, vk, L.kv, Nv); else basis_dyn(q, sv, vk, L.kv, Nv);
    double acc[4] = {0, 0, 0, 0};
    for (int a = 0; a <= p; ++a) {
      const double* row = L.pw + (static_cast<long>(su - p + a) * L.nv + (sv - q)) * 4;
      double t4[4] = {0, 0, 0, 0};
      for (int b = 0; b <= q; ++b)
        for (int c = 0; c < 4; ++c) t4[c] += Nv[b] * row[b * 4 + c];
      for (int c = 0; c < 4; ++c) acc[c] += Nu[a] * t4[c];
    }
    if (L.rational) {
      const double iw = 1.0 / acc[3];
      out[3 * k] = acc[0] * iw;
      out[3 * k + 1] = acc[1] * iw;
      out[3 * k + 2] = acc[2] * iw;
    } else {
      out[3 * k] = acc[0];
      out[3 * k + 1] = acc[1];
      out[3 * k + 2] = acc[2];
    }
  }
}

template <int Q>
void grid_row_kernel(const double* row, int q, const int* spans, const double* Nv_all, long n_v, bool rational,
                     double* out) {
  const int qq = Q > 0 ? Q : q;
  for (long b = 0; b < n_v; ++b) {
    const double* Nv = Nv_all + b * (qq + 1);
    const double* base = row + static_cast<long>(spans[b] - qq) * 4;
    double acc[4] = {0, 0, 0, 0};
    for (int j = 0; j <= qq; ++j)
      for (int c = 0; c < 4; ++c) acc[c] += Nv[j] * base[j * 4 + c];
    if (rational) {
      const double iw = 1.0 / acc[3];
      out[3 * b] = acc[0] * iw;
      out[3 * b + 1] = acc[1] * iw;
      out[3 * b + 2] = acc[2] * iw;
    } else {
      out[3 * b] = acc[0];
      out[3 * b + 1] = acc[1];
      out[3 * b + 2] = acc[2];
    }
  }
}

}  // namespace

NurbsSurface::NurbsSurface(int degree_u, int degree_v, Eigen::VectorXd knots_u, Eigen::VectorXd knots_v, int nu,
                           int nv, Eigen::MatrixXd control_points, Eigen::VectorXd weights)
    : pu_(degree_u), pv_(degree_v), nu_(nu), nv_(nv), ku_(std::move(knots_u)), kv_(std::move(knots_v)),
      points_(std::move(control_points)), weights_(std::move(weights)) {
  detail::require_degree(pu_, "degree_u");
  detail::require_degree(pv_, "degree_v");
  if (nu_ < 1 || nv_ < 1) fail("control net is ", nu_, " x ", nv_, "; expected a non-empty (nu, nv, 3) array");
  if (points_.rows() != static_cast<Eigen::Index>(nu_) * nv_ || points_.cols() != 3)
    fail("control_points has shape (", points_.rows(), ", ", points_.cols(), "); expected (", nu_ * nv_, ", 3)");
  detail::require_finite(points_, "control_points");
  validate_knots(ku_, pu_, nu_, "knots_u");
  validate_knots(kv_, pv_, nv_, "knots_v");
  if (weights_.size() == 0)
    weights_ = Eigen::VectorXd::Ones(points_.rows());
  else
    detail::require_weights(weights_, points_.rows());
  refresh();
}

void NurbsSurface::refresh() {
  rational_ = (weights_.array() != 1.0).any();
  pw_.resize(static_cast<size_t>(points_.rows()) * 4);
  for (Eigen::Index i = 0; i < points_.rows(); ++i) {
    for (int c = 0; c < 3; ++c) pw_[i * 4 + c] = points_(i, c) * weights_[i];
    pw_[i * 4 + 3] = weights_[i];
  }
}

std::pair<double, double> NurbsSurface::domain_u() const { return {ku_[pu_], ku_[nu_]}; }
std::pair<double, double> NurbsSurface::domain_v() const { return {kv_[pv_], kv_[nv_]}; }

Eigen::Vector3d NurbsSurface::evaluate(double u, double v) const {
  Eigen::Vector3d out;
  detail::require_finite(u, "u");
  detail::require_finite(v, "v");
  evaluate_into(&u, &v, 1, out.data());
  return out;
}

Eigen::MatrixXd NurbsSurface::evaluate(const Eigen::VectorXd& u, const Eigen::VectorXd& v) const {
  if (u.size() != v.size()) fail("u has ", u.size(), " values and v has ", v.size(), "; expected equal lengths");
  detail::require_finite(u, "u");
  detail::require_finite(v, "v");
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> out(u.size(), 3);
  evaluate_into(u.data(), v.data(), u.size(), out.data());
  return out;
}

void NurbsSurface::evaluate_into(const double* u, const double* v, long m, double* out) const {
  const auto [ua, ub] = domain_u();
  const auto [va, vb] = domain_v();
  const Layout L{ku_.data(), kv_.data(), static_cast<int>(ku_.size()), static_cast<int>(kv_.size()), nv_,
                 ua, ub, va, vb, pw_.data(), rational_};
  if (pu_ > kMaxFastDegree || pv_ > kMaxFastDegree) {
    // Rare high degrees: evaluate through the general derivative routine.
    for (long k = 0; k < m; ++k) {
      const Eigen::MatrixXd D = derivatives(u[k], v[k], 0);
      for (int c = 0; c < 3; ++c) out[3 * k + c] = D(0, c);
    }
    return;
  }
  if (pu_ == 3 && pv_ == 3) return scatter_kernel<3, 3>(L, 3, 3, u, v, m, out);
  if (pu_ == 2 && pv_ == 2) return scatter_kernel<2, 2>(L, 2, 2, u, v, m, out);
  if (pu_ == 2 && pv_ == 3) return scatter_kernel<2, 3>(L, 2, 3, u, v, m, out);
  if (pu_ == 3 && pv_ == 2) return scatter_kernel<3, 2>(L, 3, 2, u, v, m, out);
  if (pu_ == 1 && pv_ == 1) return scatter_kernel<1, 1>(L, 1, 1, u, v, m, out);
  scatter_kernel<0, 0>(L, pu_, pv_, u, v, m, out);
}

Eigen::MatrixXd NurbsSurface::evaluate_grid(const Eigen::VectorXd& us, const Eigen::VectorXd& vs) const {
  detail::require_finite(us, "us");
  detail::require_finite(vs, "vs");
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> out(us.size() * vs.size(), 3);
  evaluate_grid_into(us.data(), us.size(), vs.data(), vs.size(), out.data());
  return out;
}

void NurbsSurface::evaluate_grid_into(const double* us, long n_u, const double* vs, long n_v, double* out) const {
  const auto [ua, ub] = domain_u();
  const auto [va, vb] = domain_v();
  const int p = pu_, q = pv_;
  // Basis values along v are shared by every grid line u = const.
  std::vector<int> spans(n_v);
  std::vector<double> Nv(static_cast<size_t>(n_v) * (q + 1));
  for (long b = 0; b < n_v; ++b) {
    const double t = std::clamp(vs[b], va, vb);
    spans[b] = find_span(q, kv_.data(), static_cast<int>(kv_.size()), t);
    basis_dyn(q, spans[b], t, kv_.data(), &Nv[b * (q + 1)]);
  }
  std::vector<double> row(static_cast<size_t>(nv_) * 4);
  std::vector<double> Nu(p + 1);
  for (long a = 0; a < n_u; ++a) {
    const double t = std::clamp(us[a], ua, ub);
    const int su = find_span(p, ku_.data(), static_cast<int>(ku_.size()), t);
    basis_dyn(p, su, t, ku_.data(), Nu.data());
    // Contract the control net in u once per grid line: a homogeneous curve in v.
    std::fill(row.begin(), row.end(), 0.0);
    for (int i = 0; i <= p; ++i) {
      const double* src = &pw_[static_cast<size_t>(su - p + i) * nv_ * 4];
      const double w = Nu[i];
      for (int j = 0; j < nv_ * 4; ++j) row[j] += w * src[j];
    }
    double* dst = out + a * n_v * 3;
    switch (q) {
      case 3: grid_row_kernel<3>(row.data(), q, spans.data(), Nv.data(), n_v, rational_, dst); break;
      case 2: grid_row_kernel<2>(row.data(), q, spans.data(), Nv.data(), n_v, rational_, dst); break;
      default: grid_row_kernel<0>(row.data(), q, spans.data(), Nv.data(), n_v, rational_, dst);
    }
  }
}

Eigen::MatrixXd NurbsSurface::derivatives(double u, double v, int order) const {
  if (order < 0) fail("order is ", order, "; expected an integer >= 0");
  detail::require_finite(u, "u");
  detail::require_finite(v, "v");
  const auto [ua, ub] = domain_u();
  const auto [va, vb] = domain_v();
  u = std::clamp(u, ua, ub);
  v = std::clamp(v, va, vb);
  const int p = pu_, q = pv_, d = order;
  const int su = find_span(p, ku_, u), sv = find_span(q, kv_, v);
  Eigen::MatrixXd Nu(d + 1, p + 1), Nv(d + 1, q + 1);
  basis_derivatives(su, u, p, d, ku_, Nu);
  basis_derivatives(sv, v, q, d, kv_, Nv);
  // Homogeneous derivatives Aw(k, l) (P&T A3.6), then the rational quotient rule (A4.4).
  std::vector<Eigen::Vector4d> Aw((d + 1) * (d + 1), Eigen::Vector4d::Zero());
  for (int k = 0; k <= d; ++k) {
    std::vector<Eigen::Vector4d> temp(q + 1, Eigen::Vector4d::Zero());
    for (int s = 0; s <= q; ++s)
      for (int r = 0; r <= p; ++r)
        temp[s] += Nu(k, r) * Eigen::Map<const Eigen::Vector4d>(&pw_[(static_cast<size_t>(su - p + r) * nv_ + sv - q + s) * 4]);
    for (int l = 0; l + k <= d; ++l)
      for (int s = 0; s <= q; ++s) Aw[k * (d + 1) + l] += Nv(l, s) * temp[s];
  }
  Eigen::MatrixXd SKL = Eigen::MatrixXd::Zero((d + 1) * (d + 1), 3);
  for (int k = 0; k <= d; ++k)
    for (int l = 0; l + k <= d; ++l) {
      Eigen::Vector3d v3 = Aw[k * (d + 1) + l].head<3>();
      for (int j = 1; j <= l; ++j) v3 -= binomial(l, j) * Aw[j][3] * SKL.row(k * (d + 1) + l - j).transpose();
      for (int i = 1; i <= k; ++i) {
        v3 -= binomial(k, i) * Aw[i * (d + 1)][3] * SKL.row((k - i) * (d + 1) + l).transpose();
        Eigen::Vector3d v2 = Eigen::Vector3d::Zero();
        for (int j = 1; j <= l; ++j) v2 += binomial(l, j) * Aw[i * (d + 1) + j][3] * SKL.row((k - i) * (d + 1) + l - j).transpose();
        v3 -= binomial(k, i) * v2;
      }
      SKL.row(k * (d + 1) + l) = v3.transpose() / Aw[0][3];
    }
  return SKL;
}

Eigen::MatrixXd NurbsSurface::normal(const Eigen::VectorXd& u, const Eigen::VectorXd& v) const {
  if (u.size() != v.size()) fail("u has ", u.size(), " values and v has ", v.size(), "; expected equal lengths");
  const auto [ua, ub] = domain_u();
  const auto [va, vb] = domain_v();
  Eigen::MatrixXd out(u.size(), 3);
  // A tangent shorter than this fraction of the other one counts as collapsed (a pole).
  constexpr double kCollapsed = 1e-8;
  for (Eigen::Index k = 0; k < u.size(); ++k) {
    double uu = u[k], vv = v[k];
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    for (int attempt = 0; attempt < 8; ++attempt) {
      const Eigen::MatrixXd D = derivatives(uu, vv, 2);  // row k * 3 + l
      const Eigen::Vector3d su = D.row(3).transpose(), sv = D.row(1).transpose(), suv = D.row(4).transpose();
      const double a = su.norm(), b = sv.norm();
      // S_u vanishes along an edge v = const: S_u ~ (v - v_edge) S_uv there (l'Hopital), so
      // the limit of S_u x S_v is +-S_uv x S_v, the sign taken from the side of the domain.
      if (a < kCollapsed * b) {
        n = suv.cross(sv) * ((vv > 0.5 * (va + vb)) ? -1.0 : 1.0);
      } else if (b < kCollapsed * a) {
        n = su.cross(suv) * ((uu > 0.5 * (ua + ub)) ? -1.0 : 1.0);
      } else {
        n = su.cross(sv);
      }
      if (n.norm() > kCollapsed * (a + b) * (a + b) && n.allFinite()) break;
      // Still degenerate (e.g. a collapsed corner): step toward the domain centre.
      const double h = 1e-9 * std::pow(10.0, attempt);
      uu += h * (ub - ua) * ((uu < 0.5 * (ua + ub)) ? 1.0 : -1.0);
      vv += h * (vb - va) * ((vv < 0.5 * (va + vb)) ? 1.0 : -1.0);
    }
    out.row(k) = n.normalized().transpose();
  }
  return out;
}

std::pair<Eigen::VectorXd, Eigen::VectorXd> NurbsSurface::curvature(const Eigen::VectorXd& u,
                                                                    const Eigen::VectorXd& v) const {
  if (u.size() != v.size()) fail("u has ", u.size(), " values and v has ", v.size(), "; expected equal lengths");
  Eigen::VectorXd K(u.size()), H(u.size());
  for (Eigen::Index k = 0; k < u.size(); ++k) {
    const Eigen::MatrixXd D = derivatives(u[k], v[k], 2);  // rows k*3 + l
    const Eigen::Vector3d Su = D.row(3).transpose(), Sv = D.row(1).transpose();
    const Eigen::Vector3d Suu = D.row(6).transpose(), Suv = D.row(4).transpose(), Svv = D.row(2).transpose();
    const Eigen::Vector3d n = Su.cross(Sv);
    const double nn = n.norm();
    if (!(nn > 0.0)) fail("curvature is undefined at (u, v) = (", u[k], ", ", v[k], "): the surface is degenerate there");
    const Eigen::Vector3d nu = n / nn;
    const double E = Su.dot(Su), F = Su.dot(Sv), G = Sv.dot(Sv);
    const double L = Suu.dot(nu), M = Suv.dot(nu), N = Svv.dot(nu);
    const double det = E * G - F * F;
    K[k] = (L * N - M * M) / det;
    H[k] = (E * N - 2.0 * F * M + G * L) / (2.0 * det);
  }
  return {K, H};
}

std::tuple<double, double, Eigen::Vector3d> NurbsSurface::closest_point(const Eigen::Vector3d& p) const {
  detail::require_finite(p, "point");
  const auto [ua, ub] = domain_u();
  const auto [va, vb] = domain_v();
  auto samples = [](const Eigen::VectorXd& U, int deg, int n) {
    std::vector<double> s;
    const int per = std::max(2, std::min(2 * (deg + 1), 256 / std::max(1, n - deg)));
    for (int i = deg; i < n; ++i) {
      if (U[i + 1] <= U[i]) continue;
      for (int k = 0; k < per; ++k) s.push_back(U[i] + (U[i + 1] - U[i]) * k / per);
    }
    s.push_back(U[n]);
    return Eigen::VectorXd(Eigen::Map<Eigen::VectorXd>(s.data(), static_cast<Eigen::Index>(s.size())));
  };
  const Eigen::VectorXd us = samples(ku_, pu_, nu_), vs = samples(kv_, pv_, nv_);
  const Eigen::MatrixXd grid = evaluate_grid(us, vs);
  std::vector<std::pair<double, Eigen::Index>> cand;
  cand.reserve(grid.rows());
  for (Eigen::Index i = 0; i < grid.rows(); ++i) cand.emplace_back((grid.row(i).transpose() - p).squaredNorm(), i);
  const size_t n_starts = std::min<size_t>(4, cand.size());
  std::partial_sort(cand.begin(), cand.begin() + n_starts, cand.end());
  const double scale = std::max(1.0, (points_.colwise().maxCoeff() - points_.colwise().minCoeff()).norm());
  double best_u = us[cand[0].second / vs.size()], best_v = vs[cand[0].second % vs.size()];
  double best_d = cand[0].first;
  for (size_t c = 0; c < n_starts; ++c) {
    double uu = us[cand[c].second / vs.size()], vv = vs[cand[c].second % vs.size()];
    for (int it = 0; it < 60; ++it) {
      const Eigen::MatrixXd D = derivatives(uu, vv, 2);
      const Eigen::Vector3d S = D.row(0).transpose(), Su = D.row(3).transpose(), Sv = D.row(1).transpose();
      const Eigen::Vector3d Suu = D.row(6).transpose(), Suv = D.row(4).transpose(), Svv = D.row(2).transpose();
      const Eigen::Vector3d r = S - p;
      Eigen::Matrix2d J;
      J << Su.dot(Su) + r.dot(Suu), Su.dot(Sv) + r.dot(Suv), Su.dot(Sv) + r.dot(Suv), Sv.dot(Sv) + r.dot(Svv);
      const Eigen::Vector2d g(Su.dot(r), Sv.dot(r));
      Eigen::Vector2d delta = J.ldlt().solve(-g);
      if (!delta.allFinite() || J.determinant() <= 0.0) delta = -g / std::max(J.diagonal().maxCoeff(), 1e-300);
      const double un = std::clamp(uu + delta[0], ua, ub), vn = std::clamp(vv + delta[1], va, vb);
      const double step = (Su * (un - uu) + Sv * (vn - vv)).norm();
      uu = un;
      vv = vn;
      // Converged when a step moves the point by less than this relative tolerance.
      if (step < 1e-15 * scale) break;
    }
    const double d = (evaluate(uu, vv) - p).squaredNorm();
    if (d < best_d) {
      best_d = d;
      best_u = uu;
      best_v = vv;
    }
  }
  // Boundary curves: Newton clamped to a corner of the box can stall on an edge.
  for (int e = 0; e < 4; ++e) {
    const Direction dir = (e < 2) ? Direction::U : Direction::V;
    const double t = (e == 0) ? ua : (e == 1) ? ub : (e == 2) ? va : vb;
    const NurbsCurve edge = iso_curve(dir, t);
    const auto [s, q] = edge.closest_point(p);
    const double d = (q - p).squaredNorm();
    if (d < best_d) {
      best_d = d;
      best_u = (dir == Direction::U) ? t : s;
      best_v = (dir == Direction::U) ? s : t;
    }
  }
  return {best_u, best_v, evaluate(best_u, best_v)};
}

Eigen::MatrixXd NurbsSurface::homogeneous() const {
  return Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 4, Eigen::RowMajor>>(pw_.data(), points_.rows(), 4);
}

NurbsSurface NurbsSurface::from_homogeneous(int degree_u, int degree_v, Eigen::VectorXd knots_u, Eigen::VectorXd knots_v,
                                            int nu, int nv, const Eigen::MatrixXd& pw) {
  Eigen::VectorXd w = pw.col(3);
  for (Eigen::Index i = 0; i < w.size(); ++i)
    if (!(w[i] > 0.0)) fail("homogeneous weight ", i, " is ", w[i], "; expected > 0");
  Eigen::MatrixXd P = pw.leftCols(3).array().colwise() / w.array();
  return NurbsSurface(degree_u, degree_v, std::move(knots_u), std::move(knots_v), nu, nv, std::move(P), std::move(w));
}

namespace {

// Applies a curve operation to every row (dir V) or column (dir U) of the homogeneous
// net, treating each as a non-rational 4-D curve, and reassembles the surface.
template <typename Op>
NurbsSurface map_lines(const NurbsSurface& s, Direction dir, Op op) {
  const Eigen::MatrixXd pw = s.homogeneous();
  const int nu = s.nu(), nv = s.nv();
  const bool along_u = (dir == Direction::U);
  const int lines = along_u ? nv : nu, len = along_u ? nu : nv;
  std::vector<NurbsCurve> out;
  out.reserve(lines);
  for (int l = 0; l < lines; ++l) {
    Eigen::MatrixXd c(len, 4);
    for (int k = 0; k < len; ++k) c.row(k) = along_u ? pw.row(k * nv + l) : pw.row(l * nv + k);
    out.push_back(op(NurbsCurve(along_u ? s.degree_u() : s.degree_v(), along_u ? s.knots_u() : s.knots_v(), c)));
  }
  const int new_len = out[0].n_control();
  const int nu2 = along_u ? new_len : nu, nv2 = along_u ? nv : new_len;
  Eigen::MatrixXd pw2(static_cast<Eigen::Index>(nu2) * nv2, 4);
  for (int l = 0; l < lines; ++l)
    for (int k = 0; k < new_len; ++k) {
      const Eigen::Index row = along_u ? static_cast<Eigen::Index>(k) * nv2 + l : static_cast<Eigen::Index>(l) * nv2 + k;
      pw2.row(row) = out[l].control_points().row(k);
    }
  if (along_u)
    return NurbsSurface::from_homogeneous(out[0].degree(), s.degree_v(), out[0].knots(), s.knots_v(), nu2, nv2, pw2);
  return NurbsSurface::from_homogeneous(s.degree_u(), out[0].degree(), s.knots_u(), out[0].knots(), nu2, nv2, pw2);
}

}  // namespace

NurbsSurface NurbsSurface::insert_knot(Direction dir, double t, int times) const {
  return map_lines(*this, dir, [&](const NurbsCurve& c) { return c.insert_knot(t, times); });
}

NurbsSurface NurbsSurface::refine_knots(Direction dir, const Eigen::VectorXd& X) const {
  return map_lines(*this, dir, [&](const NurbsCurve& c) { return c.refine_knots(X); });
}

NurbsSurface NurbsSurface::elevate_degree(Direction dir, int times) const {
  return map_lines(*this, dir, [&](const NurbsCurve& c) { return c.elevate_degree(times); });
}

NurbsCurve NurbsSurface::iso_curve(Direction dir, double t) const {
  detail::require_finite(t, "t");
  const bool fix_u = (dir == Direction::U);
  const auto [a, b] = fix_u ? domain_u() : domain_v();
  t = std::clamp(t, a, b);
  const int p = fix_u ? pu_ : pv_;
  const Eigen::VectorXd& K = fix_u ? ku_ : kv_;
  const int span = find_span(p, K, t);
  std::vector<double> N(p + 1);
  basis_functions(span, t, p, K, N.data());
  const int len = fix_u ? nv_ : nu_;
  Eigen::MatrixXd pw = Eigen::MatrixXd::Zero(len, 4);
  for (int k = 0; k < len; ++k)
    for (int i = 0; i <= p; ++i) {
      const size_t idx = fix_u ? static_cast<size_t>(span - p + i) * nv_ + k : static_cast<size_t>(k) * nv_ + span - p + i;
      pw.row(k) += N[i] * Eigen::Map<const Eigen::RowVector4d>(&pw_[idx * 4]);
    }
  return NurbsCurve::from_homogeneous(fix_u ? pv_ : pu_, fix_u ? kv_ : ku_, pw);
}

void NurbsSurface::set_control_point(int i, int j, const Eigen::Vector3d& p) {
  if (i < 0 || i >= nu_ || j < 0 || j >= nv_) fail("control point index (", i, ", ", j, ") is outside the ", nu_, " x ", nv_, " net");
  detail::require_finite(p, "control point");
  points_.row(static_cast<Eigen::Index>(i) * nv_ + j) = p.transpose();
  refresh();
}

void NurbsSurface::set_weight(int i, int j, double w) {
  if (i < 0 || i >= nu_ || j < 0 || j >= nv_) fail("weight index (", i, ", ", j, ") is outside the ", nu_, " x ", nv_, " net");
  if (!(w > 0.0) || !std::isfinite(w)) fail("weight is ", w, "; expected a finite value > 0");
  weights_[static_cast<Eigen::Index>(i) * nv_ + j] = w;
  refresh();
}

}  // namespace fairlines
