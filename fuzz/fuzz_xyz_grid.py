"""Fuzz the whitespace-matrix grid readers: read_xyz_grid and the DTMB 5415 folder reader.

Input: the x, y and z matrices separated by lines '---' (missing parts are empty files). The
same three matrices serve as each of the DTMB 5415 bow, main and transom grids.
"""

import common
from common import EXPECTED

from fairlines import offsets


def test_one_input(data: bytes) -> None:
    parts = (data.split(b"\n---\n") + [b"", b""])[:3]
    paths = [common.scratch_file(p, f"grid_{c}.dat") for p, c in zip(parts, "xyz")]
    try:
        offsets.read_xyz_grid(*paths)
    except EXPECTED:
        pass
    for part in ("bow", "main", "transom"):
        for p, c in zip(parts, "xyz"):
            common.scratch_file(p, f"DTMB5415_{part}_offset_{c}.dat")
    try:
        offsets.read_dtmb5415(paths[0].parent)
    except EXPECTED:
        pass


if __name__ == "__main__":
    common.main(test_one_input)
