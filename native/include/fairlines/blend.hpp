// Blending surface between two surfaces (Kim & Hwangbo 2008, step 4): fair skinning of Hermite
// sections, quintic with curvature (G2) continuity along both boundary curves, or cubic with
// tangent-plane (G1) continuity.
#pragma once

#include <Eigen/Core>

#include "fairlines/surface.hpp"

namespace fairlines {

struct BlendOptions {
  int samples = 61;
  double tension = 1.0;
  int check_samples = 200;
  bool centre_plane_ends = true;
  /// 2: quintic sections whose second derivative across each boundary gives the surface's own
  /// normal curvature in that direction (G2: reflection lines run on across the boundary
  /// without a kink); 1: cubic sections, tangent planes only (G1).
  int continuity = 2;

  /// Each field with its name and meaning: f(name, member pointer, doc).
  template <typename F>
  static void fields(F&& f) {
    f("samples", &BlendOptions::samples, "sections skinned along the boundaries (>= 4)");
    f("tension", &BlendOptions::tension, "cross-boundary speed |S_t| / |B - A| of the cubic sections, > 0 (the quintic ones run at 0.8 of it)");
    f("check_samples", &BlendOptions::check_samples, "boundary points at which continuity is measured (>= 2)");
    f("continuity", &BlendOptions::continuity, "1: tangent planes (cubic sections), 2: also the normal curvature across each boundary (quintic sections)");
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
/// Sections are Hermite curves across (t): S(s, 0) on a, S_t(s, 0) in a's tangent plane normal to
/// the boundary and toward b, of length tension |B - A| (0.8 of it for quintic sections, whose
/// first two legs then reach about as far as a cubic's handle); with continuity 2 also S_tt(s, 0) along
/// a's normal with S_tt . n = kappa_n |S_t|^2, kappa_n a's normal curvature in S_t's direction
/// (likewise at b; where that term would exceed a quarter of the handle it is capped, and G2 holds
/// only that far); each control row is interpolated along s (common knots). The surface is
/// degree 3 along s and 3 (continuity 1) or 5 (continuity 2) across.
/// Throws InvalidInput for bad shapes, parameters outside the domains or a continuity not 1 or 2.
BlendSurface blend_surface(const NurbsSurface& a, const Eigen::MatrixXd& boundary_a, const NurbsSurface& b,
                           const Eigen::MatrixXd& boundary_b, const BlendOptions& options = {});

/// Points at which measure_boundary_continuity projects unless told otherwise.
inline constexpr int kContinuitySamples = 400;

/// Continuity of a blend along its v = 0 (at_v1 false) or v = 1 edge against surface s,
/// measured independently by closest-point projection at `samples` points.
BoundaryContinuity measure_boundary_continuity(const NurbsSurface& blend, bool at_v1, const NurbsSurface& s,
                                               int samples = kContinuitySamples);

}  // namespace fairlines
