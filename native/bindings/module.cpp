// The one place where the engine meets Python: exception translation and the module
// `fairlines._native`. Each bind_*.cpp file adds one area of the engine.
#include <pybind11/pybind11.h>

#include "fairlines/errors.hpp"

namespace py = pybind11;

namespace fairlines {
void bind_nurbs(py::module_& m);
void bind_skinning(py::module_& m);
void bind_hull(py::module_& m);
void bind_design(py::module_& m);
void bind_compose(py::module_& m);
void bind_form_curve(py::module_& m);
void bind_meshing(py::module_& m);
void bind_grids(py::module_& m);
void bind_mesh_hydrostatics(py::module_& m);
void bind_patch_hydrostatics(py::module_& m);
}  // namespace fairlines

PYBIND11_MODULE(_native, m) {
  m.doc() = "Fairlines compiled engine (private; use the `fairlines` package).";
  // Order matters: pybind11 tries translators newest first, so subclasses come last.
  auto base = py::register_exception<fairlines::Error>(m, "FairlinesError", PyExc_RuntimeError);
  auto invalid = py::register_exception<fairlines::InvalidInput>(m, "InvalidInput", PyExc_ValueError);
  py::register_exception<fairlines::InfeasibleFormParameters>(m, "InfeasibleFormParameters", invalid.ptr());
  py::register_exception<fairlines::NoBlendFits>(m, "NoBlendFits", invalid.ptr());
  py::register_exception<fairlines::ConvergenceError>(m, "ConvergenceError", base.ptr());
  fairlines::bind_nurbs(m);
  fairlines::bind_form_curve(m);
  fairlines::bind_skinning(m);
  fairlines::bind_hull(m);
  fairlines::bind_design(m);
  fairlines::bind_compose(m);
  fairlines::bind_meshing(m);
  fairlines::bind_grids(m);
  fairlines::bind_mesh_hydrostatics(m);
  fairlines::bind_patch_hydrostatics(m);
}
