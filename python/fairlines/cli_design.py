"""`fairlines design`: a whole-ship hull description from principal particulars."""

from __future__ import annotations

import pathlib
import sys
import time

COMMAND = "design"


def add_parser(sub) -> None:
    from .designer import RANGES

    d = sub.add_parser(COMMAND, help="design a whole hull from particulars; write its description JSON")
    for key, what in (("lpp", "length between perpendiculars, m (AP at x = 0)"), ("breadth", "moulded breadth B, m"),
                      ("draft", "design draft T, m"), ("depth", "depth D to the deck at side, m"),
                      ("cb", "block coefficient of the ship, its bulb included (%g-%g)" % RANGES["cb"]),
                      ("lcb", "LCB of the ship, m forward of the AP")):
        d.add_argument(f"--{key}", type=float, required=True, help=what)
    for key, what in (("cm", "midship coefficient (default: Kerlen)"), ("cwp", "waterplane coefficient (default sqrt(Cb) + 0.01)"),
                      ("lcf", "LCF, m from the AP"), ("parallel-length", "parallel middle body, m"),
                      ("parallel-centre", "middle of the parallel body, m from the AP"),
                      ("transom-immersion", "transom's lower edge below the waterline, m (< 0: dry)"),
                      ("transom-breadth", "waterline half-breadth at an immersed transom, m"),
                      ("stem-rake", "stem rake above the waterline, deg from the vertical"),
                      ("transom-rake", "the transom's rake from the vertical, deg, the top aft (default 0; a transom stern)"),
                      ("propeller-diameter", "with --skeg: the single screw's diameter, m (default 0.7 T up to Cb 0.7, 0.55 T from Cb 0.8, linear between; less under a low transom)"),
                      ("sonar-dome-nose", "with --sonar-dome: the dome's nose, m from the AP (default where the keel's flat ends "
                                          "forward; with --bulb aft of the bulb's blend)"),
                      ("flat-bottom", "flat of bottom over the parallel body, fraction of the waterline's half-breadth "
                                      "(default 0.15, none where a section would narrow it; 0: none)")):
        d.add_argument(f"--{key}", type=float, default=None, help=what)
    d.add_argument("--stern", choices=["transom", "cruiser"], default="transom", help="stern type (default transom)")
    d.add_argument("--bulb", action="store_true", help="a bulbous bow (default Kracht coefficients)")
    d.add_argument("--skeg", action="store_true", help="a single screw: a skeg under the run and a propeller aperture")
    d.add_argument("--sonar-dome", action="store_true", help="a sonar dome under the keel's forward end")
    d.add_argument("--name", default="designed hull", help="ship name, in the description and the lines' title block")
    d.add_argument("-o", "--output", required=True, help="hull description JSON to write")


def run(args) -> int:
    from .designer import design_hull

    keys = ("lpp", "breadth", "draft", "depth", "cb", "lcb", "cm", "cwp", "lcf", "parallel_length", "parallel_centre",
            "transom_immersion", "transom_breadth", "stem_rake", "transom_rake", "propeller_diameter", "flat_bottom", "stern", "bulb", "skeg", "sonar_dome",
            "sonar_dome_nose",
            "name")
    given = {k: getattr(args, k) for k in keys if getattr(args, k) is not None}
    t0 = time.perf_counter()
    print("  .. designing the hull and matching volume, LCB and Cwp on the ship", file=sys.stderr, flush=True)
    hull = design_hull(**given)
    ms = 1e3 * (time.perf_counter() - t0)
    h = hull.ship_hydrostatics()
    what = f" with the bulb (bare hull {hull.hydrostatics().volume:.1f} m^3)" if hull.description.bulb else ""
    pathlib.Path(args.output).write_text(hull.to_json())
    print(f"{given['name']}: volume {h['volume']:.1f} m^3, LCB {h['lcb']:.3f} m from the AP, Cb {h['cb']:.4f}, "
          f"Cm {h['cm']:.4f}, Cp {h['cp']:.4f}, Cwp {h['cwp']:.4f}, wetted surface {h['wetted_surface']:.1f} m^2{what} "
          f"({ms:.0f} ms)")
    print(f"wrote {args.output}")
    return 0

