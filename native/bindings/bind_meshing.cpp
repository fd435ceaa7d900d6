// Bindings of surface and hull meshing (python/fairlines/meshing.py wraps them).
#include <pybind11/functional.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "convert.hpp"
#include "option_docs.hpp"
#include "fairlines/compose.hpp"
#include "fairlines/meshing.hpp"

namespace py = pybind11;
using namespace pybind11::literals;

namespace fairlines {

namespace {

using py_convert::to_array;

py::tuple mesh_tuple(const SurfaceMesh& m) {
  py::array_t<int> f({m.faces.rows(), static_cast<Eigen::Index>(4)});
  auto r = f.mutable_unchecked<2>();
  for (Eigen::Index i = 0; i < m.faces.rows(); ++i)
    for (int k = 0; k < 4; ++k) r(i, k) = m.faces(i, k);
  py::array_t<int> part(m.face_part.size());
  std::copy(m.face_part.data(), m.face_part.data() + m.face_part.size(), part.mutable_data());
  return py::make_tuple(to_array(m.vertices), f, part, m.parts);
}

SurfaceMesh mesh_from(py::handle vertices, py::handle faces) {
  SurfaceMesh m;
  m.vertices = py_convert::matrix(vertices, "vertices", 3);
  const Eigen::MatrixXd f = py_convert::matrix(faces, "faces");
  if (f.cols() != 3 && f.cols() != 4) throw InvalidInput("faces must have 3 or 4 columns (-1 in column 3 for a triangle)");
  m.faces = Eigen::MatrixXi::Constant(f.rows(), 4, -1);
  for (Eigen::Index i = 0; i < f.rows(); ++i)
    for (Eigen::Index k = 0; k < f.cols(); ++k) {
      const double x = f(i, k);
      const bool pad = k == 3 && x == -1;
      if (!pad && (x != std::floor(x) || x < 0 || x >= static_cast<double>(m.vertices.rows()))) {
        std::ostringstream os;
        os << "faces[" << i << ", " << k << "] is " << x << "; expected a vertex index in [0, " << m.vertices.rows()
           << ")" << (k == 3 ? " or -1" : "");
        throw InvalidInput(os.str());
      }
      m.faces(i, k) = static_cast<int>(x);
    }
  m.face_part = Eigen::VectorXi::Zero(f.rows());
  return m;
}

}  // namespace

void bind_meshing(py::module_& m) {
  option_docs::bind_options<MeshOptions>(m, "MeshOptions", "Options of the surface and hull mesher (see fairlines.meshing).");
  m.def(
      "_mesh_surface",
      [](const NurbsSurface& s, const MeshOptions& o) {
        SurfaceMesh r;
        {
          py::gil_scoped_release release;
          r = mesh_surface(s, o);
        }
        return mesh_tuple(r);
      },
      "surface"_a, "options"_a);
  m.def(
      "_mesh_hull",
      [](const ComposedHull& c, const MeshOptions& o, double draft, bool lids, bool full, py::object progress) {
        HullMeshOptions h;
        h.draft = draft;
        h.lids = lids;
        h.full = full;
        if (!progress.is_none())
          h.progress = [progress](int done, int total, const std::string& name) {
            py::gil_scoped_acquire acquire;
            progress(done, total, name);
          };
        SurfaceMesh r;
        {
          py::gil_scoped_release release;
          r = mesh_hull(c, o, h);
        }
        return mesh_tuple(r);
      },
      "composed"_a, "options"_a, "draft"_a, "lids"_a, "full"_a, "progress"_a = py::none());
  m.def(
      "mesh_quality",
      [](py::handle v, py::handle f) {
        const MeshQuality q = mesh_quality(mesh_from(v, f));
        return py::dict("quads"_a = q.quads, "triangles"_a = q.triangles, "inverted"_a = q.inverted,
                        "min_scaled_jacobian"_a = q.min_scaled_jacobian,
                        "mean_scaled_jacobian"_a = q.mean_scaled_jacobian, "corners_in_45_135"_a = q.corners_in_45_135,
                        "min_angle_deg"_a = q.min_angle_deg, "max_angle_deg"_a = q.max_angle_deg,
                        "min_edge"_a = q.min_edge, "max_edge"_a = q.max_edge, "duplicate_nodes"_a = q.duplicate_nodes,
                        "open_edges"_a = q.open_edges, "non_manifold_edges"_a = q.non_manifold_edges,
                        "misoriented_edges"_a = q.misoriented_edges);
      },
      "vertices"_a, "faces"_a,
      "Quality census of a quad / triangle mesh ((n, 3) vertices, (m, 3 or 4) faces, -1 pads a triangle).");
  m.def(
      "scaled_jacobians", [](py::handle v, py::handle f) { return to_array(scaled_jacobians(mesh_from(v, f))); },
      "vertices"_a, "faces"_a, "Scaled Jacobian of every element (1: square / equilateral, <= 0: inverted).");
}

}  // namespace fairlines
