// Internal input checks shared by the NURBS sources: each throws InvalidInput with a
// message naming the argument and what was expected.
#pragma once

#include <cmath>
#include <sstream>
#include <string>

#include <Eigen/Core>

#include "fairlines/errors.hpp"

namespace fairlines::detail {

template <typename... Parts>
[[noreturn]] inline void fail(const Parts&... parts) {
  std::ostringstream os;
  (os << ... << parts);
  throw InvalidInput(os.str());
}

template <typename Derived>
inline void require_finite(const Eigen::DenseBase<Derived>& a, const std::string& what) {
  for (Eigen::Index i = 0; i < a.rows(); ++i)
    for (Eigen::Index j = 0; j < a.cols(); ++j)
      if (!std::isfinite(a(i, j))) {
        if (a.cols() == 1)
          fail(what, "[", i, "] is ", a(i, j), "; expected a finite number");
        fail(what, "[", i, ", ", j, "] is ", a(i, j), "; expected a finite number");
      }
}

inline void require_finite(double x, const std::string& what) {
  if (!std::isfinite(x)) fail(what, " is ", x, "; expected a finite number");
}

inline void require_degree(int degree, const std::string& what = "degree") {
  if (degree < 1) fail(what, " is ", degree, "; expected an integer >= 1");
}

inline void require_positive(double x, const std::string& what) {
  if (!(x > 0.0) || !std::isfinite(x)) fail(what, " is ", x, "; expected a finite value > 0");
}

inline void require_weights(const Eigen::VectorXd& w, Eigen::Index n, const std::string& what = "weights") {
  if (w.size() != n) fail(what, " has ", w.size(), " entries; expected ", n, " (one per control point)");
  for (Eigen::Index i = 0; i < w.size(); ++i)
    if (!(w[i] > 0.0) || !std::isfinite(w[i]))
      fail(what, "[", i, "] is ", w[i], "; expected a finite weight > 0");
}

inline void require_times(int times, const std::string& what = "times") {
  if (times < 1) fail(what, " is ", times, "; expected an integer >= 1");
}

}  // namespace fairlines::detail
