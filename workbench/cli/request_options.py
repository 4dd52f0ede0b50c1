"""Commands that run engines: their shared options generated, one request built from them.

:class:`RequestCommand` wraps a command function. The signature typer reads is the
command's own parameters, then ``--engines``, the drive options (``--map``, ``--profile``,
``--ego-id``, ``--ego-topic``, ``--ego-size``), ``--settings`` and every registered engine's
options (:func:`workbench.cli.options.engine_parameters`), and for the incident commands
``--min-duration`` / ``--merge-gap``.

How typer sees a generated signature: typer reads a command's parameters with
``inspect.signature(callback)`` each time it builds the click command (on every
``app(...)`` call, so also after a test registered an engine). ``inspect.signature`` of an
object takes its ``__signature__`` attribute; here that is a property computed from the
registry at that moment, and ``__call__`` pops the generated values again, builds the
:class:`~workbench.incidents.IncidentRequest` and passes it (or a per-drive factory of it,
or the drive's incidents found with it) to the command under one keyword.
"""

from __future__ import annotations

import functools
import inspect
import typing
from typing import TYPE_CHECKING, Annotated, Any, Literal

import typer

from workbench.cli.options import (
    DRIVE_PARAMETERS,
    EGO_SIZE_PARAMETER,
    engine_parameters,
    engines_parameter,
    keyword,
)
from workbench.cli.progress import frame_progress
from workbench.errors import WorkbenchError

if TYPE_CHECKING:
    from collections.abc import Callable
    from pathlib import Path

    from workbench.incidents import IncidentReport, IncidentRequest

__all__ = ["INCIDENT_PARAMETERS", "RequestCommand", "build_request", "find_with_progress"]

MinDurationOption = Annotated[
    float,
    typer.Option("--min-duration", help="Drop incidents shorter than this many seconds.", min=0.0),
]
MergeGapOption = Annotated[
    float,
    typer.Option(
        "--merge-gap", help="Bridge safe stretches of at most this many seconds.", min=0.0
    ),
]
#: The options that merge verdicts into incidents (the incident commands and ``batch``).
INCIDENT_PARAMETERS = (
    keyword("min_duration", MinDurationOption, 0.0),
    keyword("merge_gap", MergeGapOption, 0.0),
)

#: ``--engines`` not given: every registered engine, or none.
Engines = Literal["all", "none"]
_ENGINES_HELP = {
    "all": "Comma-separated (default: every registered engine; `workbench engines` lists them).",
    "none": "Also evaluate and show these (`workbench engines` lists them).",
}


def build_request(
    log: Path,
    *,
    engines: str | None = None,
    default_engines: Engines = "all",
    need_engines: bool = False,
    map_path: Path | None = None,
    profile: Path | None = None,
    ego_id: str | None = None,
    ego_topic: str | None = None,
    ego_size: str | None = None,
    settings: Path | None = None,
    min_duration: float = 0.0,
    merge_gap: float = 0.0,
    **engine_values: Any,
) -> IncidentRequest:
    """The request the options of one command describe.

    Args:
        log: The drive.
        engines: ``--engines`` (``None``: not given, ``default_engines`` apply).
        default_engines: Without ``--engines``: every registered engine, or none.
        need_engines: Refuse a request without an engine.
        map_path: ``--map``.
        profile: ``--profile`` (topic roles).
        ego_id: ``--ego-id``.
        ego_topic: ``--ego-topic``.
        ego_size: ``--ego-size L,W[,H]``.
        settings: ``--settings`` TOML (one table per engine).
        min_duration: ``--min-duration`` [s].
        merge_gap: ``--merge-gap`` [s].
        **engine_values: The generated engine options by key (``None``: not given).

    Raises:
        WorkbenchError: Unknown or repeated engine, a bad ``--ego-size``, or an engine
            option or settings file that is invalid.
    """
    from workbench.drives import parse_ego_size  # noqa: PLC0415 - light start-up
    from workbench.engines.registry import engine_options, names, parse_engines  # noqa: PLC0415
    from workbench.incidents import IncidentRequest, IncidentSettings  # noqa: PLC0415

    if engines is None:
        chosen = list(names()) if default_engines == "all" else []
    else:
        chosen = parse_engines(engines)
    if need_engines and not chosen:
        raise WorkbenchError("--engines: name at least one engine")
    return IncidentRequest(
        log=log,
        engines=tuple(chosen),
        map_path=map_path,
        profile=profile,
        ego_id=ego_id,
        ego_topic=ego_topic,
        settings=IncidentSettings(min_duration_s=min_duration, merge_gap_s=merge_gap),
        ego_size=None if ego_size is None else parse_ego_size(ego_size),
        options=engine_options(engine_values, settings),
    )


def find_with_progress(request: IncidentRequest) -> IncidentReport:
    """Find the request's incidents with a progress bar on stderr."""
    from workbench.incidents import find_incidents  # noqa: PLC0415 - light start-up

    with frame_progress() as bar:
        task = bar.add_task(f"incidents {request.log.name}", total=None)
        return find_incidents(request, progress=lambda done: bar.update(task, completed=done))


class RequestCommand:
    """A command function with the generated options; it receives what they describe.

    Args:
        command: The command; it declares ``inject`` (not a CLI parameter) and its own
            options (``log`` among them unless ``inject`` is ``requests``).
        inject: What the command gets: ``request`` (the drive's request), ``requests`` (a
            drive path -> request factory, several drives with the same options) or
            ``report`` (the drive's incidents found with the request).
        engines: ``--engines`` not given means every engine or none; ``None``: the command
            has no ``--engines`` (every engine's options still apply).
        drive: The command has the options of one drive's loader (``--map`` ...).
        incidents: The command has the incident options (``--min-duration`` ...).
        check: Validates the command's own options before anything is evaluated.
        need_engines: The command refuses to run without an engine.
        find: With ``inject="report"``: ``False`` gives the command the request under
            ``report`` instead, and it finds the incidents in a pass of its own (``review``
            with a viewer: one pass streams the drive and finds them).
    """

    def __init__(
        self,
        command: Callable[..., None],
        *,
        inject: Literal["request", "requests", "report"],
        engines: Engines | None = "all",
        drive: bool = True,
        incidents: bool = False,
        check: Callable[..., None] | None = None,
        need_engines: bool = True,
        find: bool = True,
    ) -> None:
        """Wrap ``command`` (see the class docstring)."""
        self.__wrapped__ = command
        self.__doc__ = command.__doc__
        self.__name__ = command.__name__
        self._inject = inject
        self._engines = engines
        self._drive = drive
        self._incidents = incidents
        self._check = check
        self._need_engines = need_engines
        self._find = find
        hints = typing.get_type_hints(command, include_extras=True, localns=_LOCALNS)
        self._own = [
            p.replace(annotation=hints.get(p.name, p.annotation))
            for p in inspect.signature(command).parameters.values()
            if p.name != inject
        ]

    def _shared(self) -> list[inspect.Parameter]:
        params = []
        if self._engines is not None:
            params.append(engines_parameter(None, _ENGINES_HELP[self._engines]))
        if self._drive:
            params.extend(DRIVE_PARAMETERS)
        params.extend([EGO_SIZE_PARAMETER, *engine_parameters()])
        if self._incidents:
            params.extend(INCIDENT_PARAMETERS)
        return params

    @property
    def __signature__(self) -> inspect.Signature:
        """What typer reads: the command's own parameters, then the generated ones."""
        return inspect.Signature([*self._own, *self._shared()])

    @property
    def __annotations__(self) -> dict[str, Any]:  # type: ignore[override]
        """The annotations of :attr:`__signature__` (typer resolves hints with them)."""
        return {p.name: p.annotation for p in self.__signature__.parameters.values()}

    def __call__(self, **kwargs: Any) -> None:
        """Build the request from the generated options and run the command with it."""
        shared = {p.name: kwargs.pop(p.name) for p in self._shared()}
        if self._check is not None:
            self._check(**kwargs)
        default: Engines = self._engines or "all"
        requests: Callable[[Path], IncidentRequest] = functools.partial(
            build_request, default_engines=default, need_engines=self._need_engines, **shared
        )
        if self._inject == "requests":
            self.__wrapped__(requests=requests, **kwargs)
            return
        request = requests(kwargs["log"])
        if self._inject == "request":
            self.__wrapped__(request=request, **kwargs)
            return
        self.__wrapped__(report=find_with_progress(request) if self._find else request, **kwargs)


#: Names a command may annotate with that are imported for type checking only.
_LOCALNS = {
    "IncidentReport": Any,
    "IncidentRequest": Any,
    "Callable": typing.Callable,
}
