"""Fairlines: fair parametric hull design on a compiled NURBS engine.

Conventions: metres; x forward from the aft perpendicular, y half-breadth >= 0,
z up from the baseline. Every geometric routine runs in the compiled module
``fairlines._native``; this package re-exports it and adds thin Python conveniences.
"""

from ._native import (  # noqa: F401  (re-exported API)
    ConvergenceError,
    CurveFit,
    FairlinesError,
    Hydrostatics,
    InfeasibleFormParameters,
    InvalidInput,
    NoBlendFits,
    NurbsCurve,
    NurbsSurface,
    NurbsVolume,
    PlaneCut,
    SkinResult,
    SurfaceFit,
    arc_length,
    curve_e2,
    equal_arc_length_points,
    section_area,
    arc,
    averaged_knots,
    basis_functions,
    circle,
    clamped_uniform_knots,
    cylinder,
    ellipse,
    fit_curve,
    fit_surface,
    greville_abscissae,
    hartley_judd_knots,
    parameterize,
    plane_cut,
    revolve,
    section_knot_vector,

    SectionDesign,
    SectionSpec,
    SplineBound,
    SplineCondition,
    SplineDesignRequest,
    SplineFitPoint,
    SplineFlat,
    SplineIntegral,
    SplineShape,
    design_section,
    design_sections,
    design_spline_function,
    section_fullness_bounds,
    section_fullness_range,
    spline_function_knots,
    spline_product_integral,
    sphere,
    unclamped_uniform_knots,
    validate_knots,
)
from .basic_curves import BasicCurve  # noqa: F401
from .description import BasicCurveSpec, BulbSpec, HullDescription, PrincipalDimensions  # noqa: F401
from .hull import Hull  # noqa: F401
from .skinning import SkinOptions, fair_skin  # noqa: F401

from .hydrostatics_surface import hydrostatics, hydrostatics_options  # noqa: F401,E402
from .form_curve import FORM_PARAMETERS, FormCurveResult, design_curve, fairness_of, form_parameters_of  # noqa: F401,E402
from ._native import (  # noqa: F401,E402
    BlendPlacementOptions,
    BulbOptions,
    HydrostaticsOptions,
    IntersectOptions,
    KrachtCoefficients,
    boundary_continuity,
    mesh_volume,
    orient_bare_hull,
    triangulate_polygon,
)
from .bulb import KRACHT_NAMES, BulbousBow, measure_kracht  # noqa: F401,E402
from .blend import BlendPlacement, BlendSurface, blend_surface, placement_options, seam_blend_placement  # noqa: F401,E402
from .compose import (  # noqa: F401,E402
    ComposedHull,
    Mesh,
    compose,
    compose_options,
    compose_with_blend,
    intersect_surfaces,
    mesh_hydrostatics,
)

__version__ = "0.1.0"
from .designer import Particulars, design_description, design_hull  # noqa: F401,E402

# Surface grids and solver meshes (Yoon 2007 NURBS grid control; Yoon & Kim 1997 hull meshing).
from . import grids  # noqa: F401,E402
from . import mesh_io  # noqa: F401,E402
from ._native import MeshOptions  # noqa: F401,E402
from .meshing import SurfaceMesh, mesh_hull, mesh_options, mesh_quality, mesh_surface  # noqa: F401,E402
from .mesh_io import read_mesh, read_plot3d, write_gdf, write_mar, write_mesh, write_plot3d  # noqa: F401,E402

# Design-space sweeps on Dask (the `sweep` extra: dask[distributed], pyarrow, scipy; imported on use).
from .sweep import sweep  # noqa: F401,E402
# Real hull data back as whole-ship designs (offsets tables, KCS, DTMB 5415 grids).
from .import_design import import_design, measure_hull_data  # noqa: F401,E402

# Hydrostatics of triangle meshes (the engine's divergence-theorem sums over the clipped triangles).
from .hydrostatics_mesh import (  # noqa: F401,E402
    MeshHydrostatics,
    MeshHydrostaticsOptions,
    displaced_volume_of_mesh,
    hydrostatics_of_mesh,
    mesh_hydrostatics_options,
)
from .grid_faces import grid_quads, grid_triangles  # noqa: F401,E402

# Hull data import and pre-processing in the fl namespace (fl.preprocess.mesh_hydrostatics keeps its
# module name: fl.mesh_hydrostatics is the composed hull's).
from . import preprocess  # noqa: F401,E402
from .offsets import (  # noqa: F401,E402
    HullData,
    PointGrid,
    Section,
    check_sections,
    check_station_range,
    hull_data_from_dict,
    hull_data_to_dict,
    knuckles,
    read_dtmb5415,
    read_hull_data,
    read_kcs,
    read_offsets_csv,
    read_sections_csv,
    read_tecplot,
    read_tecplot_hull,
    read_xyz_grid,
    section_from_offsets,
)
globals().update({name: getattr(preprocess, name) for name in preprocess.__all__ if name != "mesh_hydrostatics"})

# Hydrostatics of several NURBS patches bounding a hull together (the pre-processor's surfaces).
from ._native import PatchHydrostatics, hydrostatics_of_patches  # noqa: F401,E402
# Option structs of the composition and the blend (defaults in the engine's headers).
from ._native import BlendOptions, ComposeOptions  # noqa: F401,E402
