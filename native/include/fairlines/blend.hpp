// Blending surface between two surfaces (Kim & Hwangbo 2008, step 4): fair skinning of cubic Hermite
// sections with C1 (tangent-plane) continuity along both boundary curves.
#pragma once

#include <Eigen/Core>

#include "fairlines/surface.hpp"

namespace fairlines {

struct BlendOptions {
  int samples = 61;
  double tension = 1.0;
  int check_samples = 200;
  bool centre_plane_ends = true;

  /// Each field with its name and meaning: f(name, member pointer, doc).
  template <typename F>
  static void fields(F&& f) {
    f("samples", &BlendOptions::samples, "sections skinned along the boundaries (>= 4)");
    f("tension", &BlendOptions::tension, "cross-boundary tangent length / (|B - A| / 3), > 0");
    f("check_samples", &BlendOptions::check_samples, "boundary points at which continuity is measured (>= 2)");
    f("centre_plane_ends", &BlendOptions::centre_plane_ends, "when both boundaries start (end) on y = 0, keep that end section in the centre plane so a half hull closes");
  }
};

/// Measured continuity of one blend boundary.
struct BoundaryContinuity {
  double max_angle_deg = 0.0;  ///< max angle between blend and surface normals (degrees)
  double max_gap = 0.0;        ///< max distance of the blend boundary from the surface (m)
};

struct BlendSurface {
  NurbsSurface surface;  ///< s along the boundaries (u), t from boundary a (v = 0) to b (v = 1)
  BoundaryContinuity at_a, at_b;
  Eigen::MatrixXd params_a;  ///< (samples, 2) (u, v) on a of the skinned sections
  Eigen::MatrixXd params_b;  ///< (samples, 2) (u, v) on b
  Eigen::VectorXd params_s;  ///< (samples) blend u of each section (v = 0 on a, 1 on b)
};

/// boundary_a, boundary_b  (k, 2) polylines in the (u, v) parameter space of a and b (k >= 2;
///                         a polyline in parameter space is a curve on the surface). Both
///                         are sampled at equal fractions of their 3-D arc length, first
///                         point to first point.
/// Sections are cubic: S(s, 0) on a, S_t(s, 0) in a's tangent plane normal to the boundary
/// and toward b (likewise at b); each control row is interpolated along s (common knots).
/// Throws InvalidInput for bad shapes or parameters outside the domains.
BlendSurface blend_surface(const NurbsSurface& a, const Eigen::MatrixXd& boundary_a, const NurbsSurface& b,
                           const Eigen::MatrixXd& boundary_b, const BlendOptions& options = {});

/// Points at which measure_boundary_continuity projects unless told otherwise.
inline constexpr int kContinuitySamples = 400;

/// Continuity of a blend along its v = 0 (at_v1 false) or v = 1 edge against surface s,
/// measured independently by closest-point projection at `samples` points.
BoundaryContinuity measure_boundary_continuity(const NurbsSurface& blend, bool at_v1, const NurbsSurface& s,
                                               int samples = kContinuitySamples);

}  // namespace fairlines
