"""Engine options: each engine declares its own, one generic reader for the CLI, TOML and JSON.

An engine's options are the fields of one frozen dataclass (``EngineSpec.options``), each
made with :func:`option`:

* **name**: the field name, also the key in the engine's section of a ``--settings`` TOML
  file (``[reachsets] method = "bound"``) and of the request stored in ``batch.json``;
* **type**: the annotation: ``str``, ``int``, ``float``, ``bool``, ``Path`` or a ``StrEnum``
  (its values are the choices), each optionally ``| None``;
* **default**: the field default;
* **help** and **flag**: the CLI option (``--reach-method``); the flag without ``--`` and
  with ``_`` for ``-`` is its key in :meth:`IncidentRequest.record
  <workbench.incidents.IncidentRequest.record>`;
* **validation**: the type's conversion here, then the dataclass' own ``__post_init__``
  (a ``ValueError`` there becomes a one-line :class:`EngineOptionError`).

Two engines may declare the same flag (``rss`` and ``unstructured`` both read
``--rss-params``) when both declare it alike; the CLI then has one option feeding both.
A value given on the command line wins over the settings file, which wins over the default.
"""

from __future__ import annotations

import dataclasses
import enum
import math
import tomllib
import typing
from dataclasses import dataclass
from pathlib import Path
from types import NoneType, UnionType
from typing import TYPE_CHECKING, Any, Protocol

from workbench.errors import WorkbenchError

if TYPE_CHECKING:
    from collections.abc import Callable, Mapping

__all__ = [
    "Declared",
    "EngineOptionError",
    "OptionMeta",
    "declared",
    "option",
    "options_from",
    "options_json",
    "read_settings",
]

_META = "workbench.engine_option"
_SCALARS = (str, int, float, bool, Path)


class EngineSpec(Protocol):
    """What this module reads of an engine's spec (:class:`workbench.engines.EngineSpec`)."""

    @property
    def name(self) -> str:
        """The engine's name."""
        ...

    @property
    def options(self) -> type[Any]:
        """Its options dataclass."""
        ...


class EngineOptionError(WorkbenchError):
    """An engine option's value (command line, settings file or stored request) is invalid."""


@dataclass(frozen=True, slots=True)
class OptionMeta:
    """What an option declares besides its name, type and default.

    Attributes:
        flag: The CLI flag (``--reach-method``).
        help: One line for ``--help``.
        record: The value as recorded beside labels (default: enums by value, paths as
            they are — the request hashes them —, everything else as is).
    """

    flag: str
    help: str
    record: Callable[[Any], Any] | None = None


def option(
    default: Any,
    *,
    flag: str,
    help: str,  # noqa: A002 - the name typer and argparse give it
    record: Callable[[Any], Any] | None = None,
) -> Any:
    """A field of an engine's options dataclass (see the module docstring)."""
    meta = OptionMeta(flag, help, record)
    return dataclasses.field(default=default, metadata={_META: meta})


@dataclass(frozen=True, slots=True)
class Declared:
    """One option as an engine declares it.

    Attributes:
        engine: The engine's name.
        name: The field name (settings-file and stored-request key).
        kind: The value type without ``None``.
        optional: ``None`` is a valid value.
        default: The default value.
        meta: Flag, help and record conversion.
    """

    engine: str
    name: str
    kind: type
    optional: bool
    default: Any
    meta: OptionMeta

    @property
    def key(self) -> str:
        """CLI parameter name and record key: the flag without ``--``, ``_`` for ``-``."""
        return self.meta.flag.removeprefix("--").replace("-", "_")

    def same_as(self, other: Declared) -> bool:
        """Whether two engines declare this flag alike (so one CLI option can feed both)."""
        return (self.kind, self.optional, self.default, self.meta) == (
            other.kind,
            other.optional,
            other.default,
            other.meta,
        )

    def recorded(self, value: Any) -> Any:
        """The value as :meth:`IncidentRequest.record` keeps it."""
        if self.meta.record is not None:
            return self.meta.record(value)
        return value.value if isinstance(value, enum.Enum) else value


def _kind(annotation: Any) -> tuple[type, bool]:
    args = typing.get_args(annotation)
    if typing.get_origin(annotation) in {UnionType, typing.Union} and NoneType in args:
        (kind,) = (a for a in args if a is not NoneType)
        return kind, True
    return annotation, False


def declared(spec: EngineSpec) -> tuple[Declared, ...]:
    """The options ``spec`` declares, in field order.

    Raises:
        EngineOptionError: A field made without :func:`option` or of an unsupported type.
    """
    hints = typing.get_type_hints(spec.options)
    found = []
    for f in dataclasses.fields(spec.options):
        meta = f.metadata.get(_META)
        kind, optional = _kind(hints[f.name])
        if meta is None or not (issubclass(kind, enum.StrEnum) or kind in _SCALARS):
            msg = f"engine {spec.name!r}: option {f.name!r} needs option() and a plain type"
            raise EngineOptionError(msg)
        found.append(Declared(spec.name, f.name, kind, optional, f.default, meta))
    return tuple(found)


def _convert(d: Declared, raw: object, where: str, base: Path | None) -> Any:
    """``raw`` (a CLI value, or TOML / JSON data) as a value of ``d``'s type."""
    if raw is None and d.optional:
        return None
    if issubclass(d.kind, enum.StrEnum):
        if isinstance(raw, d.kind):
            return raw
        choices = [m.value for m in d.kind]
        if raw not in choices:
            raise EngineOptionError(f"{where}: {raw!r}: choose one of {', '.join(choices)}")
        return d.kind(raw)
    if d.kind is Path and isinstance(raw, str | Path):
        path = Path(raw)
        return path if base is None or path.is_absolute() else base / path
    if d.kind is float and isinstance(raw, int | float) and not isinstance(raw, bool):
        if not math.isfinite(raw):
            raise EngineOptionError(f"{where}: {raw!r}: give a finite number")
        return float(raw)
    if (
        d.kind is not float
        and isinstance(raw, d.kind)
        and not (d.kind is int and isinstance(raw, bool))
    ):
        return raw
    raise EngineOptionError(f"{where}: {raw!r}: expected a {d.kind.__name__}")


def options_from(
    spec: EngineSpec,
    cli: Mapping[str, Any] | None = None,
    section: Mapping[str, Any] | None = None,
    *,
    where: str = "settings",
    base: Path | None = None,
) -> Any:
    """The engine's typed options object from CLI values (by key) over a settings section.

    Args:
        spec: The engine.
        cli: CLI values by :attr:`Declared.key`; ``None`` values mean "not given".
        section: The engine's section of a settings file or stored request (by field name).
        where: How messages name the section (``settings.toml [rss]``).
        base: Directory relative paths of the section are relative to.

    Raises:
        EngineOptionError: An unknown key, a value of the wrong type, or one the options'
            own validation refuses.
    """
    cli, section = cli or {}, section or {}
    options = declared(spec)
    unknown = sorted(set(section) - {d.name for d in options})
    if unknown:
        known = ", ".join(d.name for d in options) or "none"
        raise EngineOptionError(f"{where}: unknown option {unknown[0]!r} (known: {known})")
    values: dict[str, Any] = {}
    for d in options:
        if cli.get(d.key) is not None:
            values[d.name] = _convert(d, cli[d.key], d.meta.flag, None)
        elif d.name in section:
            values[d.name] = _convert(d, section[d.name], f"{where} {d.name}", base)
    try:
        return spec.options(**values)
    except ValueError as err:
        source = where if section else f"engine {spec.name}"
        raise EngineOptionError(f"{source}: {err}") from err


def options_json(spec: EngineSpec, options: Any) -> dict[str, Any]:
    """The options as JSON data by field name (enums by value, paths as text)."""
    out: dict[str, Any] = {}
    for d in declared(spec):
        value = getattr(options, d.name)
        if isinstance(value, Path):
            value = str(value)
        out[d.name] = value.value if isinstance(value, enum.Enum) else value
    return out


def read_settings(path: Path) -> dict[str, dict[str, Any]]:
    """``--settings FILE.toml``: one table per engine, by engine name.

    Raises:
        EngineOptionError: The file cannot be read or parsed, or a top-level key is not a
            table.
    """
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except OSError as err:
        raise EngineOptionError(f"--settings {path}: {err.strerror}") from err
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as err:
        raise EngineOptionError(f"--settings {path}: not TOML ({err})") from err
    for name, table in data.items():
        if not isinstance(table, dict):
            msg = f"--settings {path}: {name!r} must be a table ([{name}]), one per engine"
            raise EngineOptionError(msg)
    return data
