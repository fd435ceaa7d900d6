"""The issue's point 3 over the design space: from each of the first 60 Latin-hypercube designs
of bench_hull.py, a +-10 % change of volume or Cwp and a +-1 % Lpp change of LCB, made two ways:
by particulars (fl.design_hull again: Cb x0.9 / x1.1, the built design's Cwp x0.9 / x1.1, LCB
+-1 % Lpp), and by editing the built description with its other curves kept (SAC volume,
waterplane area, SAC LCB). Prints how many build; a refusal names what to change. Beside each
count, the range of what was asked: the Cb of a change of Cb or LCB by particulars; of every
other change, the vertical prismatic coefficient Cvp = V / (Awp T) = Cb / Cwp, the
underwater body's fullness under its waterplane (1 for a wall-sided box; full tankers have
about 0.92) and, where the waterplane changes, its Cwp too (1 is the rectangle Lpp B, which a waterline
closing at the stem cannot fill). Run by bench/run_all.py (FAIRLINES_EDIT_SAMPLES overrides the count).
"""

import json
import os
import pathlib
import sys

import fairlines as fl

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from bench_hull import sample  # noqa: E402  the same design space and sampler

SAMPLES = int(os.environ.get("FAIRLINES_EDIT_SAMPLES", "60"))
RANGE_CB = (0.45, 0.9)  # the designer's range (fl.designer.RANGES)


def builds(fn, asked: dict) -> tuple[str, dict]:
    """("built" or "refused", the edit's `asked` coefficients {name: value})."""
    try:
        fn()
        return "built", asked
    except fl.InfeasibleFormParameters:
        return "refused", asked


def by_particulars(p: dict, cwp: float) -> dict:
    out = {}
    for name, change in (("Cb x0.9", {"cb": 0.9 * p["cb"]}), ("Cb x1.1", {"cb": 1.1 * p["cb"]}),
                         ("Cwp x0.9", {"cwp": 0.9 * cwp}), ("Cwp x1.1", {"cwp": 1.1 * cwp}),
                         ("LCB -1 % Lpp", {"lcb": p["lcb"] - 0.01 * p["lpp"]}),
                         ("LCB +1 % Lpp", {"lcb": p["lcb"] + 0.01 * p["lpp"]})):
        q = {**p, **change}
        inside = RANGE_CB[0] <= q["cb"] <= RANGE_CB[1] and q["cb"] < q.get("cwp", cwp) < 1.0
        asked = {"Cwp": q["cwp"], "Cvp": q["cb"] / q["cwp"]} if "cwp" in change else {"Cb": q["cb"]}
        out[name] = builds(lambda: fl.design_hull(**q), asked) if inside else ("outside the range", asked)
    return out


def by_description(desc: dict, lpp: float) -> dict:
    out = {}
    pr = desc["principal"]
    for name, curve, key, change in (("volume -10 %", "sac", "volume", 0.9), ("volume +10 %", "sac", "volume", 1.1),
                                     ("waterplane -10 %", "dwl", "waterplane_area", 0.9),
                                     ("waterplane +10 %", "dwl", "waterplane_area", 1.1),
                                     ("LCB -1 % Lpp", "sac", "lcb", -0.01), ("LCB +1 % Lpp", "sac", "lcb", 0.01)):
        d = json.loads(json.dumps(desc))
        if key == "lcb":
            d["basic_curves"][curve][key] += change * lpp
        else:
            d["basic_curves"][curve][key] *= change
        area = d["basic_curves"]["dwl"]["waterplane_area"]
        asked = {"Cvp": d["basic_curves"]["sac"]["volume"] / (area * pr["T"])}
        if curve == "dwl":
            asked["Cwp"] = area / (pr["Lpp"] * pr["B"])
        out[name] = builds(lambda: fl.Hull.from_json(json.dumps(d)).hydrostatics(), asked)
    return out


def tally(rows: list[dict]) -> None:
    for name in rows[0]:
        col = [r[name] for r in rows]
        said = []
        for v in ("built", "refused", "outside the range"):
            asked = [a for k, a in col if k == v]
            if asked:
                spans = ", ".join(f"{c} {min(a[c] for a in asked):.3f}-{max(a[c] for a in asked):.3f}" for c in asked[0])
                said.append(f"{len(asked)} {v} ({spans})")
        print(f"  {name:<18s}", ", ".join(said))


def main():
    particulars, description = [], []
    for p in sample(SAMPLES):
        hull = fl.design_hull(**p)
        particulars.append(by_particulars(p, hull.hydrostatics().cwp))
        description.append(by_description(json.loads(hull.to_json()), p["lpp"]))
    print(f"{SAMPLES} designs; a change by particulars (fl.design_hull again):")
    tally(particulars)
    print("the same built descriptions edited, the other curves kept:")
    tally(description)


if __name__ == "__main__":
    main()
