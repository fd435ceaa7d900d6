// The fields that the hydrostatics results of meshes and of surface patches share, bound once.
#pragma once

#include <pybind11/pybind11.h>

namespace fairlines::hydrostatics_fields {

namespace py = pybind11;

/// def_readonly of draft, volume, lcb, vcb, waterplane_area, lcf and wetted_surface (m, m^2, m^3).
template <typename Result>
py::class_<Result>& bind(py::class_<Result>& cls) {
  return cls.def_readonly("draft", &Result::draft)
      .def_readonly("volume", &Result::volume)
      .def_readonly("lcb", &Result::lcb, "x of the centre of buoyancy (m)")
      .def_readonly("vcb", &Result::vcb, "z of the centre of buoyancy, KB (m)")
      .def_readonly("waterplane_area", &Result::waterplane_area)
      .def_readonly("lcf", &Result::lcf, "x of the waterplane centroid (m)")
      .def_readonly("wetted_surface", &Result::wetted_surface);
}

}  // namespace fairlines::hydrostatics_fields
