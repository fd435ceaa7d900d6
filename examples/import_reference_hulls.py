"""Pipeline step 1 (pre-processor) on the three reference hulls: read the Series 60 Cb 0.80
offsets, the DTMB 5415 grids and the KCS grid, find their form parameters, rebuild faired
surfaces, and print the hydrostatics of input, surface and a fine mesh of the surface next to
the published particulars, with the deviation of the surface from every input point.

    python examples/import_reference_hulls.py --out out/

Series 60 is dimensionless: it is built here at Lpp 121.92 m (400 ft), L/B 6.5 and B/T 2.5,
the parent's proportions (Todd 1963); its coefficients do not depend on that choice.
"""

import argparse
import json
import os
import pathlib

from fairlines import offsets
from fairlines.preprocess import build_hull, comparison_table, import_hull

HERE = pathlib.Path(__file__).resolve().parent
# The reference hulls live next to the repository (../shared/data; see its README.md).
DATA = pathlib.Path(os.environ.get("FAIRLINES_DATA", HERE.parents[1] / "shared" / "data"))

S60_LPP = 121.92
S60_B = S60_LPP / 6.5
S60_T = S60_B / 2.5


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default="out", help="output folder (default: out)")
    args = ap.parse_args()
    out = pathlib.Path(args.out)
    hulls = [
        ("series60", offsets.read_offsets_csv(DATA / "series60_cb080_offsets.csv", S60_LPP, S60_B, S60_T)),
        ("dtmb5415", offsets.read_dtmb5415(DATA / "dtmb5415")),
        ("kcs", offsets.read_kcs(DATA / "kcs")),
    ]
    for key, data in hulls:
        print(f"\n--- {data.name}: Lpp {data.lpp:g} m, B {data.beam:g} m, T {data.draft:g} m ---")
        doc = import_hull(data)
        (out / f"{key}_hull.json").parent.mkdir(parents=True, exist_ok=True)
        (out / f"{key}_hull.json").write_text(json.dumps(doc))
        report = build_hull(doc, out / f"{key}_rebuilt")
        print(comparison_table(report))
        fp = doc["form_parameters"]
        bow = fp["bow"]
        extra = ", ".join(f"{k} {v:.4g}" for k, v in bow.items() if k != "kind" and isinstance(v, float))
        print(f"bow feature: {bow['kind']}" + (f" ({extra})" if extra else ""))
        pub = data.published
        if "wetted_surface" in pub:
            s = report["hydrostatics"]["surface"]["wetted_surface"]
            print(f"wetted surface S/L^2: surface {s / data.lpp ** 2:.4f}, published bare hull "
                  f"{pub['wetted_surface'] / data.lpp ** 2:.4f}")
        for note in data.notes:
            print(f"note: {note}")
    print(f"\nhull descriptions and rebuilt surfaces are in {out}")


if __name__ == "__main__":
    main()
