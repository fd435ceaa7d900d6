"""The compiled engine, imported once and safely.

The add-on must register even when ``fairlines._native`` cannot be imported (wrong Python,
missing numpy, a broken install): the node editor then shows why instead of failing to load.

Where the engine comes from:
- a 4.2+ extension: Blender installs the wheel listed in blender_manifest.toml into the
  extension site-packages, so ``import fairlines`` just works;
- a legacy add-on (3.4 .. 4.1): the wheel ships in ``wheels/``; it is unpacked once into a
  folder named after the wheel's hash in the user's scripts directory and put on sys.path.
  Never unpacking into the add-on folder itself matters: re-installing the add-on over a
  running one rewrites its files in place, and rewriting a loaded shared library crashes
  Blender. A new build has a new hash, so it gets a new folder.
"""

import glob
import hashlib
import os
import sys
import zipfile

fl = None
np = None
IMPORT_ERROR = ""
SOURCE = ""


def _unpack_wheel():
    wheels = sorted(glob.glob(os.path.join(os.path.dirname(os.path.abspath(__file__)), "wheels",
                                           "fairlines-*.whl")))
    if not wheels:
        return None
    wheel = wheels[-1]
    with open(wheel, "rb") as f:
        digest = hashlib.sha256(f.read()).hexdigest()[:16]
    import bpy
    base = bpy.utils.user_resource("SCRIPTS", path="fairlines_engine", create=True)
    target = os.path.join(base, digest)
    done = os.path.join(target, ".complete")
    if not os.path.exists(done):
        tmp = "%s.tmp%d" % (target, os.getpid())
        with zipfile.ZipFile(wheel) as z:
            z.extractall(tmp)
        open(os.path.join(tmp, ".complete"), "w").close()
        try:
            os.rename(tmp, target)
        except OSError:  # another Blender unpacked it first: use theirs
            import shutil
            shutil.rmtree(tmp, ignore_errors=True)
    return target


def _load():
    global fl, np, IMPORT_ERROR, SOURCE
    try:
        import numpy
        try:
            import fairlines
        except ImportError:
            if sys.modules.get("fairlines", False) is None:
                raise  # explicitly blocked (tests of the engine-missing path)
            path = _unpack_wheel()
            if path is None:
                raise
            if path not in sys.path:
                sys.path.append(path)
            import fairlines
    except Exception as exc:  # any failure (ImportError, ABI mismatch, ...) is reported, not raised
        fl, np = None, None
        IMPORT_ERROR = "Fairlines engine unavailable: %s: %s (Python %d.%d)" % (
            type(exc).__name__, exc, sys.version_info[0], sys.version_info[1])
        return
    fl, np, IMPORT_ERROR = fairlines, numpy, ""
    SOURCE = os.path.dirname(os.path.abspath(fairlines.__file__))


def available():
    return fl is not None


class EngineMissing(RuntimeError):
    """Raised inside node evaluation so the node shows the import failure."""


def require():
    if fl is None:
        raise EngineMissing(IMPORT_ERROR or "Fairlines engine unavailable")
    return fl, np


_load()
