// Hydrostatics of a hull surface at any draft, by Gauss-Legendre quadrature on the NURBS
// surface itself (no meshing), clipped exactly at the draft plane.
//
// The surface is a HALF hull (y >= 0, the starboard side). The enclosed body is the
// region between the surface, the centre plane y = 0 and the waterplane z = draft; any other
// opening of the surface (e.g. the aft cut of a forebody at a station) must lie in a plane
// x = const (a vertical transverse plane). Volume, areas and the SAC are returned for the
// FULL ship (twice the half hull) when `half_hull` is true; centroids do not change.
//
// Method (divergence theorem, n the outward unit normal, dS = |S_u x S_v| du dv):
//   V            = int y n_y dS                (F = (0, y, 0); zero flux through y = 0, the
//                                               waterplane and planes x = const)
//   V LCB        = int x y n_y dS,  V VCB = int z y n_y dS
//   waterplane   below
//   wetted area  = int dS over z < draft
// Each v node line is clipped where z(u, v) crosses the draft (sign changes by sampling,
// then bisection to 1e-14), and every piece is integrated per knot span.
//
// The waterplane's area, first and second moments follow from divergence-free fields
// F = (0, 0, g(x, y)), whose flux through the waterplane is int g dA_h (dA_h the waterplane
// area element projected on z = 0) and is zero through y = 0 and planes x = const:
//   Awp_h        = -int n_z dS,   Awp_h LCF = -int x n_z dS
//   I_T,h        = -int y^2 n_z dS              (about the centre line y = 0)
//   I_L,h        = -int x^2 n_z dS - Awp_h LCF^2 (about the transverse axis through F)
// With trim the waterplane z = draft + trim (L/2 - x) / L (L = trim_length, AP at x = 0) is
// inclined by theta = atan(trim / L); its true area and transverse moment are the projected
// ones over cos(theta), its longitudinal moment (measured along the plane) over cos^3(theta).
// Volume, LCB and VCB need no change (n_y = 0 on the inclined plane). KMt = VCB + I_T / V and
// KMl = VCB + I_L / V; MCT1cm = displacement BML / (100 L) with GML taken as BML (the
// centre of gravity is not known here), the usual entry of a hydrostatic table.
#pragma once

#include <limits>
#include <vector>

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
  /// Trim by the stern (m): draft at the AP (x = 0) minus draft at the FP (x = trim_length);
  /// `draft` is then the draft at x = trim_length / 2. Negative: trim by the bow.
  double trim = 0;
  double trim_length = 0; ///< AP to FP (m) over which `trim` is measured; > 0 when trim != 0
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
                                    ///< (below the local waterline when trimmed)
  double trim = 0;             ///< trim by the stern (m) as asked
  double inertia_t = 0;        ///< I_T: waterplane 2nd moment about the centre line (m^4, full ship when half_hull)
  double inertia_l = 0;        ///< I_L: waterplane 2nd moment about the transverse axis through F (m^4)
  double bmt = 0, bml = 0;     ///< I_T / V, I_L / V (m)
  double kmt = 0, kml = 0;     ///< VCB + BMt, VCB + BMl (m above base)
  double tpc = 0;              ///< tonnes per cm immersion: density Awp / 100 (t/cm)
  double mct1cm = 0;           ///< moment to change trim 1 cm: displacement BML / (100 length) (t m/cm)
  double z_max = 0;            ///< highest point of the surface (m above base)
};

/// Hydrostatics of `surface` floating at `draft` (m, > 0), upright or trimmed (options.trim).
/// Throws InvalidInput for a non-finite / non-positive draft, bad options, a waterplane
/// above the surface's highest point anywhere along the surface (naming both), or a
/// surface with nothing below the draft.
Hydrostatics hydrostatics(const NurbsSurface& surface, double draft, const HydrostaticsOptions& options = {});

/// Hydrostatics of several half-hull patches (y >= 0) that bound the body together, at an
/// upright `draft` (m, > 0): the integrals above summed over every patch's part below the
/// draft, each patch turned outward first (a side-like patch, int |n_y| >= int |n_x|, must
/// have int y n_y dS > 0; an end-like one int (x - end_x) n_x dS > 0, end_x the x of a
/// station between the ends, metres). A patch wholly above the draft adds nothing; none is
/// required to reach the waterplane. Volume, areas: full ship when half_hull. `gauss`:
/// Gauss-Legendre points per knot span (2..32). Throws InvalidInput for a non-positive or
/// non-finite draft, a non-finite end_x, a bad gauss or no patches.
struct PatchHydrostatics {
  double draft = 0;            ///< m above the baseline
  double volume = 0;           ///< m^3 (full ship when half_hull)
  double lcb = 0, vcb = 0;     ///< centre of buoyancy x, z (m); 0 when the volume is 0
  double waterplane_area = 0;  ///< Awp (m^2)
  double lcf = 0;              ///< x of the waterplane centroid (m); 0 when Awp is 0
  double wetted_surface = 0;   ///< m^2 of the patches below the draft
};
PatchHydrostatics hydrostatics_of_patches(const std::vector<NurbsSurface>& patches, double draft, double end_x,
                                          bool half_hull = true, int gauss = 8);

/// Area (m^2) below `draft` of the section of the surface by the plane x = `x` (half the
/// section when half_hull is false, the full section when true) and its centroid height
/// (m). The longitudinal parameter direction is the one along which x varies most; x must be
/// monotone along it. Returns {0, 0} when the plane misses the submerged surface.
std::pair<double, double> section_area(const NurbsSurface& surface, double x, double draft,
                                       bool half_hull = true, int gauss = 8);

}  // namespace fairlines
