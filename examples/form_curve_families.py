"""Families of form-parameter curves (Kim, Shin & Kim 2002, Figs. 3-4): sweep Area and yC.

Base request: Kim, Shin & Kim 2002, Table 3 (xB=0, yB=0.569026, xE=1, yE=0, alphaB=-31,
alphaE=-58, CAB=-1.5, CAE=-4.41, Area=0.1925, xC=0.28489, yC=0.16952).

  * Area family: every parameter but xC and yC kept, Area swept.
  * yC family: every parameter kept, yC swept from just above its lower bound for a
    non-folding curve, yC >= (A/2L)(1 + 12((xC - xm)/L)^2), upwards.

Every member is solved exactly (|residual| <= 1e-9) by fl.design_curve; the script
prints the residuals and writes form_curve_families.png to the output directory.

usage: python examples/form_curve_families.py [OUT_DIR]   (default: out/)
"""

from __future__ import annotations

import argparse
import pathlib

import numpy as np

import fairlines as fl

TABLE3 = dict(xB=0.0, yB=0.569026, xE=1.0, yE=0.0, alphaB=-31.0, alphaE=-58.0, CAB=-1.5, CAE=-4.41,
              Area=0.1925, xC=0.28489, yC=0.16952)

AREAS = np.linspace(0.12, 0.32, 9)
YC_LOWER = TABLE3["Area"] / 2 * (1 + 12 * (TABLE3["xC"] - 0.5) ** 2)
YCS = np.linspace(0.155, 0.19, 8)


def family(base: dict, key: str, values) -> list:
    out = []
    for v in values:
        req = dict(base, **{key: float(v)})
        res = fl.design_curve(req)
        out.append((float(v), res))
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out_dir", nargs="?", default=None, help="output directory (default out/)")
    ap.add_argument("--out", dest="out_opt", default=None, help="output directory (same as OUT_DIR)")
    args = ap.parse_args(argv)
    out = pathlib.Path(args.out_opt or args.out_dir or "out")
    out.mkdir(parents=True, exist_ok=True)

    base_area = {k: v for k, v in TABLE3.items() if k not in ("xC", "yC")}
    fam_a = family(base_area, "Area", AREAS)
    fam_y = family(TABLE3, "yC", YCS)

    print(f"yC lower bound for a non-folding curve with Area={TABLE3['Area']}, xC={TABLE3['xC']}: {YC_LOWER:.6f}")
    for name, fam in (("Area", fam_a), ("yC", fam_y)):
        worst = max(r.max_residual() for _, r in fam)
        print(f"{name} family: {len(fam)} curves, {name} from {fam[0][0]:.4f} to {fam[-1][0]:.4f}, "
              f"max |residual| {worst:.2e}, E2 from {min(r.fairness['E2'] for _, r in fam):.3f} "
              f"to {max(r.fairness['E2'] for _, r in fam):.3f}")

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    t = np.linspace(0.0, 1.0, 400)
    fig, axes = plt.subplots(1, 2, figsize=(12, 5))
    for ax, (name, fam) in zip(axes, (("Area", fam_a), ("yC", fam_y))):
        cmap = plt.get_cmap("viridis")
        for k, (v, res) in enumerate(fam):
            pts = np.asarray(res.curve.evaluate(t))
            ax.plot(pts[:, 0], pts[:, 1], color=cmap(k / max(1, len(fam) - 1)), label=f"{name} = {v:.4f}")
        ax.set_title(f"Kim, Shin & Kim 2002, Table 3: {name} swept" + (" (xC, yC free)" if name == "Area" else ""))
        ax.set_xlabel("x")
        ax.set_ylabel("y")
        ax.set_aspect("equal")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    path = out / "form_curve_families.png"
    fig.savefig(path, dpi=120)
    print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
