"""Checks of user values shared by the readers of hull descriptions and option keywords: each
returns the value converted, or raises InvalidInput naming the value's path and what was
expected."""

from __future__ import annotations

import difflib
import math
from typing import Any, Callable

import numpy as np

from ._native import InvalidInput


def bad(path: str, value: Any, expected: str) -> InvalidInput:
    """The error for `value` at `path`: "<path> is <value>; expected <expected>"."""
    return InvalidInput(f"{path} is {value!r}; expected {expected}")


def number(path: str, value: Any, *, positive: bool = False) -> float:
    """value as a finite float (> 0 when `positive`).
    Raises InvalidInput naming the value."""
    if isinstance(value, bool) or not isinstance(value, (int, float, np.floating, np.integer)):
        raise bad(path, value, "a number")
    v = float(value)
    if not math.isfinite(v):
        raise bad(path, v, "a finite number")
    if positive and not v > 0:
        raise bad(path, v, "a number > 0")
    return v


def integer(path: str, value: Any, lo: int | None = None, hi: int | None = None) -> int:
    """value as an int (not a bool, not a float) within [lo, hi] where given.
    Raises InvalidInput naming the value."""
    ok = not isinstance(value, bool) and isinstance(value, (int, np.integer))
    if ok and ((lo is not None and int(value) < lo) or (hi is not None and int(value) > hi)):
        ok = False
    if not ok:
        expected = ("an integer" if lo is None and hi is None else f"an integer from {lo} to {hi}"
                    if lo is not None and hi is not None else f"an integer >= {lo}" if lo is not None
                    else f"an integer <= {hi}")
        raise bad(path, value, expected)
    return int(value)


def integral(path: str) -> Callable[[Any], int]:
    """A conversion to int that takes an int or a float with an integral value (not a bool);
    the conversion raises InvalidInput naming the value."""
    def convert(value):
        if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)) \
                or not float(value).is_integer():
            raise bad(path, value, "an integer")
        return int(value)
    return convert


def keyed_object(path: str, value: Any, known: tuple[str, ...] | list[str]) -> dict:
    """value as a dict whose keys are all in `known`; an unknown key names the nearest valid one.
    Raises InvalidInput naming the value or the unknown key."""
    if not isinstance(value, dict):
        raise bad(path, value, "an object with keys from " + ", ".join(known))
    for key in value:
        if key not in known:
            near = difflib.get_close_matches(str(key), list(known), n=1)
            hint = f"; did you mean {near[0]!r}?" if near else ""
            raise InvalidInput(f"{path}.{key} is not a known key{hint} (expected one of {', '.join(known)})")
    return value


def text_value(path: str, value: Any) -> str:
    """value when it is text (a JSON string).
    Raises InvalidInput naming the value."""
    if not isinstance(value, str):
        raise bad(path, value, "text (a JSON string)")
    return value
