"""The one registry of engines: built-ins, installed plugins and ones registered at run time.

Every place that lists engines (CLI choices and help, the blueprint, the demo table, the
Rerun and JSON sinks) iterates over this registry; adding an engine is one
:class:`~workbench.engines.base.EngineSpec` in one folder, registered by:

* being a built-in (:data:`BUILTIN`, a module with a ``SPEC`` attribute),
* an installed distribution's entry point in the group :data:`ENTRY_POINT_GROUP` naming an
  ``EngineSpec`` object, or
* :func:`register` at run time.

Built-ins and entry points load on first use, which keeps CLI start-up light.
"""

from __future__ import annotations

import dataclasses
import importlib
from importlib.metadata import entry_points
from typing import TYPE_CHECKING

from workbench.errors import WorkbenchError

if TYPE_CHECKING:
    from loaders.maps.model import LaneMap
    from workbench.engines.base import EngineRunner, EngineSettings, EngineSpec

__all__ = [
    "BUILTIN",
    "ENTRY_POINT_GROUP",
    "build_runners",
    "engine",
    "find",
    "names",
    "parse_engines",
    "register",
    "unregister",
]

#: Modules of the built-in engines, in the order they are listed and run.
BUILTIN = (
    "workbench.engines.reachsets",
    "workbench.engines.rss",
    "workbench.engines.unstructured",
)
#: Entry-point group of engine plugins of other distributions.
ENTRY_POINT_GROUP = "rss_workbench.engines"

_SPECS: dict[str, EngineSpec] = {}
_loaded = False


def _load() -> None:
    global _loaded  # noqa: PLW0603 - the registry is loaded once per process
    if _loaded:
        return
    _loaded = True
    for module in BUILTIN:
        spec = importlib.import_module(module).SPEC
        _SPECS.setdefault(spec.name, spec)
    for point in entry_points(group=ENTRY_POINT_GROUP):
        spec = point.load()
        _SPECS.setdefault(spec.name, spec)


def register(spec: EngineSpec) -> None:
    """Add an engine.

    Raises:
        WorkbenchError: An engine of that name exists.
    """
    _load()
    if spec.name in _SPECS:
        raise WorkbenchError(f"engine {spec.name!r} is registered already")
    _SPECS[spec.name] = spec


def unregister(name: str) -> None:
    """Remove an engine registered with :func:`register` (tests)."""
    _load()
    _SPECS.pop(name, None)


def names() -> tuple[str, ...]:
    """Names of every registered engine, built-ins first."""
    _load()
    return tuple(_SPECS)


def find(name: str) -> EngineSpec | None:
    """The spec of engine ``name``; ``None`` when none of that name is registered."""
    _load()
    return _SPECS.get(name)


def engine(name: str) -> EngineSpec:
    """The spec of engine ``name``.

    Raises:
        WorkbenchError: No such engine (the message lists the known ones).
    """
    spec = find(name)
    if spec is None:
        known = ", ".join(_SPECS)
        raise WorkbenchError(f"--engines: unknown engine {name!r} (known: {known})")
    return spec


def parse_engines(text: str) -> list[str]:
    """Split ``--engines a,b`` into validated names (empty names dropped, order kept).

    Raises:
        WorkbenchError: An unknown name.
    """
    found = [n.strip() for n in text.split(",") if n.strip()]
    for name in found:
        engine(name)
    return found


def build_runners(
    names_: list[str], lane_map: LaneMap | None, settings: EngineSettings
) -> list[EngineRunner]:
    """One runner per engine name, bound to the drive's lane map and one actor label table."""
    from workbench.engines.ids import ActorIds  # noqa: PLC0415 - light start-up

    drive_settings = dataclasses.replace(settings, actor_ids=ActorIds())
    return [engine(name).build(lane_map, drive_settings) for name in names_]
