// Internal input checks shared by the NURBS sources: each throws InvalidInput with a
// message naming the argument and what was expected.
#pragma once

#include <cmath>
#include <initializer_list>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>

#include <Eigen/Core>

#include "fairlines/errors.hpp"
#include "fairlines/limits.hpp"

namespace fairlines::detail {

template <typename... Parts>
[[noreturn]] inline void fail(const Parts&... parts) {
  std::ostringstream os;
  (os << ... << parts);
  throw InvalidInput(os.str());
}

/// v with `digits` significant digits, for messages.
inline std::string format_number(double v, int digits) {
  std::ostringstream os;
  os.precision(digits);
  os << v;
  return os.str();
}

template <typename Derived>
inline void require_finite(const Eigen::DenseBase<Derived>& a, std::string_view what) {
  for (Eigen::Index i = 0; i < a.rows(); ++i)
    for (Eigen::Index j = 0; j < a.cols(); ++j)
      if (!std::isfinite(a(i, j))) {
        if (a.cols() == 1)
          fail(what, "[", i, "] is ", a(i, j), "; expected a finite number");
        fail(what, "[", i, ", ", j, "] is ", a(i, j), "; expected a finite number");
      }
}

// The name as a view: the checks sit in hot evaluations (NurbsSurface::evaluate), where a
// std::string built from a literal per call cost more than the check.
inline void require_finite(double x, std::string_view what) {
  if (!std::isfinite(x)) fail(what, " is ", x, "; expected a finite number");
}

inline void require_degree(int degree, const std::string& what = "degree") {
  if (degree < 1 || degree > limits::kMaxDegree)
    fail(what, " is ", degree, "; expected an integer in [1, ", limits::kMaxDegree, "] (the degree limit)");
}

/// Order of derivatives: 0 <= order <= limits::kMaxDerivativeOrder.
inline void require_order(int order, const std::string& what = "order") {
  if (order < 0 || order > limits::kMaxDerivativeOrder)
    fail(what, " is ", order, "; expected an integer in [0, ", limits::kMaxDerivativeOrder,
         "] (the derivative order limit)");
}

/// A result of `count` values (a product of caller sizes) within limits::kMaxResultValues.
inline void require_result_size(double count, const std::string& what) {
  if (count > static_cast<double>(limits::kMaxResultValues))
    fail(what, " would hold ", count, " values; the limit is ", limits::kMaxResultValues,
         " per call: ask for fewer points or split the call");
}

inline void require_positive(double x, const std::string& what) {
  if (!(x > 0.0) || !std::isfinite(x)) fail(what, " is ", x, "; expected a finite value > 0");
}

/// require_positive over a list of {value, name} pairs (the fields of one struct).
inline void require_positive(std::initializer_list<std::pair<double, const char*>> named) {
  for (const auto& [x, what] : named) require_positive(x, what);
}

inline void require_weights(const Eigen::VectorXd& w, Eigen::Index n, const std::string& what = "weights") {
  if (w.size() != n) fail(what, " has ", w.size(), " entries; expected ", n, " (one per control point)");
  for (Eigen::Index i = 0; i < w.size(); ++i)
    if (!(w[i] > 0.0) || !std::isfinite(w[i]))
      fail(what, "[", i, "] is ", w[i], "; expected a finite weight > 0");
}

/// The weights of n control points: `w`, checked, or all ones when `w` is empty (non-rational).
inline Eigen::VectorXd weights_or_ones(Eigen::VectorXd w, Eigen::Index n) {
  if (w.size() == 0) return Eigen::VectorXd::Ones(n);
  require_weights(w, n);
  return w;
}

inline void require_times(int times, const std::string& what = "times") {
  if (times < 1) fail(what, " is ", times, "; expected an integer >= 1");
}

}  // namespace fairlines::detail
