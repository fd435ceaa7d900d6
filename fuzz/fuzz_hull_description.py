"""Fuzz the hull-description loader: JSON text -> fl.Hull.from_json (no geometry is built).

Inputs are JSON text; one that does not start with '{' is given a leading '{' so the loader
always parses text rather than opening a file named by random bytes.
"""

import common
from common import EXPECTED, fl


def test_one_input(data: bytes) -> None:
    text = data.decode("utf-8", errors="replace")
    if not text.lstrip().startswith("{"):
        text = "{" + text
    try:
        fl.Hull.from_json(text)
    except EXPECTED:
        pass


if __name__ == "__main__":
    common.main(test_one_input)
