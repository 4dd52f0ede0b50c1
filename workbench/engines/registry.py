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

import importlib
from importlib.metadata import entry_points
from typing import TYPE_CHECKING

from workbench.engines.base import BoundRunner
from workbench.errors import USER_ERRORS, WorkbenchError

if TYPE_CHECKING:
    from collections.abc import Mapping
    from pathlib import Path
    from typing import Any

    from loaders.maps.model import LaneMap
    from workbench.engines.base import EngineSpec
    from workbench.engines.options import Declared

__all__ = [
    "BUILTIN",
    "ENTRY_POINT_GROUP",
    "build_runners",
    "cli_options",
    "engine",
    "engine_options",
    "find",
    "names",
    "parse_engines",
    "register",
    "unregister",
    "user_errors",
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
        _add(importlib.import_module(module).SPEC)
    for point in entry_points(group=ENTRY_POINT_GROUP):
        spec = point.load()
        if spec.name not in _SPECS:
            _add(spec)


def _add(spec: EngineSpec) -> None:
    """Add ``spec`` once its options agree with the flags other engines declare."""
    from workbench.engines.options import declared  # noqa: PLC0415

    taken = {d.key: d for s in _SPECS.values() for d in declared(s)}
    for d in declared(spec):
        other = taken.get(d.key)
        if other is not None and not d.same_as(other):
            msg = f"engine {spec.name!r}: {d.meta.flag} is declared otherwise by {other.engine!r}"
            raise WorkbenchError(msg)
    _SPECS[spec.name] = spec


def register(spec: EngineSpec) -> None:
    """Add an engine.

    Raises:
        WorkbenchError: An engine of that name exists, or one of its option flags is
            declared otherwise by another engine.
    """
    _load()
    if spec.name in _SPECS:
        raise WorkbenchError(f"engine {spec.name!r} is registered already")
    _add(spec)


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
        WorkbenchError: An unknown name, or one named twice.
    """
    found = [n.strip() for n in text.split(",") if n.strip()]
    for k, name in enumerate(found):
        engine(name)
        if name in found[:k]:
            raise WorkbenchError(f"--engines {text}: {name!r} named twice")
    return found


def cli_options() -> dict[str, tuple[Declared, tuple[str, ...]]]:
    """Every option flag of the registered engines, by key: its declaration and its engines."""
    from workbench.engines.options import declared  # noqa: PLC0415

    out: dict[str, tuple[Declared, tuple[str, ...]]] = {}
    for spec in _all():
        for d in declared(spec):
            first, engines = out.get(d.key, (d, ()))
            out[d.key] = (first, (*engines, spec.name))
    return out


def engine_options(
    cli: Mapping[str, Any] | None = None, settings: Path | None = None
) -> dict[str, Any]:
    """Every registered engine's typed options: CLI values (by key) over ``--settings``.

    Raises:
        EngineOptionError: A bad value, a settings file that cannot be read or whose
            section names no engine or an unknown option.
    """
    from workbench.engines.options import (  # noqa: PLC0415
        EngineOptionError,
        options_from,
        read_settings,
    )

    sections = {} if settings is None else read_settings(settings)
    unknown = sorted(set(sections) - set(names()))
    if unknown:
        msg = f"--settings {settings}: [{unknown[0]}] names no engine (known: {', '.join(_SPECS)})"
        raise EngineOptionError(msg)
    base = None if settings is None else settings.parent
    return {
        spec.name: options_from(
            spec, cli, sections.get(spec.name), where=f"{settings} [{spec.name}]", base=base
        )
        for spec in _all()
    }


def _all() -> list[EngineSpec]:
    _load()
    return list(_SPECS.values())


def user_errors() -> tuple[type[Exception], ...]:
    """Errors that are the user's input: the workbench's, the loaders' and each engine's."""
    errors = [*USER_ERRORS]
    for spec in _all():
        errors.extend(e for e in spec.errors if e not in errors)
    return tuple(errors)


def build_runners(
    names_: list[str],
    lane_map: LaneMap | None,
    options: Mapping[str, Any] | None = None,
    *,
    full_geometry: bool = False,
) -> list[BoundRunner]:
    """One runner per engine name for the drive's lane map: own options, one actor label table.

    Each runner carries its engine's spec (:class:`~workbench.engines.base.BoundRunner`).

    Args:
        names_: Engine names, in order.
        lane_map: The drive's lane map.
        options: Each engine's options object by name (missing: the engine's defaults).
        full_geometry: Compute everything the viewer draws (replays), not only the verdicts.
    """
    from workbench.engines.ids import ActorIds  # noqa: PLC0415 - light start-up

    options = options or {}
    actor_ids = ActorIds()  # one label table for all the drive's engines
    runners = []
    for name in names_:
        spec = engine(name)
        own = options.get(name)
        own = spec.options() if own is None else own
        runner = spec.build(lane_map, own, full_geometry=full_geometry, actor_ids=actor_ids)
        runners.append(BoundRunner(spec, runner))
    return runners
