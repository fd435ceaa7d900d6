// Python bindings of the hull designer's solvers: fairest spline functions (basic curves) and
// sections (fairlines/spline_design.hpp, fairlines/sections.hpp). Request structs are bound
// once, field by field, so their defaults live only in the C++ headers.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "convert.hpp"
#include "option_docs.hpp"
#include "fairlines/sections.hpp"
#include "fairlines/spline_design.hpp"

#include <tuple>

namespace py = pybind11;
using namespace pybind11::literals;

namespace fairlines {

using namespace py_convert;

namespace {

/// The conditions a spline function request is made of.
void bind_spline_conditions(py::module_& m) {
  py::class_<SplineCondition>(m, "SplineCondition", "f^(derivative)(x) = value (a form parameter of a basic curve).")
      .def(py::init([](double x, int derivative, double value, std::string name, std::vector<double> combination) {
             return SplineCondition{x, derivative, value, std::move(name), std::move(combination)};
           }),
           "x"_a, "derivative"_a, "value"_a, "name"_a, "combination"_a = std::vector<double>{})
      .def_readwrite("combination", &SplineCondition::combination)
      .def_readwrite("x", &SplineCondition::x).def_readwrite("derivative", &SplineCondition::derivative)
      .def_readwrite("value", &SplineCondition::value).def_readwrite("name", &SplineCondition::name);
  py::class_<SplineIntegral>(m, "SplineIntegral",
                             "int_{from_}^{to} x^power f(x) w(x) dx = value, w the product of the 1-D spline `factors`; with `centroid`\n"
                             "the condition is the centroid of f w instead.")
      .def(py::init([](double from, double to, double value, int power, std::vector<NurbsCurve> factors, double centroid, std::string name) {
             return SplineIntegral{from, to, power, std::move(factors), value, centroid, std::move(name)};
           }),
           "from_"_a, "to"_a, "value"_a = SplineIntegral{}.value, "power"_a = SplineIntegral{}.power,
           "factors"_a = std::vector<NurbsCurve>{}, "centroid"_a = SplineIntegral{}.centroid, "name"_a = "integral")
      .def_readwrite("from_", &SplineIntegral::from).def_readwrite("to", &SplineIntegral::to)
      .def_readwrite("power", &SplineIntegral::power).def_readwrite("factors", &SplineIntegral::factors)
      .def_readwrite("value", &SplineIntegral::value).def_readwrite("centroid", &SplineIntegral::centroid)
      .def_readwrite("name", &SplineIntegral::name);
  py::class_<SplineFlat>(m, "SplineFlat", "f = value on [from_, to] exactly (left with G2 for cubics).")
      .def(py::init<double, double, double, std::string>(), "from_"_a, "to"_a, "value"_a, "name"_a)
      .def_readwrite("from_", &SplineFlat::from).def_readwrite("to", &SplineFlat::to)
      .def_readwrite("value", &SplineFlat::value).def_readwrite("name", &SplineFlat::name);
  py::class_<SplineBound>(m, "SplineBound", "lower <= f <= upper on [from_, to] (NaN: no bound).")
      .def(py::init<double, double, double, double, std::string>(), "from_"_a, "to"_a, "lower"_a = SplineBound{}.lower,
           "upper"_a = SplineBound{}.upper, "name"_a = "bound")
      .def_readwrite("from_", &SplineBound::from).def_readwrite("to", &SplineBound::to)
      .def_readwrite("lower", &SplineBound::lower).def_readwrite("upper", &SplineBound::upper).def_readwrite("name", &SplineBound::name);
  py::class_<SplineShape>(m, "SplineShape", "sign * f^(derivative) >= 0 on [from_, to] (derivative 1 or 2, sign +1 / -1).")
      .def(py::init<double, double, int, int, std::string, double>(), "from_"_a, "to"_a, "derivative"_a, "sign"_a, "name"_a = "shape",
           "margin"_a = SplineShape{}.margin)
      .def_readwrite("margin", &SplineShape::margin)
      .def_readwrite("from_", &SplineShape::from).def_readwrite("to", &SplineShape::to)
      .def_readwrite("derivative", &SplineShape::derivative).def_readwrite("sign", &SplineShape::sign).def_readwrite("name", &SplineShape::name);
  py::class_<SplineFitPoint>(m, "SplineFitPoint", "Pass near (x, y) with weight w (least squares).")
      .def(py::init<double, double, double>(), "x"_a, "y"_a, "weight"_a = SplineFitPoint{}.weight)
      .def_readwrite("x", &SplineFitPoint::x).def_readwrite("y", &SplineFitPoint::y).def_readwrite("weight", &SplineFitPoint::weight);
}

/// The request, its solver and its knots.
void bind_spline_design(py::module_& m) {
  bind_spline_conditions(m);
  py::class_<SplineDesignRequest>(m, "SplineDesignRequest", "A fairest spline function y = f(x) and its form parameters.")
      .def(py::init<>())
      .def_readwrite("name", &SplineDesignRequest::name).def_readwrite("degree", &SplineDesignRequest::degree)
      .def_property("knots", [](const SplineDesignRequest& r) { return to_array(r.knots); },
                    [](SplineDesignRequest& r, py::handle k) { r.knots = vector(k, "knots"); }, "clamped knot vector in x (m)")
      .def_readwrite("conditions", &SplineDesignRequest::conditions).def_readwrite("integrals", &SplineDesignRequest::integrals)
      .def_readwrite("flats", &SplineDesignRequest::flats).def_readwrite("bounds", &SplineDesignRequest::bounds)
      .def_readwrite("shapes", &SplineDesignRequest::shapes).def_readwrite("fit", &SplineDesignRequest::fit)
      .def_readwrite("linear", &SplineDesignRequest::linear)
      .def_readwrite("e2", &SplineDesignRequest::e2).def_readwrite("e3", &SplineDesignRequest::e3)
      .def_property("reference", [](const SplineDesignRequest& r) { return to_array(r.reference); },
                    [](SplineDesignRequest& r, py::handle k) { r.reference = k.is_none() ? Eigen::VectorXd() : vector(k, "reference"); },
                    "coefficients of a reference function on `knots` (the fairness measures f - reference); empty: none");
  m.def("design_spline_function", &design_spline_function, "request"_a, py::call_guard<py::gil_scoped_release>(),
        "The fairest spline function meeting the request: a NurbsCurve of dimension 1 whose parameter is x (m).\n"
        "Raises InvalidInput (malformed request) or InfeasibleFormParameters (conditions in conflict, named).");
  m.def("spline_function_knots", [](double x0, double x1, const std::vector<double>& breaks, int spans, int degree, int min_piece_spans) {
          return to_array(spline_function_knots(x0, x1, breaks, spans, degree, min_piece_spans));
        },
        "x0"_a, "x1"_a, "breaks"_a = std::vector<double>{}, "spans"_a = kKnotSpans, "degree"_a = kKnotDegree,
        "min_piece_spans"_a = kMinPieceSpans,
        "Clamped knots on [x0, x1] keeping `breaks` as knots, about `spans` spans spread by length.");
  m.def("spline_product_integral", &spline_product_integral, "factors"_a, "from_"_a, "to"_a, "power"_a,
        py::call_guard<py::gil_scoped_release>(),
        "int_{from_}^{to} x^power f_1(x) ... f_m(x) dx of 1-D spline functions of x (NurbsCurves whose parameter is x),\n"
        "exact: Gauss-Legendre per piece between the factors' knots, as the SplineIntegral conditions.\n"
        "Raises InvalidInput (from_ > to, a range beyond a factor's domain, a rational or vector factor).");
}

void bind_sections(py::module_& m) {
  py::class_<SectionSpec> spec(m, "SectionSpec", "One hull section's numbers (metres, degrees); see fairlines/sections.hpp.");
  spec.def(py::init<>());
  // A given shape is an (m, 2) array of (y, z) points; None or an empty array clears it.
  const auto points = option_docs::for_type<Eigen::MatrixXd>([](auto& cls, const char* name, auto member, const char* doc) {
    cls.def_property(
        name, [member](const SectionSpec& s) { return to_array(s.*member); },
        [member, name](SectionSpec& s, py::handle v) {
          const bool empty = v.is_none() || (py::len(v) == 0);
          s.*member = empty ? Eigen::MatrixXd() : matrix(v, name, 2);
        },
        doc);
  });
  option_docs::bind_fields(spec, points);
  py::class_<SectionDesign>(m, "SectionDesign", "A designed section and what was needed to build it.")
      .def_readonly("curve", &SectionDesign::curve)
      .def_readonly("shape", &SectionDesign::shape, "shape knob used")
      .def_readonly("fullness", &SectionDesign::fullness, "area below T / (y_dwl (T - z_keel)) achieved")
      .def_readonly("fullness_min", &SectionDesign::fullness_min)
      .def_readonly("fullness_max", &SectionDesign::fullness_max)
      .def_readonly("area_met", &SectionDesign::area_met, "false when the asked area lies outside what the family holds here")
      .def_readonly("immersion", &SectionDesign::immersion, "weight of the waterline and area conditions (0 .. 1)")
      .def_readonly("flat_kept", &SectionDesign::flat_kept, "share of the asked flat of bottom kept (< 1: the asked area is too fine for all of it)");
  m.def("design_section", &design_section, "spec"_a, py::call_guard<py::gil_scoped_release>(),
        "One section: its template (deck, waterline and keel points, rounded corners) sampled on the shared knot vector.\n"
        "Raises InvalidInput (malformed numbers) or InfeasibleFormParameters (no one-curve section through the points).");
  m.def("design_sections", &design_sections, "specs"_a, py::call_guard<py::gil_scoped_release>(),
        "design_section for each spec, in order; all on section_knot_vector(n_control).");
  m.def("section_fullness_range", &section_fullness_range, "spec"_a, py::call_guard<py::gil_scoped_release>(),
        "(least, largest) fullness area / (y_dwl (T - z_keel)) the section family holds here (NaN: not immersed);\n"
        "the least narrows the flat of bottom as far as it goes.");
  m.def("section_fullness_bounds", [](const SectionSpec& spec) {
          const FullnessBounds f = section_fullness_bounds(spec);
          return std::tuple{f.least_whole_flat, f.least, f.largest};
        }, "spec"_a, py::call_guard<py::gil_scoped_release>(),
        "(least keeping the whole flat of bottom, least, largest) fullness the section family holds here (NaN: not immersed).");
  m.def("section_knot_vector", [](int n) { return to_array(section_knot_vector(n)); }, "n_control"_a,
        "The clamped uniform cubic knot vector every section of a hull shares.");
  m.attr("END_BAND") = kEndBand;
  m.attr("MAX_SHAPE_KNOB") = kMaxShapeKnob;
}

}  // namespace

void bind_design(py::module_& m) {
  bind_spline_design(m);
  bind_sections(m);
}

}  // namespace fairlines
