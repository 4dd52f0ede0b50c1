"""Engine selection shared by ``evaluate``, ``replay`` and ``demo``."""

from __future__ import annotations

import enum
from typing import TYPE_CHECKING

from workbench.errors import WorkbenchError

if TYPE_CHECKING:
    from pathlib import Path

    from loaders.drive import Drive
    from rss.params import RssParams
    from workbench.evaluate.pipeline import EngineRunner

__all__ = [
    "AVAILABLE_ENGINES",
    "ReachMethodOption",
    "build_engines",
    "load_rss_params",
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


def load_rss_params(path: Path | None) -> RssParams | None:
    """Read ``--rss-params FILE.toml`` (DESIGN.md); ``None`` keeps the defaults.

    Raises:
        WorkbenchError: The file cannot be read.
        RssParameterError: The TOML is malformed or has an unknown table, key or bad value.
    """
    from rss.params import parse_rss_params  # noqa: PLC0415 - keeps CLI start-up light

    if path is None:
        return None
    try:
        text = path.read_text()
    except OSError as err:
        raise WorkbenchError(f"--rss-params {path}: {err.strerror}") from err
    return parse_rss_params(text)


def build_engines(
    drive: Drive,
    names: list[str],
    reach_method: str,
    *,
    full_geometry: bool = False,
    rss_params: RssParams | None = None,
) -> list[EngineRunner]:
    """Engine runners for ``names`` (validated), bound to the drive's lane map.

    Args:
        drive: The opened drive (its lane map feeds the engines).
        names: Engine names from ``--engines``.
        reach_method: ``simple``, ``turn`` or ``bound``.
        full_geometry: Compute the geometry the viewer draws (every reachable set in full,
            RSS road-area outlines).
        rss_params: RSS dynamics and scene settings for ``rss`` and ``unstructured``.
    """
    from reachsets.params import ReachMethod  # noqa: PLC0415 - keeps CLI start-up light
    from workbench.evaluate.reach_runner import ReachRunner  # noqa: PLC0415
    from workbench.evaluate.rss_runner import RssRunner  # noqa: PLC0415
    from workbench.evaluate.unstructured_runner import UnstructuredRunner  # noqa: PLC0415

    engines: list[EngineRunner] = []
    for name in names:
        if name not in AVAILABLE_ENGINES:
            known = ", ".join(AVAILABLE_ENGINES)
            raise WorkbenchError(f"--engines: unknown engine {name!r} (known: {known})")
        if name == "rss":
            engines.append(RssRunner(drive.lane_map, rss_params, outlines=full_geometry))
            continue
        if name == "unstructured":
            engines.append(UnstructuredRunner(drive.lane_map, rss_params))
            continue
        engines.append(
            ReachRunner(
                drive.lane_map, method=ReachMethod(reach_method), full_geometry=full_geometry
            )
        )
    return engines
