"""The causes RSS verdicts name, and how one object's incident joins them.

A frame's cause is the proper responses it demands, typed (:class:`RssCause`: the
longitudinal, lateral left and lateral right response of the frame); its text, written only
by the sinks, lists the non-``None`` ones: ``"RSS lon BrakeMin, lat-left BrakeMin"``, or
``"RSS dangerous"`` when none is demanded. Over an approach of one object the responses
change from frame to frame (a second object's danger changes the frame's responses too), so
an RSS incident is one per object and unsafe run, and its cause joins the responses its
frames demanded, the strongest per direction (``BrakeMin`` over ``BrakeMinCorrect``).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from rss.structured.states import LateralResponse, LongitudinalResponse

if TYPE_CHECKING:
    from collections.abc import Sequence

__all__ = ["CAUSES", "RssCause", "join_causes"]

PREFIX = "RSS "
_NONE = "dangerous"


@dataclass(frozen=True, slots=True)
class RssCause:
    """The proper responses an unsafe frame (or an incident, joined) demands.

    Attributes:
        lon: Longitudinal response.
        lat_left: Lateral response towards the left.
        lat_right: Lateral response towards the right.
    """

    lon: LongitudinalResponse = LongitudinalResponse.None_
    lat_left: LateralResponse = LateralResponse.None_
    lat_right: LateralResponse = LateralResponse.None_

    def __str__(self) -> str:
        """``"RSS lon BrakeMin, lat-left BrakeMin"``: the demanded responses, in that order."""
        parts = [
            f"{name} {response}"
            for name, response in (
                ("lon", self.lon),
                ("lat-left", self.lat_left),
                ("lat-right", self.lat_right),
            )
            if response != 0
        ]
        return PREFIX + (", ".join(parts) if parts else _NONE)

    def joined(self, other: RssCause) -> RssCause:
        """The stronger response of the two causes in each direction."""
        return RssCause(
            max(self.lon, other.lon),
            max(self.lat_left, other.lat_left),
            max(self.lat_right, other.lat_right),
        )


#: The single responses (``EngineSpec.causes``), as text.
CAUSES = tuple(
    str(cause)
    for cause in (
        RssCause(lon=LongitudinalResponse.BrakeMinCorrect),
        RssCause(lon=LongitudinalResponse.BrakeMin),
        RssCause(lat_left=LateralResponse.BrakeMin),
        RssCause(lat_right=LateralResponse.BrakeMin),
    )
)


def join_causes(causes: Sequence[object]) -> str:
    """``"RSS lon BrakeMin, lat-left BrakeMin"``: the text of ``causes`` joined.

    Raises:
        TypeError: A cause that is not an :class:`RssCause` (another engine's).
    """
    joined = RssCause()
    for cause in causes:
        if not isinstance(cause, RssCause):
            msg = f"not an RSS cause: {cause!r}"
            raise TypeError(msg)
        joined = joined.joined(cause)
    return str(joined)
