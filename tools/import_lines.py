"""Import the four reference ships, print their fidelity table and draw their lines plans.

    .venv/bin/python tools/import_lines.py [--out docs]

Writes docs/imported_<ship>.png (small lines plans) and prints the Markdown table of
docs/import.md (distances to the data's points, volume, LCB and wetted surface against the
published particulars or the exact Wigley figures)."""

from __future__ import annotations

import argparse
import pathlib
import sys
import time

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "tests" / "python"))

import fairlines as fl  # noqa: E402
from fairlines.lines_plan import lines_plan  # noqa: E402
from fairlines.import_design import fidelity  # noqa: E402
from import_fixtures import SHIPS, read, truth  # noqa: E402


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", default="docs")
    args = ap.parse_args()
    out = pathlib.Path(args.out)
    print("| ship | import s | RMS / B | max / B | volume | LCB / Lpp | wetted surface |")
    print("|---|---|---|---|---|---|---|")
    for ship in SHIPS:
        data = read(ship)
        t0 = time.perf_counter()
        desc = fl.import_design(data)
        dt = time.perf_counter() - t0
        hull = fl.Hull.from_json(desc)
        f, t = fidelity(hull, data), truth(ship)
        ws = f"{100 * (f['wetted_surface'] / t['wetted_surface'] - 1):+.2f} %" if t["wetted_surface"] else "no published figure"
        print(f"| {ship} | {dt:.1f} | {100 * f['rms_of_B']:.2f} % | {100 * f['max_of_B']:.2f} % | "
              f"{100 * (f['volume'] / t['volume'] - 1):+.2f} % | {100 * (f['lcb'] - t['lcb']) / t['lpp']:+.3f} % | {ws} |")
        pr = desc["principal"]
        drawn = hull.composed_hull() if hull.description.bulb is not None else hull.bare_hull_surface()
        plan = lines_plan(drawn, lpp=pr["Lpp"], beam=pr["B"], draft=pr["T"], depth=pr["D"],
                             name=f"{data.name} (imported)")
        plan.save(out / f"imported_{ship}.png", dpi=100)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
