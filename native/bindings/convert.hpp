// numpy <-> Eigen conversions with shape checks that name the argument (bindings only).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <sstream>
#include <string>

#include <Eigen/Core>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "fairlines/errors.hpp"

namespace fairlines::py_convert {

namespace py = pybind11;
using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

inline std::string shape_of(const py::array& a) {
  std::ostringstream os;
  os << "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) os << (i ? ", " : "") << a.shape(i);
  if (a.ndim() == 1) os << ",";
  os << ")";
  return os.str();
}

/// Any array-like to a C-contiguous float64 array; non-numeric input is InvalidInput.
inline Array as_array(const py::handle& obj, const char* what) {
  if (obj.is_none()) throw InvalidInput(std::string(what) + " is None; expected an array of numbers");
  Array a = Array::ensure(obj);  // returns a null array (error cleared) when conversion fails
  if (!a) throw InvalidInput(std::string(what) + " could not be read as an array of numbers");
  return a;
}

/// Index of the first k with a[k] or b[k] not finite, or n. Runs over every point of a batch
/// call with the GIL held, so blocks are screened by a branch-free exponent test (all-ones
/// exponent <=> inf/NaN) that the compiler vectorises; only a flagged block is rescanned.
inline py::ssize_t first_nonfinite_pair(const double* a, const double* b, py::ssize_t n) {
  constexpr py::ssize_t kBlock = 512;
  for (py::ssize_t k0 = 0; k0 < n; k0 += kBlock) {
    const py::ssize_t k1 = std::min(n, k0 + kBlock);
    std::uint64_t flags = 0;
    for (py::ssize_t k = k0; k < k1; ++k) {
      std::uint64_t x, y;
      std::memcpy(&x, a + k, 8);
      std::memcpy(&y, b + k, 8);
      flags |= (((x >> 52) & 0x7FF) + 1) | (((y >> 52) & 0x7FF) + 1);  // bit 11 set iff exponent is 0x7FF
    }
    if (flags & 0x800)
      for (py::ssize_t k = k0; k < k1; ++k)
        if (!std::isfinite(a[k]) || !std::isfinite(b[k])) return k;
  }
  return n;
}

/// 1-D vector (a scalar becomes length 1).
inline Eigen::VectorXd vector(const py::handle& obj, const char* what) {
  Array a = as_array(obj, what);
  if (a.ndim() > 1) throw InvalidInput(std::string(what) + " has shape " + shape_of(a) + "; expected a 1-D array");
  Eigen::VectorXd v(a.size());
  for (py::ssize_t i = 0; i < a.size(); ++i) v[i] = a.data()[i];
  return v;
}

/// (rows, cols) matrix; cols == -1 accepts any column count >= 1.
inline Eigen::MatrixXd matrix(const py::handle& obj, const char* what, long cols = -1) {
  Array a = as_array(obj, what);
  if (a.ndim() != 2 || a.shape(0) == 0 || (cols >= 0 && a.shape(1) != cols) || a.shape(1) == 0) {
    std::ostringstream os;
    os << what << " has shape " << shape_of(a) << "; expected (n, " << (cols >= 0 ? std::to_string(cols) : "dim")
       << ") with n >= 1";
    throw InvalidInput(os.str());
  }
  Eigen::MatrixXd m(a.shape(0), a.shape(1));
  for (py::ssize_t i = 0; i < a.shape(0); ++i)
    for (py::ssize_t j = 0; j < a.shape(1); ++j) m(i, j) = a.data()[i * a.shape(1) + j];
  return m;
}

/// Row-major (rows, cols) result array from an Eigen matrix.
inline py::array_t<double> to_array(const Eigen::MatrixXd& m) {
  py::array_t<double> out({m.rows(), m.cols()});
  auto r = out.mutable_unchecked<2>();
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    for (Eigen::Index j = 0; j < m.cols(); ++j) r(i, j) = m(i, j);
  return out;
}

inline py::array_t<double> to_array(const Eigen::VectorXd& v) {
  py::array_t<double> out(v.size());
  std::copy(v.data(), v.data() + v.size(), out.mutable_data());
  return out;
}

/// A Python integer (or an integral float such as 3.0) that fits an int; anything else,
/// including a bool or an integer beyond the int range, is InvalidInput naming `what`.
inline int checked_int(const py::handle& obj, const char* what) {
  if (!py::isinstance<py::bool_>(obj) && py::isinstance<py::float_>(obj)) {
    const double d = obj.cast<double>();
    if (std::isfinite(d) && d == std::floor(d) && std::abs(d) <= 2147483647.0) return static_cast<int>(d);
  }
  const std::string shown = py::repr(obj).cast<std::string>();
  PyObject* index = py::isinstance<py::bool_>(obj) ? nullptr : PyNumber_Index(obj.ptr());
  if (index == nullptr) {
    PyErr_Clear();
    throw InvalidInput(std::string(what) + " is " + shown + "; expected an integer");
  }
  const py::object held = py::reinterpret_steal<py::object>(index);
  int overflow = 0;
  const long long v = PyLong_AsLongLongAndOverflow(held.ptr(), &overflow);
  if (PyErr_Occurred()) PyErr_Clear();
  if (overflow != 0 || v < -2147483648LL || v > 2147483647LL)
    throw InvalidInput(std::string(what) + " is " + shown + "; expected an integer of a sensible size (far below 2^31)");
  return static_cast<int>(v);
}

/// True when obj is a Python or numpy scalar (so results drop the sample axis).
inline bool is_scalar(const py::handle& obj) {
  if (py::isinstance<py::float_>(obj) || py::isinstance<py::int_>(obj)) return true;
  if (py::isinstance<py::array>(obj)) return py::reinterpret_borrow<py::array>(obj).ndim() == 0;
  return py::hasattr(obj, "__float__") && !py::hasattr(obj, "__len__");
}

}  // namespace fairlines::py_convert
