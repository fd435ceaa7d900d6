"""Bulb, blend and composition on the whole Panamax container ship of examples/container_ship.json:
the bulbous bow from the Kracht coefficients of its "bulb" section, a C1 blending surface and
the Boolean composition into one watertight half hull, the Kracht quantities measured back,
OBJ / STL of the half and the mirrored full hull, hydrostatics.

    python examples/compose_ship.py --out out/ [--description examples/container_ship.json]

``compose_ship(bare_hull_surface, ship, kracht, bulb_shape)`` runs the same on any bare
hull surface with its ship particulars.
"""

import argparse
import json
import pathlib
import time

import numpy as np

import fairlines as fl

HERE = pathlib.Path(__file__).resolve().parent


def compose_ship(bare_hull, ship, kracht=None, bulb_shape=None, out=None, name="ship", blend=True,
                     **compose_options):
    """Bulb + union for any bare hull surface.

    bare_hull   NurbsSurface with edges on the aft cut, deck and centre plane (keel, stem)
    ship        dict: lpp, beam, draft_fp, midship_area, displacement_volume (optional x_fp)
    kracht      dict of Kracht coefficients (fl.KRACHT_NAMES); defaults of fl.BulbousBow
    bulb_shape  dict of shape controls (aft_length, nose_height_shift, ...)
    out         folder for <name>_half.obj/.stl, <name>_full.obj/.stl and <name>.json
    blend       also build the blending surface (C1 to hull and bulb) and compose all three
    Returns (bulb, composed, report dict).
    """
    t0 = time.perf_counter()
    bulb = fl.BulbousBow.from_dict({"kracht": dict(kracht or {}), "shape": dict(bulb_shape or {})}, ship)
    t1 = time.perf_counter()
    composed = fl.compose_with_blend(bare_hull, bulb, blend=blend, **compose_options)
    blend_note = composed.blend_note
    t2 = time.perf_counter()
    bare = fl.compose([bare_hull], **{k: v for k, v in compose_options.items() if k in ("hull_u", "hull_v")})
    x_fp = ship.get("x_fp", ship["lpp"])
    measured = fl.measure_kracht(composed.mesh, x_fp=x_fp, **{k: ship[k] for k in
                                 ("lpp", "beam", "draft_fp", "midship_area", "displacement_volume")})
    hydro = fl.mesh_hydrostatics(composed.mesh, ship["draft_fp"])
    report = dict(
        bulb_shape=bulb.shape,
        kracht_requested=bulb.kracht,
        kracht_measured=measured,
        seam_max_gap_m=max(c["max_gap"] for c in composed.intersection_curves),
        blend=blend_note,
        half_volume_bare_m3=bare.volume,
        half_volume_composed_m3=composed.volume,
        volume_added_by_bulb_m3=2.0 * (composed.volume - bare.volume),
        hydrostatics_at_draft_fp=dict(volume=hydro.volume, lcb=hydro.lcb, vcb=hydro.vcb),
        mesh=dict(vertices=len(composed.mesh.vertices), faces=len(composed.mesh.faces)),
        time_ms=dict(bulb=1e3 * (t1 - t0), blend_and_compose=1e3 * (t2 - t1)),
    )
    if out is not None:
        out = pathlib.Path(out)
        out.mkdir(parents=True, exist_ok=True)
        composed.write_obj(out / f"{name}_half.obj")
        composed.write_stl(out / f"{name}_half.stl")
        composed.write_obj(out / f"{name}_full.obj", full=True)
        composed.write_stl(out / f"{name}_full.stl", full=True)
        (out / f"{name}.json").write_text(json.dumps(report, indent=2, default=float))
    return bulb, composed, report


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default="out")
    ap.add_argument("--description", default=str(HERE / "container_ship.json"), help="hull description (JSON) with a bulb section")
    args = ap.parse_args()
    hull = fl.Hull.from_json(args.description)
    spec = hull.description.bulb
    if spec is None:
        raise SystemExit(f"{args.description} has no \"bulb\" section")
    ship = hull.ship_particulars()
    T = ship["draft_fp"]
    name = "container_ship"
    bulb, composed, rep = compose_ship(hull.bare_hull_surface(), ship, spec.kracht, spec.shape, out=args.out, name=name)
    print(hull.description.name)
    print(f"  ship: A_MS {ship['midship_area']:.1f} m^2 (hull hydrostatics), displacement volume "
          f"{ship['displacement_volume']:.0f} m^3 (bulb section)")
    print(" ", bulb)
    print(f"  bulb {rep['time_ms']['bulb']:.1f} ms, blend + compose {rep['time_ms']['blend_and_compose']:.1f} ms; "
          f"{rep['mesh']['vertices']} vertices, {rep['mesh']['faces']} faces; seam gap {rep['seam_max_gap_m']:.1e} m")
    print(f"  {rep['blend']}")
    for k in fl.KRACHT_NAMES:
        req, got = rep["kracht_requested"][k], rep["kracht_measured"][k]
        print(f"  {k:6s} requested {req:.5f} measured {got:.5f} ({100 * (got / req - 1):+.2f} %)")
    h = rep["hydrostatics_at_draft_fp"]
    hb = hull.hydrostatics()
    print(f"  bulb adds {rep['volume_added_by_bulb_m3']:.1f} m^3 (both sides, whole bulb); displacement at "
          f"T = {T} m: bare {hb.volume:.0f} m^3 (NURBS quadrature), with bulb {h['volume']:.0f} m^3 (mesh), "
          f"LCB {h['lcb']:.2f} m, KB {h['vcb']:.2f} m")
    print(f"  wrote {args.out}/{name}_{{half,full}}.{{obj,stl}} and {name}.json")


if __name__ == "__main__":
    main()
