"""Fuzz the Tecplot point-grid readers: read_tecplot_hull on one file, and read_kcs on a folder
whose two grid files are both the input.

Input: one byte choosing the principal dimensions (common.DIMENSIONS), then the .dat file.
"""

import common
from common import EXPECTED

from fairlines import offsets


def test_one_input(data: bytes) -> None:
    (lpp, beam, draft), body = common.dimensions(data)
    path = common.scratch_file(body, "hull.dat")
    try:
        offsets.read_tecplot_hull(path, lpp, beam, draft)
    except EXPECTED:
        pass
    common.scratch_file(body, "kcs_bow2.dat")
    common.scratch_file(body, "kcs_stn2.dat")
    try:
        offsets.read_kcs(path.parent, lpp=lpp, beam=beam, draft=draft)
    except EXPECTED:
        pass


if __name__ == "__main__":
    common.main(test_one_input)
