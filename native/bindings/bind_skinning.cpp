// Python bindings of fair skinning (fairlines/skinning.hpp) and hydrostatics
// (fairlines/hydrostatics.hpp).
#include <cmath>
#include <limits>

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "convert.hpp"
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
template <typename Options, int Options::*field>
void def_int(py::class_<Options>& c, const char* name, const char* doc) {
  c.def_property(
      name, [](const Options& o) { return o.*field; },
      [name](Options& o, py::handle value) { o.*field = as_int(value, name); },
      option_docs::with_default(doc, Options{}.*field).c_str());
}

void bind_hydrostatics_options(py::module_& m) {
  using option_docs::field;
  using O = HydrostaticsOptions;
  py::class_<O> c(m, "HydrostaticsOptions", "Options of hydrostatics (fairlines.hydrostatics sets them by keyword).");
  c.def(py::init<>());
  field(c, "half_hull", &O::half_hull, "the surface is the y >= 0 half: volume, areas and SAC are doubled");
  field(c, "length", &O::length, "length for the coefficients (m); 0: submerged length x_max - x_min");
  field(c, "breadth", &O::breadth, "breadth for the coefficients (m); 0: 2 x max submerged half-breadth");
  c.def_property(
      "midship_x",
      [](const O& o) -> py::object {
        if (std::isnan(o.midship_x)) return py::none();
        return py::float_(o.midship_x);
      },
      [](O& o, py::handle x) {
        if (x.is_none()) { o.midship_x = std::numeric_limits<double>::quiet_NaN(); return; }
        o.midship_x = x.cast<double>();
        if (std::isnan(o.midship_x)) throw InvalidInput("midship_x is nan; expected a finite x (m) or None");
      },
      "x of the midship section for Am and Cm (m); None: the middle of [x_min, x_max] (default None)");
  def_int<O, &O::gauss>(c, "gauss", "Gauss-Legendre points per knot span in each direction (2..32)");
  def_int<O, &O::sac_stations>(c, "sac_stations", "equally spaced stations of the returned SAC (>= 2), ends included");
  field(c, "density", &O::density, "water density (t/m^3) for the displacement mass");
  field(c, "trim", &O::trim, "trim by the stern (m) over trim_length; draft is then the draft at trim_length / 2");
  field(c, "trim_length", &O::trim_length, "AP to FP (m) over which trim is measured; > 0 when trim != 0");
}

void bind_skin_options(py::module_& m) {
  using option_docs::field;
  py::class_<SkinOptions> c(m, "SkinOptions", "Options of fair_skin (fairlines.fair_skin sets them by keyword).");
  c.def(py::init<>());
  def_int<SkinOptions, &SkinOptions::n_control>(c, "n_control", "control points per section in u; 0: max(12, 2 x largest section count)");
  def_int<SkinOptions, &SkinOptions::degree_u>(c, "degree_u", "degree across the sections (>= 1)");
  def_int<SkinOptions, &SkinOptions::degree_v>(c, "degree_v", "degree of the longitudinal curves (>= 2)");
  def_int<SkinOptions, &SkinOptions::samples>(c, "samples", "equally spaced points per section; 0: 4 x n_control, else >= n_control");
  field(c, "curvature_weight", &SkinOptions::curvature_weight,
        "w >= 0: section points equally spaced in ds (1 + w L |k|), L the section length; 0 plain arc length");
  c.def_property(
      "mode", [](const SkinOptions& o) { return skin_mode_name(o.mode); },
      [](SkinOptions& o, const std::string& v) { o.mode = parse_skin_mode(v); },
      option_docs::with_default("'interpolate' (through every row point, least E2) or 'approximate' (least squares + "
                                "smoothing h^4 E2)", skin_mode_name(SkinOptions{}.mode)).c_str());
  field(c, "e2", &SkinOptions::e2, "weight of E2 = int |C''(v)|^2 dv in the longitudinal fairness");
  field(c, "e3", &SkinOptions::e3, "weight of h^2 E3 = h^2 int |C'''(v)|^2 dv, h = 1/(q-1)");
  field(c, "smoothing", &SkinOptions::smoothing, "approximate mode: weight of h^4 E2 (>= 0)");
  c.def_property(
      "start", [](const SkinOptions& o) { return skin_end_name(o.start); },
      [](SkinOptions& o, const std::string& v) { o.start = parse_skin_end(v); },
      option_docs::with_default("'free' (natural) or 'parallel' (dy/dv = dz/dv = 0) at the first section",
                                skin_end_name(SkinOptions{}.start)).c_str());
  c.def_property(
      "end", [](const SkinOptions& o) { return skin_end_name(o.end); },
      [](SkinOptions& o, const std::string& v) { o.end = parse_skin_end(v); },
      option_docs::with_default("'free' (natural) or 'parallel' (dy/dv = dz/dv = 0) at the last section",
                                skin_end_name(SkinOptions{}.end)).c_str());
  c.def_property(
      "params", [](const SkinOptions& o) { return skin_params_name(o.params); },
      [](SkinOptions& o, const std::string& v) { o.params = parse_skin_params(v); },
      option_docs::with_default("section parameters v: 'station' (proportional to x), 'chord', or 'auto' (station when "
                                "planar at monotone x)", skin_params_name(SkinOptions{}.params)).c_str());
  field(c, "c1_sections", &SkinOptions::c1_sections,
        "interior section indices where the longitudinal curves are only C1");
  field(c, "flats", &SkinOptions::flats,
        "planes (axis 0 / 1 / 2 for x / y / z, value m) the sections' fits keep exactly where they lie in them");
  field(c, "hold_runs", &SkinOptions::hold_runs,
        "hold a row coordinate constant over three or more sections where the rows keep it");
  field(c, "straight_groups", &SkinOptions::straight_groups,
        "row ranges (first, last) kept straight between their end rows' longitudinal curves");
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
                    "row coordinates (y or z of a control row) held constant over at least one run of sections");

  bind_skin_options(m);
  m.def("_fair_skin",
        [](py::handle curves, const SkinOptions& options) {
          const std::vector<NurbsCurve> cs = as_curves(curves);
          py::gil_scoped_release release;
          return fair_skin(cs, options);
        },
        "curves"_a, "options"_a = SkinOptions{});

  m.def("equal_arc_length_points", [](const NurbsCurve& c, py::handle mobj, double w) { return to_array(equal_arc_length_points(c, as_int(mobj, "m"), w)); },
        "curve"_a, "m"_a, "curvature_weight"_a = 0.0,
        "m points at equal arc-length spacing along the curve, ends included: (m, dim). curvature_weight w > 0:\n"
        "equal spacing in ds (1 + w L |k|) instead (L the curve length).");
  m.def("arc_length", &arc_length, "curve"_a, "Arc length of the curve (m).");
  m.def("curve_e2", &curve_e2, "curve"_a, "E2 = integral of |C''(t)|^2 dt over the curve's parameter domain.");

  py::class_<Hydrostatics>(m, "Hydrostatics",
                           "Hydrostatics at one draft. Volume, areas and SAC are for the full ship when the "
                           "surface was a half hull (half_hull=True); lengths in m, areas m^2, volume m^3, "
                           "displacement t.")
      .def_readonly("draft", &Hydrostatics::draft)
      .def_readonly("volume", &Hydrostatics::volume)
      .def_readonly("displacement", &Hydrostatics::displacement)
      .def_readonly("lcb", &Hydrostatics::lcb)
      .def_readonly("vcb", &Hydrostatics::vcb)
      .def_readonly("waterplane_area", &Hydrostatics::waterplane_area)
      .def_readonly("lcf", &Hydrostatics::lcf)
      .def_readonly("wetted_surface", &Hydrostatics::wetted_surface)
      .def_readonly("x_min", &Hydrostatics::x_min)
      .def_readonly("x_max", &Hydrostatics::x_max)
      .def_readonly("length", &Hydrostatics::length)
      .def_readonly("breadth", &Hydrostatics::breadth)
      .def_readonly("midship_x", &Hydrostatics::midship_x)
      .def_readonly("midship_area", &Hydrostatics::midship_area)
      .def_readonly("cb", &Hydrostatics::cb)
      .def_readonly("cp", &Hydrostatics::cp)
      .def_readonly("cm", &Hydrostatics::cm)
      .def_readonly("cwp", &Hydrostatics::cwp)
      .def_readonly("trim", &Hydrostatics::trim, "trim by the stern (m)")
      .def_readonly("inertia_t", &Hydrostatics::inertia_t, "I_T, waterplane 2nd moment about the centre line (m^4)")
      .def_readonly("inertia_l", &Hydrostatics::inertia_l, "I_L, waterplane 2nd moment about the axis through F (m^4)")
      .def_readonly("bmt", &Hydrostatics::bmt, "I_T / V (m)")
      .def_readonly("bml", &Hydrostatics::bml, "I_L / V (m)")
      .def_readonly("kmt", &Hydrostatics::kmt, "VCB + BMt (m above base)")
      .def_readonly("kml", &Hydrostatics::kml, "VCB + BMl (m above base)")
      .def_readonly("tpc", &Hydrostatics::tpc, "tonnes per cm immersion (t/cm)")
      .def_readonly("mct1cm", &Hydrostatics::mct1cm, "moment to change trim 1 cm, GML taken as BML (t m/cm)")
      .def_readonly("z_max", &Hydrostatics::z_max, "highest point of the surface (m)")
      .def_property_readonly("sac_x", [](const Hydrostatics& h) { return to_array(h.sac_x); })
      .def_property_readonly("sac_area", [](const Hydrostatics& h) { return to_array(h.sac_area); })
      .def("as_dict", [](const Hydrostatics& h) {
        py::dict d;
        d["draft"] = h.draft; d["volume"] = h.volume; d["displacement"] = h.displacement; d["lcb"] = h.lcb;
        d["vcb"] = h.vcb; d["waterplane_area"] = h.waterplane_area; d["lcf"] = h.lcf;
        d["wetted_surface"] = h.wetted_surface; d["x_min"] = h.x_min; d["x_max"] = h.x_max;
        d["length"] = h.length; d["breadth"] = h.breadth; d["midship_x"] = h.midship_x;
        d["midship_area"] = h.midship_area; d["cb"] = h.cb; d["cp"] = h.cp; d["cm"] = h.cm; d["cwp"] = h.cwp;
        d["trim"] = h.trim; d["inertia_t"] = h.inertia_t; d["inertia_l"] = h.inertia_l; d["bmt"] = h.bmt;
        d["bml"] = h.bml; d["kmt"] = h.kmt; d["kml"] = h.kml; d["tpc"] = h.tpc; d["mct1cm"] = h.mct1cm;
        d["z_max"] = h.z_max;
        return d;
      }, "Scalar results as a dict.");

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
  m.def("section_area", &section_area, "surface"_a, "x"_a, "draft"_a, "half_hull"_a = true, "gauss"_a = 8,
        "(area below the draft of the section x = const (m^2; full section when half_hull), centroid height (m)).");
}

}  // namespace fairlines
