"""Package the Blender add-on in the two forms Blender users install:

  dist/fairlines_blender-<v>-extension.zip   Blender 4.2+ extension: blender_manifest.toml at
                                             the root, the engine wheel in wheels/
  dist/fairlines_blender-<v>-legacy.zip      Blender 3.4 .. 4.1 add-on: folder fairlines_blender/
                                             with the same wheel in wheels/ (engine.py unpacks it)

The engine wheel is built from this checkout with the project's .venv (incremental: it reuses
the scikit-build-core build directory). Usage: python tools/package_addon.py [--wheel PATH]
"""

import argparse
import glob
import os
import re
import subprocess
import sys
import zipfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ADDON = os.path.join(ROOT, "addon")
DIST = os.path.join(ROOT, "dist")
LEGACY_NAME = "fairlines_blender"  # not "fairlines": that is the engine package's name


def build_wheel():
    out = os.path.join(DIST, "wheels")
    os.makedirs(out, exist_ok=True)
    for old in glob.glob(os.path.join(out, "fairlines-*.whl")):
        os.remove(old)
    subprocess.check_call([sys.executable, "-m", "pip", "wheel", "-q", "--no-deps",
                           "--no-build-isolation", "-w", out, ROOT])
    wheels = glob.glob(os.path.join(out, "fairlines-*.whl"))
    if len(wheels) != 1:
        sys.exit("expected one fairlines wheel in %s, found %s" % (out, wheels))
    return wheels[0]


def addon_files():
    for base, dirs, files in os.walk(ADDON):
        dirs[:] = sorted(d for d in dirs if d not in ("__pycache__", "wheels"))
        for f in sorted(files):
            if not f.endswith((".pyc",)):
                path = os.path.join(base, f)
                yield path, os.path.relpath(path, ADDON)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--wheel", help="use this engine wheel instead of building one")
    args = ap.parse_args()
    wheel = args.wheel or build_wheel()
    wheel_name = os.path.basename(wheel)
    manifest = open(os.path.join(ADDON, "blender_manifest.toml"), encoding="utf-8").read()
    version = re.search(r'^version = "([^"]+)"', manifest, re.M).group(1)
    manifest = re.sub(r"^wheels = \[.*\]$", 'wheels = ["./wheels/%s"]' % wheel_name, manifest, flags=re.M)

    ext = os.path.join(DIST, "fairlines_blender-%s-extension.zip" % version)
    with zipfile.ZipFile(ext, "w", zipfile.ZIP_DEFLATED) as z:
        for path, rel in addon_files():
            if rel == "blender_manifest.toml":
                z.writestr(rel, manifest)
            else:
                z.write(path, rel)
        z.write(wheel, "wheels/" + wheel_name)

    legacy = os.path.join(DIST, "fairlines_blender-%s-legacy.zip" % version)
    with zipfile.ZipFile(legacy, "w", zipfile.ZIP_DEFLATED) as z:
        for path, rel in addon_files():
            if rel != "blender_manifest.toml":  # 4.2+ would take a manifest for an extension
                z.write(path, LEGACY_NAME + "/" + rel)
        z.write(wheel, LEGACY_NAME + "/wheels/" + wheel_name)
    print(ext)
    print(legacy)


if __name__ == "__main__":
    main()
