"""Whole ships from particulars: the container ship of examples/container_ship.json and three
other types, each designed by fl.design_hull, its hydrostatics measured on the surface against
what was asked, its lines cut and judged (fairness report), its description written as JSON,
and a sheet of their lines drawn to docs/designed_ships.png.

    python examples/design_ship.py --out out/ [--docs docs/]
"""

import argparse
import json
import pathlib
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import fairlines as fl  # noqa: E402

HERE = pathlib.Path(__file__).resolve().parent

#: Ship types of the gallery (name, particulars); the first is examples/container_ship.json.
SHIPS = [
    ("Panamax container ship", dict(lpp=244.8, breadth=32.25, draft=11.0, depth=19.0, cb=0.65, lcb=118.73, bulb=True)),
    ("Product tanker", dict(lpp=180.0, breadth=32.0, draft=11.5, depth=17.0, cb=0.82, lcb=95.4, skeg=True)),
    ("Fast ferry (fine), transom raked 15 deg", dict(lpp=140.0, breadth=17.0, draft=5.5, depth=10.0, cb=0.50, lcb=67.2,
                                                    transom_rake=15.0)),
    ("Coaster, cruiser stern", dict(lpp=100.0, breadth=16.0, draft=6.0, depth=9.0, cb=0.75, lcb=51.0,
                                    stern="cruiser")),
]


def draw_lines(ax_profile, ax_plan, ax_body, hull, title):
    """Buttocks in the profile, waterlines in the half-breadth plan, stations in the body plan
    (aft half left, fore half right), all cut from the bare-hull surface."""
    s = hull.bare_hull_surface()
    pr = hull.description.principal
    x0, x1 = hull.description.x_aft, hull.description.x_fore
    for y in np.linspace(0, 0.5 * pr.breadth, 6)[1:-1]:
        p = np.asarray(fl.plane_cut(s, 1, float(y), 601).points)
        if len(p):
            ax_profile.plot(p[:, 0], p[:, 2], "g", lw=0.7)
    for z in list(np.linspace(0, pr.depth, 9)[1:-1]) + [pr.draft]:
        p = np.asarray(fl.plane_cut(s, 2, float(z), 801).points)
        if len(p):
            ax_plan.plot(p[:, 0], p[:, 1], "r" if z == pr.draft else "b", lw=1.1 if z == pr.draft else 0.7)
    for x in np.linspace(x0, x1, 23)[1:-1]:
        p = np.asarray(fl.plane_cut(s, 0, float(x), 301).points)
        if len(p):
            ax_body.plot((1 if x > 0.5 * pr.lpp else -1) * p[:, 1], p[:, 2], "k", lw=0.7)
    # the outline: keel and deck edge (the surface's u ends), transom and stem (its v ends)
    edges = np.asarray(s.evaluate_grid([s.domain_u[0], s.domain_u[1]], np.linspace(*s.domain_v, 400))).reshape(2, -1, 3)
    ends = np.asarray(s.evaluate_grid(np.linspace(*s.domain_u, 200), [s.domain_v[0], s.domain_v[1]])).reshape(-1, 2, 3)
    for e in [*edges, ends[:, 0], ends[:, 1]]:
        ax_profile.plot(e[:, 0], e[:, 2], "k", lw=1)
        ax_plan.plot(e[:, 0], e[:, 1], "k", lw=1)
    for a in (ax_profile, ax_plan, ax_body):
        a.set_aspect("equal")
        a.grid(alpha=0.3)
        a.tick_params(labelsize=7)
    ax_profile.axhline(pr.draft, color="r", lw=0.5)
    ax_body.axhline(pr.draft, color="r", lw=0.5)
    ax_body.axvline(0, color="k", lw=0.5)
    ax_profile.set_title(title, fontsize=10, loc="left")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default="out")
    ap.add_argument("--docs", default=str(HERE.parent / "docs"), help="where designed_ships.png goes")
    args = ap.parse_args()
    out = pathlib.Path(args.out) / "designed"
    out.mkdir(parents=True, exist_ok=True)
    fig = plt.figure(figsize=(16, 4.2 * len(SHIPS)))
    grid = fig.add_gridspec(2 * len(SHIPS), 2, width_ratios=[4.2, 1])
    for k, (name, particulars) in enumerate(SHIPS):
        t0 = time.perf_counter()
        hull = fl.design_hull(**particulars, name=name)
        ms = 1e3 * (time.perf_counter() - t0)
        p = fl.Particulars(**particulars)
        h = hull.ship_hydrostatics()  # with a bulb the composed ship's
        asked = p.cb * p.lpp * p.breadth * p.draft
        fair = hull.fairness_report()["summary"]
        print(f"{name}: designed in {ms:.0f} ms; volume {h['volume']:.1f} m3 (asked {asked:.1f}, "
              f"{100 * (h['volume'] / asked - 1):+.5f} %), LCB {h['lcb']:.3f} m (asked {p.lcb}), Cb {h['cb']:.4f} "
              f"Cm {h['cm']:.4f} Cp {h['cp']:.4f} Cwp {h['cwp']:.4f}; curvature sign changes per cut family {fair}")
        stem = name.lower().replace(" ", "_").replace(",", "").replace("(", "").replace(")", "")
        (out / f"{stem}.json").write_text(hull.to_json())
        draw_lines(fig.add_subplot(grid[2 * k, 0]), fig.add_subplot(grid[2 * k + 1, 0]),
                   fig.add_subplot(grid[2 * k:2 * k + 2, 1]), hull,
                   f"{name}: Lpp {p.lpp} m, B {p.breadth} m, T {p.draft} m, Cb {p.cb}, LCB {p.lcb} m"
                   + (", single screw aft of a skeg" if p.skeg else ""))
    fig.tight_layout()
    docs = pathlib.Path(args.docs)
    docs.mkdir(parents=True, exist_ok=True)
    fig.savefig(docs / "designed_ships.png", dpi=80)
    plt.close(fig)
    print(f"wrote {out}/*.json and {docs / 'designed_ships.png'}")


if __name__ == "__main__":
    main()
