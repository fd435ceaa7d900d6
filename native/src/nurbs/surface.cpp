#include "fairlines/surface.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>
#include <utility>

#include <Eigen/Dense>

#include "basis_table.hpp"
#include "checks.hpp"
#include "knot_refinement.hpp"
#include "fairlines/basis.hpp"
#include "fairlines/knots.hpp"
#include "homogeneous.hpp"

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

// The SIMD helpers below are always inlined, so no vector value crosses an ABI boundary.
#pragma GCC diagnostic ignored "-Wpsabi"

// Hot kernels are compiled twice when the compiler can: for AVX2/FMA machines and a
// portable baseline, picked at load time (GCC function multiversioning). The clone is the
// x86-64-v3 ISA level, dispatched on CPU features: an "arch=haswell" clone is dispatched
// on the CPU model and so ran only on Haswell itself (every later CPU got the baseline).
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && __GNUC__ >= 12
#define FAIRLINES_MULTIVERSION __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define FAIRLINES_MULTIVERSION
#endif
using detail::basis_table_eval;
using detail::SpanLocator;
using detail::v4d;
using detail::v4du;

struct Layout {
  const double* ku;
  const double* kv;
  const double* inv_u;
  const double* inv_v;
  int nu, nv;  // control points per direction
  double ua, ub, va, vb;
  const double* pw;
  bool rational;
  const SpanLocator* span_u;
  const SpanLocator* span_v;
  const double* pow_u;
  const double* pow_v;
};

Layout make_layout(const Eigen::VectorXd& ku, const Eigen::VectorXd& kv, const std::vector<double>& inv_u,
                   const std::vector<double>& inv_v, int pu, int pv, int nu, int nv, const std::vector<double>& pw,
                   bool rational, const std::shared_ptr<const void>& span_u, const std::shared_ptr<const void>& span_v,
                   const std::vector<double>& pow_u, const std::vector<double>& pow_v) {
  return {ku.data(), kv.data(), inv_u.data(), inv_v.data(), nu, nv, ku[pu], ku[nu], kv[pv], kv[nv], pw.data(), rational,
          static_cast<const SpanLocator*>(span_u.get()), static_cast<const SpanLocator*>(span_v.get()), pow_u.data(),
          pow_v.data()};
}

FAIRLINES_INLINE v4d load4(const double* p) { return *reinterpret_cast<const v4du*>(p); }

// std::clamp is not inlined into the multiversioned kernels (target mismatch): clamp here.
// Two separate selects compile to max/min (no branch) and keep a NaN.
FAIRLINES_INLINE double clamp_to(double t, double lo, double hi) {
  t = t < lo ? lo : t;
  return t > hi ? hi : t;
}

// Broadcast of lane I: one permute (an initializer {x[I], ...} compiles to far more code).
template <int I>
FAIRLINES_INLINE v4d lane(v4d x) {
#if defined(__clang__) || __GNUC__ >= 12
  return __builtin_shufflevector(x, x, I, I, I, I);
#else
  typedef long long v4di __attribute__((vector_size(32)));
  return __builtin_shuffle(x, v4di{I, I, I, I});
#endif
}

// sum_B N[B] * row[B] over homogeneous points row[0..]: index packs unroll at compile time.
template <int... B>
FAIRLINES_INLINE v4d combine(const double* row, v4d N, std::integer_sequence<int, B...>) {
  return (... + (lane<B>(N) * load4(row + 4 * B)));
}
template <int... A>
FAIRLINES_INLINE v4d combine_rows(const double* row, long stride, v4d Nu, v4d Nv, std::integer_sequence<int, A...>,
                                  auto qs) {
  return (... + (lane<A>(Nu) * combine(row + A * stride, Nv, qs)));
}

/// The power-table kernels' view of a layout, copied into locals (the output stores could
/// alias the layout's doubles and force reloads), and the spans of a clamped (u, v).
struct PowerSpans {
  double ua, ub, va, vb, au, scale_u, av, scale_v;
  unsigned bu, bv;
  const int *table_u, *table_v;
  const double *ku, *kv, *pow_u, *pow_v, *pw;
  long stride;
  explicit PowerSpans(const Layout& L)
      : ua(L.ua), ub(L.ub), va(L.va), vb(L.vb), au(L.span_u->a), scale_u(L.span_u->scale), av(L.span_v->a),
        scale_v(L.span_v->scale), bu(L.span_u->buckets), bv(L.span_v->buckets), table_u(L.span_u->table.data()),
        table_v(L.span_v->table.data()), ku(L.span_u->knots.data()), kv(L.span_v->knots.data()), pow_u(L.pow_u),
        pow_v(L.pow_v), pw(L.pw), stride(static_cast<long>(L.nv) * 4) {}
  /// The spans su, sv of (u, v) clamped to the domain and the offsets du, dv into them.
  FAIRLINES_INLINE void find(double u, double v, long& su, long& sv, double& du, double& dv) const {
    const double uk = clamp_to(u, ua, ub), vk = clamp_to(v, va, vb);
    su = SpanLocator::find(uk, au, scale_u, bu, table_u, ku);
    sv = SpanLocator::find(vk, av, scale_v, bv, table_v, kv);
    du = uk - ku[su];
    dv = vk - kv[sv];
  }
};

// Scattered points for degrees P, Q <= 3: both bases by one SIMD Horner each, then the
// (P + 1) x (Q + 1) homogeneous block contracted row by row in v, then in u.
template <int P, int Q, bool Rational>
FAIRLINES_INLINE void scatter_power_kernel(const Layout& L, const double* u, const double* v, long m, double* out) {
  const PowerSpans T(L);
  for (long k = 0; k < m; ++k) {
    long su, sv;
    double du, dv;
    T.find(u[k], v[k], su, sv, du, dv);
    const v4d Nu = detail::basis_power4<P>(T.pow_u + su * 16, du);
    const v4d Nv = detail::basis_power4<Q>(T.pow_v + sv * 16, dv);
    const double* row = T.pw + (su - P) * T.stride + (sv - Q) * 4;
    v4d acc = combine_rows(row, T.stride, Nu, Nv, std::make_integer_sequence<int, P + 1>(),
                           std::make_integer_sequence<int, Q + 1>());
    if constexpr (Rational) acc *= 1.0 / acc[3];
    out[3 * k] = acc[0];
    out[3 * k + 1] = acc[1];
    out[3 * k + 2] = acc[2];
  }
}

template <int P, int Q>
FAIRLINES_INLINE void scatter_power(const Layout& L, const double* u, const double* v, long m, double* out) {
  if (L.rational) scatter_power_kernel<P, Q, true>(L, u, v, m, out);
  else scatter_power_kernel<P, Q, false>(L, u, v, m, out);
}

// Scattered points for any degree up to kMaxFastDegree (the Cox-de Boor triangle).
FAIRLINES_INLINE void scatter_kernel(const Layout& L, int pu, int pv, const double* u, const double* v, long m,
                                     double* out) {
  double Nu[kMaxFastDegree + 1], Nv[kMaxFastDegree + 1];
  for (long k = 0; k < m; ++k) {
    const double uk = clamp_to(u[k], L.ua, L.ub), vk = clamp_to(v[k], L.va, L.vb);
    const int su = L.span_u->find(uk), sv = L.span_v->find(vk);
    basis_table_eval<0>(pu, su, uk, L.ku, L.inv_u, Nu);
    basis_table_eval<0>(pv, sv, vk, L.kv, L.inv_v, Nv);
    v4d acc = {0, 0, 0, 0};
    for (int a = 0; a <= pu; ++a) {
      const double* row = L.pw + (static_cast<long>(su - pu + a) * L.nv + (sv - pv)) * 4;
      v4d t4 = Nv[0] * load4(row);
      for (int b = 1; b <= pv; ++b) t4 += Nv[b] * load4(row + 4 * b);
      acc += Nu[a] * t4;
    }
    const double iw = L.rational ? 1.0 / acc[3] : 1.0;
    out[3 * k] = acc[0] * iw;
    out[3 * k + 1] = acc[1] * iw;
    out[3 * k + 2] = acc[2] * iw;
  }
}

FAIRLINES_MULTIVERSION
void scatter_dispatch(const Layout& L, int p, int q, const double* u, const double* v, long m, double* out) {
  if (p == 3 && q == 3) return scatter_power<3, 3>(L, u, v, m, out);
  if (p == 2 && q == 2) return scatter_power<2, 2>(L, u, v, m, out);
  if (p == 2 && q == 3) return scatter_power<2, 3>(L, u, v, m, out);
  if (p == 3 && q == 2) return scatter_power<3, 2>(L, u, v, m, out);
  if (p == 1 && q == 1) return scatter_power<1, 1>(L, u, v, m, out);
  scatter_kernel(L, p, q, u, v, m, out);
}

// Points and first partials at scattered parameters: row k of out = [S, S_u, S_v].
template <int P, int Q>
FAIRLINES_INLINE void d1_kernel(const Layout& L, int p, int q, const double* u, const double* v, long m, double* out) {
  const int pu = P > 0 ? P : p, pv = Q > 0 ? Q : q;
  double Nu[kMaxFastDegree + 1], Nv[kMaxFastDegree + 1], dNu[kMaxFastDegree + 1], dNv[kMaxFastDegree + 1];
  for (long k = 0; k < m; ++k) {
    const double uk = clamp_to(u[k], L.ua, L.ub), vk = clamp_to(v[k], L.va, L.vb);
    const int su = L.span_u->find(uk), sv = L.span_v->find(vk);
    basis_table_eval<P>(pu, su, uk, L.ku, L.inv_u, Nu, dNu);
    basis_table_eval<Q>(pv, sv, vk, L.kv, L.inv_v, Nv, dNv);
    v4d A = {0, 0, 0, 0}, Au = {0, 0, 0, 0}, Av = {0, 0, 0, 0};
    for (int a = 0; a <= pu; ++a) {
      const double* row = L.pw + (static_cast<long>(su - pu + a) * L.nv + (sv - pv)) * 4;
      v4d t4 = Nv[0] * load4(row), d4 = dNv[0] * load4(row);
      for (int b = 1; b <= pv; ++b) {
        const v4d c = load4(row + 4 * b);
        t4 += Nv[b] * c;
        d4 += dNv[b] * c;
      }
      A += Nu[a] * t4;
      Au += dNu[a] * t4;
      Av += Nu[a] * d4;
    }
    // Quotient rule on the homogeneous sums (w = A[3]).
    const double iw = 1.0 / A[3];
    double* o = out + 9 * k;
    for (int c = 0; c < 3; ++c) {
      const double S = A[c] * iw;
      o[c] = S;
      o[3 + c] = (Au[c] - Au[3] * S) * iw;
      o[6 + c] = (Av[c] - Av[3] * S) * iw;
    }
  }
}

// Points and first partials for degrees P, Q <= 3 from the power tables (as
// scatter_power_kernel; the point is its contraction, so it equals evaluate()'s): the
// meshers' hot evaluation, about half the instructions of the Cox-de Boor kernel above.
template <int P, int Q, bool Rational>
FAIRLINES_INLINE void d1_power_kernel(const Layout& L, const double* u, const double* v, long m, double* out) {
  const PowerSpans T(L);
  const auto ps = std::make_integer_sequence<int, P + 1>();
  const auto qs = std::make_integer_sequence<int, Q + 1>();
  for (long k = 0; k < m; ++k) {
    long su, sv;
    double du, dv;
    T.find(u[k], v[k], su, sv, du, dv);
    v4d Nu, dNu, Nv, dNv;
    detail::basis_power4_d1<P>(T.pow_u + su * 16, du, Nu, dNu);
    detail::basis_power4_d1<Q>(T.pow_v + sv * 16, dv, Nv, dNv);
    const double* row = T.pw + (su - P) * T.stride + (sv - Q) * 4;
    const v4d A = combine_rows(row, T.stride, Nu, Nv, ps, qs);
    const v4d Au = combine_rows(row, T.stride, dNu, Nv, ps, qs), Av = combine_rows(row, T.stride, Nu, dNv, ps, qs);
    double* o = out + 9 * k;
    const double iw = Rational ? 1.0 / A[3] : 1.0;
    for (int c = 0; c < 3; ++c) {  // the quotient rule on the homogeneous sums (w = A[3])
      const double S = Rational ? A[c] * iw : A[c];
      o[c] = S;
      o[3 + c] = Rational ? (Au[c] - Au[3] * S) * iw : Au[c];
      o[6 + c] = Rational ? (Av[c] - Av[3] * S) * iw : Av[c];
    }
  }
}

template <int P, int Q>
FAIRLINES_INLINE void d1_power(const Layout& L, const double* u, const double* v, long m, double* out) {
  if (L.rational) d1_power_kernel<P, Q, true>(L, u, v, m, out);
  else d1_power_kernel<P, Q, false>(L, u, v, m, out);
}

FAIRLINES_MULTIVERSION
void d1_dispatch(const Layout& L, int p, int q, const double* u, const double* v, long m, double* out) {
  if (p == 3 && q == 3) return d1_power<3, 3>(L, u, v, m, out);
  if (p == 2 && q == 2) return d1_power<2, 2>(L, u, v, m, out);
  if (p == 2 && q == 3) return d1_power<2, 3>(L, u, v, m, out);
  if (p == 3 && q == 2) return d1_power<3, 2>(L, u, v, m, out);
  d1_kernel<0, 0>(L, p, q, u, v, m, out);
}

// One grid line u = const: `row` is the control net contracted in u (nv homogeneous
// points); every v sample combines q + 1 of them.
template <int Q>
FAIRLINES_INLINE void grid_line(const double* row, int q, const int* spans, const double* Nv_all, long n_v,
                                bool rational, double* out) {
  const int qq = Q > 0 ? Q : q;
  for (long b = 0; b < n_v; ++b) {
    const double* Nv = Nv_all + b * (qq + 1);
    const double* base = row + static_cast<long>(spans[b] - qq) * 4;
    v4d acc = Nv[0] * load4(base);
    for (int j = 1; j <= qq; ++j) acc += Nv[j] * load4(base + 4 * j);
    const double iw = rational ? 1.0 / acc[3] : 1.0;
    out[3 * b] = acc[0] * iw;
    out[3 * b + 1] = acc[1] * iw;
    out[3 * b + 2] = acc[2] * iw;
  }
}

FAIRLINES_MULTIVERSION
void grid_dispatch(const Layout& L, int p, int q, const int* su_all, const double* Nu_all, long n_u, const int* sv_all,
                   const double* Nv_all, long n_v, double* row, double* out) {
  const long width = static_cast<long>(L.nv) * 4;
  for (long a = 0; a < n_u; ++a) {
    const double* Nu = Nu_all + a * (p + 1);
    const double* src = L.pw + static_cast<long>(su_all[a] - p) * width;
    // Contract the control net in u once per grid line.
    for (long j = 0; j < width; ++j) row[j] = Nu[0] * src[j];
    for (int i = 1; i <= p; ++i) {
      const double w = Nu[i];
      const double* s = src + i * width;
      for (long j = 0; j < width; ++j) row[j] += w * s[j];
    }
    double* dst = out + a * n_v * 3;
    switch (q) {
      case 3: grid_line<3>(row, q, sv_all, Nv_all, n_v, L.rational, dst); break;
      case 2: grid_line<2>(row, q, sv_all, Nv_all, n_v, L.rational, dst); break;
      default: grid_line<0>(row, q, sv_all, Nv_all, n_v, L.rational, dst);
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
  weights_ = detail::weights_or_ones(std::move(weights_), points_.rows());
  refresh();
}

void NurbsSurface::refresh() {
  rational_ = (weights_.array() != 1.0).any();
  inv_u_ = detail::make_basis_table(ku_, pu_);
  inv_v_ = detail::make_basis_table(kv_, pv_);
  pow_u_ = detail::make_power_table(ku_, pu_);
  pow_v_ = detail::make_power_table(kv_, pv_);
  span_u_ = std::make_shared<const SpanLocator>(ku_, pu_);
  span_v_ = std::make_shared<const SpanLocator>(kv_, pv_);
  detail::pack_homogeneous(points_, weights_, pw_);
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
  if (pu_ > kMaxFastDegree || pv_ > kMaxFastDegree) {
    // Rare high degrees: evaluate through the general derivative routine.
    for (long k = 0; k < m; ++k) {
      const Eigen::MatrixXd D = derivatives(u[k], v[k], 0);
      for (int c = 0; c < 3; ++c) out[3 * k + c] = D(0, c);
    }
    return;
  }
  scatter_dispatch(make_layout(ku_, kv_, inv_u_, inv_v_, pu_, pv_, nu_, nv_, pw_, rational_, span_u_, span_v_, pow_u_, pow_v_), pu_, pv_, u, v, m, out);
}

void NurbsSurface::evaluate_first_derivatives_into(const double* u, const double* v, long m, double* out) const {
  if (pu_ > kMaxFastDegree || pv_ > kMaxFastDegree) {
    for (long k = 0; k < m; ++k) {
      const Eigen::MatrixXd D = derivatives(u[k], v[k], 1);  // rows (0,0), (0,1) = S_v, (1,0) = S_u
      for (int c = 0; c < 3; ++c) {
        out[9 * k + c] = D(0, c);
        out[9 * k + 3 + c] = D(2, c);
        out[9 * k + 6 + c] = D(1, c);
      }
    }
    return;
  }
  d1_dispatch(make_layout(ku_, kv_, inv_u_, inv_v_, pu_, pv_, nu_, nv_, pw_, rational_, span_u_, span_v_, pow_u_, pow_v_), pu_, pv_, u, v,
              m, out);
}

Eigen::MatrixXd NurbsSurface::evaluate_grid(const Eigen::VectorXd& us, const Eigen::VectorXd& vs) const {
  detail::require_finite(us, "us");
  detail::require_finite(vs, "vs");
  detail::require_result_size(3.0 * static_cast<double>(us.size()) * static_cast<double>(vs.size()), "evaluate_grid");
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> out(us.size() * vs.size(), 3);
  evaluate_grid_into(us.data(), us.size(), vs.data(), vs.size(), out.data());
  return out;
}

void NurbsSurface::evaluate_grid_into(const double* us, long n_u, const double* vs, long n_v, double* out) const {
  if (pu_ > kMaxFastDegree || pv_ > kMaxFastDegree) {
    for (long a = 0; a < n_u; ++a)
      for (long b = 0; b < n_v; ++b) {
        const Eigen::MatrixXd D = derivatives(us[a], vs[b], 0);
        for (int c = 0; c < 3; ++c) out[(a * n_v + b) * 3 + c] = D(0, c);
      }
    return;
  }
  const Layout L = make_layout(ku_, kv_, inv_u_, inv_v_, pu_, pv_, nu_, nv_, pw_, rational_, span_u_, span_v_, pow_u_, pow_v_);
  // Basis values are computed once per grid line in each direction.
  auto tabulate = [](const double* ts, long n, int p, const double* U, const SpanLocator* loc, const double* inv, double lo,
                     double hi, std::vector<int>& spans, std::vector<double>& N) {
    spans.resize(n);
    N.resize(static_cast<size_t>(n) * (p + 1));
    for (long k = 0; k < n; ++k) {
      const double t = std::clamp(ts[k], lo, hi);
      spans[k] = loc->find(t);
      basis_table_eval<0>(p, spans[k], t, U, inv, &N[k * (p + 1)]);
    }
  };
  std::vector<int> su, sv;
  std::vector<double> Nu, Nv;
  tabulate(us, n_u, pu_, L.ku, L.span_u, L.inv_u, L.ua, L.ub, su, Nu);
  tabulate(vs, n_v, pv_, L.kv, L.span_v, L.inv_v, L.va, L.vb, sv, Nv);
  std::vector<double> row(static_cast<size_t>(nv_) * 4);
  grid_dispatch(L, pu_, pv_, su.data(), Nu.data(), n_u, sv.data(), Nv.data(), n_v, row.data(), out);
}

Eigen::MatrixXd NurbsSurface::derivatives(double u, double v, int order) const {
  detail::require_order(order);
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

namespace {

// A partial shorter than this fraction of the other one, or a normal S_u x S_v shorter
// than this fraction of |S_u| |S_v|, marks a degenerate point of the parametrisation
// (a pole, a collapsed edge or corner) where the curvature formulas divide 0 by 0.
constexpr double kDegenerate = 1e-8;
// Steps toward the interior, as fractions of the parameter range, at which the curvature
// is sampled to extrapolate its limit at a degenerate point.
constexpr double kLimitStep = 1e-3;
// Two extrapolations of the limit from successively halved steps must agree to this
// relative size, otherwise the curvature has no limit there (e.g. a cone apex).
constexpr double kLimitAgreement = 1e-6;

// Gaussian and mean curvature from the partials D of derivatives(u, v, 2) (row k*3 + l);
// false where the tangent plane is degenerate.
bool curvature_from(const Eigen::MatrixXd& D, double& K, double& H) {
  const Eigen::Vector3d Su = D.row(3).transpose(), Sv = D.row(1).transpose();
  const Eigen::Vector3d Suu = D.row(6).transpose(), Suv = D.row(4).transpose(), Svv = D.row(2).transpose();
  const Eigen::Vector3d n = Su.cross(Sv);
  const double a = Su.norm(), b = Sv.norm(), nn = n.norm();
  if (!(nn > kDegenerate * a * b) || a < kDegenerate * b || b < kDegenerate * a) return false;
  const Eigen::Vector3d nu = n / nn;
  const double E = Su.dot(Su), F = Su.dot(Sv), G = Sv.dot(Sv);
  const double L = Suu.dot(nu), M = Suv.dot(nu), N = Svv.dot(nu);
  const double det = E * G - F * F;
  K = (L * N - M * M) / det;
  H = (E * N - 2.0 * F * M + G * L) / (2.0 * det);
  return true;
}

// Limit of (K, H) at a degenerate point (u, v), approached from the interior along the
// parameter that does not collapse: curvature at steps h, h/2, h/4, h/8 and Richardson
// extrapolation to h = 0 (error O(h^3)) from two triples that must agree.
std::pair<double, double> curvature_limit(const NurbsSurface& s, double u, double v, const Eigen::MatrixXd& D) {
  const auto [ua, ub] = s.domain_u();
  const auto [va, vb] = s.domain_v();
  const double a = D.row(3).norm(), b = D.row(1).norm();
  // S_u collapsed: the edge is a line v = const, approach it along v; S_v likewise along u;
  // parallel partials (or both zero): along both.
  const bool u_collapsed = a < kDegenerate * b, v_collapsed = b < kDegenerate * a;
  const bool step_u = !u_collapsed, step_v = !v_collapsed;
  const double du = step_u ? kLimitStep * (ub - ua) * (u < 0.5 * (ua + ub) ? 1.0 : -1.0) : 0.0;
  const double dv = step_v ? kLimitStep * (vb - va) * (v < 0.5 * (va + vb) ? 1.0 : -1.0) : 0.0;
  double K[4], H[4];
  for (int i = 0; i < 4; ++i) {
    const double f = std::ldexp(1.0, -i);
    if (!curvature_from(s.derivatives(u + f * du, v + f * dv, 2), K[i], H[i]))
      fail("curvature is undefined at (u, v) = (", u, ", ", v, "): the surface is degenerate there and near it");
  }
  auto extrapolate = [](const double* f) { return (8.0 * f[2] - 6.0 * f[1] + f[0]) / 3.0; };
  const double K1 = extrapolate(K), K2 = extrapolate(K + 1), H1 = extrapolate(H), H2 = extrapolate(H + 1);
  const Eigen::MatrixXd& P = s.control_points();
  const double size = std::max((P.colwise().maxCoeff() - P.colwise().minCoeff()).norm(), 1e-300);
  const bool k_ok = std::abs(K1 - K2) <= kLimitAgreement * std::max({std::abs(K1), std::abs(K2), 1.0 / (size * size)});
  const bool h_ok = std::abs(H1 - H2) <= kLimitAgreement * std::max({std::abs(H1), std::abs(H2), 1.0 / size});
  if (!k_ok || !h_ok)
    fail("curvature is singular at (u, v) = (", u, ", ", v, "): the surface has no tangent plane there and the ",
         k_ok ? "mean" : "Gaussian", " curvature has no limit (e.g. a cone apex)");
  return {K2, H2};
}

}  // namespace

std::pair<Eigen::VectorXd, Eigen::VectorXd> NurbsSurface::curvature(const Eigen::VectorXd& u,
                                                                    const Eigen::VectorXd& v) const {
  if (u.size() != v.size()) fail("u has ", u.size(), " values and v has ", v.size(), "; expected equal lengths");
  Eigen::VectorXd K(u.size()), H(u.size());
  for (Eigen::Index k = 0; k < u.size(); ++k) {
    const Eigen::MatrixXd D = derivatives(u[k], v[k], 2);  // rows k*3 + l
    if (!curvature_from(D, K[k], H[k])) std::tie(K[k], H[k]) = curvature_limit(*this, u[k], v[k], D);
  }
  return {K, H};
}

namespace {

// One knot-span patch of the closest-point search: its parameter rectangle and the bounding box
// of the control points that shape it (the patch lies in their convex hull, weights being
// positive). Built once per surface for a batch of points.
struct PatchBox {
  Eigen::Vector3d lo, hi;
  double u0, u1, v0, v1;
};

// A patch with the squared distance from the point to its box: a lower bound for the patch.
struct SpanPatch {
  double bound2, u0, u1, v0, v1;
};

// Every non-empty span patch of s, u-span major.
std::vector<PatchBox> patch_boxes(const NurbsSurface& s) {
  const Eigen::VectorXd &U = s.knots_u(), &V = s.knots_v();
  const Eigen::MatrixXd& P = s.control_points();
  const int pu = s.degree_u(), pv = s.degree_v(), nv = s.nv();
  std::vector<PatchBox> out;
  for (int i = pu; i < s.nu(); ++i) {
    if (U[i + 1] <= U[i]) continue;
    for (int j = pv; j < nv; ++j) {
      if (V[j + 1] <= V[j]) continue;
      Eigen::Vector3d lo = P.row((i - pu) * nv + j - pv).transpose(), hi = lo;
      for (int a = i - pu; a <= i; ++a)
        for (int b = j - pv; b <= j; ++b) {
          lo = lo.cwiseMin(P.row(a * nv + b).transpose());
          hi = hi.cwiseMax(P.row(a * nv + b).transpose());
        }
      out.push_back({lo, hi, U[i], U[i + 1], V[j], V[j + 1]});
    }
  }
  return out;
}

// The patches with their bounds for p, nearest bound first.
std::vector<SpanPatch> span_patches(const std::vector<PatchBox>& boxes, const Eigen::Vector3d& p) {
  std::vector<SpanPatch> out;
  out.reserve(boxes.size());
  for (const PatchBox& b : boxes)
    out.push_back({(b.lo - p).cwiseMax(p - b.hi).cwiseMax(0.0).squaredNorm(), b.u0, b.u1, b.v0, b.v1});
  std::sort(out.begin(), out.end(), [](const SpanPatch& a, const SpanPatch& b) { return a.bound2 < b.bound2; });
  return out;
}

// The domain ends and the interior knots of multiplicity >= degree (creases: the surface is
// only C0 across them), increasing.
std::vector<double> crease_values(const Eigen::VectorXd& K, int deg, int n) {
  std::vector<double> out{K[deg]};
  for (int i = deg + 1; i < n;) {
    int j = i;
    while (j + 1 < n && K[j + 1] == K[i]) ++j;
    if (j - i + 1 >= deg && K[i] > K[deg] && K[i] < K[n]) out.push_back(K[i]);
    i = j + 1;
  }
  out.push_back(K[n]);
  return out;
}

// The crease intervals [c_k, c_k+1] holding t: two when t sits on an interior crease. An
// interior crease ends its box one double below the knot: evaluated on the knot itself the
// derivatives are the next span's (Newton stopped on the crease, 1.1e-5 m farther than the
// minimum beside it).
std::vector<std::pair<double, double>> crease_boxes(const std::vector<double>& c, double t) {
  std::vector<std::pair<double, double>> out;
  for (size_t k = 0; k + 1 < c.size(); ++k)
    if (t >= c[k] && t <= c[k + 1])
      out.emplace_back(c[k], k + 2 < c.size() ? std::nextafter(c[k + 1], c[k]) : c[k + 1]);
  return out;
}

// Two sampled squared distances within this of each other, relative to the net's size times
// the distance, are the same to round-off: on a collapsed row (a pole) every sample is the one
// point, and which of them counted as a minimum and which were started from was round-off's choice.
constexpr double kSampleTie = 1e-12;

// Indices (into the row-major sample grid) of local minima of the sampled squared distance,
// nearest first: the `count` nearest values, each with every minimum tied to it by round-off
// (a pole's samples: which of them leads to the basin only Newton from each tells).
std::vector<Eigen::Index> sampled_minima(const Eigen::VectorXd& d2, Eigen::Index nus, Eigen::Index nvs, size_t count,
                                         double scale) {
  const auto tie = [&](double x) { return kSampleTie * scale * std::sqrt(x); };
  std::vector<std::pair<double, Eigen::Index>> cand;
  for (Eigen::Index a = 0; a < nus; ++a)
    for (Eigen::Index b = 0; b < nvs; ++b) {
      const double here = d2[a * nvs + b];
      bool minimum = true;
      for (Eigen::Index da = -1; da <= 1 && minimum; ++da)
        for (Eigen::Index db = -1; db <= 1 && minimum; ++db) {
          const Eigen::Index aa = a + da, bb = b + db;
          if ((da || db) && aa >= 0 && aa < nus && bb >= 0 && bb < nvs && d2[aa * nvs + bb] < here - tie(here))
            minimum = false;
        }
      if (minimum) cand.emplace_back(here, a * nvs + b);
    }
  std::sort(cand.begin(), cand.end());
  std::vector<Eigen::Index> out;
  for (size_t i = 0, runs = 0; i < cand.size() && runs < count; ++runs) {
    const double first = cand[i].first;
    for (; i < cand.size() && cand[i].first - first <= tie(first); ++i) out.push_back(cand[i].second);
  }
  return out;
}

// Projected Newton on |S - p|^2: iterations at most (a saddle or an edge approach takes a few
// more than the usual handful; the search stops earlier when no step brings the point nearer).
constexpr int kClosestNewtonSteps = 100;
// Halvings of a step that does not bring the point nearer before the search stops there.
constexpr int kClosestBacktracks = 40;
// Smallest Hessian eigenvalue magnitude used for a negative (or round-off) one, relative to the
// largest: across a saddle or a flat direction the step stays finite and scaled to that
// direction (backtracking shortens it).
constexpr double kClosestEigenFloor = 1e-3;
// A positive eigenvalue above this fraction of the largest is curvature, and its Newton step is
// taken in full: near a pole (a collapsed row) the distance's valley along the row is 1e-6 of
// the other direction's curvature, and the floor above cut its step 400 times (100 steps crawled
// to 4.8e-4 m from a point 1.8e-7 m off the surface). Below it, round-off decides its sign.
constexpr double kClosestEigenRoundoff = 1e-12;
// Converged when a step moves the point by less than this, relative to the net's size.
constexpr double kClosestStepTolerance = 1e-15;
// A full step moving the point by less than this, relative to the net's size, is taken without
// the nearer test: the distance it gains (that move squared) is below the distance's round-off,
// and the test stopped Newton 1e-8 short of a sphere's foot, a step before converging.
constexpr double kClosestFinalStep = 1e-7;
// Doublings at most of a step's floored part while it brings the point nearer (2^30: from the
// floor's scale to any length a box allows).
constexpr int kClosestExpansions = 30;

// The curvature a Newton step along one direction divides by (`largest`: the Hessian's scale).
double step_curvature(double lambda, double largest) {
  if (lambda > kClosestEigenRoundoff * largest) return lambda;
  return std::max(std::abs(lambda), std::max(kClosestEigenFloor * largest, 1e-300));
}

// A box of parameters free of creases: [first, second] in u or in v.
using Box = std::pair<double, double>;

// One Newton step of the search: the step in (u, v) and its part along directions whose
// curvature was floored (they have no Newton length: expand_floored may lengthen it).
struct ClosestStep {
  Eigen::Vector2d delta = Eigen::Vector2d::Zero(), floored = Eigen::Vector2d::Zero();
};

// The step from the Hessian H and gradient g of |S - p|^2. Where H is indefinite its
// eigenvalues are taken by magnitude, so the step still descends at Newton's scale in each
// direction (a gradient step scaled by the largest curvature crawled along a saddle's flat
// direction). With one parameter held (`held`: 0 for u, 1 for v) the other is solved alone,
// scaled by its own curvature, not the held direction's (a steep held side floored it at several
// times its Newton step and the search crawled along the edge); `tangent` is S_u or S_v there.
ClosestStep newton_step(const Eigen::Matrix2d& H, const Eigen::Vector2d& g, int held, const Eigen::Vector3d& tangent) {
  ClosestStep out;
  if (held >= 0) {
    const int k = 1 - held;
    const double c = step_curvature(H(k, k), std::max(std::abs(H(k, k)), tangent.squaredNorm()));
    out.delta[k] = -g[k] / c;
    if (c != H(k, k)) out.floored = out.delta;
    return out;
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig;
  eig.computeDirect(H);
  const Eigen::Vector2d lam = eig.eigenvalues();
  const double largest = lam.cwiseAbs().maxCoeff();
  for (int i = 0; i < 2; ++i) {
    const double c = step_curvature(lam[i], largest);
    const Eigen::Vector2d part = -eig.eigenvectors().col(i) * (eig.eigenvectors().col(i).dot(g) / c);
    out.delta += part;
    if (c != lam[i]) out.floored += part;
  }
  return out;
}

// Where a search trial lands: parameters clamped to the box and the squared distance there.
struct ClosestTrial {
  double u, v, d2;
};

ClosestTrial trial_at(const NurbsSurface& s, const Eigen::Vector3d& p, double u, double v, const Box& bu, const Box& bv) {
  const double ut = std::clamp(u, bu.first, bu.second), vt = std::clamp(v, bv.first, bv.second);
  return {ut, vt, (s.evaluate(ut, vt) - p).squaredNorm()};
}

// Newton on the stationarity of |S - p|^2 from (u, v), kept in a box free of creases. A
// parameter on an edge of the box whose gradient points out of it is held there.
std::pair<double, double> newton_closest(const NurbsSurface& s, const Eigen::Vector3d& p, double u, double v,
                                         const Box& bu, const Box& bv, double scale) {
  for (int it = 0; it < kClosestNewtonSteps; ++it) {
    const Eigen::MatrixXd D = s.derivatives(u, v, 2);
    const Eigen::Vector3d S = D.row(0).transpose(), Su = D.row(3).transpose(), Sv = D.row(1).transpose();
    const Eigen::Vector3d Suu = D.row(6).transpose(), Suv = D.row(4).transpose(), Svv = D.row(2).transpose();
    const Eigen::Vector3d r = S - p;
    Eigen::Matrix2d H;
    H << Su.dot(Su) + r.dot(Suu), Su.dot(Sv) + r.dot(Suv), Su.dot(Sv) + r.dot(Suv), Sv.dot(Sv) + r.dot(Svv);
    const Eigen::Vector2d g(Su.dot(r), Sv.dot(r));
    const bool hold_u = (u <= bu.first && g[0] > 0.0) || (u >= bu.second && g[0] < 0.0);
    const bool hold_v = (v <= bv.first && g[1] > 0.0) || (v >= bv.second && g[1] < 0.0);
    if (hold_u && hold_v) break;  // a corner of the box, the gradient pointing out on both sides
    ClosestStep step = newton_step(H, g, hold_u ? 0 : hold_v ? 1 : -1, hold_u ? Sv : Su);
    if (!step.delta.allFinite()) break;
    // Backtracking: a step that does not bring the point nearer is halved (a strongly curved
    // surface sends the full Newton step far past the minimum); none that does: a minimum.
    // A step within round-off of the minimum is taken as it is (kClosestFinalStep).
    ClosestTrial at{u, v, r.squaredNorm()};
    bool nearer = false;
    int half = 0;
    for (; half < kClosestBacktracks && !nearer; ++half, step.delta *= 0.5) {
      at = trial_at(s, p, u + step.delta[0], v + step.delta[1], bu, bv);
      nearer = at.d2 < r.squaredNorm() || (half == 0 && (Su * (at.u - u) + Sv * (at.v - v)).norm() < kClosestFinalStep * scale);
    }
    if (!nearer) break;
    // A full step with a floored part that brought the point nearer: that part is doubled while
    // it still does (along a saddle's gently curving side the floored step crawled, 100 steps
    // of 2.4e-4 in v next to a pole).
    if (half == 1 && step.floored.squaredNorm() > 0.0) {
      Eigen::Vector2d grown = step.delta * 2.0;  // the full step (the loop halved it once more)
      for (int k = 0; k < kClosestExpansions; ++k) {
        grown += step.floored * std::ldexp(1.0, k);
        const ClosestTrial t = trial_at(s, p, u + grown[0], v + grown[1], bu, bv);
        if (!(t.d2 < at.d2)) break;
        at = t;
      }
    }
    const double moved = (Su * (at.u - u) + Sv * (at.v - v)).norm();
    u = at.u;
    v = at.v;
    if (moved < kClosestStepTolerance * scale) break;
  }
  return {u, v};
}

// Sample intervals per direction of a span patch at least (and twice the degree + 1): fewer
// let a narrow valley of the distance between two samples go unseen.
constexpr int kPatchIntervals = 12;
// Newton starts per span patch: its sampled local minima, nearest first (those tied to one by
// round-off not counted).
constexpr size_t kPatchStarts = 3;
// Fraction of its box by which a Newton start is moved off the box's edges.
constexpr double kStartInset = 1e-6;
// A patch that could bring the point nearer by less than this, relative to the net's size, is
// not searched: round-off. A point on the surface lies in the boxes of several patches, all
// with a bound of 0; once the best is 0 to round-off, the others are not searched.
constexpr double kBoundSlack = 1e-12;

// The global closest-point search of one surface: what depends on the surface alone (span-patch
// boxes, creases, scale) is built once and serves every point of a batch.
class ClosestSearch {
 public:
  explicit ClosestSearch(const NurbsSurface& s)
      : s_(s),
        boxes_(patch_boxes(s)),
        cu_(crease_values(s.knots_u(), s.degree_u(), s.nu())),
        cv_(crease_values(s.knots_v(), s.degree_v(), s.nv())),
        scale_(std::max(1.0, (s.control_points().colwise().maxCoeff() - s.control_points().colwise().minCoeff()).norm())) {}

  // (u, v) of the point of the surface nearest p.
  std::pair<double, double> find(const Eigen::Vector3d& p) const;

 private:
  void search_patch(const SpanPatch& patch, const Eigen::Vector3d& p) const;
  void search_lines(const std::vector<SpanPatch>& patches, std::vector<SpanPatch>::const_iterator live,
                    const Eigen::Vector3d& p) const;
  void keep(double u, double v, const Eigen::Vector3d& p) const {
    const double d = (s_.evaluate(u, v) - p).squaredNorm();
    if (d < best_d_) best_d_ = d, best_u_ = u, best_v_ = v;
  }
  bool searched(const SpanPatch& q) const { return std::sqrt(q.bound2) < std::sqrt(best_d_) - kBoundSlack * scale_; }

  const NurbsSurface& s_;
  const std::vector<PatchBox> boxes_;
  const std::vector<double> cu_, cv_;
  const double scale_;
  mutable double best_u_ = 0.0, best_v_ = 0.0, best_d_ = 0.0;
};

std::pair<double, double> ClosestSearch::find(const Eigen::Vector3d& p) const {
  best_u_ = s_.knots_u()[s_.degree_u()];
  best_v_ = s_.knots_v()[s_.degree_v()];
  best_d_ = (s_.evaluate(best_u_, best_v_) - p).squaredNorm();
  // Span patches nearest bound first; a patch whose bound is no nearer than the best point so
  // far cannot hold a nearer one, nor can any after it (P&T 6.1's start search, pruned by the
  // convex hull property so a hull's far patches cost nothing).
  const std::vector<SpanPatch> patches = span_patches(boxes_, p);
  for (const SpanPatch& patch : patches) {
    if (!searched(patch)) break;
    search_patch(patch, p);
  }
  search_lines(patches, std::partition_point(patches.begin(), patches.end(), [&](const SpanPatch& q) { return searched(q); }), p);
  return {best_u_, best_v_};
}

// Newton from the patch's sampled local minima (one per basin), inside the crease-free box of
// each; a start on a crease is tried on both sides of it.
void ClosestSearch::search_patch(const SpanPatch& patch, const Eigen::Vector3d& p) const {
  const int ku = std::max(kPatchIntervals, 2 * (s_.degree_u() + 1)), kv = std::max(kPatchIntervals, 2 * (s_.degree_v() + 1));
  const Eigen::VectorXd us = Eigen::VectorXd::LinSpaced(ku + 1, patch.u0, patch.u1);
  const Eigen::VectorXd vs = Eigen::VectorXd::LinSpaced(kv + 1, patch.v0, patch.v1);
  const Eigen::VectorXd d2 = (s_.evaluate_grid(us, vs).rowwise() - p.transpose()).rowwise().squaredNorm();
  for (const Eigen::Index k : sampled_minima(d2, us.size(), vs.size(), kPatchStarts, scale_)) {
    const double u0 = us[k / vs.size()], v0 = vs[k % vs.size()];
    if (d2[k] < best_d_) best_d_ = d2[k], best_u_ = u0, best_v_ = v0;
    for (const auto& bu : crease_boxes(cu_, u0))
      for (const auto& bv : crease_boxes(cv_, v0)) {
        // Started just inside its box, so the derivatives are those of the box's side.
        const auto inside = [](double t, const std::pair<double, double>& b) {
          const double margin = kStartInset * (b.second - b.first);
          return std::clamp(t, b.first + margin, b.second - margin);
        };
        const auto [u, v] = newton_closest(s_, p, inside(u0, bu), inside(v0, bv), bu, bv, scale_);
        keep(u, v, p);
      }
  }
}

// Boundary and crease lines: a minimum on them is a 1-D problem along an iso-curve, solved
// where a patch along the line (one before `live`) could still hold a nearer point.
void ClosestSearch::search_lines(const std::vector<SpanPatch>& patches, std::vector<SpanPatch>::const_iterator live,
                                 const Eigen::Vector3d& p) const {
  for (const Direction dir : {Direction::U, Direction::V})
    for (const double t : dir == Direction::U ? cu_ : cv_) {
      const bool open = std::any_of(patches.begin(), live, [&](const SpanPatch& q) {
        return dir == Direction::U ? (q.u0 == t || q.u1 == t) : (q.v0 == t || q.v1 == t);
      });
      if (!open) continue;
      const auto [w, q] = s_.iso_curve(dir, t).closest_point(p);
      if (dir == Direction::U) keep(t, w, p);
      else keep(w, t, p);
    }
}

}  // namespace

std::tuple<double, double, Eigen::Vector3d> NurbsSurface::closest_point(const Eigen::Vector3d& p) const {
  detail::require_finite(p, "point");
  const auto [u, v] = ClosestSearch(*this).find(p);
  return {u, v, evaluate(u, v)};
}

std::tuple<Eigen::VectorXd, Eigen::VectorXd, Eigen::MatrixXd> NurbsSurface::closest_points(const Eigen::MatrixXd& points) const {
  if (points.cols() != 3) fail("points have ", points.cols(), " columns; expected (m, 3)");
  detail::require_finite(points, "points");
  const ClosestSearch search(*this);
  Eigen::VectorXd u(points.rows()), v(points.rows());
  Eigen::MatrixXd feet(points.rows(), 3);
  for (Eigen::Index k = 0; k < points.rows(); ++k) {
    std::tie(u[k], v[k]) = search.find(points.row(k).transpose());
    feet.row(k) = evaluate(u[k], v[k]).transpose();
  }
  return {u, v, feet};
}

std::tuple<Eigen::VectorXd, Eigen::VectorXd, Eigen::MatrixXd> NurbsSurface::closest_points(
    const Eigen::MatrixXd& points, const Eigen::VectorXd& u0, const Eigen::VectorXd& v0) const {
  if (points.cols() != 3) fail("points have ", points.cols(), " columns; expected (m, 3)");
  if (u0.size() != points.rows() || v0.size() != points.rows())
    fail("u0 / v0 have ", u0.size(), " / ", v0.size(), " values; expected one per point (", points.rows(), ")");
  detail::require_finite(points, "points");
  detail::require_finite(u0, "u0");
  detail::require_finite(v0, "v0");
  const std::pair<double, double> bu{ku_[pu_], ku_[nu_]}, bv{kv_[pv_], kv_[nv_]};
  const double scale = std::max(1.0, (points_.colwise().maxCoeff() - points_.colwise().minCoeff()).norm());
  Eigen::VectorXd u(points.rows()), v(points.rows());
  Eigen::MatrixXd feet(points.rows(), 3);
  for (Eigen::Index k = 0; k < points.rows(); ++k) {
    const Eigen::Vector3d p = points.row(k).transpose();
    std::tie(u[k], v[k]) = newton_closest(*this, p, std::clamp(u0[k], bu.first, bu.second),
                                          std::clamp(v0[k], bv.first, bv.second), bu, bv, scale);
    feet.row(k) = evaluate(u[k], v[k]).transpose();
  }
  return {u, v, feet};
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
  if (X.size() == 0) return map_lines(*this, dir, [&](const NurbsCurve& c) { return c.refine_knots(X); });
  detail::require_finite(X, "new_knots");
  const bool along_u = (dir == Direction::U);
  const auto [a0, b0] = along_u ? domain_u() : domain_v();
  if (X.minCoeff() < a0 || X.maxCoeff() > b0)
    fail("new_knots span [", X.minCoeff(), ", ", X.maxCoeff(), "] outside the domain [", a0, ", ", b0, "]");
  // Every line at once: row k holds point k of each line as the line curve of map_lines has
  // it (a non-rational 4-D curve of the homogeneous net, with a weight of its own, 1), so the
  // result is that of refining the lines one by one, bit for bit, without a curve per line.
  constexpr int W = 5;
  const int lines = along_u ? nv_ : nu_, len = along_u ? nu_ : nv_;
  detail::RowMatrix A(len, static_cast<Eigen::Index>(lines) * W);
  for (int k = 0; k < len; ++k)
    for (int l = 0; l < lines; ++l) {
      const size_t idx = along_u ? static_cast<size_t>(k) * nv_ + l : static_cast<size_t>(l) * nv_ + k;
      for (int c = 0; c < 4; ++c) A(k, l * W + c) = pw_[idx * 4 + c];
      A(k, l * W + 4) = 1.0;
    }
  auto [Q, knots] = detail::refine_rows(along_u ? pu_ : pv_, along_u ? ku_ : kv_, X, A);
  const int new_len = static_cast<int>(Q.rows());
  const int nu2 = along_u ? new_len : nu_, nv2 = along_u ? nv_ : new_len;
  Eigen::MatrixXd pw2(static_cast<Eigen::Index>(nu2) * nv2, 4);
  for (int k = 0; k < new_len; ++k)
    for (int l = 0; l < lines; ++l) {
      const Eigen::Index row = along_u ? static_cast<Eigen::Index>(k) * nv2 + l : static_cast<Eigen::Index>(l) * nv2 + k;
      for (int c = 0; c < 4; ++c) pw2(row, c) = Q(k, l * W + c) / Q(k, l * W + 4);
    }
  if (along_u) return from_homogeneous(pu_, pv_, std::move(knots), kv_, nu2, nv2, pw2);
  return from_homogeneous(pu_, pv_, ku_, std::move(knots), nu2, nv2, pw2);
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
