// Kracht's (1978) bulbous-bow coefficients measured on a closed, outward-oriented half-hull
// triangle mesh (y >= 0), on its part below the waterline z = draft_fp (a raked stem reaches
// forward of the FP above it and is not bulb):
//   C_LPR = (x_nose - x_fp) / Lpp          protrusion of the foremost submerged point
//   C_BB  = 2 y_max(x_fp) / B              breadth of the section x = x_fp
//   C_ZB  = z_nose / T_FP                  height of the foremost point
//   C_ABT = 2 int_{x > x_fp} n_x dS / A_M  section area at the FP (closed-surface identity:
//                                           the waterplane and centre plane have n_x = 0)
//   C_ABL = A_cp(x > x_fp) / A_M           centre-plane area forward of the FP
//   C_VPR = 2 int_{x > x_fp} (x - x_fp) n_x dS / V   volume forward of the FP (divergence
//                                           theorem with (x - x_fp, 0, 0), zero on the cut)
// n dS is the outward area vector; centre-plane faces are those with every vertex at y = 0.
#pragma once

#include "fairlines/mesh.hpp"

namespace fairlines {

/// The six Kracht (1978) coefficients (dimensionless): designed (the defaults are the bulb
/// designer's) or measured on a mesh (see the key above).
struct KrachtCoefficients {
  double c_lpr = 0.025;
  double c_bb = 0.18;
  double c_zb = 0.45;
  double c_abt = 0.10;
  double c_abl = 0.10;
  double c_vpr = 0.0022;

  /// Each field with its name and meaning: f(name, member pointer, doc).
  template <typename F>
  static void fields(F&& f) {
    f("c_lpr", &KrachtCoefficients::c_lpr, "protrusion beyond FP / Lpp");
    f("c_bb", &KrachtCoefficients::c_bb, "bulb breadth at FP / B");
    f("c_zb", &KrachtCoefficients::c_zb, "height of the bulb's foremost point / T_FP");
    f("c_abt", &KrachtCoefficients::c_abt, "bulb section area at FP (both sides) / midship section area");
    f("c_abl", &KrachtCoefficients::c_abl, "lateral (profile) area forward of FP / midship section area");
    f("c_vpr", &KrachtCoefficients::c_vpr, "bulb volume forward of FP (both sides) / displacement volume");
  }
};

/// The ship quantities the coefficients are relative to (metres, m^2, m^3).
struct ShipParticulars {
  double lpp = 0.0;
  double beam = 0.0;
  double draft_fp = 0.0;
  double midship_area = 0.0;
  double displacement_volume = 0.0;
  double x_fp = -1.0;

  /// Each field with its name and meaning: f(name, member pointer, doc).
  template <typename F>
  static void fields(F&& f) {
    f("lpp", &ShipParticulars::lpp, "length between perpendiculars (m), > 0");
    f("beam", &ShipParticulars::beam, "moulded breadth B (m), > 0");
    f("draft_fp", &ShipParticulars::draft_fp, "draught at FP (m), > 0");
    f("midship_area", &ShipParticulars::midship_area, "midship section area A_MS, both sides (m^2), > 0");
    f("displacement_volume", &ShipParticulars::displacement_volume, "moulded displacement volume, both sides (m^3), > 0");
    f("x_fp", &ShipParticulars::x_fp, "x of FP from AP (m); < 0 means x_fp = lpp");
  }
};

/// x of the forward perpendicular: ship.x_fp, or lpp when x_fp < 0.
inline double fp_x(const ShipParticulars& ship) { return ship.x_fp < 0.0 ? ship.lpp : ship.x_fp; }

/// Kracht coefficients of `mesh` (a closed half hull, outward faces) for `ship` (its FP at
/// fp_x(ship)). A mesh with nothing forward of the FP below draft_fp gives C_LPR = -inf. Throws
/// InvalidInput for a bad mesh or a non-finite / non-positive ship dimension (x_fp only finite).
KrachtCoefficients measure_kracht(const TriMesh& mesh, const ShipParticulars& ship);

}  // namespace fairlines
