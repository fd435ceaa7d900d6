// Python bindings of the form-parameter curve solver (private functions; the public
// API is fairlines.design_curve in python/fairlines/form_curve.py).
#include <cmath>
#include <string>

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "convert.hpp"
#include "fairlines/errors.hpp"
#include "fairlines/form_curve.hpp"

namespace py = pybind11;
using namespace pybind11::literals;

namespace fairlines {

namespace {

double number(const py::handle& obj, const std::string& what) {
  if (py::isinstance<py::bool_>(obj) || !(py::isinstance<py::float_>(obj) || py::isinstance<py::int_>(obj) ||
                                          py::hasattr(obj, "__float__")))
    throw InvalidInput(what + " must be a number, got " + std::string(py::str(py::type::of(obj).attr("__name__"))));
  return obj.cast<double>();
}

FormCurveRequest make_request(const py::dict& params, int n_control, int degree, int dim, const py::dict& fairness,
                              const py::list& points, const py::dict& bounds, const py::dict& options,
                              const py::handle& tangent_start, const py::handle& tangent_end,
                              const py::handle& initial) {
  FormCurveRequest r;
  r.dim = dim;
  r.n_control = n_control;
  r.degree = degree;
  for (auto [k, v] : params) {
    const std::string key = py::str(k);
    r.params[key] = number(v, "form parameter " + key);
  }
  for (auto [k, v] : fairness) {
    const std::string key = py::str(k);
    const double val = number(v, "fairness weight " + key);
    if (key == "e1") r.fairness.e1 = val;
    else if (key == "e2") r.fairness.e2 = val;
    else if (key == "e3") r.fairness.e3 = val;
    else if (key == "length" || key == "s" || key == "S") r.fairness.length = val;
    else throw InvalidInput("unknown fairness weight '" + key + "'; expected e1, e2, e3 or length");
  }
  for (size_t j = 0; j < points.size(); ++j) {
    const py::tuple item = points[j].cast<py::tuple>();
    FormPoint fp;
    const std::string nm = "points[" + std::to_string(j) + "]";
    fp.position = py_convert::vector(item[0], nm.c_str());
    fp.weight = number(item[1], nm + " weight");
    r.points.push_back(fp);
  }
  for (auto [k, v] : bounds) {
    const std::string key = py::str(k);
    if (key == "monotone_axis") r.bounds.monotone_axis = v.cast<int>();
    else if (key == "y_nonnegative") r.bounds.y_nonnegative = v.cast<bool>();
    else if (key == "min_end_speed") r.bounds.min_end_speed = number(v, "bounds min_end_speed");
    else throw InvalidInput("unknown bound '" + key + "'");
  }
  for (auto [k, v] : options) {
    const std::string key = py::str(k);
    if (key == "tolerance") r.options.tolerance = number(v, "tolerance");
    else if (key == "max_iterations") r.options.max_iterations = v.cast<int>();
    else if (key == "continuation") r.options.continuation = v.cast<bool>();
    else if (key == "multistart") r.options.multistart = v.cast<int>();
    else if (key == "seed") r.options.seed = v.cast<unsigned>();
    else throw InvalidInput("unknown solver option '" + key + "'");
  }
  if (!tangent_start.is_none()) r.tangent_start = py_convert::vector(tangent_start, "tangent_start");
  if (!tangent_end.is_none()) r.tangent_end = py_convert::vector(tangent_end, "tangent_end");
  if (!initial.is_none()) r.initial_control_points = py_convert::matrix(initial, "initial_control_points", dim);
  return r;
}

}  // namespace

void bind_form_curve(py::module_& m) {
  m.def(
      "_design_form_curve",
      [](const py::dict& params, int n_control, int degree, int dim, const py::dict& fairness, const py::list& points,
         const py::dict& bounds, const py::dict& options, const py::handle& tangent_start,
         const py::handle& tangent_end, const py::handle& initial) {
        const FormCurveRequest req = make_request(params, n_control, degree, dim, fairness, points, bounds, options,
                                                  tangent_start, tangent_end, initial);
        FormCurveResult res;
        {
          py::gil_scoped_release release;
          res = design_form_curve(req);
        }
        py::dict out;
        out["degree"] = res.degree;
        out["knots"] = py_convert::to_array(res.knots);
        out["control_points"] = py_convert::to_array(res.control_points);
        out["achieved"] = res.achieved;
        out["residuals"] = res.residuals;
        out["point_parameters"] = py_convert::to_array(res.point_parameters);
        out["point_residuals"] = py_convert::to_array(res.point_residuals);
        out["fairness"] = py::dict("E1"_a = res.fairness.E1, "E2"_a = res.fairness.E2, "E3"_a = res.fairness.E3,
                                   "length"_a = res.fairness.length);
        out["objective"] = res.objective;
        out["iterations"] = res.iterations;
        out["continuation_steps"] = res.continuation_steps;
        out["converged"] = res.converged;
        return out;
      },
      "params"_a, "n_control"_a, "degree"_a, "dim"_a, "fairness"_a, "points"_a, "bounds"_a, "options"_a,
      "tangent_start"_a = py::none(), "tangent_end"_a = py::none(), "initial_control_points"_a = py::none(),
      "Form-parameter curve solver (private; use fairlines.design_curve).");

  m.def(
      "form_parameters_of",
      [](int degree, const py::handle& cps) {
        return form_parameters_of(degree, py_convert::matrix(cps, "control_points"));
      },
      "degree"_a, "control_points"_a,
      "Every form parameter (xB.., alphaB/E in degrees, CAB/CAE, Area, xC, yC) of the clamped uniform "
      "B-spline with these control points (n x 2 or n x 3).");

  m.def(
      "fairness_of",
      [](int degree, const py::handle& cps) {
        const FairnessMeasures f = fairness_of(degree, py_convert::matrix(cps, "control_points"));
        return py::dict("E1"_a = f.E1, "E2"_a = f.E2, "E3"_a = f.E3, "length"_a = f.length);
      },
      "degree"_a, "control_points"_a,
      "E1, E2, E3 (int |C^(k)|^2 dt over t in [0,1]) and arc length of a clamped uniform B-spline.");

  m.def(
      "form_parameter_names", [] { return form_parameter_names(); },
      "Names accepted as form parameters.");

  m.def(
      "_form_curve_derivatives",
      [](const py::dict& params, int n_control, int degree, int dim, const py::dict& fairness, const py::list& points,
         const py::handle& z, const py::handle& lambda) {
        const FormCurveRequest req = make_request(params, n_control, degree, dim, fairness, points, py::dict(),
                                                  py::dict(), py::none(), py::none(), py::none());
        const auto d = form_curve_detail::evaluate_problem(req, py_convert::vector(z, "z"),
                                                           lambda.is_none() ? Eigen::VectorXd()
                                                                            : py_convert::vector(lambda, "lambda"));
        return py::dict("c"_a = py_convert::to_array(d.c), "J"_a = py_convert::to_array(d.J),
                        "HL"_a = py_convert::to_array(d.HL), "f"_a = d.f, "g"_a = py_convert::to_array(d.g),
                        "H"_a = py_convert::to_array(d.H), "names"_a = d.names);
      },
      "params"_a, "n_control"_a, "degree"_a, "dim"_a, "fairness"_a, "points"_a, "z"_a, "lambda"_a = py::none(),
      "Testing hook: constraints, Jacobian, sum lambda_i Hess c_i, objective, gradient and Hessian at z.");
}

}  // namespace fairlines
