// Where the blending surface around a hull/bulb seam goes: its boundary on the bare hull (an
// ellipse arc in the hull's (u, v) parameter space clear of the seam) and on the bulb (an iso-u
// section ahead of the seam). compose_hull takes the result as its BlendSpec.
#pragma once

#include <Eigen/Core>

#include "fairlines/compose.hpp"
#include "fairlines/errors.hpp"
#include "fairlines/surface.hpp"

namespace fairlines {

struct BlendPlacementOptions {
  double clearance_u = 0.05;
  double clearance_v = 0.01;
  double bulb_clearance = 0.01;
  double tension = 0.6;  // 0.6 keeps a long blend under a bulb below a raised forefoot above the base line
  int points = 65;

  /// Each field with its name and meaning: f(name, member pointer, doc).
  template <typename F>
  static void fields(F&& f) {
    f("clearance_u", &BlendPlacementOptions::clearance_u, "hull u between the seam and the blend's boundary (parameter units, >= 0)");
    f("clearance_v", &BlendPlacementOptions::clearance_v, "hull v between the seam and the blend's boundary (parameter units, >= 0)");
    f("bulb_clearance", &BlendPlacementOptions::bulb_clearance, "bulb u between the seam's foremost point and the blend's boundary (>= 0)");
    f("tension", &BlendPlacementOptions::tension, "cross-boundary tangent length / (|B - A| / 3), > 0");
    f("points", &BlendPlacementOptions::points, "points on the hull boundary's arc (>= 3)");
  }
};

/// The blend's boundaries around a seam on an oriented bare hull (orient_bare_hull: u aft cut ->
/// stem, v keel -> deck).
///   seam_uv_hull   (k, 2) seam points' (u, v) on the hull, k >= 2, bottom to top
///   seam_uv_bulb   (k, 2) the same points' (u, v) on the bulb
/// On the hull: a half ellipse from the stem edge below the seam to the stem edge above it when
/// the seam ends on the stem at both ends; a quarter ellipse about the forefoot corner from the
/// keel edge to the stem edge when it starts on the keel; two quarter ellipses over the seam
/// when it starts and ends on the keel-and-stem edge of a whole-ship hull. Each is scaled to
/// hold the whole seam and widened by the clearances; where the hull has a straight keel zone
/// (a C0 knot in the first tenth of v) the boundary crosses it along v. On the bulb: the
/// section bulb_clearance ahead of the seam's foremost point.
/// Returns the BlendSpec (hull_uv (m, 2), bulb_u, tension). Throws InvalidInput for bad shapes
/// or options, NoBlendFits (message "no blend fits between hull and bulb: <why>") when the
/// boundary would leave the hull, reach the deck or the aft end.
BlendSpec blend_boundaries_around_seam(const NurbsSurface& oriented_hull, const Eigen::MatrixXd& seam_uv_hull,
                                       const Eigen::MatrixXd& seam_uv_bulb, const BlendPlacementOptions& options = {});

/// hull_bulb_seam followed by blend_boundaries_around_seam: the oriented hull and the BlendSpec
/// compose_hull(hull, bulb, compose_options, &spec) composes with. Throws as those two do.
std::pair<NurbsSurface, BlendSpec> seam_blend_placement(const NurbsSurface& hull, const NurbsSurface& bulb,
                                                        const ComposeOptions& compose_options = {},
                                                        const BlendPlacementOptions& options = {});

}  // namespace fairlines
