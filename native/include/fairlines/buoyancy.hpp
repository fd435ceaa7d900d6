// The figures every hydrostatics result holds: of a NURBS surface (hydrostatics.hpp), of a
// triangle mesh (mesh_hydrostatics.hpp) and of surface patches (hydrostatics_of_patches).
#pragma once

namespace fairlines {

/// A body floating at one draft; volume and areas for the full ship when the body was a half
/// hull. Centroids are 0 when the volume (lcb, vcb) or the waterplane (lcf) is empty.
struct BuoyancyFigures {
  double draft = 0;
  double volume = 0;
  double lcb = 0;
  double vcb = 0;
  double waterplane_area = 0;
  double lcf = 0;
  double wetted_surface = 0;

  /// Each field with its name and meaning: f(name, member pointer, doc).
  template <typename F>
  static void fields(F&& f) {
    f("draft", &BuoyancyFigures::draft, "m above the baseline z = 0");
    f("volume", &BuoyancyFigures::volume, "m^3 (full ship when half_hull)");
    f("lcb", &BuoyancyFigures::lcb, "x of the centre of buoyancy (m)");
    f("vcb", &BuoyancyFigures::vcb, "z of the centre of buoyancy, KB (m)");
    f("waterplane_area", &BuoyancyFigures::waterplane_area, "Awp (m^2)");
    f("lcf", &BuoyancyFigures::lcf, "x of the waterplane centroid (m)");
    f("wetted_surface", &BuoyancyFigures::wetted_surface, "m^2 below the draft (centre plane not counted)");
  }
};

}  // namespace fairlines
