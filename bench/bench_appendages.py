"""The README's appendage table and fairness counts ("A single screw, a skeg and its aperture; a
sonar dome."), measured on the installed fairlines and printed in the README's format. Run by
bench/run_all.py (make bench).

Ships: the tanker, the container ship (with its bulb) and the cruiser-stern coaster of
tests/python/test_designer_appendages.py (SHIPS: skeg=True, the coaster with a 3.8 m
propeller) and its FRIGATE (sonar_dome=True); "without" is the same particulars with the
appendage (and the coaster's propeller_diameter) taken off. One process, run after run.

design      wall clock (time.perf_counter) of ``fl.design_hull(**p).bare_hull_surface()``, the
            Python build caches emptied first (fairlines.hull._clear_build_caches), median of 3,
            with and without the appendage. design_hull builds and matches the surface itself,
            so bare_hull_surface() only hands it back; the engine's own cache of fair_skin
            factorisations cannot be emptied from Python and stays warm. One untimed design
            runs first so that imports are not timed.
volume / LCB   (V - Cb Lpp B T) / (Cb Lpp B T) and (LCB - lcb) / Lpp from hull.ship_hydrostatics()
               (with a bulb the composed ship's).
blade-tip clearance   as the test measures it: the least distance of the frames (fl.plane_cut,
            801 points) at the propeller plane and PROPELLER_HALF_WIDTH D either side of it from
            the shaft, less D / 2, in D. D is the one the designer used (the skeg's
            half-thickness / SKEG_HALF_THICKNESS), x and the shaft from designer.propeller.
mesh at 3 m   fl.mesh_hull(c, size=3.0) of the composed whole hull (lids on), c composed as the
            tests compose it: hull.composed_hull() with a bulb, else fl.compose([surface],
            hull_u=96, hull_v=40 (skeg) or 60 (dome)); % quads, min scaled Jacobian, % of quad
            corners within 45-135 deg from mesh.quality(); its open / non-manifold /
            misoriented edges are printed below the table.
fairness counts   fairlines.fairness_plot.sign_change_counts of the bare hull surface, with -> without.
"""

import os
import statistics
import time

import numpy as np

import fairlines as fl
from fairlines import hull as hull_module
from fairlines.designer import PROPELLER_HALF_WIDTH, SKEG_HALF_THICKNESS, propeller
from fairlines.fairness_plot import sign_change_counts

TANKER = dict(lpp=180.0, breadth=32.0, draft=11.5, depth=17.0, cb=0.82, lcb=95.4, skeg=True)
CONTAINER = dict(lpp=244.8, breadth=32.25, draft=11.0, depth=19.0, cb=0.65, lcb=118.73, bulb=True, skeg=True)
COASTER = dict(lpp=100.0, breadth=16.0, draft=6.0, depth=9.0, cb=0.75, lcb=51.0, stern="cruiser", skeg=True,
               propeller_diameter=3.8)
FRIGATE = dict(lpp=140.0, breadth=17.0, draft=5.5, depth=10.0, cb=0.50, lcb=67.2, sonar_dome=True)
#: (name in the sentence, table label with {D}, particulars)
SHIPS = [("tanker", "tanker, skeg (D {D:.2f} m)", TANKER),
         ("container ship", "container ship, skeg and bulb (D {D:.2f} m)", CONTAINER),
         ("coaster", "coaster, cruiser stern, skeg (D {D:.1f} m)", COASTER),
         ("frigate", "frigate, sonar dome", FRIGATE)]
APPENDAGE_KEYS = ("skeg", "sonar_dome", "propeller_diameter")
REPEATS = 3
MESH_SIZE = 3.0


def without(p):
    return {k: v for k, v in p.items() if k not in APPENDAGE_KEYS}


def design_ms(p):
    """Median wall clock (ms) of a cold-cache design and its surface."""
    times = []
    for _ in range(REPEATS):
        hull_module._clear_build_caches()
        t = time.perf_counter()
        fl.design_hull(**p).bare_hull_surface()
        times.append(time.perf_counter() - t)
    return 1e3 * statistics.median(times)


def match_errors(p, hull):
    h = hull.ship_hydrostatics()  # with a bulb the composed ship's
    asked = p["cb"] * p["lpp"] * p["breadth"] * p["draft"]
    return (h["volume"] - asked) / asked, (h["lcb"] - p["lcb"]) / p["lpp"]


def tip_clearance(p, hull):
    """(D, least clearance of the frames through the blades from the disc, in D)."""
    d = hull.description.skeg.half_thickness / SKEG_HALF_THICKNESS
    pr = propeller(fl.Particulars(**{**p, "propeller_diameter": d}))
    gaps = []
    for x in pr.x + np.array([-1.0, 0.0, 1.0]) * PROPELLER_HALF_WIDTH * d:
        f = np.asarray(fl.plane_cut(hull.bare_hull_surface(), 0, float(x), 801).points)
        gaps.append(np.hypot(f[:, 1], f[:, 2] - pr.shaft_height).min() - d / 2)
    return d, min(gaps) / d


def mesh_census(p, hull):
    if p.get("bulb"):
        c = hull.composed_hull()
    else:
        c = fl.compose([hull.bare_hull_surface()], hull_u=96, hull_v=60 if p.get("sonar_dome") else 40)
    return fl.mesh_hull(c, size=MESH_SIZE).quality()


def sci(x):
    """-1e-7, +7e-8: one significant figure, signed, no exponent padding."""
    if x == 0:
        return "0"
    m, e = f"{x:+.0e}".split("e")
    return f"{m}e{int(e)}"


def row(first, label, p, hull, t_with, t_without):
    dv, dl = match_errors(p, hull)
    d, clear = tip_clearance(p, hull) if p.get("skeg") else (None, None)
    q = mesh_census(p, hull)
    sj = q["min_scaled_jacobian"]
    sj_text = f"{sj:.2f}" if sj >= 0.1 else f"{sj:.1g}"
    times = f"{t_with:.0f} ms ({t_without:.0f} ms{' without' if first else ''})"
    cells = [label.format(D=d or 0.0), times, f"{sci(dv)} / {sci(dl)} Lpp", "" if clear is None else f"{clear:.3f} D",
             f"{100 * q['quad_fraction']:.1f} % quads, min SJ {sj_text}, {100 * q['corners_in_45_135']:.1f} % corners"]
    edges = {k: q[k] for k in q if "edge" in k and isinstance(q[k], int)}
    return "| " + " | ".join(cells) + " |", edges


def main():
    print(f"load average at start: {' '.join(f'{x:.2f}' for x in os.getloadavg())}")
    fl.design_hull(**without(TANKER)).bare_hull_surface()  # imports and first calls, untimed
    rows, sentence, notes = [], [], []
    for i, (name, label, p) in enumerate(SHIPS):
        t_with, t_without = design_ms(p), design_ms(without(p))
        hull, plain = fl.design_hull(**p), fl.design_hull(**without(p))
        text, edges = row(i == 0, label, p, hull, t_with, t_without)
        rows.append(text)
        notes.append(f"{name}: mesh edges {edges}")
        a, b = (sign_change_counts(h.bare_hull_surface()) for h in (hull, plain))
        fmt = lambda c: f"{c['waterline']}/{c['buttock']}/{c['frame']}"  # noqa: E731
        sentence.append(f"{name} {fmt(a)} -> {fmt(b)}")
    print("| ship | design | volume / LCB on the surface | blade-tip clearance (asked 0.25 D) | mesh at 3 m |")
    print("|---|---|---|---|---|")
    print("\n".join(rows))
    print("\n".join(notes))
    print("fairness counts, waterlines / buttocks / frames, with -> without: " + ", ".join(sentence))
    print(f"load average at end: {' '.join(f'{x:.2f}' for x in os.getloadavg())}")


if __name__ == "__main__":
    main()
