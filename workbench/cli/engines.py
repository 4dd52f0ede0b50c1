"""Engine selection shared by ``evaluate``, ``replay`` and ``demo``."""

from __future__ import annotations

import enum
from typing import TYPE_CHECKING

from workbench.errors import WorkbenchError

if TYPE_CHECKING:
    from loaders.drive import Drive
    from workbench.evaluate.pipeline import EngineRunner

__all__ = [
    "AVAILABLE_ENGINES",
    "PENDING_ENGINES",
    "ReachMethodOption",
    "build_engines",
    "parse_engines",
]


class ReachMethodOption(enum.StrEnum):
    """``--reach-method`` values."""

    simple = "simple"
    turn = "turn"
    bound = "bound"


def parse_engines(text: str) -> list[str]:
    """Split ``--engines a,b`` into names (empty names dropped)."""
    return [n.strip() for n in text.split(",") if n.strip()]


#: Engines that evaluate recorded drives in this build.
AVAILABLE_ENGINES = ("reachsets", "rss", "unstructured")
#: Engines that exist but cannot run on recorded drives yet, with the reason.
PENDING_ENGINES: dict[str, str] = {}


def build_engines(
    drive: Drive, names: list[str], reach_method: str, *, full_geometry: bool = False
) -> list[EngineRunner]:
    """Engine runners for ``names`` (validated), bound to the drive's lane map.

    Args:
        drive: The opened drive (its lane map feeds the engines).
        names: Engine names from ``--engines``.
        reach_method: ``simple``, ``turn`` or ``bound``.
        full_geometry: Compute every reachable set in full (needed to draw them).
    """
    from reachsets.params import ReachMethod  # noqa: PLC0415 - keeps CLI start-up light
    from workbench.evaluate.reach_runner import ReachRunner  # noqa: PLC0415
    from workbench.evaluate.rss_runner import RssRunner  # noqa: PLC0415
    from workbench.evaluate.unstructured_runner import UnstructuredRunner  # noqa: PLC0415

    engines: list[EngineRunner] = []
    for name in names:
        if name in PENDING_ENGINES:
            raise WorkbenchError(f"--engines {name}: {PENDING_ENGINES[name]}")
        if name not in AVAILABLE_ENGINES:
            known = ", ".join([*AVAILABLE_ENGINES, *PENDING_ENGINES])
            raise WorkbenchError(f"--engines: unknown engine {name!r} (known: {known})")
        if name == "rss":
            engines.append(RssRunner(drive.lane_map))
            continue
        if name == "unstructured":
            engines.append(UnstructuredRunner(drive.lane_map))
            continue
        engines.append(
            ReachRunner(
                drive.lane_map, method=ReachMethod(reach_method), full_geometry=full_geometry
            )
        )
    return engines
