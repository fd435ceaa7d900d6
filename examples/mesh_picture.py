"""Renders docs/hull_mesh.png: the quad-dominant mesh of the whole container ship (bare hull +
bulb + blend, transom stern), whole hull and a bow / bulb close-up, elements coloured by part and
quads with a corner outside 45-135 deg in red."""

import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

import fairlines as fl  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[1]
COLOURS = {"hull": "#9ecae1", "bulb": "#fdae6b", "blend": "#a1d99b", "centre_plane": "#dddddd", "deck": "#eeeeee",
           "aft": "#bcbddc", "waterplane": "#c6dbef"}
BAD = "#e31a1c"  # a quad with a corner outside CORNERS
CORNERS = (45.0, 135.0)  # deg


def bad_corner(q):
    """True for a quad (4 x 3 points) with a corner angle outside CORNERS."""
    if len(q) != 4:
        return False
    e1, e2 = np.roll(q, -1, axis=0) - q, np.roll(q, 1, axis=0) - q
    cos = np.sum(e1 * e2, axis=1) / (np.linalg.norm(e1, axis=1) * np.linalg.norm(e2, axis=1))
    angles = np.degrees(np.arccos(np.clip(cos, -1.0, 1.0)))
    return bool(np.any((angles < CORNERS[0]) | (angles > CORNERS[1])))


def draw(ax, mesh, keep, elev, azim, title, box, zoom=1.3):
    polys, colours = [], []
    for f, p in zip(mesh.faces, mesh.face_part):
        name = mesh.parts[p]
        if name not in keep:
            continue
        q = mesh.vertices[f[f >= 0]]
        if box is not None and not np.all((q >= box[0]) & (q <= box[1])):
            continue
        polys.append(q)
        colours.append(BAD if bad_corner(q) else COLOURS.get(name, "w"))
    # drawn past the axes' square: a 3-D axes is square, the whole ship is long and low
    ax.add_collection3d(Poly3DCollection(polys, facecolors=colours, edgecolors="k", linewidths=0.15, clip_on=False))
    pts = np.concatenate(polys)
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_zlim(lo[2], hi[2])
    ax.set_box_aspect(hi - lo, zoom=zoom)  # true proportions
    ax.view_init(elev=elev, azim=azim)
    ax.set_axis_off()
    ax.set_title(title, fontsize=9)


def main(out=ROOT / "docs" / "hull_mesh.png"):
    hull = fl.Hull.from_json(ROOT / "examples" / "container_ship.json")
    c = hull.composed_hull()
    whole = fl.mesh_hull(c, size=3.0, full=True)
    bow = fl.mesh_hull(c, size=1.0)
    bow_quads = fl.mesh_hull(c, size=1.5, all_quad=True)
    q = whole.quality()
    fig = plt.figure(figsize=(14, 10))
    ax = fig.add_axes((0.0, 0.45, 1.0, 0.55), projection="3d")
    fig.suptitle(
        f"whole container ship, size 3 m: {len(whole.faces)} elements, {q['quad_fraction']:.1%} quads, "
        f"{q['corners_in_45_135']:.1%} of quad corners in 45-135 deg (red: a quad with one outside), scaled "
        f"Jacobian min {q['min_scaled_jacobian']:.2f} mean {q['mean_scaled_jacobian']:.2f}\n(hull blue, blend green, "
        "bulb orange, deck grey)", y=0.97)
    draw(ax, whole, ("hull", "bulb", "blend", "deck", "aft"), 12, -72, "", None, zoom=2.4)
    ax = fig.add_axes((0.0, 0.0, 0.5, 0.47), projection="3d")
    box = (np.array([215.0, -1.0, -1.0]), np.array([260.0, 40.0, 20.0]))
    qb = bow.quality()
    draw(ax, bow, ("hull", "bulb", "blend"), 10, -50, f"bow and bulb, quad-dominant, size 1 m: {qb['quad_fraction']:.1%} "
         f"quads, {qb['corners_in_45_135']:.1%} of corners in 45-135 deg", box)
    ax = fig.add_axes((0.5, 0.0, 0.5, 0.47), projection="3d")
    qa = bow_quads.quality()
    draw(ax, bow_quads, ("hull", "bulb", "blend"), 10, -50,
         f"all_quad=True, size 1.5 m: {qa['quad_fraction']:.0%} quads, {qa['corners_in_45_135']:.1%} of corners in "
         f"45-135 deg, scaled Jacobian mean {qa['mean_scaled_jacobian']:.2f}", box)
    fig.savefig(out, dpi=110)
    from PIL import Image  # a 64-colour palette: a third of the bytes, the same picture
    Image.open(out).convert("RGB").quantize(64).save(out, optimize=True)
    print("wrote", out)


if __name__ == "__main__":
    main(*sys.argv[1:])
