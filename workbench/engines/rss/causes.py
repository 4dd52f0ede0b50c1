"""The causes RSS verdicts name, and how one object's incident joins them.

A frame's cause lists the proper responses it demands (``runner._cause``):
``"RSS lon BrakeMin, lat-left BrakeMin"`` — the non-``None`` ones of longitudinal, lateral
left and lateral right; ``"RSS dangerous"`` when none is demanded. Over an approach of one
object these change from frame to frame (a second object's danger changes the frame's
responses too), so an RSS incident is one per object and unsafe run, and its cause is the
union of the responses its frames demanded, the stronger longitudinal one kept
(``BrakeMin`` over ``BrakeMinCorrect``).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from collections.abc import Sequence

__all__ = ["CAUSES", "join_causes"]

PREFIX = "RSS "
#: Every response a cause can name, strongest first per direction.
_ORDER = ("lon BrakeMin", "lon BrakeMinCorrect", "lat-left BrakeMin", "lat-right BrakeMin")
#: The single responses (``EngineSpec.causes``).
CAUSES = tuple(PREFIX + part for part in _ORDER[1::-1] + _ORDER[2:])
_NONE = "dangerous"


def join_causes(causes: Sequence[str]) -> str:
    """``"RSS lon BrakeMin, lat-left BrakeMin"``: the union of ``causes``' responses.

    Parts this module does not know are kept after the known ones, in order of appearance.
    """
    parts: list[str] = []
    for cause in causes:
        for part in cause.removeprefix(PREFIX).split(", "):
            if part and part not in parts:
                parts.append(part)
    if "lon BrakeMin" in parts and "lon BrakeMinCorrect" in parts:
        parts.remove("lon BrakeMinCorrect")
    known = [p for p in _ORDER if p in parts]
    other = [p for p in parts if p not in _ORDER and p != _NONE]
    joined = known + other
    return PREFIX + (", ".join(joined) if joined else _NONE)
