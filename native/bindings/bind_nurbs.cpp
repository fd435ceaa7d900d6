// Python bindings of the NURBS core, one function per area: knots and basis functions,
// curves, surfaces, volumes, conics and revolutions, fitting.
#include <cmath>
#include <numbers>
#include <type_traits>

#include <Eigen/Dense>

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "convert.hpp"
#include "option_docs.hpp"
#include "fairlines/basis.hpp"
#include "fairlines/conics.hpp"
#include "fairlines/curve.hpp"
#include "fairlines/fitting.hpp"
#include "fairlines/knots.hpp"
#include "fairlines/limits.hpp"
#include "fairlines/surface.hpp"
#include "fairlines/volume.hpp"

namespace py = pybind11;
using namespace pybind11::literals;

namespace fairlines {

using namespace py_convert;

namespace {

// ---- conversions and checks shared by the parts below ------------------------------

Eigen::Vector3d vec3(const py::handle& obj, const char* what) {
  const Eigen::VectorXd v = vector(obj, what);
  if (v.size() != 3) throw InvalidInput(std::string(what) + " has " + std::to_string(v.size()) + " values; expected 3 (x, y, z)");
  return v;
}

/// Derivative order of a Python argument: an integer in [0, limits::kMaxDerivativeOrder].
int checked_order(const py::handle& obj) {
  const int order = checked_int(obj, "order");
  if (order < 0 || order > limits::kMaxDerivativeOrder)
    throw InvalidInput("order is " + std::to_string(order) + "; expected an integer in [0, " +
                       std::to_string(limits::kMaxDerivativeOrder) + "] (the derivative order limit)");
  return order;
}

/// Refuses a result of `count` doubles beyond limits::kMaxResultValues before allocating it.
void check_result_size(double count, const char* what) {
  if (count > static_cast<double>(limits::kMaxResultValues)) {
    std::ostringstream os;
    os << what << " would return " << count << " values; the limit is " << limits::kMaxResultValues
       << " per call: ask for fewer points or split the call";
    throw InvalidInput(os.str());
  }
}

void require_finite_entries(const Eigen::VectorXd& t, const char* what) {
  for (Eigen::Index k = 0; k < t.size(); ++k)
    if (!std::isfinite(t[k]))
      throw InvalidInput(std::string(what) + "[" + std::to_string(k) + "] is not finite; expected a finite parameter");
}

// (nu, nv, 3) control net -> (nu*nv) x 3 plus its dimensions.
Eigen::MatrixXd net(const py::handle& obj, int& nu, int& nv) {
  Array a = as_array(obj, "control_points");
  if (a.ndim() != 3 || a.shape(2) != 3 || a.shape(0) == 0 || a.shape(1) == 0)
    throw InvalidInput("control_points has shape " + shape_of(a) + "; expected (nu, nv, 3)");
  nu = static_cast<int>(a.shape(0));
  nv = static_cast<int>(a.shape(1));
  Eigen::MatrixXd m(static_cast<Eigen::Index>(nu) * nv, 3);
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    for (int c = 0; c < 3; ++c) m(i, c) = a.data()[i * 3 + c];
  return m;
}

Eigen::VectorXd net_weights(const py::handle& obj, int nu, int nv) {
  if (obj.is_none()) return {};
  Array a = as_array(obj, "weights");
  if (a.ndim() != 2 || a.shape(0) != nu || a.shape(1) != nv)
    throw InvalidInput("weights has shape " + shape_of(a) + "; expected (" + std::to_string(nu) + ", " + std::to_string(nv) + ")");
  return Eigen::Map<const Eigen::VectorXd>(a.data(), a.size());
}

py::array_t<double> as_net(const Eigen::MatrixXd& m, int nu, int nv, int comps) {
  py::array_t<double> out(comps == 1 ? std::vector<py::ssize_t>{nu, nv} : std::vector<py::ssize_t>{nu, nv, comps});
  double* d = out.mutable_data();
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    for (int c = 0; c < comps; ++c) d[i * comps + c] = m(i, c);
  return out;
}

NurbsCurve make_curve(const py::handle& degree, const py::handle& knots, const py::handle& cps, const py::handle& weights) {
  return NurbsCurve(checked_int(degree, "degree"), vector(knots, "knots"), matrix(cps, "control_points"),
                    weights.is_none() ? Eigen::VectorXd() : vector(weights, "weights"));
}

NurbsSurface make_surface(const py::handle& du, const py::handle& dv, const py::handle& ku, const py::handle& kv,
                          const py::handle& cps, const py::handle& weights) {
  int nu = 0, nv = 0;
  Eigen::MatrixXd P = net(cps, nu, nv);
  return NurbsSurface(checked_int(du, "degree_u"), checked_int(dv, "degree_v"), vector(ku, "knots_u"),
                      vector(kv, "knots_v"), nu, nv, std::move(P), net_weights(weights, nu, nv));
}

std::string curve_repr(const NurbsCurve& c) {
  std::ostringstream os;
  os << "NurbsCurve(degree=" << c.degree() << ", n_control=" << c.n_control() << ", dim=" << c.dim()
     << (c.is_rational() ? ", rational" : "") << ", domain=[" << c.domain().first << ", " << c.domain().second << "])";
  return os.str();
}

// ---- knots and basis ------------------------------------------------------------------

/// All basis functions and derivatives 0..order at the parameters t: (m, order + 1, n).
py::array_t<double> basis_table(py::handle knots_obj, py::handle degree, py::handle t_obj, py::handle order_obj) {
  const Eigen::VectorXd U = vector(knots_obj, "knots");
  const int p = checked_int(degree, "degree");
  const int order = checked_order(order_obj);
  const int n = static_cast<int>(U.size()) - p - 1;
  validate_knots(U, p, n);
  const Eigen::VectorXd t = vector(t_obj, "t");
  require_finite_entries(t, "t");
  check_result_size(static_cast<double>(t.size()) * (order + 1) * n, "basis_functions");
  py::array_t<double> out({static_cast<py::ssize_t>(t.size()), static_cast<py::ssize_t>(order + 1), static_cast<py::ssize_t>(n)});
  auto r = out.mutable_unchecked<3>();
  Eigen::MatrixXd ders(order + 1, p + 1);
  for (Eigen::Index k = 0; k < t.size(); ++k) {
    const double tk = std::clamp(t[k], U[p], U[n]);
    const int span = find_span(p, U, tk);
    basis_derivatives(span, tk, p, order, U, ders);
    for (int d = 0; d <= order; ++d) {
      for (int i = 0; i < n; ++i) r(k, d, i) = 0.0;
      for (int j = 0; j <= p; ++j) r(k, d, span - p + j) = ders(d, j);
    }
  }
  return out;
}

void bind_knots(py::module_& m) {
  m.def("validate_knots", [](py::handle knots, py::handle degree, py::handle n_control) {
        validate_knots(vector(knots, "knots"), checked_int(degree, "degree"), checked_int(n_control, "n_control"));
      }, "knots"_a, "degree"_a, "n_control"_a,
      "Raise ValueError naming the problem if `knots` is not a valid knot vector for `n_control` control points of `degree`.");
  m.def("clamped_uniform_knots", [](py::handle n, py::handle p, double t0, double t1) {
        return to_array(clamped_uniform_knots(checked_int(n, "n_control"), checked_int(p, "degree"), t0, t1));
      }, "n_control"_a, "degree"_a, "t0"_a = 0.0, "t1"_a = 1.0,
      "Clamped (open) uniform knot vector, n_control + degree + 1 values on [t0, t1].");
  m.def("unclamped_uniform_knots", [](py::handle n, py::handle p, double t0, double t1) {
        return to_array(unclamped_uniform_knots(checked_int(n, "n_control"), checked_int(p, "degree"), t0, t1));
      }, "n_control"_a, "degree"_a, "t0"_a = 0.0, "t1"_a = 1.0,
      "Unclamped uniform knot vector whose valid domain [knots[degree], knots[n_control]] is [t0, t1].");
  m.def("parameterize", [](py::handle points, const std::string& method) {
        return to_array(parameterize(matrix(points, "points"), parse_parameterization(method)));
      }, "points"_a, "method"_a = parameterization_name(FitOptions{}.parameterization),
      "Parameters in [0, 1] for (m, dim) points: 'chord', 'centripetal' or 'uniform'.");
  m.def("averaged_knots", [](py::handle params, py::handle p, py::handle n) {
        return to_array(averaged_knots(vector(params, "params"), checked_int(p, "degree"), checked_int(n, "n_control")));
      }, "params"_a, "degree"_a, "n_control"_a, "Clamped knots on [0, 1] by averaging of the data parameters.");
  m.def("hartley_judd_knots", [](py::handle points, py::handle p, py::handle n, const std::string& metric) {
        return to_array(hartley_judd_knots(matrix(points, "points"), checked_int(p, "degree"), checked_int(n, "n_control"),
                                           parse_parameterization(metric)));
      }, "points"_a, "degree"_a, "n_control"_a, "metric"_a = parameterization_name(Parameterization::ChordLength),
      "Clamped knots on [0, 1] by Hartley-Judd (1980): spacings are sums of `degree` chords measured by "
      "'chord' (length), 'centripetal' (sqrt of length) or 'uniform'.");
  m.def("greville_abscissae", [](py::handle knots, py::handle p) {
        return to_array(greville_abscissae(vector(knots, "knots"), checked_int(p, "degree")));
      }, "knots"_a, "degree"_a, "Knot averages, one per control point.");
  m.def("basis_functions", &basis_table, "knots"_a, "degree"_a, "t"_a, "order"_a = 0,
        "All basis functions and derivatives at t: (m, order + 1, n_control) array. "
        "order <= fairlines.limits.MAX_DERIVATIVE_ORDER.");
}

// ---- curves -------------------------------------------------------------------------

py::object curve_points(const NurbsCurve& c, py::handle t) {
  if (is_scalar(t)) return to_array(c.evaluate(vector(t, "t")).row(0).transpose().eval());
  return to_array(c.evaluate(vector(t, "t")));
}

py::object curve_derivatives(const NurbsCurve& c, py::handle t, py::handle order_obj) {
  const int order = checked_order(order_obj);
  const Eigen::VectorXd tv = vector(t, "t");
  check_result_size(static_cast<double>(tv.size()) * (order + 1) * c.dim(), "derivatives");
  const Eigen::MatrixXd D = c.derivatives(tv, order);
  if (is_scalar(t)) return to_array(D);
  py::array_t<double> out({static_cast<py::ssize_t>(tv.size()), static_cast<py::ssize_t>(order + 1), static_cast<py::ssize_t>(c.dim())});
  double* d = out.mutable_data();
  for (Eigen::Index r = 0; r < D.rows(); ++r)
    for (int k = 0; k < c.dim(); ++k) d[r * c.dim() + k] = D(r, k);
  return out;
}

py::object scalar_or_array(const Eigen::VectorXd& values, py::handle t) {
  if (is_scalar(t)) return py::float_(values[0]);
  return to_array(values);
}

void bind_curve_copies(py::class_<NurbsCurve>& cls) {
  cls.def("copy", [](const NurbsCurve& c) { return NurbsCurve(c); })
      .def("__copy__", [](const NurbsCurve& c) { return NurbsCurve(c); })
      .def("__deepcopy__", [](const NurbsCurve& c, py::dict) { return NurbsCurve(c); }, "memo"_a)
      .def("__repr__", &curve_repr)
      .def(py::pickle(
          [](const NurbsCurve& c) { return py::make_tuple(c.degree(), to_array(c.knots()), to_array(c.control_points()), to_array(c.weights())); },
          [](py::tuple t) {
            if (t.size() != 4) throw InvalidInput("NurbsCurve pickle has " + std::to_string(t.size()) + " fields; expected 4");
            return make_curve(t[0], t[1], t[2], t[3]);
          }));
}

void bind_curves(py::module_& m) {
  py::class_<NurbsCurve> cls(m, "NurbsCurve", "A NURBS curve in any dimension (2-D and 3-D in hull work), metres.");
  cls.def(py::init(&make_curve), "degree"_a, "knots"_a, "control_points"_a, "weights"_a = py::none(),
          "degree in [1, fairlines.limits.MAX_DEGREE]; knots: n + degree + 1 non-decreasing values; "
          "control_points: (n, dim); weights: (n,) > 0 or None.")
      .def_property_readonly("degree", &NurbsCurve::degree)
      .def_property_readonly("dim", &NurbsCurve::dim)
      .def_property_readonly("n_control", &NurbsCurve::n_control)
      .def_property_readonly("knots", [](const NurbsCurve& c) { return to_array(c.knots()); })
      .def_property_readonly("control_points", [](const NurbsCurve& c) { return to_array(c.control_points()); })
      .def_property_readonly("weights", [](const NurbsCurve& c) { return to_array(c.weights()); })
      .def_property_readonly("is_rational", &NurbsCurve::is_rational)
      .def_property_readonly("domain", &NurbsCurve::domain)
      .def("evaluate", &curve_points, "t"_a, "Points: (dim,) for a scalar t, (m, dim) for an array of m parameters.")
      .def("__call__", &curve_points, "t"_a)
      .def("derivatives", &curve_derivatives, "t"_a, "order"_a = 1,
           "Derivatives 0..order (order <= fairlines.limits.MAX_DERIVATIVE_ORDER): (order + 1, dim) for a scalar t, "
           "(m, order + 1, dim) for an array.")
      .def("curvature", [](const NurbsCurve& c, py::handle t) { return scalar_or_array(c.curvature(vector(t, "t")), t); },
           "t"_a, "Curvature (1/m): signed in 2-D, (x'y'' - y'x'')/|C'|^3; |C' x C''|/|C'|^3 in 3-D.")
      .def("torsion", [](const NurbsCurve& c, py::handle t) { return scalar_or_array(c.torsion(vector(t, "t")), t); },
           "t"_a, "Torsion (1/m) of a 3-D curve.")
      .def("closest_point", [](const NurbsCurve& c, py::handle p) {
            const auto [t, q] = c.closest_point(vector(p, "point"));
            return py::make_tuple(t, to_array(q));
          }, "point"_a, "Closest point on the curve: (t, point).")
      .def("insert_knot", [](const NurbsCurve& c, double t, py::handle times) { return c.insert_knot(t, checked_int(times, "times")); },
           "t"_a, "times"_a = 1, "New curve with knot t inserted `times` times (up to the degree); same shape.")
      .def("refine_knots", [](const NurbsCurve& c, py::handle X) { return c.refine_knots(vector(X, "new_knots")); },
           "new_knots"_a, "New curve with all `new_knots` inserted; same shape.")
      .def("elevate_degree", [](const NurbsCurve& c, py::handle times) { return c.elevate_degree(checked_int(times, "times")); },
           "times"_a = 1, "New curve of degree + times (at most fairlines.limits.MAX_DEGREE); same shape.")
      .def("split", &NurbsCurve::split_range, "a"_a, "b"_a, "The piece on [a, b] as a clamped curve.")
      .def("set_control_point", [](NurbsCurve& c, py::handle i, py::handle p) { c.set_control_point(checked_int(i, "index"), vector(p, "point")); },
           "index"_a, "point"_a, "Move control point `index` (in place).")
      .def("set_weight", [](NurbsCurve& c, py::handle i, double w) { c.set_weight(checked_int(i, "index"), w); },
           "index"_a, "weight"_a, "Set the weight of control point `index` (> 0, in place).");
  bind_curve_copies(cls);
}

// ---- surfaces -----------------------------------------------------------------------

py::object surface_points(const NurbsSurface& s, py::handle u, py::handle v) {
  const bool scalar = is_scalar(u) && is_scalar(v);
  Array ua = as_array(u, "u"), va = as_array(v, "v");
  if (ua.ndim() > 1 || va.ndim() > 1) throw InvalidInput("u and v must be 1-D arrays; got shapes " + shape_of(ua) + " and " + shape_of(va));
  if (ua.size() != va.size())
    throw InvalidInput("u has " + std::to_string(ua.size()) + " values and v has " + std::to_string(va.size()) + "; expected equal lengths");
  const py::ssize_t m = ua.size();
  if (const py::ssize_t k = first_nonfinite_pair(ua.data(), va.data(), m); k < m)
    throw InvalidInput("parameter pair " + std::to_string(k) + " is not finite; expected finite (u, v)");
  py::array_t<double> out({m, py::ssize_t(3)});
  {
    py::gil_scoped_release release;
    s.evaluate_into(ua.data(), va.data(), m, out.mutable_data());
  }
  if (scalar) return out.attr("reshape")(3);
  return out;
}

py::array_t<double> surface_grid(const NurbsSurface& s, py::handle us, py::handle vs) {
  const Eigen::VectorXd u = vector(us, "us"), v = vector(vs, "vs");
  require_finite_entries(u, "us");
  require_finite_entries(v, "vs");
  check_result_size(3.0 * static_cast<double>(u.size()) * static_cast<double>(v.size()), "evaluate_grid");
  py::array_t<double> out({static_cast<py::ssize_t>(u.size()), static_cast<py::ssize_t>(v.size()), py::ssize_t(3)});
  {
    py::gil_scoped_release release;
    s.evaluate_grid_into(u.data(), u.size(), v.data(), v.size(), out.mutable_data());
  }
  return out;
}

// [S, S_u, S_v] per point from the fast kernel, laid out as D[0,0], D[1,0], D[0,1]; D[1,1] = 0.
void first_derivatives_into(const NurbsSurface& s, const Eigen::VectorXd& uu, const Eigen::VectorXd& vv, double* d) {
  std::vector<double> d1(9 * static_cast<size_t>(uu.size()));
  s.evaluate_first_derivatives_into(uu.data(), vv.data(), uu.size(), d1.data());
  std::fill(d, d + 12 * uu.size(), 0.0);
  for (Eigen::Index k = 0; k < uu.size(); ++k)
    for (int c = 0; c < 3; ++c) {
      d[k * 12 + 0 + c] = d1[9 * k + c];      // (0, 0)
      d[k * 12 + 3 + c] = d1[9 * k + 6 + c];  // (0, 1) = S_v
      d[k * 12 + 6 + c] = d1[9 * k + 3 + c];  // (1, 0) = S_u
    }
}

py::object surface_derivatives(const NurbsSurface& s, py::handle u, py::handle v, py::handle order_obj) {
  const int order = checked_order(order_obj);
  const Eigen::VectorXd uu = vector(u, "u"), vv = vector(v, "v");
  if (uu.size() != vv.size())
    throw InvalidInput("u has " + std::to_string(uu.size()) + " values and v has " + std::to_string(vv.size()) + "; expected equal lengths");
  const py::ssize_t k1 = order + 1;
  check_result_size(3.0 * static_cast<double>(uu.size()) * k1 * k1, "derivatives");
  if (const py::ssize_t k = first_nonfinite_pair(uu.data(), vv.data(), uu.size()); k < uu.size())
    throw InvalidInput("parameter pair " + std::to_string(k) + " is not finite; expected finite (u, v)");
  py::array_t<double> out({static_cast<py::ssize_t>(uu.size()), k1, k1, py::ssize_t(3)});
  double* d = out.mutable_data();
  if (order == 1) {
    first_derivatives_into(s, uu, vv, d);
  } else {
    for (Eigen::Index k = 0; k < uu.size(); ++k) {
      const Eigen::MatrixXd D = s.derivatives(uu[k], vv[k], order);
      for (Eigen::Index r = 0; r < D.rows(); ++r)
        for (int c = 0; c < 3; ++c) d[(k * D.rows() + r) * 3 + c] = D(r, c);
    }
  }
  if (is_scalar(u) && is_scalar(v)) return out.attr("reshape")(k1, k1, 3);
  return out;
}

void bind_surface_queries(py::class_<NurbsSurface>& cls) {
  cls.def("evaluate", &surface_points, "u"_a, "v"_a, "Points at (u_k, v_k): (m, 3), or (3,) for scalars.")
      .def("evaluate_grid", &surface_grid, "us"_a, "vs"_a,
           "Grid of points (len(us), len(vs), 3); basis values reused along grid lines. "
           "3 len(us) len(vs) <= fairlines.limits.MAX_RESULT_VALUES.")
      .def("derivatives", &surface_derivatives, "u"_a, "v"_a, "order"_a = 1,
           "D[k, l] = d^(k+l) S / du^k dv^l for k + l <= order (higher entries 0): (order+1, order+1, 3) for scalars, "
           "(m, order+1, order+1, 3) for arrays.")
      .def("normal", [](const NurbsSurface& s, py::handle u, py::handle v) -> py::object {
            const Eigen::MatrixXd n = s.normal(vector(u, "u"), vector(v, "v"));
            if (is_scalar(u) && is_scalar(v)) return to_array(Eigen::VectorXd(n.row(0).transpose()));
            return to_array(n);
          }, "u"_a, "v"_a, "Unit normals S_u x S_v / |S_u x S_v|: (m, 3) or (3,).")
      .def("curvature", [](const NurbsSurface& s, py::handle u, py::handle v) -> py::object {
            const auto [K, H] = s.curvature(vector(u, "u"), vector(v, "v"));
            if (is_scalar(u) && is_scalar(v)) return py::make_tuple(K[0], H[0]);
            return py::make_tuple(to_array(K), to_array(H));
          }, "u"_a, "v"_a,
          "(gaussian 1/m^2, mean 1/m) curvature; mean > 0 where the surface bends toward its normal. At a "
          "degenerate point (a pole) the limit from the interior; InvalidInput where there is none (a cone apex).")
      .def("closest_point", [](const NurbsSurface& s, py::handle p) {
            const auto [u, v, q] = s.closest_point(vec3(p, "point"));
            return py::make_tuple(u, v, to_array(Eigen::VectorXd(q)));
          }, "point"_a, "Closest point on the surface: (u, v, point).")
      .def("closest_points", [](const NurbsSurface& s, py::handle points, py::handle u0, py::handle v0) {
            const Eigen::MatrixXd P = matrix(points, "points", 3);
            const bool local = !u0.is_none() || !v0.is_none();
            const Eigen::VectorXd a = local ? vector(u0, "u0") : Eigen::VectorXd(), b = local ? vector(v0, "v0") : Eigen::VectorXd();
            std::tuple<Eigen::VectorXd, Eigen::VectorXd, Eigen::MatrixXd> r;
            {
              py::gil_scoped_release release;
              r = local ? s.closest_points(P, a, b) : s.closest_points(P);
            }
            return py::make_tuple(to_array(std::get<0>(r)), to_array(std::get<1>(r)), to_array(std::get<2>(r)));
          }, "points"_a, "u0"_a = py::none(), "v0"_a = py::none(),
          "Closest points of points (m, 3). Without u0, v0: closest_point's global search for each (the\n"
          "surface's span-patch boxes built once). With u0, v0 (m,): local Newton from each start, never\n"
          "moving away from the point. Returns (u (m,), v (m,), points (m, 3)). Raises InvalidInput for bad shapes.")
      .def("iso_curve", [](const NurbsSurface& s, const std::string& dir, double t) { return s.iso_curve(parse_direction(dir), t); },
           "direction"_a, "t"_a, "'u': the curve u = t (running in v); 'v': the curve v = t.");
}

void bind_surface_edits(py::class_<NurbsSurface>& cls) {
  cls.def("insert_knot", [](const NurbsSurface& s, const std::string& dir, double t, py::handle times) {
        return s.insert_knot(parse_direction(dir), t, checked_int(times, "times"));
      }, "direction"_a, "t"_a, "times"_a = 1, "New surface with knot t inserted in direction 'u' or 'v'; same shape.")
      .def("refine_knots", [](const NurbsSurface& s, const std::string& dir, py::handle X) {
            return s.refine_knots(parse_direction(dir), vector(X, "new_knots"));
          }, "direction"_a, "new_knots"_a)
      .def("elevate_degree", [](const NurbsSurface& s, const std::string& dir, py::handle times) {
            return s.elevate_degree(parse_direction(dir), checked_int(times, "times"));
          }, "direction"_a, "times"_a = 1,
          "New surface with the degree in 'u' or 'v' raised (at most fairlines.limits.MAX_DEGREE); same shape.")
      .def("set_control_point", [](NurbsSurface& s, py::handle i, py::handle j, py::handle p) {
            s.set_control_point(checked_int(i, "i"), checked_int(j, "j"), vec3(p, "point"));
          }, "i"_a, "j"_a, "point"_a)
      .def("set_weight", [](NurbsSurface& s, py::handle i, py::handle j, double w) { s.set_weight(checked_int(i, "i"), checked_int(j, "j"), w); },
           "i"_a, "j"_a, "weight"_a)
      .def("copy", [](const NurbsSurface& s) { return NurbsSurface(s); })
      .def("__copy__", [](const NurbsSurface& s) { return NurbsSurface(s); })
      .def("__deepcopy__", [](const NurbsSurface& s, py::dict) { return NurbsSurface(s); }, "memo"_a)
      .def("__repr__", [](const NurbsSurface& s) {
            std::ostringstream os;
            os << "NurbsSurface(degrees=(" << s.degree_u() << ", " << s.degree_v() << "), shape=(" << s.nu() << ", " << s.nv() << ")"
               << (s.is_rational() ? ", rational" : "") << ")";
            return os.str();
          })
      .def(py::pickle(
          [](const NurbsSurface& s) {
            return py::make_tuple(s.degree_u(), s.degree_v(), to_array(s.knots_u()), to_array(s.knots_v()),
                                  as_net(s.control_points(), s.nu(), s.nv(), 3), as_net(s.weights(), s.nu(), s.nv(), 1));
          },
          [](py::tuple t) {
            if (t.size() != 6) throw InvalidInput("NurbsSurface pickle has " + std::to_string(t.size()) + " fields; expected 6");
            return make_surface(t[0], t[1], t[2], t[3], t[4], t[5]);
          }));
}

void bind_surfaces(py::module_& m) {
  py::class_<NurbsSurface> cls(m, "NurbsSurface", "A tensor-product NURBS surface, metres.");
  cls.def(py::init(&make_surface), "degree_u"_a, "degree_v"_a, "knots_u"_a, "knots_v"_a, "control_points"_a,
          "weights"_a = py::none(), "control_points: (nu, nv, 3); weights: (nu, nv) > 0 or None.")
      .def_property_readonly("degree_u", &NurbsSurface::degree_u)
      .def_property_readonly("degree_v", &NurbsSurface::degree_v)
      .def_property_readonly("knots_u", [](const NurbsSurface& s) { return to_array(s.knots_u()); })
      .def_property_readonly("knots_v", [](const NurbsSurface& s) { return to_array(s.knots_v()); })
      .def_property_readonly("shape", [](const NurbsSurface& s) { return py::make_tuple(s.nu(), s.nv()); })
      .def_property_readonly("control_points", [](const NurbsSurface& s) { return as_net(s.control_points(), s.nu(), s.nv(), 3); })
      .def_property_readonly("weights", [](const NurbsSurface& s) { return as_net(s.weights(), s.nu(), s.nv(), 1); })
      .def_property_readonly("is_rational", &NurbsSurface::is_rational)
      .def_property_readonly("domain_u", &NurbsSurface::domain_u)
      .def_property_readonly("domain_v", &NurbsSurface::domain_v);
  bind_surface_queries(cls);
  bind_surface_edits(cls);
}

// ---- volumes ------------------------------------------------------------------------

NurbsVolume make_volume(py::handle degrees, py::sequence knots, py::handle cps, py::handle weights) {
  if (py::len(degrees) != 3 || py::len(knots) != 3) throw InvalidInput("degrees and knots must each have 3 entries (s, t, r)");
  Array a = as_array(cps, "control_points");
  if (a.ndim() != 4 || a.shape(3) != 3) throw InvalidInput("control_points has shape " + shape_of(a) + "; expected (ns, nt, nr, 3)");
  std::array<int, 3> counts{static_cast<int>(a.shape(0)), static_cast<int>(a.shape(1)), static_cast<int>(a.shape(2))};
  Eigen::MatrixXd P(a.size() / 3, 3);
  for (Eigen::Index i = 0; i < P.rows(); ++i) for (int c = 0; c < 3; ++c) P(i, c) = a.data()[i * 3 + c];
  Eigen::VectorXd W;
  if (!weights.is_none()) {
    Array w = as_array(weights, "weights");
    if (w.ndim() != 3 || w.shape(0) != counts[0] || w.shape(1) != counts[1] || w.shape(2) != counts[2])
      throw InvalidInput("weights has shape " + shape_of(w) + "; expected (ns, nt, nr)");
    W = Eigen::Map<const Eigen::VectorXd>(w.data(), w.size());
  }
  const py::sequence dg = py::reinterpret_borrow<py::sequence>(degrees);
  std::array<int, 3> deg{checked_int(dg[0], "degrees[0]"), checked_int(dg[1], "degrees[1]"), checked_int(dg[2], "degrees[2]")};
  std::array<Eigen::VectorXd, 3> kv{vector(knots[0], "knots[0]"), vector(knots[1], "knots[1]"), vector(knots[2], "knots[2]")};
  return NurbsVolume(deg, kv, counts, P, W);
}

void bind_volumes(py::module_& m) {
  py::class_<NurbsVolume>(m, "NurbsVolume", "A trivariate NURBS volume (free-form deformation lattice), metres.")
      .def(py::init([](py::handle degrees, py::sequence knots, py::handle cps, py::handle weights) {
             if (!py::isinstance<py::sequence>(degrees)) throw InvalidInput("degrees must be a sequence of 3 integers (s, t, r)");
             return make_volume(degrees, knots, cps, weights);
           }), "degrees"_a, "knots"_a, "control_points"_a, "weights"_a = py::none())
      .def("evaluate", [](const NurbsVolume& v, py::handle s, py::handle t, py::handle r) -> py::object {
            const Eigen::MatrixXd out = v.evaluate(vector(s, "s"), vector(t, "t"), vector(r, "r"));
            if (is_scalar(s) && is_scalar(t) && is_scalar(r)) return to_array(Eigen::VectorXd(out.row(0).transpose()));
            return to_array(out);
          }, "s"_a, "t"_a, "r"_a, "Points at (s_k, t_k, r_k): (m, 3).")
      .def("derivatives", [](const NurbsVolume& vol, py::handle s, py::handle t, py::handle r) -> py::object {
            const Eigen::MatrixXd D = vol.derivatives(vector(s, "s"), vector(t, "t"), vector(r, "r"));
            const py::ssize_t m = D.rows() / 4;
            py::array_t<double> out({m, py::ssize_t(4), py::ssize_t(3)});
            double* d = out.mutable_data();
            for (Eigen::Index i = 0; i < D.rows(); ++i) for (int c = 0; c < 3; ++c) d[i * 3 + c] = D(i, c);
            if (is_scalar(s) && is_scalar(t) && is_scalar(r)) return out.attr("reshape")(4, 3);
            return out;
          }, "s"_a, "t"_a, "r"_a, "Point and first partials [V, dV/ds, dV/dt, dV/dr]: (m, 4, 3), or (4, 3) for scalars.")
      .def_property_readonly("degrees", &NurbsVolume::degrees)
      .def_property_readonly("shape", &NurbsVolume::counts);
}

// ---- conics and revolution ----------------------------------------------------------

Eigen::Vector3d lift(const Eigen::VectorXd& c, const char* what) {
  if (c.size() == 2) return Eigen::Vector3d(c[0], c[1], 0.0);
  if (c.size() != 3) throw InvalidInput(std::string(what) + " has " + std::to_string(c.size()) + " values; expected 2 or 3");
  return Eigen::Vector3d(c);
}

// A curve built in 3-D returned as a 2-D curve when its centre was given in 2-D.
NurbsCurve planar_if(const NurbsCurve& c, bool planar) {
  if (!planar) return c;
  return NurbsCurve(c.degree(), c.knots(), c.control_points().leftCols(2), c.weights());
}

NurbsCurve make_arc(py::handle center, double radius, double start_angle, double end_angle, py::handle normal, py::handle x_axis) {
  const Eigen::VectorXd c = vector(center, "center");
  const Eigen::Vector3d n = vec3(normal, "normal").normalized();
  Eigen::Vector3d X;
  if (x_axis.is_none()) {
    const Eigen::Vector3d trial = (std::abs(n.x()) < 0.9) ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    X = (trial - trial.dot(n) * n).normalized();
  } else {
    X = vec3(x_axis, "x_axis");
  }
  return planar_if(arc(lift(c, "center"), X, n.cross(X.normalized()), radius, start_angle, end_angle), c.size() == 2);
}

void bind_conics(py::module_& m) {
  m.def("circle", [](py::handle center, double radius, py::handle normal) {
        const Eigen::VectorXd c = vector(center, "center");
        return planar_if(circle(lift(c, "center"), radius, vec3(normal, "normal")), c.size() == 2);
      }, "center"_a, "radius"_a, "normal"_a = py::make_tuple(0.0, 0.0, 1.0),
      "Exact full circle (degree 2, 9 control points). A 2-D center gives a 2-D curve.");
  m.def("arc", &make_arc, "center"_a, "radius"_a, "start_angle"_a, "end_angle"_a, "normal"_a = py::make_tuple(0.0, 0.0, 1.0),
        "x_axis"_a = py::none(),
        "Exact circular arc, angles in radians from x_axis toward normal x x_axis (0 < end - start <= 2 pi).");
  m.def("ellipse", [](py::handle center, py::handle a, py::handle b) {
        const Eigen::VectorXd c = vector(center, "center");
        return planar_if(ellipse(lift(c, "center"), lift(vector(a, "semi_axis_a"), "semi_axis_a"),
                                 lift(vector(b, "semi_axis_b"), "semi_axis_b")), c.size() == 2);
      }, "center"_a, "semi_axis_a"_a, "semi_axis_b"_a, "Exact ellipse; the semi-axis vectors give directions and lengths (metres).");
  m.def("revolve", [](const NurbsCurve& profile, py::handle axis_point, py::handle axis_dir, double angle) {
        return revolve(profile, vec3(axis_point, "axis_point"), vec3(axis_dir, "axis_dir"), angle);
      }, "profile"_a, "axis_point"_a, "axis_dir"_a, "angle"_a = 2.0 * std::numbers::pi,
      "Surface of revolution of a 3-D profile about an axis, angle in radians; u runs around the axis.");
  m.def("cylinder", [](py::handle base, py::handle axis_dir, double radius, double height) {
        return cylinder(vec3(base, "base"), vec3(axis_dir, "axis_dir"), radius, height);
      }, "base"_a, "axis_dir"_a, "radius"_a, "height"_a, "Exact cylinder (metres).");
  m.def("sphere", [](py::handle center, double radius) { return sphere(vec3(center, "center"), radius); },
        "center"_a, "radius"_a, "Exact sphere (metres).");
}

// ---- fitting ------------------------------------------------------------------------

FitOptions fit_options(const py::handle& degree, const py::handle& n_control, const std::string& param,
                       const std::string& knots) {
  FitOptions o;
  o.degree = checked_int(degree, "degree");
  o.n_control = n_control.is_none() ? 0 : checked_int(n_control, "n_control");
  if (!n_control.is_none() && o.n_control < 1)
    throw InvalidInput("n_control is " + std::to_string(o.n_control) + "; expected None (interpolate) or an integer >= degree + 1");
  o.parameterization = parse_parameterization(param);
  o.knot_method = parse_knot_method(knots);
  return o;
}

SurfaceFit fit_grid(py::handle grid, const FitOptions& ou, const FitOptions& ov) {
  Array a = as_array(grid, "grid");
  if (a.ndim() != 3 || a.shape(2) != 3) throw InvalidInput("grid has shape " + shape_of(a) + "; expected (rows, cols, 3)");
  const int rows = static_cast<int>(a.shape(0)), cols = static_cast<int>(a.shape(1));
  Eigen::MatrixXd G(static_cast<Eigen::Index>(rows) * cols, 3);
  for (Eigen::Index i = 0; i < G.rows(); ++i) for (int c = 0; c < 3; ++c) G(i, c) = a.data()[i * 3 + c];
  py::gil_scoped_release release;
  return fit_surface(G, rows, cols, ou, ov);
}

void bind_fit_results(py::module_& m) {
  py::class_<CurveFit>(m, "CurveFit", "A fitted curve and its deviation from the data (metres).")
      .def_readonly("curve", &CurveFit::curve)
      .def_property_readonly("params", [](const CurveFit& f) { return to_array(f.params); })
      .def_readonly("max_deviation", &CurveFit::max_deviation)
      .def_readonly("rms_deviation", &CurveFit::rms_deviation)
      .def("__repr__", [](const CurveFit& f) {
        std::ostringstream os;
        os << "CurveFit(" << curve_repr(f.curve) << ", max_deviation=" << f.max_deviation << ", rms_deviation=" << f.rms_deviation << ")";
        return os.str();
      });
  py::class_<SurfaceFit>(m, "SurfaceFit", "A fitted surface and its deviation from the grid (metres).")
      .def_readonly("surface", &SurfaceFit::surface)
      .def_property_readonly("params_u", [](const SurfaceFit& f) { return to_array(f.params_u); })
      .def_property_readonly("params_v", [](const SurfaceFit& f) { return to_array(f.params_v); })
      .def_readonly("max_deviation", &SurfaceFit::max_deviation)
      .def_readonly("rms_deviation", &SurfaceFit::rms_deviation)
      .def("__repr__", [](const SurfaceFit& f) {
        std::ostringstream os;
        os << "SurfaceFit(shape=(" << f.surface.nu() << ", " << f.surface.nv() << "), max_deviation=" << f.max_deviation
           << ", rms_deviation=" << f.rms_deviation << ")";
        return os.str();
      });
}

void bind_fit_options(py::module_& m) {
  py::class_<FitOptions> c(m, "FitOptions", "Options of fit_curve and fit_surface (one direction); the defaults of both.");
  c.def(py::init<>());
  using option_docs::by_name;
  option_docs::bind_fields(c, by_name(parameterization_name, parse_parameterization),
                           by_name(knot_method_name, parse_knot_method));
}

void bind_fitting(py::module_& m) {
  bind_fit_options(m);
  bind_fit_results(m);
  // Defaults come from FitOptions (fitting.hpp) so they live in one place.
  const FitOptions d;
  m.def("fit_curve", [](py::handle points, py::handle degree, py::handle n_control, const std::string& param, const std::string& knots) {
        const FitOptions o = fit_options(degree, n_control, param, knots);
        const Eigen::MatrixXd P = matrix(points, "points");
        py::gil_scoped_release release;
        return fit_curve(P, o);
      }, "points"_a, "degree"_a = d.degree, "n_control"_a = py::none(), "parameterization"_a = parameterization_name(d.parameterization),
      "knots"_a = knot_method_name(d.knot_method),
      "Fit (m, dim) points: n_control None interpolates, fewer control points approximate (ends interpolated). "
      "m <= fairlines.limits.MAX_FIT_POINTS.");
  m.def("fit_surface", [](py::handle grid, py::handle du, py::handle dv, py::handle ncu, py::handle ncv, const std::string& param,
                          const std::string& knots) {
        return fit_grid(grid, fit_options(du, ncu, param, knots), fit_options(dv, ncv, param, knots));
      }, "grid"_a, "degree_u"_a = d.degree, "degree_v"_a = d.degree, "n_control_u"_a = py::none(), "n_control_v"_a = py::none(),
      "parameterization"_a = parameterization_name(d.parameterization), "knots"_a = knot_method_name(d.knot_method),
      "Fit a (rows, cols, 3) point grid; u runs over rows, v over columns; rows, cols <= fairlines.limits.MAX_FIT_POINTS.");
}

void bind_limits(py::module_& m) {
  py::module_ lim = m.def_submodule("limits", "Sizes and orders beyond which calls raise InvalidInput (fairlines/limits.hpp).");
  lim.attr("MAX_DEGREE") = limits::kMaxDegree;
  lim.attr("MAX_DERIVATIVE_ORDER") = limits::kMaxDerivativeOrder;
  lim.attr("MAX_CONTROL_POINTS") = limits::kMaxControlPoints;
  lim.attr("MAX_RESULT_VALUES") = limits::kMaxResultValues;
  lim.attr("MAX_FIT_POINTS") = limits::kMaxFitPoints;
  lim.attr("MAX_FORM_CURVE_CONTROL_POINTS") = limits::kMaxFormCurveControlPoints;
  lim.attr("MAX_FORM_CURVE_POINTS") = limits::kMaxFormCurvePoints;
  lim.attr("MAX_FORM_CURVE_ITERATIONS") = limits::kMaxFormCurveIterations;
  lim.attr("MAX_FORM_CURVE_MULTISTART") = limits::kMaxFormCurveMultistart;
  lim.attr("MAX_FORM_CURVE_LENGTH") = limits::kMaxFormCurveLength;
  lim.attr("MAX_ANGLE_DEGREES") = limits::kMaxAngleDegrees;
}

}  // namespace

void bind_nurbs(py::module_& m) {
  bind_limits(m);
  bind_knots(m);
  bind_curves(m);
  bind_surfaces(m);
  bind_volumes(m);
  bind_conics(m);
  bind_fitting(m);
}

}  // namespace fairlines
