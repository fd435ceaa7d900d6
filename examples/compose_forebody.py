"""Issue 5 pipeline steps 4-5 on any bare hull: bulbous bow from Kracht coefficients,
blending surface and Boolean composition into one watertight half hull, the Kracht quantities
measured back, OBJ / STL of the half and the mirrored full hull, hydrostatics.

    python examples/compose_forebody.py --out out/

Without issue 4's hull this runs on an analytic Wigley-type Panamax forebody; to use a real
hull call ``compose_forebody(hull.bare_hull_surface(), ship, ...)``.
"""

import argparse
import json
import pathlib
import time

import numpy as np

import fairlines as fl

PANAMAX = dict(lpp=244.8, beam=32.25, draft_fp=11.0)


def stand_in_forebody(lpp=244.8, beam=32.25, depth=19.0, rows=41, cols=25):
    """Wigley-type forebody y = B/2 (1 - xi^4)(1 - (1 - z/D)^6) from midship to a vertical
    stem at FP, fitted as a bicubic surface (u forward, v keel -> deck)."""
    r = np.arange(rows)[:, None]
    c = np.arange(cols)[None, :]
    x = 0.5 * lpp + 0.5 * lpp * (1 - np.cos(np.pi * 0.5 * r / (rows - 1))) + 0 * c
    z = depth * (1 - np.cos(np.pi * 0.5 * c / (cols - 1))) + 0 * r
    xi = (x - 0.5 * lpp) / (0.5 * lpp)
    y = 0.5 * beam * (1 - xi**4) * (1 - (1 - z / depth) ** 6)
    return fl.fit_surface(np.stack([x, y, z], axis=-1), n_control_u=16, n_control_v=12).surface


def blend_boundaries(union, clearance_u=0.02, clearance_v=0.03, bulb_clearance=0.04):
    """Blend boundaries around the union seam: on the hull a half ellipse in (u, v) from the
    stem edge below the bulb to the stem edge above it, on the bulb the section just ahead of
    the seam. Returns None when the seam does not end on the stem edge at both ends."""
    uv = union.intersection_curves[0]["uv_a"]
    hull = union.trimmed_surfaces[0][0]
    u1 = hull.knots_u[-1]
    if not (abs(uv[0, 0] - u1) < 1e-6 and abs(uv[-1, 0] - u1) < 1e-6):
        return None
    tlo, thi = uv[:, 1].min(), uv[:, 1].max()
    tc, R = 0.5 * (tlo + thi), 0.5 * (thi - tlo) + clearance_v
    if tc - R <= hull.knots_v[0] or tc + R >= hull.knots_v[-1]:
        return None
    phi = np.linspace(0.0, np.pi, 65)
    on_hull = np.column_stack([u1 - (u1 - uv[:, 0].min() + clearance_u) * np.sin(phi), tc - R * np.cos(phi)])
    on_bulb = ("u", float(union.intersection_curves[0]["uv_b"][:, 0].max()) + bulb_clearance)
    return on_hull, on_bulb


def compose_forebody(bare_hull, ship, kracht=None, bulb_shape=None, out=None, name="forebody", blend=True,
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
    composed = fl.compose([bare_hull, bulb], **compose_options)
    blend_note = "no blend requested"
    if blend:
        bounds = blend_boundaries(composed)
        if bounds is None:
            blend_note = "no blend: the seam does not end on the stem edge at both ends"
        else:
            hull_s = composed.trimmed_surfaces[0][0]
            bl = fl.blend_surface(hull_s, bounds[0], bulb.surface, bounds[1])
            composed = fl.compose([hull_s, bulb, bl], **compose_options)
            blend_note = "blend: max normal angle %.3f deg at the hull, %.3f deg at the bulb" % tuple(
                d["max_angle_deg"] for d in composed.blend_continuity)
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
        hydrostatics_at_draft_fp=hydro,
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
    args = ap.parse_args()
    L, B, T = PANAMAX["lpp"], PANAMAX["beam"], PANAMAX["draft_fp"]
    ship = dict(lpp=L, beam=B, draft_fp=T, midship_area=0.97 * B * T, displacement_volume=0.65 * L * B * T)
    bulb, composed, rep = compose_forebody(stand_in_forebody(L, B), ship, out=args.out, name="panamax_standin_forebody")
    print(bulb)
    print(f"  bulb {rep['time_ms']['bulb']:.1f} ms, blend + compose {rep['time_ms']['blend_and_compose']:.1f} ms; "
          f"{rep['mesh']['vertices']} vertices, {rep['mesh']['faces']} faces")
    print(f"  {rep['blend']}")
    for k in fl.KRACHT_NAMES:
        req, got = rep["kracht_requested"][k], rep["kracht_measured"][k]
        print(f"  {k:6s} requested {req:.5f} measured {got:.5f} ({100 * (got / req - 1):+.2f} %)")
    h = rep["hydrostatics_at_draft_fp"]
    print(f"  bulb adds {rep['volume_added_by_bulb_m3']:.1f} m^3; forebody displacement at T = {T} m: "
          f"{h['volume']:.0f} m^3, LCB {h['lcb']:.2f} m, KB {h['kb']:.2f} m")
    print(f"  wrote {args.out}/panamax_standin_forebody_{{half,full}}.{{obj,stl}} and .json")


if __name__ == "__main__":
    main()
