// Binding of mesh hydrostatics (python/fairlines/mesh_hydrostatics.py wraps it).
#include <cmath>
#include <string>

#include <pybind11/pybind11.h>

#include "convert.hpp"
#include "hydrostatics_fields.hpp"
#include "option_docs.hpp"
#include "fairlines/kracht.hpp"
#include "fairlines/mesh_hydrostatics.hpp"

namespace py = pybind11;
using namespace pybind11::literals;

namespace fairlines {

namespace {

TriMesh tri_mesh(py::handle vertices, py::handle faces) {
  TriMesh m;
  m.vertices = py_convert::matrix(vertices, "vertices", 3);
  const Eigen::MatrixXd f = py_convert::matrix(faces, "faces", 3);
  m.faces.resize(f.rows(), 3);
  for (Eigen::Index i = 0; i < f.size(); ++i) {
    const double x = f.data()[i];
    if (x != std::floor(x) || x < 0 || x >= static_cast<double>(m.vertices.rows()))
      throw InvalidInput("faces hold " + std::to_string(x) + "; expected vertex indices 0 <= i < " +
                         std::to_string(m.vertices.rows()));
    m.faces.data()[i] = static_cast<int>(x);
  }
  return m;
}

void bind_result(py::module_& m) {
  py::class_<MeshHydrostatics> c(m, "MeshHydrostatics",
                                 "Hydrostatics of a triangle mesh at one draft (full ship when half_hull): "
                                 "lengths m, areas m^2, volume m^3.");
  hydrostatics_fields::bind(c)
      .def_readonly("midship_x", &MeshHydrostatics::midship_x)
      .def_readonly("midship_area", &MeshHydrostatics::midship_area, "section area below the draft at midship_x")
      .def_readonly("flipped", &MeshHydrostatics::flipped, "the mesh was reoriented (options.orient)");
}

void bind_kracht(py::module_& m) {
  m.def("_measure_kracht",
        [](py::handle vertices, py::handle faces, const ShipParticulars& ship) {
          const TriMesh mesh = tri_mesh(vertices, faces);
          py::gil_scoped_release release;
          return measure_kracht(mesh, ship);
        },
        "vertices"_a, "faces"_a, "ship"_a,
        "KrachtCoefficients of a closed, outward half-hull mesh (vertices (n, 3) m, faces (m, 3)) below\n"
        "ship.draft_fp (ship a BulbShip; x_fp < 0 puts the FP at lpp). Raises InvalidInput for bad shapes,\n"
        "indices or ship dimensions.");
}

}  // namespace

void bind_mesh_hydrostatics(py::module_& m) {
  option_docs::bind_options<MeshHydrostaticsOptions>(m, "MeshHydrostaticsOptions", "Options of mesh_hydrostatics.");
  bind_result(m);
  bind_kracht(m);
  m.def("mesh_hydrostatics",
        [](py::handle vertices, py::handle faces, double draft, const MeshHydrostaticsOptions& options) {
          const TriMesh mesh = tri_mesh(vertices, faces);
          py::gil_scoped_release release;
          return mesh_hydrostatics(mesh, draft, options);
        },
        "vertices"_a, "faces"_a, "draft"_a, "options"_a = MeshHydrostaticsOptions{},
        "Hydrostatics of a half-hull triangle mesh (vertices (n, 3) m, faces (m, 3)) clipped at z = draft,\n"
        "by the divergence theorem. Raises InvalidInput for bad shapes, indices or a non-finite draft.");
}

}  // namespace fairlines
