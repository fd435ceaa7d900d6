"""Engine option structs filled by keyword: their fields and defaults live in the C++ headers."""

from __future__ import annotations

from collections.abc import Callable, Mapping
from functools import lru_cache
from typing import Any

from ._native import InvalidInput


@lru_cache(maxsize=None)
def option_names(options_type: type) -> tuple[str, ...]:
    """The fields of a bound option struct (a bound class does not change: kept per type)."""
    return tuple(n for n in dir(options_type) if not n.startswith("_"))


def fill_options(options_type: type, what: str, values: Mapping[str, Any],
                 convert: Mapping[str, Callable[[Any], Any]] | None = None):
    """``options_type()`` with the fields in ``values`` set, each through ``convert[name]`` when
    given (a check or a conversion the bound field does not make). Raises InvalidInput naming
    an unknown field or a value of the wrong type (one the field or its conversion refuses)."""
    o = options_type()
    names = option_names(options_type)
    for name, value in values.items():
        if name not in names:
            raise InvalidInput(f"{what} option {name!r} is unknown; expected one of " + ", ".join(names))
        try:
            setattr(o, name, convert[name](value) if convert and name in convert else value)
        except InvalidInput:
            raise
        except (TypeError, ValueError):
            expected = type(getattr(options_type(), name)).__name__
            raise InvalidInput(f"{what} option {name} is {value!r}; expected a {expected}") from None
    return o
