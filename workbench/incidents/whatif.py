"""What if: would an incident still be one under other options of its engine?

The variants are the engine's own (``EngineSpec.what_if``: the RSS engines try every
parameter profile). The incident's window (with a margin before it, so the engines' memory
settles) is evaluated again with the same engine and settings but the variant's options;
the incident *stays* when the re-evaluation has an incident of the same engine and object
overlapping its frames.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from loaders.timebase import s_to_ns
from workbench.errors import WorkbenchError
from workbench.incidents.find import find_incidents

if TYPE_CHECKING:
    from workbench.incidents.find import IncidentRequest
    from workbench.incidents.model import Incident

__all__ = ["WhatIf", "variants", "what_if"]

#: Seconds evaluated before and after the incident.
MARGIN_S = 3.0


@dataclass(frozen=True, slots=True)
class WhatIf:
    """The incident under a variant of its engine's options.

    Attributes:
        profile: The variant tried (its label, e.g. a profile name).
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


def _offer(request: IncidentRequest, incident: Incident) -> dict[str, Any]:
    """The incident's engine's what-if variants: options by label."""
    from workbench.engines.registry import engine  # noqa: PLC0415

    offer = engine(incident.engine).what_if
    return {} if offer is None else dict(offer(request.options_of(incident.engine)))


def variants(request: IncidentRequest, incident: Incident) -> tuple[str, ...]:
    """Labels of the what-if variants the incident's engine offers (none: no what-if)."""
    return tuple(_offer(request, incident))


def what_if(request: IncidentRequest, incident: Incident, variant: str) -> WhatIf:
    """Re-evaluate ``incident``'s window with its engine's what-if variant ``variant``.

    Raises:
        WorkbenchError: The engine offers no such variant.
        LoaderError: The drive cannot be read.
    """
    name, chosen = incident.engine, _offer(request, incident)
    if variant not in chosen:
        known = ", ".join(chosen) or "none"
        raise WorkbenchError(f"what-if {variant!r}: engine {name} offers {known}")
    other = dataclasses.replace(request.with_options(name, chosen[variant]), engines=(name,))
    margin_ns = s_to_ns(MARGIN_S)
    window = (incident.start_ns - margin_ns, incident.end_ns + margin_ns + 1)
    matches = tuple(
        i
        for i in find_incidents(other, window=window).incidents
        if i.objects == incident.objects
        and i.start_ns <= incident.end_ns
        and i.end_ns >= incident.start_ns
    )
    return WhatIf(variant, bool(matches), matches)
