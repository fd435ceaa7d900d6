// Hydrostatics of a hull surface at any draft, by Gauss-Legendre quadrature on the NURBS
// surface itself (no meshing), clipped exactly at the draft plane.
//
// The surface is a HALF hull (y >= 0, the starboard side). The enclosed body is the
// region between the surface, the centre plane y = 0 and the waterplane z = draft; any other
// opening of the surface (the aft cut of a forebody at a station, a transom) must lie in a
// plane whose normal has no y part: x = const, or raked (x a function of z alone); the ends
// v = v_min and v = v_max of the surface (its u lines running most nearly vertical) may be such
// openings. Volume, areas and the SAC are returned for the
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
// A raked end's lid has n_z != 0: its fluxes are added by Stokes' theorem along the end
// curve below the waterline (the waterline's chord across the lid and the centre plane add
// nothing): int_lid g n_z dS = closed integral of G dy with dG/dx = g (x - x_w, ...).
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

#include "fairlines/buoyancy.hpp"
#include "fairlines/surface.hpp"

namespace fairlines {

struct HydrostaticsOptions {
  bool half_hull = true;
  double length = 0;
  double breadth = 0;
  /// x of the midship section for Am and Cm (m); NaN: the middle of [x_min, x_max].
  double midship_x = std::numeric_limits<double>::quiet_NaN();
  int gauss = 8;
  int sac_stations = 41;
  double density = 1.025;
  /// Trim by the stern (m): draft at the AP (x = 0) minus draft at the FP (x = trim_length);
  /// `draft` is then the draft at x = trim_length / 2. Negative: trim by the bow.
  double trim = 0;
  double trim_length = 0;

  /// Each field with its name and meaning: f(name, member pointer, doc).
  template <typename F>
  static void fields(F&& f) {
    f("half_hull", &HydrostaticsOptions::half_hull, "the surface is the y >= 0 half: volume, areas and SAC are doubled");
    f("length", &HydrostaticsOptions::length, "length for the coefficients (m); 0: submerged length x_max - x_min");
    f("breadth", &HydrostaticsOptions::breadth, "breadth for the coefficients (m); 0: 2 x max submerged half-breadth");
    f("midship_x", &HydrostaticsOptions::midship_x, "x of the midship section for Am and Cm (m); None: the middle of [x_min, x_max]");
    f("gauss", &HydrostaticsOptions::gauss, "Gauss-Legendre points per knot span in each direction (2..32)");
    f("sac_stations", &HydrostaticsOptions::sac_stations, "equally spaced stations of the returned SAC (>= 2), ends included");
    f("density", &HydrostaticsOptions::density, "water density (t/m^3) for the displacement mass");
    f("trim", &HydrostaticsOptions::trim, "trim by the stern (m) over trim_length; draft is then the draft at trim_length / 2");
    f("trim_length", &HydrostaticsOptions::trim_length, "AP to FP (m) over which trim is measured; > 0 when trim != 0");
  }
};

struct Hydrostatics : BuoyancyFigures {
  double displacement = 0;
  double x_min = 0, x_max = 0;
  double length = 0, breadth = 0;
  double midship_x = 0, midship_area = 0;
  double cb = 0, cp = 0, cm = 0, cwp = 0;
  Eigen::VectorXd sac_x, sac_area;  ///< sectional area curve: stations (m) and areas (m^2)
                                    ///< (below the local waterline when trimmed)
  double trim = 0;
  double inertia_t = 0;
  double inertia_l = 0;
  double bmt = 0, bml = 0;
  double kmt = 0, kml = 0;
  double tpc = 0;
  double mct1cm = 0;
  double z_max = 0;

  /// Each scalar field, those of BuoyancyFigures first: f(name, member pointer, doc).
  template <typename F>
  static void fields(F&& f) {
    BuoyancyFigures::fields(f);
    f("displacement", &Hydrostatics::displacement, "t = density x volume");
    f("x_min", &Hydrostatics::x_min, "aft end of the submerged surface (m)");
    f("x_max", &Hydrostatics::x_max, "fore end of the submerged surface (m)");
    f("length", &Hydrostatics::length, "length used for the coefficients (m)");
    f("breadth", &Hydrostatics::breadth, "breadth used for the coefficients (m)");
    f("midship_x", &Hydrostatics::midship_x, "x of the midship section (m)");
    f("midship_area", &Hydrostatics::midship_area, "Am, midship section area below the draft (m^2)");
    f("cb", &Hydrostatics::cb, "block coefficient V / (L B T)");
    f("cp", &Hydrostatics::cp, "prismatic coefficient V / (Am L)");
    f("cm", &Hydrostatics::cm, "midship section coefficient Am / (B T)");
    f("cwp", &Hydrostatics::cwp, "waterplane coefficient Awp / (L B)");
    f("trim", &Hydrostatics::trim, "trim by the stern (m)");
    f("inertia_t", &Hydrostatics::inertia_t, "I_T, waterplane 2nd moment about the centre line (m^4)");
    f("inertia_l", &Hydrostatics::inertia_l, "I_L, waterplane 2nd moment about the axis through F (m^4)");
    f("bmt", &Hydrostatics::bmt, "I_T / V (m)");
    f("bml", &Hydrostatics::bml, "I_L / V (m)");
    f("kmt", &Hydrostatics::kmt, "VCB + BMt (m above base)");
    f("kml", &Hydrostatics::kml, "VCB + BMl (m above base)");
    f("tpc", &Hydrostatics::tpc, "tonnes per cm immersion, density Awp / 100 (t/cm)");
    f("mct1cm", &Hydrostatics::mct1cm, "moment to change trim 1 cm, displacement BML / (100 L): GML taken as BML (t m/cm)");
    f("z_max", &Hydrostatics::z_max, "highest point of the surface (m)");
  }
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
struct PatchHydrostatics : BuoyancyFigures {};
PatchHydrostatics hydrostatics_of_patches(const std::vector<NurbsSurface>& patches, double draft, double end_x,
                                          bool half_hull = HydrostaticsOptions{}.half_hull,
                                          int gauss = HydrostaticsOptions{}.gauss);

/// Area (m^2) below `draft` of the section of the surface by the plane x = `x` (half the
/// section when half_hull is false, the full section when true) and its centroid height
/// (m). The longitudinal parameter direction is the one along which x varies most; x must be
/// monotone along it. Returns {0, 0} when the plane misses the submerged surface.
std::pair<double, double> section_area(const NurbsSurface& surface, double x, double draft,
                                       bool half_hull = HydrostaticsOptions{}.half_hull,
                                       int gauss = HydrostaticsOptions{}.gauss);

}  // namespace fairlines
