// Binding of the hydrostatics of several surface patches (python/fairlines/preprocess/quadrature.py
// wraps it).
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "fairlines/hydrostatics.hpp"
#include "hydrostatics_fields.hpp"

namespace py = pybind11;
using namespace pybind11::literals;

namespace fairlines {

void bind_patch_hydrostatics(py::module_& m) {
  py::class_<PatchHydrostatics> c(m, "PatchHydrostatics",
                                  "Hydrostatics of half-hull surface patches at one draft (full ship when half_hull): "
                                  "lengths m, areas m^2, volume m^3.");
  hydrostatics_fields::bind(c);
  m.def("hydrostatics_of_patches",
        [](const std::vector<NurbsSurface>& patches, double draft, double end_x, bool half_hull, int gauss) {
          py::gil_scoped_release release;
          return hydrostatics_of_patches(patches, draft, end_x, half_hull, gauss);
        },
        "patches"_a, "draft"_a, "end_x"_a, "half_hull"_a = HydrostaticsOptions{}.half_hull, "gauss"_a = HydrostaticsOptions{}.gauss,
        "Hydrostatics of half-hull NURBS patches that bound the body together, upright at `draft` (m), by\n"
        "Gauss-Legendre quadrature on each patch clipped at the waterplane; each patch is turned outward\n"
        "first (side-like: int y n_y > 0, end-like: int (x - end_x) n_x > 0). Raises InvalidInput for a bad\n"
        "draft, end_x or gauss, or no patches.");
}

}  // namespace fairlines
