"""Node modules; importing them fills base.NODE_CLASSES. A new engine operator is a class in
one of these modules (or a new module added to the import below)."""

from . import base, values, curves, surfaces, hulldata, hull, design, mesh, output, solver, files, study  # noqa: F401  (registration order)

NODE_CLASSES = base.NODE_CLASSES
CATEGORIES = base.CATEGORIES
