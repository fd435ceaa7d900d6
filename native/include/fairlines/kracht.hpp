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

#include <limits>

#include "fairlines/mesh.hpp"

namespace fairlines {

/// The ship the coefficients are made dimensionless by (metres, m^2, m^3).
struct KrachtShip {
  double x_fp = std::numeric_limits<double>::quiet_NaN();      ///< x of the forward perpendicular (m)
  double lpp = std::numeric_limits<double>::quiet_NaN();       ///< length between perpendiculars (m), > 0
  double beam = std::numeric_limits<double>::quiet_NaN();      ///< moulded breadth B (m), > 0
  double draft_fp = std::numeric_limits<double>::quiet_NaN();  ///< draft at the FP, T_FP (m), > 0
  double midship_area = std::numeric_limits<double>::quiet_NaN();         ///< A_M (m^2), > 0
  double displacement_volume = std::numeric_limits<double>::quiet_NaN();  ///< V (m^3), > 0
};

struct Kracht {
  double c_lpr = 0, c_bb = 0, c_zb = 0, c_abt = 0, c_abl = 0, c_vpr = 0;  ///< see the file's key
};

/// Kracht coefficients of `mesh` (a closed half hull, outward faces) for `ship`. A mesh with
/// nothing forward of x_fp below draft_fp gives C_LPR = -inf. Throws InvalidInput for a bad
/// mesh or a non-finite / non-positive ship dimension (x_fp only finite).
Kracht measure_kracht(const TriMesh& mesh, const KrachtShip& ship);

}  // namespace fairlines
