"""Build the Panamax bare forebody from its basic curves, print its hydrostatics and write
the surface control net and a fairness report.

    python examples/build_hull.py --out DIR [--description examples/panamax_forebody.json]

Writes DIR/bare_hull_surface.json (degrees, knots, control net (nu, nv, 3) in metres; u from
deck to keel, v from the first station to the last; the half hull y >= 0) and
DIR/fairness_report.json (waterlines, buttocks and frames cut from the surface: E2, bending
energy, curvature sign changes and where they are, each judged real -- called for by the
designed sections, with the reason -- or false).
"""

import argparse
import json
import pathlib
import time

import fairlines as fl

HERE = pathlib.Path(__file__).resolve().parent


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", required=True, help="output directory")
    ap.add_argument("--description", default=str(HERE / "panamax_forebody.json"), help="hull description (JSON)")
    args = ap.parse_args(argv)
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)

    t0 = time.perf_counter()
    hull = fl.Hull.from_json(args.description)
    surface = hull.bare_hull_surface()
    t_build = (time.perf_counter() - t0) * 1e3
    d = hull.description
    pr = d.principal
    sac = hull.basic_curves["sac"].form_parameters()
    h = hull.hydrostatics()
    skin = hull.skin()

    print(f"{d.name}")
    print(f"  Lpp {pr.lpp} m, B {pr.breadth} m, T {pr.draft} m, D {pr.depth} m; modelled x = {d.x_start} .. {d.x_end} m")
    print(f"  {len(hull.sections)} sections, surface {surface.control_points.shape[0]} x {surface.control_points.shape[1]} "
          f"control points, built in {t_build:.1f} ms")
    print("Hydrostatics at T (both sides, by quadrature on the surface):")
    rows = [
        ("volume", h.volume, "m^3", f"SAC asks {sac['Area']:.1f} m^3 ({(h.volume / sac['Area'] - 1) * 100:+.3f} %)"),
        ("displacement (sw 1.025 t/m^3)", h.displacement, "t", ""),
        ("LCB", h.lcb, "m from AP", f"SAC asks {sac['xC']:.3f} m ({(h.lcb - sac['xC']) / pr.lpp * 100:+.4f} % Lpp)"),
        ("VCB (KB)", h.vcb, "m above base", ""),
        ("waterplane area", h.waterplane_area, "m^2", ""),
        ("LCF", h.lcf, "m from AP", ""),
        ("wetted surface", h.wetted_surface, "m^2", "hull only, no centre plane / aft cut"),
        ("midship section area Am", h.midship_area, "m^2", f"at x = {h.midship_x:.2f} m"),
        ("Cb", h.cb, "", f"on length {h.length:.2f} m, B {h.breadth:.2f} m"),
        ("Cp", h.cp, "", ""),
        ("Cm", h.cm, "", ""),
        ("Cwp", h.cwp, "", ""),
    ]
    for name, val, unit, note in rows:
        print(f"  {name:32s} {val:12.4f} {unit:14s} {note}")
    print(f"  section fit (common knots) max deviation {skin.section_fit_max * 1000:.1f} mm; "
          f"longitudinal max deviation {skin.longitudinal_max:.1e} m")

    net = {
        "name": d.name,
        "units": "m",
        "half_hull": True,
        "degree_u": surface.degree_u,
        "degree_v": surface.degree_v,
        "knots_u": surface.knots_u.tolist(),
        "knots_v": surface.knots_v.tolist(),
        "control_points": surface.control_points.tolist(),
        "hydrostatics": h.as_dict(),
    }
    (out / "bare_hull_surface.json").write_text(json.dumps(net))
    report = hull.fairness_report()
    (out / "fairness_report.json").write_text(json.dumps(report, indent=1))
    print("Fairness (per cut: position: curvature sign changes = real + false; real ones are called for by the "
          "designed sections, see fairlines.inflections):")
    for kind, cuts in report.items():
        print(f"  {kind:10s} " + ", ".join(f"{c['value']:.2f}:{c['sign_changes']}={c['real_inflections']}+{c['false_inflections']}"
                                           for c in cuts))
    for kind, cuts in report.items():
        total = sum(c["sign_changes"] for c in cuts)
        false = sum(c["false_inflections"] for c in cuts)
        print(f"  {kind}s: {total} sign changes, {total - false} real, {false} false")
    print(f"wrote {out / 'bare_hull_surface.json'} and {out / 'fairness_report.json'}")


if __name__ == "__main__":
    main()
