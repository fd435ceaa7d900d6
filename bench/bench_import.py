"""Import speed: data -> whole-ship description (fl.import_design: measuring, building, fitting
the section shapes, matching volume and LCB, measuring the bulb) and description -> surface of
the imported hull, for the four reference ships, medians of repeated runs. Prints figures; run
by bench/run_all.py. No goal is set yet: importing is a one-off step.

Usage: python bench/bench_import.py [--repeat N]
"""

import argparse
import pathlib
import sys

from common import median_time, report

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "tests" / "python"))

import fairlines as fl  # noqa: E402
from import_fixtures import SHIPS, read  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=3)
    a = ap.parse_args()
    for ship in SHIPS:
        data = read(ship)
        desc = fl.import_design(data)
        t_import = median_time(lambda: fl.import_design(data), repeat=a.repeat, min_time=0.0)
        t_surface = median_time(lambda: fl.Hull.from_json(desc).bare_hull_surface(), repeat=a.repeat, min_time=0.0)
        report(f"import {ship}: data -> description", 1e3 * t_import, "ms")
        report(f"import {ship}: description -> surface", 1e3 * t_surface, "ms")


if __name__ == "__main__":
    main()
