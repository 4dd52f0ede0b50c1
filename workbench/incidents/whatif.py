"""What if: would an incident still be one under another RSS parameter profile?

The incident's window (with a margin before it, so the engines' memory settles) is evaluated
again with the same engine and settings but the other profile; the incident *stays* when the
re-evaluation has an incident of the same engine and object overlapping its frames.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import TYPE_CHECKING

from loaders.timebase import s_to_ns
from workbench.incidents.find import find_incidents

if TYPE_CHECKING:
    from workbench.incidents.find import IncidentRequest
    from workbench.incidents.model import Incident

__all__ = ["WhatIf", "what_if"]

#: Seconds evaluated before and after the incident.
MARGIN_S = 3.0


@dataclass(frozen=True, slots=True)
class WhatIf:
    """The incident under another profile.

    Attributes:
        profile: The profile tried.
        stays: Whether it is still an incident there.
        matches: The re-evaluation's incidents of the same engine and object that overlap it.
    """

    profile: str
    stays: bool
    matches: tuple[Incident, ...]

    def line(self) -> str:
        """One line for the reviewer."""
        if not self.stays:
            return f"what-if {self.profile}: no longer an incident"
        worst = min(m.severity.worst_margin for m in self.matches)
        return f"what-if {self.profile}: stays an incident (worst margin {worst:.2f})"


def what_if(request: IncidentRequest, incident: Incident, profile: str) -> WhatIf:
    """Re-evaluate ``incident``'s window with the RSS parameter profile ``profile``.

    Raises:
        RssParameterError: Unknown profile.
        LoaderError: The drive cannot be read.
    """
    other = dataclasses.replace(request, engines=(incident.engine,), rss_profile=profile)
    margin_ns = s_to_ns(MARGIN_S)
    window = (incident.start_ns - margin_ns, incident.end_ns + margin_ns + 1)
    matches = tuple(
        i
        for i in find_incidents(other, window=window).incidents
        if i.objects == incident.objects
        and i.start_ns <= incident.end_ns
        and i.end_ns >= incident.start_ns
    )
    return WhatIf(profile, bool(matches), matches)
