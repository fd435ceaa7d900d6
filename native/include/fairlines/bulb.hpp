// Bulbous bow from the Kracht (1978) coefficients, fair-skinned into a NURBS surface.
#pragma once

#include <Eigen/Core>

#include "fairlines/kracht.hpp"
#include "fairlines/surface.hpp"

namespace fairlines {

/// Shape controls and resolution of the bulb surface.
struct BulbOptions {
  double aft_length = 0.0;
  double nose_height_shift = 0.0;
  int sections = 81;
  int section_points = 41;
  int control_u = 24;
  int control_v = 12;

  /// Each field with its name and meaning: f(name, member pointer, doc).
  template <typename F>
  static void fields(F&& f) {
    f("aft_length", &BulbOptions::aft_length, "length of the constant-section body aft of FP that runs into the hull (m); 0: 2 (protrusion + breadth)");
    f("nose_height_shift", &BulbOptions::nose_height_shift, "z of the section centres minus the nose height at FP (m): > 0 lifts the bulb body behind a lower nose");
    f("sections", &BulbOptions::sections, "sampled sections along the bulb (>= 8)");
    f("section_points", &BulbOptions::section_points, "sampled points per half section (>= 8)");
    f("control_u", &BulbOptions::control_u, "control points along (>= 4)");
    f("control_v", &BulbOptions::control_v, "control points around the half section (>= 4)");
  }
};

/// The dimensions and derived shape of a bulb.
struct BulbShape {
  double x_fp, length, breadth, nose_height, height;  ///< metres: L_PR, B_B, Z_B, section height H
  double section_fullness;   ///< superellipse exponent n of the sections (2 = ellipse)
  double nose_shape;         ///< superellipse exponent m of the plan/profile outline forward of FP
  double section_area, lateral_area, volume;  ///< requested A_BT, A_BL, V_PR (m^2, m^2, m^3)
};

/// Bulb body: starboard half (y >= 0). u runs from the aft end (u = 0, inside the hull) to
/// the nose (u = 1, a pole); v runs around the half section from the bottom centre line
/// (v = 0, y = 0) to the top centre line (v = 1, y = 0). Forward of FP the half-breadth and
/// half-height scale by f(xi) = (1 - xi^m)^(1/m), xi = (x - x_fp) / L_PR; sections are
/// superellipses |2y / B_B|^n + |2 (z - z_c) / H|^n = f^n.
struct BulbousBow {
  NurbsSurface surface;
  BulbShape shape;
  double max_fit_deviation;  ///< max distance of the surface from its sampled analytic points (m)
};

/// Solves the shape (H, n, m) so that A_BT, A_BL and V_PR hold exactly for the analytic body,
/// then skins it. Throws InvalidInput naming the value out of range and
/// InfeasibleFormParameters naming the coefficients in conflict when no shape meets them.
BulbousBow make_bulbous_bow(const KrachtCoefficients& k, const ShipParticulars& ship,
                            const BulbOptions& options = {});

/// The section fullness A_BT / (B_B H) the coefficients ask of the bulb's sections (H from
/// c_abl through the nose shape), and the range [lo, hi] a bulb section can have (superellipse
/// exponents kSectionExponentMin .. kExponentMax). It scales as 1 / c_abl: c_abl kappa / k
/// gives fullness k. Throws InvalidInput as make_bulbous_bow does for bad values and
/// InfeasibleFormParameters when c_vpr, c_abt and c_lpr leave no nose shape.
struct SectionFullness {
  double kappa, lo, hi;
};
SectionFullness bulb_section_fullness(const KrachtCoefficients& k, const ShipParticulars& ship);

}  // namespace fairlines
