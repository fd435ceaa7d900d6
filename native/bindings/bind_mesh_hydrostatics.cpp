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

void bind_options(py::module_& m) {
  using option_docs::field;
  py::class_<MeshHydrostaticsOptions> c(m, "MeshHydrostaticsOptions", "Options of mesh_hydrostatics.");
  c.def(py::init<>());
  field(c, "half_hull", &MeshHydrostaticsOptions::half_hull,
        "the mesh is the y >= 0 half: volume and areas doubled, centroids kept");
  field(c, "orient", &MeshHydrostaticsOptions::orient,
        "flip an inward mesh: a side-like mesh must have int y n_y dS > 0, an end-like one "
        "int (x - midship_x) n_x dS > 0");
  field(c, "midship_x", &MeshHydrostaticsOptions::midship_x,
        "x of the section measured as midship_area (m); NaN: the middle of the mesh's x extent");
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
  py::class_<KrachtShip>(m, "KrachtShip", "The ship Kracht's coefficients are made dimensionless by (all required).")
      .def(py::init<>())
      .def_readwrite("x_fp", &KrachtShip::x_fp, "x of the forward perpendicular (m)")
      .def_readwrite("lpp", &KrachtShip::lpp, "length between perpendiculars (m), > 0")
      .def_readwrite("beam", &KrachtShip::beam, "moulded breadth (m), > 0")
      .def_readwrite("draft_fp", &KrachtShip::draft_fp, "draft at the FP (m), > 0: the mesh above it is not bulb")
      .def_readwrite("midship_area", &KrachtShip::midship_area, "midship section area A_M (m^2), > 0")
      .def_readwrite("displacement_volume", &KrachtShip::displacement_volume, "displaced volume V (m^3), > 0");
  py::class_<Kracht>(m, "Kracht", "Kracht's (1978) bulbous-bow coefficients measured on a mesh.")
      .def_readonly("c_lpr", &Kracht::c_lpr, "protrusion of the foremost submerged point / Lpp")
      .def_readonly("c_bb", &Kracht::c_bb, "breadth of the section at the FP / B")
      .def_readonly("c_zb", &Kracht::c_zb, "height of the foremost point / T_FP")
      .def_readonly("c_abt", &Kracht::c_abt, "section area at the FP / A_M")
      .def_readonly("c_abl", &Kracht::c_abl, "centre-plane area forward of the FP / A_M")
      .def_readonly("c_vpr", &Kracht::c_vpr, "volume forward of the FP / V");
  m.def("_measure_kracht",
        [](py::handle vertices, py::handle faces, const KrachtShip& ship) {
          const TriMesh mesh = tri_mesh(vertices, faces);
          py::gil_scoped_release release;
          return measure_kracht(mesh, ship);
        },
        "vertices"_a, "faces"_a, "ship"_a,
        "Kracht coefficients of a closed, outward half-hull mesh (vertices (n, 3) m, faces (m, 3)) below\n"
        "ship.draft_fp. Raises InvalidInput for bad shapes, indices or ship dimensions.");
}

}  // namespace

void bind_mesh_hydrostatics(py::module_& m) {
  bind_options(m);
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
