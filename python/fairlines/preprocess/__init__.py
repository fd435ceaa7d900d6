"""Pre-processor: from hull data read by :mod:`fairlines.offsets` to
form parameters found automatically, a rebuilt faired surface, its deviation from every input
point, and the hydrostatics of both the input and the surface.

Hydrostatics are computed three independent ways:

* ``offsets_hydrostatics``: Simpson's rule on the offsets table itself (irregular spacing in
  both directions, the half-breadths read as a section's polyline below the draft);
* ``mesh_hydrostatics``: exact integrals over a triangle mesh (an input grid triangulated, or a
  surface tessellated) clipped at the waterline, by the divergence theorem;
* ``surface_hydrostatics``: Gauss quadrature over the NURBS parameter domain, each iso-line
  cut exactly at the waterline.

The volume identities used by both surface paths, with n the outward normal of the half-hull
below the draft: V = ∫ y n_y dS, V·LCB = ∫ x y n_y dS, V·VCB = ∫ z y n_y dS, and the
half-waterplane A_wp = -∫ n_z dS. The field (0, y f(x, z), 0) has no flux through the
centreplane, the waterplane or any plane x = const, so neither the waterplane, nor a cut at a
transom or a perpendicular, needs closing.
"""

# One concern per module; the public names (and the two helpers the tests use) are re-exported here.
from .integrate import (  # noqa: F401
    ImportHydrostatics,
    simpson,
    offsets_hydrostatics,
    AREA_FRACTION_TOL,
    sections_hydrostatics,
    polyline_area,
    polyline_area as _polyline_area,
)
from .sections import (  # noqa: F401
    SECTION_SAMPLES_U,
    SECTION_SAMPLES_V,
    dense_samples,
    section_at,
)
from .meshes import (  # noqa: F401
    grid_mesh,
    mesh_hydrostatics,
    surface_meshes,
    input_hydrostatics,
)
from .quadrature import surface_hydrostatics  # noqa: F401
from .parameters import (  # noqa: F401
    FLAT_TOL,
    FOB_MIN_HALF_WIDTH,
    DOME_MIN_DEPTH,
    section_parameters,
    form_parameters,
)
from .rebuild import (  # noqa: F401
    DEVIATION_EXACT_TOL,
    GRID_MIN_CONTROL,
    Rebuild,
    resample_section,
    sections_grid,
    rebuild,
    deviation_report,
    project_points,
)
from .forebody import (  # noqa: F401
    PARALLEL_TOL,
    STEM_KEEL_FRACTION,
    DESCRIPTION_POINTS,
    hull_description,
)
from .files import (  # noqa: F401
    HULL_JSON_TYPE,
    import_hull,
    load_imported,
    build_hull,
)
from .report import (  # noqa: F401
    comparison_table,
)

__all__ = [
    "ImportHydrostatics", "SECTION_SAMPLES_U", "SECTION_SAMPLES_V", "dense_samples", "simpson", "offsets_hydrostatics",
    "AREA_FRACTION_TOL", "sections_hydrostatics", "section_at",
    "grid_mesh", "mesh_hydrostatics", "surface_meshes", "input_hydrostatics",
    "surface_hydrostatics", "FLAT_TOL", "FOB_MIN_HALF_WIDTH",
    "DOME_MIN_DEPTH", "section_parameters", "form_parameters", "DEVIATION_EXACT_TOL", "GRID_MIN_CONTROL",
    "Rebuild", "sections_grid", "rebuild", "deviation_report", "project_points", "PARALLEL_TOL",
    "STEM_KEEL_FRACTION", "DESCRIPTION_POINTS", "hull_description", "HULL_JSON_TYPE", "import_hull",
    "load_imported", "build_hull", "comparison_table",
]
