// Division-free B-spline basis evaluation for hot loops.
//
// The denominators of the Cox-de Boor triangle, U[s+r+1] - U[s+1-j+r], depend only on
// the knot span s, not on the parameter, so they are inverted once per curve/surface
// and the evaluation multiplies. Spans are found in O(1) through a bucket table.
#pragma once

#include <algorithm>
#include <limits>
#include <vector>

#include <Eigen/Core>

#include "fairlines/basis.hpp"

#define FAIRLINES_INLINE inline __attribute__((always_inline))

namespace fairlines::detail {

/// Four doubles as one SIMD value (GCC/Clang vector extension): one homogeneous point
/// (w x, w y, w z, w). The unaligned variant loads from any double array.
typedef double v4d __attribute__((vector_size(32)));
typedef double v4du __attribute__((vector_size(32), aligned(8)));

/// Finds knot spans in O(1): the domain is cut into equal buckets, each remembering the
/// span at its left edge; a lookup then steps forward over at most a few knots.
struct SpanLocator {
  double a = 0, scale = 0;   // domain start, buckets per unit parameter
  int buckets = 0, last_span = 0;
  std::vector<int> table;    // span at each bucket's left edge; entry `buckets` is last_span
  // The knots with +inf after last_span: stepping needs one test (t >= knots[s + 1]), and
  // knots[s] is still U[s] for the local parameter of any span found.
  std::vector<double> knots;

  SpanLocator() = default;
  SpanLocator(const Eigen::VectorXd& U, int p) {
    const int n = static_cast<int>(U.size()) - p - 1;
    a = U[p];
    const double b = U[n];
    last_span = n - 1;
    while (last_span > p && !(U[last_span + 1] > U[last_span])) --last_span;
    buckets = std::max(16, 4 * (n - p));
    scale = buckets / (b - a);
    table.resize(buckets + 1);
    int s = p;
    for (int k = 0; k <= buckets; ++k) {
      const double x = k == buckets ? b : a + k / scale;
      while (s < last_span && U[s + 1] <= x) ++s;
      table[k] = s;
    }
    knots.assign(U.size(), std::numeric_limits<double>::infinity());
    for (int i = 0; i <= last_span; ++i) knots[i] = U[i];
  }
  /// Span of t, which must already be clamped to the domain (NaN gives some valid span).
  FAIRLINES_INLINE int find(double t) const {
    return static_cast<int>(find(t, a, scale, buckets, table.data(), knots.data()));
  }
  /// The same from copies of the fields, which a hot loop can keep in registers.
  static FAIRLINES_INLINE long find(double t, double a, double scale, unsigned buckets, const int* table,
                                    const double* knots) {
    // Unsigned, a NaN's INT_MIN lands on the last bucket instead of outside the table.
    unsigned k = static_cast<unsigned>(static_cast<int>((t - a) * scale));
    k = k < buckets ? k : buckets;
    long s = table[k];
    while (t >= knots[s + 1]) ++s;
    return s;
  }
};

/// Entries per span of the reciprocal table for degree p: p (p + 1) / 2.
inline int basis_table_stride(int p) { return p * (p + 1) / 2; }

/// Reciprocal table for every span index s in [0, n_knots): entry (s, j, r) at
/// s * stride + j (j - 1) / 2 + r holds 1 / (U[s+r+1] - U[s+1-j+r]) for non-empty spans
/// inside the domain, 0 elsewhere (never read there).
inline std::vector<double> make_basis_table(const Eigen::VectorXd& U, int p) {
  const int n = static_cast<int>(U.size()) - p - 1;
  const int stride = basis_table_stride(p);
  std::vector<double> inv(static_cast<size_t>(U.size()) * stride, 0.0);
  for (int s = p; s < n; ++s) {
    if (!(U[s + 1] > U[s])) continue;
    for (int j = 1; j <= p; ++j)
      for (int r = 0; r < j; ++r) inv[s * stride + j * (j - 1) / 2 + r] = 1.0 / (U[s + r + 1] - U[s + 1 - j + r]);
  }
  return inv;
}

/// Power-basis coefficients of the non-zero basis functions on every span, in the local
/// parameter s = t - U[span], for degree p <= 3 (empty above): entry (span, k, j) at
/// span * 16 + k * 4 + j is N_{span-p+j}^(k)(U[span]) / k!, so N_{span-p+j}(t) =
/// sum_k entry(span, k, j) s^k exactly (a B-spline is one polynomial per span). Rows are
/// padded to 4 lanes with zeros so the p + 1 basis values are one SIMD Horner evaluation.
/// Zero for empty spans (never read).
inline constexpr int kPowerMaxDegree = 3;
inline std::vector<double> make_power_table(const Eigen::VectorXd& U, int p) {
  if (p > kPowerMaxDegree) return {};
  const int n = static_cast<int>(U.size()) - p - 1;
  std::vector<double> c(static_cast<size_t>(U.size()) * 16, 0.0);
  Eigen::MatrixXd ders(p + 1, p + 1);
  for (int s = p; s < n; ++s) {
    if (!(U[s + 1] > U[s])) continue;
    basis_derivatives(s, U[s], p, p, U, ders);
    double fact = 1.0;
    for (int k = 0; k <= p; ++k) {
      if (k > 0) fact *= k;
      for (int j = 0; j <= p; ++j) c[static_cast<size_t>(s) * 16 + k * 4 + j] = ders(k, j) / fact;
    }
  }
  return c;
}

/// The P + 1 non-zero basis functions (lanes above P are zero) at local parameter s from
/// the span's block of the power table: Horner over s, 4 coefficient lanes per degree.
/// Written per lane: the AVX2 clone vectorises it into 4-lane FMAs, while the SSE2 baseline
/// stays scalar instead of assembling 256-bit broadcasts through the stack.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"  // always inlined: no vector crosses an ABI boundary
template <int P>
FAIRLINES_INLINE v4d basis_power4(const double* block, double s) {
  double N[4] = {0, 0, 0, 0};
  for (int j = 0; j <= P; ++j) N[j] = block[4 * P + j];
  for (int k = P - 1; k >= 0; --k)
    for (int j = 0; j <= P; ++j) N[j] = N[j] * s + block[4 * k + j];
  return v4d{N[0], N[1], N[2], N[3]};
}

/// basis_power4 and the first derivatives dN (d/ds of the same polynomials, one Horner
/// pass: the value's recurrence and its derivative's run side by side).
template <int P>
FAIRLINES_INLINE void basis_power4_d1(const double* block, double s, v4d& N4, v4d& dN4) {
  double N[4] = {0, 0, 0, 0}, dN[4] = {0, 0, 0, 0};
  for (int j = 0; j <= P; ++j) N[j] = block[4 * P + j];
  for (int k = P - 1; k >= 0; --k)
    for (int j = 0; j <= P; ++j) {
      dN[j] = dN[j] * s + N[j];
      N[j] = N[j] * s + block[4 * k + j];
    }
  N4 = v4d{N[0], N[1], N[2], N[3]};
  dN4 = v4d{dN[0], dN[1], dN[2], dN[3]};
}
#pragma GCC diagnostic pop

/// The deg + 1 non-zero basis functions N at t in `span`, using the reciprocal table, and,
/// when dN is given, their first derivatives: the triangle's degree deg - 1 values give
/// N'_{i,p} = p (N_{i,p-1} / (U_{i+p} - U_i) - N_{i+1,p-1} / (U_{i+p+1} - U_{i+1})), whose
/// reciprocals are the table's j = deg row. P > 0 fixes the degree at compile time (loops
/// unroll); P == 0 takes it from p. Inlined, so dN == nullptr costs nothing.
template <int P>
FAIRLINES_INLINE void basis_table_eval(int p, int span, double t, const double* U, const double* inv, double* N,
                                       double* dN = nullptr) {
  const int deg = P > 0 ? P : p;
  double left[kMaxFastDegree + 1], right[kMaxFastDegree + 1];
  const double* iv = inv + span * (deg * (deg + 1) / 2);
  N[0] = 1.0;
  for (int j = 1; j <= deg; ++j) {
    left[j] = t - U[span + 1 - j];
    right[j] = U[span + j] - t;
    const double* ivj = iv + j * (j - 1) / 2;
    if (dN != nullptr && j == deg) {
      // N holds the degree deg - 1 values here.
      dN[0] = -deg * N[0] * ivj[0];
      for (int r = 1; r < deg; ++r) dN[r] = deg * (N[r - 1] * ivj[r - 1] - N[r] * ivj[r]);
      dN[deg] = deg * N[deg - 1] * ivj[deg - 1];
    }
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      const double temp = N[r] * ivj[r];
      N[r] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    N[j] = saved;
  }
}

}  // namespace fairlines::detail
