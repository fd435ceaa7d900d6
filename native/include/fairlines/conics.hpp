// Exact conic sections and surfaces of revolution as rational B-splines
// (P&T A7.1 and A8.1; a circular arc of angle theta per quadratic segment has middle
// weight cos(theta/2)).
#pragma once

#include <Eigen/Core>

#include "fairlines/curve.hpp"
#include "fairlines/surface.hpp"

namespace fairlines {

/// Circular arc in 3-D: centre O, orthonormal in-plane axes x_axis and y_axis (normalised
/// here; must not be parallel), radius r > 0 (metres), from angle a0 to a1 (radians,
/// measured from x_axis toward y_axis, 0 < a1 - a0 <= 2 pi). Degree 2, one segment per
/// <= 90 degrees.
NurbsCurve arc(const Eigen::Vector3d& center, const Eigen::Vector3d& x_axis,
               const Eigen::Vector3d& y_axis, double radius, double a0, double a1);

/// Full circle of radius r about `center` in the plane with unit `normal`.
NurbsCurve circle(const Eigen::Vector3d& center, double radius, const Eigen::Vector3d& normal);

/// Full ellipse with semi-axes given as vectors (their lengths are the semi-axis lengths);
/// the axes must be perpendicular.
NurbsCurve ellipse(const Eigen::Vector3d& center, const Eigen::Vector3d& semi_axis_a,
                   const Eigen::Vector3d& semi_axis_b);

/// Surface of revolution: `profile` (a 3-D curve) swept by angle (radians, 0 < angle <= 2 pi)
/// about the line through axis_point with direction axis_dir. u runs around the axis
/// (degree 2, exact circles), v along the profile.
NurbsSurface revolve(const NurbsCurve& profile, const Eigen::Vector3d& axis_point,
                     const Eigen::Vector3d& axis_dir, double angle);

/// Exact cylinder: radius r, axis from base along unit axis_dir, height h.
NurbsSurface cylinder(const Eigen::Vector3d& base, const Eigen::Vector3d& axis_dir, double radius,
                      double height);

/// Exact sphere of radius r about center (a revolved semicircle; poles are degenerate).
NurbsSurface sphere(const Eigen::Vector3d& center, double radius);

}  // namespace fairlines
