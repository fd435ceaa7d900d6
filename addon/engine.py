"""The compiled engine, imported once and safely.

The add-on must register even when ``fairlines._native`` cannot be imported (wrong Python,
missing numpy, a broken install): the node editor then shows why instead of failing to load.
A legacy (pre-4.2) install ships the engine unpacked in ``_vendor`` next to this file; a 4.2+
extension gets it from the wheel listed in blender_manifest.toml, installed by Blender.
"""

import os
import sys

fl = None
np = None
IMPORT_ERROR = ""


def _load():
    global fl, np, IMPORT_ERROR
    vendor = os.path.join(os.path.dirname(os.path.abspath(__file__)), "_vendor")
    if os.path.isdir(vendor) and vendor not in sys.path:
        sys.path.append(vendor)  # after site-packages: an installed engine wins over the bundled one
    try:
        import numpy
        import fairlines
    except Exception as exc:  # any failure (ImportError, ABI mismatch, ...) is reported, not raised
        fl, np = None, None
        IMPORT_ERROR = "Fairlines engine unavailable: %s: %s (Python %d.%d)" % (
            type(exc).__name__, exc, sys.version_info[0], sys.version_info[1])
        return
    fl, np, IMPORT_ERROR = fairlines, numpy, ""


def available():
    return fl is not None


class EngineMissing(RuntimeError):
    """Raised inside node evaluation so the node shows the import failure."""


def require():
    if fl is None:
        raise EngineMissing(IMPORT_ERROR or "Fairlines engine unavailable")
    return fl, np


_load()
