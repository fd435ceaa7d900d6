// Surface-surface intersection: subdivision by control-net bounding boxes of the Bezier
// patches, Newton seeding, then marching along S_a = S_b with Newton correction.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "fairlines/surface.hpp"

namespace fairlines {

/// One point of an intersection curve, with its parameters on both surfaces.
struct IntersectionPoint {
  Eigen::Vector3d point;  ///< (S_a + S_b) / 2 at the refined parameters (metres)
  Eigen::Vector2d uv_a;   ///< (u, v) on surface a
  Eigen::Vector2d uv_b;   ///< (u, v) on surface b
};

/// A traced branch of the intersection. Open branches end where a parameter domain ends.
struct IntersectionCurve {
  std::vector<IntersectionPoint> points;
  bool closed = false;
  double max_gap = 0.0;  ///< max |S_a(uv_a) - S_b(uv_b)| over the points (metres)
};

struct IntersectOptions {
  int subdivisions = 12;
  double tolerance = 1e-7;
  double step = 0.0;
  double max_turn_deg = 4.0;
  int max_points = 100000;

  /// Each field with its name and meaning: f(name, member pointer, doc).
  template <typename F>
  static void fields(F&& f) {
    f("subdivisions", &IntersectOptions::subdivisions, "extra breakpoints per direction before the Bezier split (>= 1)");
    f("tolerance", &IntersectOptions::tolerance, "Newton target |S_a - S_b| (m), > 0, <= 1e-6");
    f("step", &IntersectOptions::step, "marching step (m); 0: 1/150 of the smaller box diagonal");
    f("max_turn_deg", &IntersectOptions::max_turn_deg, "tangent turn per step above which the step is halved (deg)");
    f("max_points", &IntersectOptions::max_points, "cap on points per branch (> 10)");
  }
};

/// Every intersection branch of two clamped NURBS surfaces (weights > 0).
/// Throws InvalidInput for unclamped knot vectors or bad options; ConvergenceError when a
/// branch cannot be traced to the tolerance (e.g. tangential contact).
std::vector<IntersectionCurve> intersect_surfaces(const NurbsSurface& a, const NurbsSurface& b,
                                                  const IntersectOptions& options = {});

/// Newton refinement of x = (u_a, v_a, u_b, v_b) onto S_a = S_b (minimum-norm steps,
/// parameters clamped to the domains). Returns the final gap |S_a - S_b| (metres).
double refine_intersection(const NurbsSurface& a, const NurbsSurface& b, Eigen::Vector4d& x,
                           double tolerance = 1e-9, int max_iterations = 40);

}  // namespace fairlines
