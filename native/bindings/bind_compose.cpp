// Bindings of the composition area: surface-surface intersection, the Kracht bulb, the
// composed hull and mesh export (python/fairlines/compose.py wraps them).
#include <type_traits>

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "convert.hpp"
#include "option_docs.hpp"
#include "fairlines/blend.hpp"
#include "fairlines/blend_placement.hpp"
#include "fairlines/bulb.hpp"
#include "fairlines/compose.hpp"
#include "fairlines/intersect.hpp"
#include "fairlines/mesh.hpp"

namespace py = pybind11;
using namespace pybind11::literals;

namespace fairlines {

namespace {

using py_convert::to_array;

py::array_t<int> faces_array(const Eigen::MatrixXi& f) {
  py::array_t<int> out({f.rows(), static_cast<Eigen::Index>(3)});
  auto r = out.mutable_unchecked<2>();
  for (Eigen::Index i = 0; i < f.rows(); ++i)
    for (int k = 0; k < 3; ++k) r(i, k) = f(i, k);
  return out;
}

TriMesh mesh_from(py::handle vertices, py::handle faces) {
  TriMesh m;
  m.vertices = py_convert::matrix(vertices, "vertices", 3);
  const Eigen::MatrixXd f = py_convert::matrix(faces, "faces", 3);
  m.faces.resize(f.rows(), 3);
  for (Eigen::Index i = 0; i < f.rows(); ++i)
    for (int k = 0; k < 3; ++k) {
      const double x = f(i, k);
      if (x != std::floor(x) || x < 0 || x >= static_cast<double>(m.vertices.rows())) {
        std::ostringstream os;
        os << "faces[" << i << ", " << k << "] is " << x << "; expected a vertex index in [0, " << m.vertices.rows() << ")";
        throw InvalidInput(os.str());
      }
      m.faces(i, k) = static_cast<int>(x);
    }
  return m;
}

py::dict curve_dict(const IntersectionCurve& c) {
  const Eigen::Index n = static_cast<Eigen::Index>(c.points.size());
  Eigen::MatrixXd p(n, 3), a(n, 2), b(n, 2);
  for (Eigen::Index i = 0; i < n; ++i) {
    p.row(i) = c.points[i].point.transpose();
    a.row(i) = c.points[i].uv_a.transpose();
    b.row(i) = c.points[i].uv_b.transpose();
  }
  return py::dict("points"_a = to_array(p), "uv_a"_a = to_array(a), "uv_b"_a = to_array(b), "closed"_a = c.closed,
                  "max_gap"_a = c.max_gap);
}

py::dict continuity_dict(const BoundaryContinuity& c) {
  return py::dict("max_angle_deg"_a = c.max_angle_deg, "max_gap"_a = c.max_gap);
}

py::array_t<int> int_array(const Eigen::VectorXi& v) {
  py::array_t<int> out(v.size());
  std::copy(v.data(), v.data() + v.size(), out.mutable_data());
  return out;
}

void bind_compose_options(py::module_& m) {
  using option_docs::bind_options;
  bind_options<ComposeOptions>(m, "ComposeOptions", "Options of compose (fairlines.compose sets them by keyword).");
  py::class_<BlendSpec> s(m, "BlendSpec", "The blend of a composition: its boundary on the hull and on the bulb.");
  s.def(py::init<>());
  const auto hull_uv = [](py::class_<BlendSpec>& cls, const char* name, const char* doc) {
    cls.def_property(
        name, [](const BlendSpec& b) { return to_array(b.hull_uv); },
        [](BlendSpec& b, py::handle uv) { b.hull_uv = py_convert::matrix(uv, "blend hull boundary", 2); }, doc);
  };
  option_docs::bind_fields(s, option_docs::for_member(&BlendSpec::hull_uv, hull_uv));
  bind_options<BlendOptions>(m, "BlendOptions", "Options of blend_surface (fairlines.blend_surface sets them by keyword).");
  bind_options<IntersectOptions>(m, "IntersectOptions",
                                 "Options of intersect_surfaces (fairlines.intersect_surfaces sets them by keyword).");
  bind_options<KrachtCoefficients>(m, "KrachtCoefficients", "Kracht's (1978) six bulb coefficients.");
  bind_options<ShipParticulars>(m, "BulbShip", "The ship quantities Kracht's coefficients are relative to (all required).");
  bind_options<BulbOptions>(m, "BulbOptions", "Shape controls and resolution of the bulb surface (fairlines.BulbousBow).");
  bind_options<BlendPlacementOptions>(m, "BlendPlacementOptions",
                                      "Options of seam_blend_placement (fairlines.seam_blend_placement sets them by keyword).");
}

/// Surface-surface intersection and the Kracht bulb.
void bind_intersect_and_bulb(py::module_& m) {
  m.def(
      "_intersect_surfaces",
      [](const NurbsSurface& a, const NurbsSurface& b, const IntersectOptions& options) {
        py::list out;
        for (const auto& c : intersect_surfaces(a, b, options)) out.append(curve_dict(c));
        return out;
      },
      "a"_a, "b"_a, "options"_a = IntersectOptions{});

  m.def(
      "_bulb_section_fullness",
      [](const KrachtCoefficients& k, const ShipParticulars& ship) {
        const SectionFullness f = bulb_section_fullness(k, ship);
        return py::make_tuple(f.kappa, f.lo, f.hi);
      },
      "kracht"_a, "ship"_a,
      "(A_BT / (B_B H) the coefficients ask of the bulb's sections, least and largest a section can have); "
      "scales as 1 / c_abl (see bulb.hpp).");

  py::class_<BulbousBow>(m, "_BulbousBow")
      .def(py::init(&make_bulbous_bow), "kracht"_a, "ship"_a, "options"_a = BulbOptions{})
      .def_property_readonly("surface", [](const BulbousBow& b) { return b.surface; })
      .def_property_readonly("max_fit_deviation", [](const BulbousBow& b) { return b.max_fit_deviation; })
      .def_property_readonly("shape", [](const BulbousBow& b) {
        const BulbShape& s = b.shape;
        return py::dict("x_fp"_a = s.x_fp, "length"_a = s.length, "breadth"_a = s.breadth,
                        "nose_height"_a = s.nose_height, "height"_a = s.height,
                        "section_fullness"_a = s.section_fullness, "nose_shape"_a = s.nose_shape,
                        "section_area"_a = s.section_area, "lateral_area"_a = s.lateral_area, "volume"_a = s.volume);
      });
}

/// The composed hull's read-only view: its mesh, trims, seams and surfaces.
void bind_composed_hull(py::module_& m) {
  py::class_<ComposedHull>(m, "_ComposedHull")
      .def_property_readonly("vertices", [](const ComposedHull& c) { return to_array(c.mesh.vertices); })
      .def_property_readonly("faces", [](const ComposedHull& c) { return faces_array(c.mesh.faces); })
      .def_property_readonly("face_part", [](const ComposedHull& c) { return int_array(c.face_part); })
      .def_property_readonly("seam_vertices", [](const ComposedHull& c) { return int_array(c.seam_vertices); })
      .def_property_readonly("trimmed_surfaces", [](const ComposedHull& c) {
        py::list out;
        for (const auto& t : c.trimmed_surfaces) {
          py::list loops;
          for (const auto& l : t.loops) loops.append(to_array(l));
          out.append(py::make_tuple(t.subdomain, loops));
        }
        return out;
      })
      .def_property_readonly("intersection_curves", [](const ComposedHull& c) {
        py::list out;
        for (const auto& x : c.intersection_curves) out.append(curve_dict(x));
        return out;
      })
      .def_property_readonly("x_aft", [](const ComposedHull& c) { return c.x_aft; })
      .def_property_readonly("z_deck", [](const ComposedHull& c) { return c.z_deck; })
      .def_property_readonly("hull", [](const ComposedHull& c) { return c.hull; })
      .def_property_readonly("hull_face_uv", [](const ComposedHull& c) { return to_array(c.hull_face_uv); })
      .def_property_readonly("blend", [](const ComposedHull& c) -> py::object {
        if (c.blend.empty()) return py::none();
        return py::cast(c.blend[0]);
      })
      .def_property_readonly("blend_continuity", [](const ComposedHull& c) {
        return py::make_tuple(continuity_dict(c.blend_at_hull), continuity_dict(c.blend_at_bulb));
      })
      .def("full_mesh", [](const ComposedHull& c) {
        const TriMesh f = mirror_full_hull(c);
        return py::make_tuple(to_array(f.vertices), faces_array(f.faces));
      });
}

/// compose_hull and the blend around its seam (placement, boundaries, surface, continuity).
void bind_compose_and_blend(py::module_& m) {
  m.def(
      "_compose_hull",
      [](const NurbsSurface& hull, const NurbsSurface* bulb, const ComposeOptions& options, const BlendSpec* blend) {
        py::gil_scoped_release release;
        return compose_hull(hull, bulb, options, blend);
      },
      "hull"_a, "bulb"_a = nullptr, "options"_a = ComposeOptions{}, "blend"_a = nullptr);
  m.def(
      "_hull_chord_difference",
      [](const ComposedHull& a, const ComposedHull& b, double draft, double trim, double lpp) {
        const BelowPlane d = [&] {
          py::gil_scoped_release release;
          return hull_chord_difference(a, b, draft, trim, lpp);
        }();
        return py::dict("volume"_a = d.volume, "mx"_a = d.mx, "mz"_a = d.mz, "wetted"_a = d.wetted);
      },
      "a"_a, "b"_a, "draft"_a, "trim"_a, "lpp"_a,
      "What a's flat hull faces miss of the hull surface below the waterplane less what b's miss, over the faces\n"
      "one has and the other not (half hull, the waterplane's frame): dict volume (m^3), mx, mz (m^4), wetted (m^2).");
  m.def(
      "_seam_blend_placement",
      [](const NurbsSurface& hull, const NurbsSurface& bulb, const ComposeOptions& compose_options,
         const BlendPlacementOptions& options) {
        auto [oriented, spec] = [&] {
          py::gil_scoped_release release;
          return seam_blend_placement(hull, bulb, compose_options, options);
        }();
        return py::make_tuple(oriented, py_convert::to_array(spec.hull_uv), spec.bulb_u, spec.tension);
      },
      "hull"_a, "bulb"_a, "compose_options"_a = ComposeOptions{}, "options"_a = BlendPlacementOptions{},
      "(oriented hull, boundary on it (k, 2) (u, v), bulb u of the boundary on the bulb, tension) "
      "of the blend around the seam (see blend_placement.hpp).");
  m.def(
      "_blend_boundaries_around_seam",
      [](const NurbsSurface& oriented_hull, py::handle uv_hull, py::handle uv_bulb, const BlendPlacementOptions& options) {
        const BlendSpec spec = blend_boundaries_around_seam(oriented_hull, py_convert::matrix(uv_hull, "seam_uv_hull", 2),
                                                            py_convert::matrix(uv_bulb, "seam_uv_bulb", 2), options);
        return py::make_tuple(py_convert::to_array(spec.hull_uv), spec.bulb_u);
      },
      "oriented_hull"_a, "seam_uv_hull"_a, "seam_uv_bulb"_a, "options"_a = BlendPlacementOptions{},
      "(boundary on the hull (k, 2) (u, v), bulb u) of the blend around a seam (see blend_placement.hpp).");
  m.def(
      "_blend_surface",
      [](const NurbsSurface& a, py::handle ba, const NurbsSurface& b, py::handle bb, const BlendOptions& options) {
        const BlendSurface r = blend_surface(a, py_convert::matrix(ba, "boundary_a", 2), b,
                                             py_convert::matrix(bb, "boundary_b", 2), options);
        return py::make_tuple(r.surface, continuity_dict(r.at_a), continuity_dict(r.at_b));
      },
      "a"_a, "boundary_a"_a, "b"_a, "boundary_b"_a, "options"_a = BlendOptions{});
  m.def(
      "boundary_continuity",
      [](const NurbsSurface& blend, bool at_v1, const NurbsSurface& s, int samples) {
        return continuity_dict(measure_boundary_continuity(blend, at_v1, s, samples));
      },
      "blend"_a, "at_v1"_a, "surface"_a, "samples"_a = kContinuitySamples,
      "Max normal angle (deg) and gap (m) between a blend's v = 0 (or v = 1) edge and a surface, "
      "by closest-point projection at `samples` points.");
  m.def("orient_bare_hull", &orient_bare_hull, "hull"_a, "plane_tolerance"_a = ComposeOptions{}.plane_tolerance,
        "The hull surface re-oriented to u aft->stem, v keel->deck (see compose.hpp).");
}

/// Triangle-mesh export, volume and polygon triangulation.
void bind_mesh_io(py::module_& m) {
  m.def(
      "write_obj", [](py::handle v, py::handle f, const std::string& path) { write_obj(mesh_from(v, f), path); },
      "vertices"_a, "faces"_a, "path"_a, "Writes a triangle mesh ((n, 3) vertices, (m, 3) faces) as Wavefront OBJ.");
  m.def(
      "write_stl",
      [](py::handle v, py::handle f, const std::string& path, bool binary) { write_stl(mesh_from(v, f), path, binary); },
      "vertices"_a, "faces"_a, "path"_a, "binary"_a = true, "Writes a triangle mesh as binary (or ASCII) STL.");
  m.def(
      "mesh_volume", [](py::handle v, py::handle f) { return mesh_volume(mesh_from(v, f)); }, "vertices"_a, "faces"_a,
      "Signed enclosed volume (m^3) by the divergence theorem.");
  m.def(
      "triangulate_polygon",
      [](py::handle pts) {
        const auto tris = triangulate_polygon(py_convert::matrix(pts, "points", 2));
        Eigen::MatrixXi f(static_cast<Eigen::Index>(tris.size()), 3);
        for (size_t i = 0; i < tris.size(); ++i)
          for (int k = 0; k < 3; ++k) f(static_cast<Eigen::Index>(i), k) = tris[i][k];
        return faces_array(f);
      },
      "points"_a, "Ear-clipping triangulation of a simple polygon (n, 2): (n - 2, 3) indices.");
}

}  // namespace

void bind_compose(py::module_& m) {
  bind_compose_options(m);
  bind_intersect_and_bulb(m);
  bind_composed_hull(m);
  bind_compose_and_blend(m);
  bind_mesh_io(m);
}

}  // namespace fairlines
