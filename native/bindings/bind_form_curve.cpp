// Python bindings of the form-parameter curve solver. The request and its option structs
// are bound once (their defaults live in fairlines/form_curve.hpp); the public API is
// fairlines.design_curve in python/fairlines/form_curve.py.
#include <cmath>
#include <string>

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "convert.hpp"
#include "option_docs.hpp"
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

std::map<std::string, double> form_params(const py::dict& params) {
  std::map<std::string, double> out;
  for (auto [k, v] : params) {
    if (!py::isinstance<py::str>(k))
      throw InvalidInput("form parameter name " + py::repr(k).cast<std::string>() + " is not a string");
    const std::string key = py::str(k);
    out[key] = number(v, "form parameter " + key);
  }
  return out;
}

// Offset points: a list of (position, weight) pairs, weight inf = interpolate.
std::vector<FormPoint> form_points(const py::list& points) {
  std::vector<FormPoint> out;
  for (size_t j = 0; j < points.size(); ++j) {
    const std::string nm = "points[" + std::to_string(j) + "]";
    if (!py::isinstance<py::tuple>(points[j]) || py::len(points[j]) != 2)
      throw InvalidInput(nm + " must be a pair (position, weight)");
    const py::tuple item = points[j].cast<py::tuple>();
    FormPoint fp;
    fp.position = py_convert::vector(item[0], nm.c_str());
    fp.weight = number(item[1], nm + " weight");
    out.push_back(fp);
  }
  return out;
}

// Fairness weights from a dict {e1, e2, e3, length}; unlisted weights are zero.
FairnessWeights fairness_from(const py::dict& fairness) {
  FairnessWeights w{0.0, 0.0, 0.0, 0.0};
  for (auto [k, v] : fairness) {
    const std::string key = py::str(k);
    const double val = number(v, "fairness weight " + key);
    if (key == "e1") w.e1 = val;
    else if (key == "e2") w.e2 = val;
    else if (key == "e3") w.e3 = val;
    else if (key == "length") w.length = val;
    else throw InvalidInput("unknown fairness weight '" + key + "'; expected e1, e2, e3 or length");
  }
  return w;
}

void set_optional_vectors(FormCurveRequest& r, const py::handle& tangent_start, const py::handle& tangent_end,
                          const py::handle& initial) {
  if (!tangent_start.is_none()) r.tangent_start = py_convert::vector(tangent_start, "tangent_start");
  if (!tangent_end.is_none()) r.tangent_end = py_convert::vector(tangent_end, "tangent_end");
  if (!initial.is_none()) r.initial_control_points = py_convert::matrix(initial, "initial_control_points", r.dim);
}

py::dict result_dict(const FormCurveResult& res) {
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
}

/// The solver (private: fairlines.design_curve checks and fills the request).
void bind_solver(py::module_& m) {
  m.def(
      "_design_form_curve",
      [](FormCurveRequest req, const py::list& points, const py::handle& tangent_start, const py::handle& tangent_end,
         const py::handle& initial) {
        req.points = form_points(points);
        set_optional_vectors(req, tangent_start, tangent_end, initial);
        FormCurveResult res;
        {
          py::gil_scoped_release release;
          res = design_form_curve(req);
        }
        return result_dict(res);
      },
      "request"_a, py::kw_only(), "points"_a = py::list(), "tangent_start"_a = py::none(), "tangent_end"_a = py::none(),
      "initial_control_points"_a = py::none(), "Form-parameter curve solver (private; use fairlines.design_curve).");
}

/// The form parameters and fairness measures of given control points, and the parameter names.
void bind_measures(py::module_& m) {
  m.def(
      "form_parameters_of",
      [](py::handle degree, const py::handle& cps) {
        return form_parameters_of(py_convert::checked_int(degree, "degree"), py_convert::matrix(cps, "control_points"));
      },
      "degree"_a, "control_points"_a,
      "Every form parameter (xB.., alphaB/E in degrees, CAB/CAE, Area, xC, yC) of the clamped uniform "
      "B-spline with these control points (n x 2 or n x 3).");

  m.def(
      "fairness_of",
      [](py::handle degree, const py::handle& cps) {
        const FairnessMeasures f = fairness_of(py_convert::checked_int(degree, "degree"), py_convert::matrix(cps, "control_points"));
        return py::dict("E1"_a = f.E1, "E2"_a = f.E2, "E3"_a = f.E3, "length"_a = f.length);
      },
      "degree"_a, "control_points"_a,
      "E1, E2, E3 (int |C^(k)|^2 dt over t in [0,1]) and arc length of a clamped uniform B-spline.");

  m.def(
      "form_parameter_names", [] { return form_parameter_names(); },
      "Names accepted as form parameters.");
}

/// The tests compare the problem's analytic derivatives with finite differences through this.
void bind_problem_derivatives(py::module_& m) {
  m.def(
      "_form_curve_derivatives",
      [](const py::dict& params, py::handle n_control, py::handle degree, py::handle dim, const py::dict& fairness,
         const py::list& points, const py::handle& z, const py::handle& lambda) {
        FormCurveRequest req;
        req.params = form_params(params);
        req.n_control = py_convert::checked_int(n_control, "n_control");
        req.degree = py_convert::checked_int(degree, "degree");
        req.dim = py_convert::checked_int(dim, "dim");
        req.fairness = fairness_from(fairness);
        req.points = form_points(points);
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

/// The request's option structs, bound once with their fields' defaults.
void bind_option_structs(py::module_& m) {
  using option_docs::bind_options;
  bind_options<FairnessWeights>(m, "FairnessWeights", "Weights of the fairness objective (all >= 0, one of e1, e2, e3 > 0).");
  bind_options<FormBounds>(m, "FormBounds", "Conditions on the control polygon that keep a section a section.");
  bind_options<FormSolverOptions>(m, "FormSolverOptions", "Options of the form-parameter solver.");
  bind_options<FormCurveRequest>(m, "FormCurveRequest",
                                 "A form-parameter curve request without its offset points, tangents and start curve.");
}

}  // namespace

void bind_form_curve(py::module_& m) {
  bind_option_structs(m);
  bind_solver(m);
  bind_measures(m);
  bind_problem_derivatives(m);
}

}  // namespace fairlines
