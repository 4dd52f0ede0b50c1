"""Facts for a person: a mapping of named values to short text with units.

Generic over the names (incident severity facts, event facts, anything JSON-like): the unit
comes from the name's suffix (``_m``, ``_mps``, ``_mps2``, ``_s``, ``_ns``, ``_rad``), numbers
get three significant digits, a missing value is ``—``::

    >>> facts_text({"ttc_min_s": 1.23456, "shortfall_max_mps2": None, "responsible": "ego"})
    'ttc min 1.23 s · shortfall max — · responsible ego'

Pure: no Rerun, no textual.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from loaders.timebase import ns_to_s

if TYPE_CHECKING:
    from collections.abc import Mapping

__all__ = ["NONE", "fact_text", "facts_text", "number_text"]

#: Shown for a fact that has no value.
NONE = "—"

#: Name suffix -> unit shown after the number (longest suffixes first).
_UNITS: tuple[tuple[str, str], ...] = (
    ("_mps2", "m/s²"),
    ("_mps", "m/s"),
    ("_rad", "rad"),
    ("_ns", "s"),
    ("_m", "m"),
    ("_s", "s"),
)
_SIGNIFICANT = 3


def number_text(value: float) -> str:
    """``value`` with three significant digits, no exponent (``-0`` is ``0``, ``inf`` is ``∞``)."""
    if math.isnan(value):
        return NONE
    if math.isinf(value):
        return "∞" if value > 0 else "-∞"
    if value == 0:
        return "0"
    magnitude = math.floor(math.log10(abs(value)))
    decimals = max(0, _SIGNIFICANT - 1 - magnitude)
    text = f"{value:.{decimals}f}"
    return "0" if float(text) == 0 else text


def _split(name: str) -> tuple[str, str]:
    for suffix, unit in _UNITS:
        if name.endswith(suffix) and len(name) > len(suffix):
            return name[: -len(suffix)], unit
    return name, ""


def fact_text(name: str, value: object, *, t0_ns: int | None = None) -> str:
    """One fact as ``"label value unit"``.

    Args:
        name: The fact's name; its suffix gives the unit, underscores become spaces.
        value: ``None``, a number, a string, a bool or a list of these.
        t0_ns: Drive start: an ``_ns`` fact (a time stamp) is shown in seconds after it;
            without it, ``_ns`` values are shown as seconds as they are.
    """
    label, unit = _split(name)
    label = label.replace("_", " ")
    return f"{label} {_value_text(value, unit, is_time=name.endswith('_ns'), t0_ns=t0_ns)}"


def _value_text(value: object, unit: str, *, is_time: bool, t0_ns: int | None) -> str:
    if value is None or value == "":
        return NONE
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, (int, float)):
        number = float(value)
        if is_time:
            number = ns_to_s(number - (t0_ns or 0))
        elif isinstance(value, int):
            return f"{value} {unit}".rstrip()
        return (
            f"{number_text(number)} {unit}".rstrip()
            if math.isfinite(number)
            else number_text(number)
        )
    if isinstance(value, (list, tuple)):
        parts = [_value_text(v, "", is_time=False, t0_ns=None) for v in value]
        return f"({', '.join(parts)}) {unit}".rstrip()
    return str(value)


def facts_text(
    facts: Mapping[str, object], *, t0_ns: int | None = None, separator: str = " · "
) -> str:
    """Every fact of ``facts`` as text, in the mapping's order (see :func:`fact_text`)."""
    return separator.join(fact_text(k, v, t0_ns=t0_ns) for k, v in facts.items())
