#include "fairlines/basis.hpp"

#include <algorithm>
#include <array>
#include <vector>

namespace fairlines {

int find_span(int degree, const double* U, int n_knots, double t) {
  const int n = n_knots - degree - 2;  // index of the last basis function
  if (t >= U[n + 1]) {
    // End of the domain: the last span with a non-zero length.
    int i = n;
    while (i > degree && U[i] >= U[n + 1]) --i;
    return i;
  }
  if (t <= U[degree]) {
    int i = degree;
    while (i < n && U[i + 1] <= U[degree]) ++i;
    return i;
  }
  // upper_bound gives the first knot > t; the span starts one before it.
  const double* it = std::upper_bound(U + degree, U + n + 2, t);
  return static_cast<int>(it - U) - 1;
}

int find_span(int degree, const Eigen::VectorXd& knots, double t) {
  return find_span(degree, knots.data(), static_cast<int>(knots.size()), t);
}

void basis_functions(int span, double t, int p, const double* U, double* N) {
  double left[kMaxFastDegree + 2], right[kMaxFastDegree + 2];
  std::vector<double> left_h, right_h;
  double* L = left;
  double* R = right;
  if (p > kMaxFastDegree) {
    left_h.resize(p + 1);
    right_h.resize(p + 1);
    L = left_h.data();
    R = right_h.data();
  }
  N[0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    L[j] = t - U[span + 1 - j];
    R[j] = U[span + j] - t;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      const double temp = N[r] / (R[r + 1] + L[j - r]);
      N[r] = saved + R[r + 1] * temp;
      saved = L[j - r] * temp;
    }
    N[j] = saved;
  }
}

void basis_functions(int span, double t, int degree, const Eigen::VectorXd& knots, double* N) {
  basis_functions(span, t, degree, knots.data(), N);
}

namespace {

/// Piegl & Tiller A2.3 with its scratch (ndu: (p+1)^2, a: 2 x (p+1), left and right: p+1)
/// passed in, so that low degrees keep it on the stack.
template <typename Scratch>
void basis_derivatives_with(int span, double t, int p, int n, const double* U, Eigen::Ref<Eigen::MatrixXd> ders,
                            Scratch& ndu, Scratch& a, double* left, double* right) {
  ndu(0, 0) = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = t - U[span + 1 - j];
    right[j] = U[span + j] - t;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      ndu(j, r) = right[r + 1] + left[j - r];  // lower triangle: knot differences
      const double temp = ndu(r, j - 1) / ndu(j, r);
      ndu(r, j) = saved + right[r + 1] * temp;  // upper triangle: basis functions
      saved = left[j - r] * temp;
    }
    ndu(j, j) = saved;
  }
  ders.setZero();
  for (int j = 0; j <= p; ++j) ders(0, j) = ndu(j, p);
  const int nmax = std::min(n, p);
  for (int r = 0; r <= p; ++r) {
    int s1 = 0, s2 = 1;
    a.setZero();
    a(0, 0) = 1.0;
    for (int k = 1; k <= nmax; ++k) {
      double d = 0.0;
      const int rk = r - k, pk = p - k;
      if (r >= k) {
        a(s2, 0) = a(s1, 0) / ndu(pk + 1, rk);
        d = a(s2, 0) * ndu(rk, pk);
      }
      const int j1 = (rk >= -1) ? 1 : -rk;
      const int j2 = (r - 1 <= pk) ? k - 1 : p - r;
      for (int j = j1; j <= j2; ++j) {
        a(s2, j) = (a(s1, j) - a(s1, j - 1)) / ndu(pk + 1, rk + j);
        d += a(s2, j) * ndu(rk + j, pk);
      }
      if (r <= pk) {
        a(s2, k) = -a(s1, k - 1) / ndu(pk + 1, r);
        d += a(s2, k) * ndu(r, pk);
      }
      ders(k, r) = d;
      std::swap(s1, s2);
    }
  }
  double factor = p;
  for (int k = 1; k <= nmax; ++k) {
    for (int j = 0; j <= p; ++j) ders(k, j) *= factor;
    factor *= (p - k);
  }
}

}  // namespace

void basis_derivatives(int span, double t, int p, int n, const Eigen::VectorXd& knots,
                       Eigen::Ref<Eigen::MatrixXd> ders) {
  constexpr int kStackDegree = 7;  // degrees up to this one work without heap allocation
  if (p <= kStackDegree) {
    using Small = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kStackDegree + 1, kStackDegree + 1>;
    Small ndu(p + 1, p + 1), a(2, p + 1);
    std::array<double, kStackDegree + 1> left{}, right{};
    basis_derivatives_with(span, t, p, n, knots.data(), ders, ndu, a, left.data(), right.data());
    return;
  }
  Eigen::MatrixXd ndu(p + 1, p + 1), a(2, p + 1);
  std::vector<double> left(p + 1), right(p + 1);
  basis_derivatives_with(span, t, p, n, knots.data(), ders, ndu, a, left.data(), right.data());
}

Eigen::RowVectorXd basis_row(const Eigen::VectorXd& knots, int degree, double t, int order) {
  const int n = static_cast<int>(knots.size()) - degree - 1;
  Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(n);
  const int span = find_span(degree, knots, t);
  Eigen::MatrixXd ders(order + 1, degree + 1);
  basis_derivatives(span, t, degree, order, knots, ders);
  for (int j = 0; j <= degree; ++j) row[span - degree + j] = ders(order, j);
  return row;
}

}  // namespace fairlines
