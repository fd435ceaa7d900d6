// Hydrostatics of a hull surface at any draft, by Gauss-Legendre quadrature on the NURBS
// surface itself (no meshing), clipped exactly at the draft plane.
//
// The surface is a HALF hull (y >= 0, the starboard side; SPEC §6). The enclosed body is the
// region between the surface, the centre plane y = 0 and the waterplane z = draft; any other
// opening of the surface (e.g. the aft cut of a forebody at a station) must lie in a plane
// x = const (a vertical transverse plane). Volume, areas and the SAC are returned for the
// FULL ship (twice the half hull) when `half_hull` is true; centroids do not change.
//
// Method (divergence theorem, n the outward unit normal, dS = |S_u x S_v| du dv):
//   V            = int y n_y dS                (F = (0, y, 0); zero flux through y = 0, the
//                                               waterplane and planes x = const)
//   V LCB        = int x y n_y dS,  V VCB = int z y n_y dS
//   waterplane   from V = T Awp + int z n_z dS and V LCB = T Awp LCF + int x z n_z dS
//   wetted area  = int dS over z < draft
// Each v node line is clipped where z(u, v) crosses the draft (sign changes by sampling,
// then bisection to 1e-14), and every piece is integrated per knot span.
#pragma once

#include <limits>

#include <Eigen/Core>

#include "fairlines/surface.hpp"

namespace fairlines {

struct HydrostaticsOptions {
  bool half_hull = true;  ///< the surface is the y >= 0 half: double volume, areas and SAC
  double length = 0;      ///< length for the coefficients (m); 0: submerged length x_max - x_min
  double breadth = 0;     ///< breadth for the coefficients (m); 0: 2 x max submerged half-breadth
  /// x of the midship section for Am and Cm (m); NaN: the middle of [x_min, x_max].
  double midship_x = std::numeric_limits<double>::quiet_NaN();
  int gauss = 8;          ///< Gauss-Legendre points per knot span in each direction (2..32)
  int sac_stations = 41;  ///< equally spaced stations of the returned SAC (>= 2), ends included
  double density = 1.025; ///< water density (t/m^3) for the displacement mass
};

struct Hydrostatics {
  double draft = 0;            ///< m above the baseline z = 0
  double volume = 0;           ///< m^3 (full ship when half_hull)
  double displacement = 0;     ///< t = density x volume
  double lcb = 0;              ///< x of the centre of buoyancy (m from AP)
  double vcb = 0;              ///< z of the centre of buoyancy (KB, m above base)
  double waterplane_area = 0;  ///< Awp (m^2)
  double lcf = 0;              ///< x of the waterplane centroid (m)
  double wetted_surface = 0;   ///< m^2, hull surface below the draft (centre plane not counted)
  double x_min = 0, x_max = 0; ///< submerged extent of the surface (m)
  double length = 0, breadth = 0;  ///< used for the coefficients (m)
  double midship_x = 0, midship_area = 0;  ///< Am (m^2) at midship_x
  double cb = 0, cp = 0, cm = 0, cwp = 0;  ///< V/(L B T), V/(Am L), Am/(B T), Awp/(L B)
  Eigen::VectorXd sac_x, sac_area;  ///< sectional area curve: stations (m) and areas (m^2)
};

/// Hydrostatics of `surface` floating upright at `draft` (m, > 0). Throws InvalidInput for a
/// non-finite / non-positive draft, bad options, or a surface with nothing below the draft.
Hydrostatics hydrostatics(const NurbsSurface& surface, double draft, const HydrostaticsOptions& options = {});

/// Area (m^2) below `draft` of the section of the surface by the plane x = `x` (half the
/// section when half_hull is false, the full section when true) and its centroid height
/// (m). The longitudinal parameter direction is the one along which x varies most; x must be
/// monotone along it. Returns {0, 0} when the plane misses the submerged surface.
std::pair<double, double> section_area(const NurbsSurface& surface, double x, double draft,
                                       bool half_hull = true, int gauss = 8);

}  // namespace fairlines
