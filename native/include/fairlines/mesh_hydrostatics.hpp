// Hydrostatics of a triangle mesh of a half hull (y >= 0) clipped at a waterplane z = draft,
// exact for the polyhedron the triangles bound together with the centre plane y = 0, the
// waterplane and any transverse planes x = const (the openings the fields below ignore).
//
// Divergence theorem with n dS the outward area vector of each clipped triangle:
//   V = int y n_y dS,  V LCB = int x y n_y dS,  V VCB = int z y n_y dS
//   Awp = -int n_z dS,  Awp LCF = -int x n_z dS,  S = int dS
// Linear integrands use the vertex mean, quadratic ones the edge-midpoint rule (both exact on
// a flat triangle). The section x = midship_x is integrated by Green's theorem, oint y dz over
// the segments where the plane cuts the submerged triangles.
#pragma once

#include <limits>

#include "fairlines/buoyancy.hpp"
#include "fairlines/mesh.hpp"

namespace fairlines {

struct MeshHydrostaticsOptions {
  bool half_hull = true;
  /// Flip the whole mesh when it is oriented inwards: a side-like mesh (|n_y| dominating
  /// |n_x|) must have int y n_y dS > 0, an end-like mesh (a transom face) int (x - midship_x) n_x dS > 0.
  bool orient = false;
  double midship_x = std::numeric_limits<double>::quiet_NaN();

  /// Each field with its name and meaning: f(name, member pointer, doc).
  template <typename F>
  static void fields(F&& f) {
    f("half_hull", &MeshHydrostaticsOptions::half_hull, "the mesh is the y >= 0 half: volume and areas doubled, centroids kept");
    f("orient", &MeshHydrostaticsOptions::orient, "flip an inward mesh: a side-like mesh must have int y n_y dS > 0, an end-like one int (x - midship_x) n_x dS > 0");
    f("midship_x", &MeshHydrostaticsOptions::midship_x, "x of the section measured as midship_area (m); NaN: the middle of the mesh's x extent");
  }
};

struct MeshHydrostatics : BuoyancyFigures {
  double midship_x = 0;        ///< x of the measured section (m)
  double midship_area = 0;     ///< section area below the draft at midship_x (m^2)
  bool flipped = false;        ///< the mesh was reoriented (options.orient)
};

/// Hydrostatics of `mesh` (vertices (n, 3) m, faces (m, 3) outward unless options.orient)
/// floating at `draft` (m). Throws InvalidInput for a non-finite draft, face indices out of
/// range, or non-finite vertices. A mesh with nothing below the draft gives zero volume
/// (callers that need a displaced volume check it).
MeshHydrostatics mesh_hydrostatics(const TriMesh& mesh, double draft, const MeshHydrostaticsOptions& options = {});

}  // namespace fairlines
