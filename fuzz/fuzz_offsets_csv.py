"""Fuzz the offsets-table reader (CSV stations x waterlines, absolute or normalised).

Input: one byte choosing the principal dimensions (common.DIMENSIONS), then the CSV file.
"""

import common
from common import EXPECTED

from fairlines import offsets

STATION_COUNTS = (20, 10, 1, 0, -3)


def test_one_input(data: bytes) -> None:
    (lpp, beam, draft), body = common.dimensions(data)
    n_stations = STATION_COUNTS[(data[0] // len(common.DIMENSIONS)) % len(STATION_COUNTS)] if data else 20
    path = common.scratch_file(body, "offsets.csv")
    try:
        offsets.read_offsets_csv(path, lpp, beam, draft, n_stations=n_stations)
    except EXPECTED:
        pass


if __name__ == "__main__":
    common.main(test_one_input)
