"""Curvature combs of the example container ship's lines (README picture).

    python examples/fairness_combs.py docs/fairness_combs.png
"""

import pathlib
import sys

import fairlines as fl
from fairlines.fairness_plot import write_fairness_plot

EXAMPLE = pathlib.Path(__file__).resolve().parent / "container_ship.json"

if __name__ == "__main__":
    out = sys.argv[1] if len(sys.argv) > 1 else "fairness_combs.png"
    hull = fl.Hull.from_json(EXAMPLE.read_text())
    judged = write_fairness_plot(hull.bare_hull_surface(), out, title=hull.description.name, dpi=80)
    total = {k: sum(c["sign_changes"] for c in v) for k, v in judged.items()}
    print(f"curvature sign changes: {total}; wrote {out}")
