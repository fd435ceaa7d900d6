// Read-only result fields bound from a table (table(f) calls f(name, member pointer, doc) once
// per field), and the figures every hydrostatics result shares (fairlines/buoyancy.hpp).
#pragma once

#include <pybind11/pybind11.h>

#include "fairlines/buoyancy.hpp"

namespace fairlines::hydrostatics_fields {

namespace py = pybind11;

/// def_readonly of every field `table(f)` visits.
template <typename Result, typename Table>
py::class_<Result>& bind_readonly(py::class_<Result>& cls, Table&& table) {
  table([&](const char* name, auto member, const char* doc) { cls.def_readonly(name, member, doc); });
  return cls;
}

/// def_readonly of the BuoyancyFigures fields of a result derived from it.
template <typename Result>
py::class_<Result>& bind(py::class_<Result>& cls) {
  return bind_readonly(cls, [](auto&& f) { BuoyancyFigures::fields(f); });
}

}  // namespace fairlines::hydrostatics_fields
