"""Fuzz the section-list reader (CSV rows x,y,z, one station after another).

Input: one byte choosing the principal dimensions (common.DIMENSIONS), then the CSV file.
"""

import common
from common import EXPECTED

from fairlines import offsets


def test_one_input(data: bytes) -> None:
    (lpp, beam, draft), body = common.dimensions(data)
    path = common.scratch_file(body, "sections.csv")
    try:
        offsets.read_sections_csv(path, lpp, beam, draft)
    except EXPECTED:
        pass


if __name__ == "__main__":
    common.main(test_one_input)
