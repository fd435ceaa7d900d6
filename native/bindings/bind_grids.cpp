// Bindings of structured surface grids (python/fairlines/grids.py wraps them).
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "convert.hpp"
#include "option_docs.hpp"
#include "fairlines/grids.hpp"

namespace py = pybind11;
using namespace pybind11::literals;

namespace fairlines {

namespace {

using py_convert::to_array;

py::tuple grid_tuple(const StructuredGrid& g) { return py::make_tuple(g.ni, g.nj, to_array(g.points), to_array(g.params)); }

/// Point distributions along a line, and arc-length parameters on a curve.
void bind_distributions(py::module_& m) {
  py::enum_<Spacing>(m, "Spacing", "How points are spaced along a grid line.")
      .value("uniform", Spacing::Uniform)
      .value("sinh", Spacing::Sinh)
      .value("tanh", Spacing::Tanh)
      .value("tanh_two_sided", Spacing::TanhTwoSided)
      .value("geometric", Spacing::Geometric);
  option_docs::bind_options<Distribution>(m, "Distribution", "A point distribution along a line (see fairlines.grids).");
  m.def(
      "distribute", [](const Distribution& d, double length) { return to_array(distribute(d, length)); }, "distribution"_a,
      "length"_a,
        "Positions (m, 0 .. length) of a distribution's points along a line of `length` metres.");
  m.def(
      "parameters_at_arc_length",
      [](const NurbsCurve& c, py::handle s) { return to_array(parameters_at_arc_length(c, py_convert::vector(s, "s"))); },
      "curve"_a, "s"_a, "Curve parameters at increasing arc lengths s (m from the start).");
}

/// Structured grids on a surface, clustering of its parameter lines, and grid quality.
void bind_surface_grids(py::module_& m) {
  m.def(
      "_surface_grid",
      [](const NurbsSurface& s, const Distribution& du, const Distribution& dv) {
        StructuredGrid g;
        {
          py::gil_scoped_release release;
          g = surface_grid(s, du, dv);
        }
        return grid_tuple(g);
      },
      "surface"_a, "du"_a, "dv"_a);
  m.def(
      "_parameter_grid",
      [](const NurbsSurface& s, py::handle us, py::handle vs) {
        return grid_tuple(parameter_grid(s, py_convert::vector(us, "us"), py_convert::vector(vs, "vs")));
      },
      "surface"_a, "us"_a, "vs"_a);
  m.def(
      "knot_line_parameters",
      [](const NurbsSurface& s, const std::string& dir, int per_span) {
        return to_array(knot_line_parameters(s, parse_direction(dir), per_span));
      },
      "surface"_a, "direction"_a, "per_span"_a, "Knot values of one direction with every span cut into per_span parts.");
  m.def(
      "_cluster_by_knots",
      [](const NurbsSurface& s, const std::string& dir, double at, double spacing, int count, double growth) {
        return cluster_by_knots(s, parse_direction(dir), at, spacing, count, growth);
      },
      "surface"_a, "direction"_a, "at"_a, "spacing"_a, "count"_a, "growth"_a);
  m.def(
      "_cluster_by_weights",
      [](const NurbsSurface& s, const std::string& dir, double ratio) { return cluster_by_weights(s, parse_direction(dir), ratio); },
      "surface"_a, "direction"_a, "ratio"_a);
  m.def(
      "_grid_quality",
      [](py::handle pts, int ni, int nj) {
        const GridQuality q = grid_quality(py_convert::matrix(pts, "points", 3), ni, nj);
        return py::dict("first_min"_a = q.first_min, "first_max"_a = q.first_max, "last_min"_a = q.last_min,
                        "last_max"_a = q.last_max, "first_min_j"_a = q.first_min_j, "first_max_j"_a = q.first_max_j,
                        "last_min_j"_a = q.last_min_j, "last_max_j"_a = q.last_max_j,
                        "max_stretching"_a = q.max_stretching, "max_orthogonality_deg"_a = q.max_orthogonality_deg,
                        "mean_orthogonality_deg"_a = q.mean_orthogonality_deg, "max_skewness"_a = q.max_skewness,
                        "max_aspect_ratio"_a = q.max_aspect_ratio, "degenerate_cells"_a = q.degenerate_cells);
      },
      "points"_a, "ni"_a, "nj"_a);
}

}  // namespace

void bind_grids(py::module_& m) {
  bind_distributions(m);
  bind_surface_grids(m);
}

}  // namespace fairlines
