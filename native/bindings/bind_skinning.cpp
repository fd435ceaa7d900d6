// Python bindings of fair skinning (fairlines/skinning.hpp) and hydrostatics
// (fairlines/hydrostatics.hpp).
#include <cmath>

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "convert.hpp"
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

  m.def("_fair_skin",
        [](py::handle curves, py::handle n_control, const std::string& mode, py::handle degree_u, py::handle degree_v,
           py::handle samples, double smoothing, const std::string& start, const std::string& end,
           const std::string& params, const std::vector<int>& c1_sections, double curvature_weight, double e2, double e3,
           const std::vector<std::pair<int, double>>& flats, bool hold_runs, const std::vector<std::pair<int, int>>& straight_groups) {
          SkinOptions o;
          o.n_control = n_control.is_none() ? 0 : as_int(n_control, "n_control");
          if (!n_control.is_none() && o.n_control <= 0)
            throw InvalidInput("n_control is " + std::to_string(o.n_control) + "; expected None or an integer >= degree_u + 1");
          o.mode = parse_skin_mode(mode);
          o.degree_u = as_int(degree_u, "degree_u");
          o.degree_v = as_int(degree_v, "degree_v");
          o.samples = samples.is_none() ? 0 : as_int(samples, "samples");
          if (!samples.is_none() && o.samples <= 0)
            throw InvalidInput("samples is " + std::to_string(o.samples) + "; expected None or an integer >= n_control");
          o.smoothing = smoothing;
          o.start = parse_skin_end(start);
          o.end = parse_skin_end(end);
          o.params = parse_skin_params(params);
          o.c1_sections = c1_sections;
          o.curvature_weight = curvature_weight;
          o.e2 = e2;
          o.e3 = e3;
          o.flats = flats;
          o.hold_runs = hold_runs;
          o.straight_groups = straight_groups;
          const std::vector<NurbsCurve> cs = as_curves(curves);
          py::gil_scoped_release release;
          return fair_skin(cs, o);
        },
        "curves"_a, "n_control"_a, "mode"_a, "degree_u"_a, "degree_v"_a, "samples"_a, "smoothing"_a, "start"_a,
        "end"_a, "params"_a, "c1_sections"_a, "curvature_weight"_a, "e2"_a, "e3"_a,
        "flats"_a = std::vector<std::pair<int, double>>{}, "hold_runs"_a = true,
        "straight_groups"_a = std::vector<std::pair<int, int>>{});

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

  m.def("hydrostatics",
        [](const NurbsSurface& s, double draft, bool half_hull, double length, double breadth, py::handle midship_x,
           py::handle gauss, py::handle sac_stations, double density, double trim, double trim_length) {
          HydrostaticsOptions o;
          o.half_hull = half_hull;
          o.length = length;
          o.breadth = breadth;
          if (!midship_x.is_none()) o.midship_x = midship_x.cast<double>();
          if (!midship_x.is_none() && std::isnan(o.midship_x))
            throw InvalidInput("midship_x is nan; expected a finite x (m) or None");
          o.gauss = as_int(gauss, "gauss");
          o.sac_stations = as_int(sac_stations, "sac_stations");
          o.density = density;
          o.trim = trim;
          o.trim_length = trim_length;
          py::gil_scoped_release release;
          return hydrostatics(s, draft, o);
        },
        "surface"_a, "draft"_a, "half_hull"_a = true, "length"_a = 0.0, "breadth"_a = 0.0, "midship_x"_a = py::none(),
        "gauss"_a = 8, "sac_stations"_a = 41, "density"_a = 1.025, "trim"_a = 0.0, "trim_length"_a = 0.0,
        "Hydrostatics of a hull surface at `draft` (m above base) by Gauss-Legendre quadrature on the surface.\n"
        "The surface is the y >= 0 half of the hull when half_hull=True (volume, areas and SAC are then doubled\n"
        "to full-ship values); openings other than the centre plane must be transverse planes x = const.\n"
        "length / breadth: for the coefficients (0: submerged extent); midship_x: station of Am (None: middle).\n"
        "trim: by the stern (m) over trim_length (AP at x = 0 to FP); draft is then the draft at trim_length / 2.\n"
        "Raises InvalidInput for a bad draft or option, or a waterplane above the surface's highest point.");
  m.def("section_area", &section_area, "surface"_a, "x"_a, "draft"_a, "half_hull"_a = true, "gauss"_a = 8,
        "(area below the draft of the section x = const (m^2; full section when half_hull), centroid height (m)).");
}

}  // namespace fairlines
