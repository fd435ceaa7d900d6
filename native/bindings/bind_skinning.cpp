// Python bindings of fair skinning (fairlines/skinning.hpp) and hydrostatics
// (fairlines/hydrostatics.hpp).
#include <cmath>
#include <limits>
#include <string>
#include <type_traits>

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "convert.hpp"
#include "hydrostatics_fields.hpp"
#include "option_docs.hpp"
#include "fairlines/hydrostatics.hpp"
#include "fairlines/skinning.hpp"

namespace py = pybind11;
using namespace pybind11::literals;

namespace fairlines {

using namespace py_convert;

namespace {

int as_int(const py::handle& obj, const char* what) {
  if (py::isinstance<py::bool_>(obj)) throw InvalidInput(std::string(what) + " is a bool; expected an integer");
  if (py::isinstance<py::int_>(obj)) return obj.cast<int>();
  if (py::isinstance<py::float_>(obj)) {
    const double d = obj.cast<double>();
    if (std::isfinite(d) && d == std::floor(d)) return static_cast<int>(d);
  }
  throw InvalidInput(std::string(what) + " is " + py::repr(obj).cast<std::string>() + "; expected an integer");
}

std::vector<NurbsCurve> as_curves(const py::handle& obj) {
  if (!py::isinstance<py::sequence>(obj)) throw InvalidInput("curves must be a list of NurbsCurve");
  std::vector<NurbsCurve> out;
  const py::sequence seq = py::reinterpret_borrow<py::sequence>(obj);
  for (py::ssize_t i = 0; i < static_cast<py::ssize_t>(seq.size()); ++i) {
    const py::object item = seq[i];
    if (!py::isinstance<NurbsCurve>(item))
      throw InvalidInput("curves[" + std::to_string(i) + "] is " + py::str(py::type::of(item)).cast<std::string>() +
                         "; expected a NurbsCurve");
    out.push_back(item.cast<NurbsCurve>());
  }
  return out;
}

// Integer fields keep the bound functions' rule: an integral float is accepted, a bool is not.
template <typename Options>
void def_int(py::class_<Options>& c, const char* name, int Options::*member, const char* doc) {
  c.def_property(
      name, [member](const Options& o) { return o.*member; },
      [name, member](Options& o, py::handle value) { o.*member = as_int(value, name); },
      option_docs::with_default(doc, Options{}.*member).c_str());
}

// The integer fields of an options struct, by def_int.
const auto integral_ints = option_docs::for_type<int>(
    [](auto& cls, const char* name, auto member, const char* doc) { def_int(cls, name, member, doc); });

void bind_hydrostatics_options(py::module_& m) {
  using O = HydrostaticsOptions;
  py::class_<O> c(m, "HydrostaticsOptions", "Options of hydrostatics (fairlines.hydrostatics sets them by keyword).");
  c.def(py::init<>());
  // midship_x reads and takes None for NaN (the middle of the submerged length).
  const auto none_for_nan = [](py::class_<O>& cls, const char* name, const char* doc) {
    cls.def_property(
        name,
        [](const O& o) -> py::object {
          if (std::isnan(o.midship_x)) return py::none();
          return py::float_(o.midship_x);
        },
        [](O& o, py::handle x) {
          if (x.is_none()) { o.midship_x = std::numeric_limits<double>::quiet_NaN(); return; }
          o.midship_x = x.cast<double>();
          if (std::isnan(o.midship_x)) throw InvalidInput("midship_x is nan; expected a finite x (m) or None");
        },
        std::string(doc).append(" (default None)").c_str());
  };
  option_docs::bind_fields(c, integral_ints, option_docs::for_member(&O::midship_x, none_for_nan));
}

void bind_skin_options(py::module_& m) {
  py::class_<SkinOptions> c(m, "SkinOptions", "Options of fair_skin (fairlines.fair_skin sets them by keyword).");
  c.def(py::init<>());
  using option_docs::by_name;
  option_docs::bind_fields(c, integral_ints, by_name(skin_mode_name, parse_skin_mode),
                           by_name(skin_end_name, parse_skin_end), by_name(skin_params_name, parse_skin_params));
}

void bind_hydrostatics_result(py::module_& m) {
  py::class_<Hydrostatics> c(m, "Hydrostatics",
                             "Hydrostatics at one draft. Volume, areas and SAC are for the full ship when the "
                             "surface was a half hull (half_hull=True); lengths in m, areas m^2, volume m^3, "
                             "displacement t.");
  hydrostatics_fields::bind_readonly(c, [](auto&& f) { Hydrostatics::fields(f); })
      .def_property_readonly("sac_x", [](const Hydrostatics& h) { return to_array(h.sac_x); })
      .def_property_readonly("sac_area", [](const Hydrostatics& h) { return to_array(h.sac_area); })
      .def("as_dict", [](const Hydrostatics& h) {
        py::dict d;
        Hydrostatics::fields([&](const char* name, auto member, const char*) { d[name] = h.*member; });
        return d;
      }, "Scalar results as a dict.");
}

}  // namespace

void bind_skinning(py::module_& m) {
  py::class_<SkinResult>(m, "SkinResult", "Result of fair_skin: the surface and how closely it follows the sections.")
      .def_readonly("surface", &SkinResult::surface, "NurbsSurface: u across the sections, v along the hull (v = 0 first section).")
      .def_property_readonly("section_params", [](const SkinResult& r) { return to_array(r.section_params); },
                             "v of each section (q,).")
      .def_readonly("section_fit_max", &SkinResult::section_fit_max,
                    "max distance (m) between the equally spaced section points and the common-knot fits")
      .def_readonly("longitudinal_max", &SkinResult::longitudinal_max,
                    "max distance (m) between the longitudinal curves and the section control rows")
      .def_property_readonly("row_e2", [](const SkinResult& r) { return to_array(r.row_e2); },
                             "E2 of each longitudinal control-row curve (n_control,).")
      .def_readonly("held_columns", &SkinResult::held_columns,
                    "row coordinates (y or z of a control row) held constant over at least one run of sections")
      .def_readonly("centre_plane_columns", &SkinResult::centre_plane_columns,
                    "y columns solved again with their controls at y >= 0 (options.y_nonnegative)")
      .def_readonly("centre_plane_miss", &SkinResult::centre_plane_miss,
                    "largest distance (m) between a row point and its longitudinal curve in those columns")
      .def_readonly("centre_plane_refused_miss", &SkinResult::centre_plane_refused_miss,
                    "> 0 when options.y_nonnegative left the skin as it was: the largest row miss (m) keeping it "
                    "off the centre plane would have cost");

  bind_skin_options(m);
  m.def("_fair_skin",
        [](py::handle curves, const SkinOptions& options) {
          const std::vector<NurbsCurve> cs = as_curves(curves);
          py::gil_scoped_release release;
          return fair_skin(cs, options);
        },
        "curves"_a, "options"_a = SkinOptions{});

  m.def("equal_arc_length_points", [](const NurbsCurve& c, py::handle mobj, double w) { return to_array(equal_arc_length_points(c, as_int(mobj, "m"), w)); },
        "curve"_a, "m"_a, "curvature_weight"_a = SkinOptions{}.curvature_weight,
        "m points at equal arc-length spacing along the curve, ends included: (m, dim). curvature_weight w > 0:\n"
        "equal spacing in ds (1 + w L |k|) instead (L the curve length).");
  m.def("arc_length", &arc_length, "curve"_a, "Arc length of the curve (m).");
  m.def("curve_e2", &curve_e2, "curve"_a, "E2 = integral of |C''(t)|^2 dt over the curve's parameter domain.");

  bind_hydrostatics_result(m);
  bind_hydrostatics_options(m);
  m.def(
      "_hydrostatics",
      [](const NurbsSurface& s, double draft, const HydrostaticsOptions& o) {
        py::gil_scoped_release release;
        return hydrostatics(s, draft, o);
      },
      "surface"_a, "draft"_a, "options"_a = HydrostaticsOptions{},
      "Hydrostatics of a hull surface at `draft` (m above base) by Gauss-Legendre quadrature on the surface\n"
      "(fairlines.hydrostatics takes the options by keyword).");
  m.def("section_area", &section_area, "surface"_a, "x"_a, "draft"_a, "half_hull"_a = HydrostaticsOptions{}.half_hull,
        "gauss"_a = HydrostaticsOptions{}.gauss,
        "(area below the draft of the section x = const (m^2; full section when half_hull), centroid height (m)).");
}

}  // namespace fairlines
