"""`fairlines fairness`: curvature combs of a hull's waterlines, buttocks and frames, and where
their curvature changes sign."""

from __future__ import annotations

import sys

COMMAND = "fairness"


def add_parser(sub) -> None:
    f = sub.add_parser(COMMAND, help="curvature combs of the cut lines of a hull description (PNG, SVG, PDF) and "
                                     "a table of their sign changes")
    f.add_argument("hull", help="hull description JSON")
    f.add_argument("-o", "--output", required=True, help="picture to write (.png, .svg or .pdf)")


def run(args) -> int:
    from .fairness_plot import write_fairness_plot
    from .hull import Hull

    hull = Hull.from_json(args.hull)
    print("  .. cutting waterlines, buttocks and frames and drawing their curvature combs", file=sys.stderr, flush=True)
    judged = write_fairness_plot(hull.bare_hull_surface(), args.output, title=hull.description.name)
    units = {"waterline": "z", "buttock": "y", "frame": "x"}
    for kind, cuts in judged.items():
        for c in cuts:
            where = "  ".join(f"({a[0]:.1f}, {a[1]:.1f}, {a[2]:.1f})" for a in (i["at"] for i in c["inflections"]))
            print(f"{kind:9s} {units[kind]} = {c['value']:7.2f} m: {c['sign_changes']} sign changes"
                  + (f" at {where}" if where else ""))
    total = {k: sum(c["sign_changes"] for c in v) for k, v in judged.items()}
    print(f"total: waterlines {total['waterline']}, buttocks {total['buttock']}, frames {total['frame']}; wrote {args.output}")
    return 0
