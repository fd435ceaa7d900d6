// Python bindings of the hull fairness check: plane cuts of a surface with analytic curvature
// (fairlines/hull.hpp). The hull description and its orchestration live in python/fairlines/hull.py.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "convert.hpp"
#include "fairlines/hull.hpp"

namespace py = pybind11;
using namespace pybind11::literals;

namespace fairlines {

using namespace py_convert;

void bind_hull(py::module_& m) {
  py::class_<PlaneCut>(m, "PlaneCut", "A waterline / buttock / frame cut from a surface, with analytic curvature.")
      .def_readonly("axis", &PlaneCut::axis, "0 frame (x = value), 1 buttock (y = value), 2 waterline (z = value)")
      .def_readonly("value", &PlaneCut::value, "plane position (m)")
      .def_property_readonly("points", [](const PlaneCut& c) { return to_array(c.points); }, "(m, 3) points (m)")
      .def_property_readonly("curvature", [](const PlaneCut& c) { return to_array(c.curvature); },
                             "(m,) signed curvature (1/m) in the plane's coordinates")
      .def_readonly("bending_energy", &PlaneCut::bending_energy, "int k^2 ds (1/m)")
      .def_readonly("e2", &PlaneCut::e2, "int |c''(w)|^2 dw, w the marching parameter on [0, 1] (m^2)")
      .def_readonly("sign_changes", &PlaneCut::sign_changes, "curvature sign changes (|k| > threshold)")
      .def_readonly("threshold", &PlaneCut::threshold, "curvature below this (1/m) counts as straight")
      .def_property_readonly("inflections", [](const PlaneCut& c) { return to_array(c.inflections); },
                             "(n, 3) points where the curvature changes sign");
  m.def("plane_cut", [](const NurbsSurface& s, py::handle axis, double value, int samples) {
          int a = -1;
          if (py::isinstance<py::str>(axis)) {
            const std::string n = axis.cast<std::string>();
            if (n == "frame" || n == "x") a = 0;
            else if (n == "buttock" || n == "y") a = 1;
            else if (n == "waterline" || n == "z") a = 2;
            else throw InvalidInput("axis is '" + n + "'; expected 'frame', 'buttock' or 'waterline' (or 0, 1, 2)");
          } else {
            a = axis.cast<int>();
          }
          return plane_cut(s, a, value, samples);
        },
        "surface"_a, "axis"_a, "value"_a, "samples"_a = kPlaneCutSamples,
        "Cut a surface by the plane x, y or z = value (axis 'frame' | 'buttock' | 'waterline'); curvature\n"
        "from the surface's derivatives. Frames march along u, waterlines and buttocks along v.");
}

}  // namespace fairlines
