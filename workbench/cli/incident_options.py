"""Options shared by the incident commands (incidents, label, labels export, review, export).

Every one of them finds the drive's incidents the same way: the options that decide the
incidents (and with them the ids) are generated once
(:mod:`workbench.cli.request_options`); the listing filters are declared here.
"""

from __future__ import annotations

import enum
import functools
from pathlib import Path
from typing import TYPE_CHECKING, Annotated

import typer

from workbench.cli.options import LogArgument
from workbench.cli.request_options import RequestCommand

if TYPE_CHECKING:
    from collections.abc import Callable

__all__ = [
    "ByOption",
    "CauseFilter",
    "EngineFilter",
    "Listing",
    "LogArgument",
    "MarginFilter",
    "ObjectFilter",
    "StoreOption",
    "with_checked_incidents",
    "with_incidents",
    "with_requests",
]

EngineFilter = Annotated[
    list[str] | None, typer.Option("--engine", help="Only this engine (repeatable).")
]
ObjectFilter = Annotated[
    list[str] | None, typer.Option("--object", help="Only this object id (repeatable).")
]
CauseFilter = Annotated[
    list[str] | None, typer.Option("--cause", help="Cause contains this (repeatable).")
]
MarginFilter = Annotated[
    float | None, typer.Option("--max-margin", help="Worst margin at most this.")
]


class Listing(enum.StrEnum):
    """``--by``: events (one per danger, all engines on one object) or incidents."""

    event = "event"
    incident = "incident"


ByOption = Annotated[
    Listing,
    typer.Option("--by", help="List events (one per danger, all engines) or incidents."),
]
StoreOption = Annotated[
    Path | None,
    typer.Option(
        "--store", help="Label store (default: $XDG_DATA_HOME/rss-workbench/labels.sqlite)."
    ),
]


def with_incidents(
    command: Callable[..., None],
    *,
    check: Callable[..., None] | None = None,
    find: bool = True,
) -> Callable[..., None]:
    """Give a command the incident options; it gets the drive's ``report`` found with them.

    The command declares ``log`` and ``report`` (not a CLI parameter) and its own options; the
    CLI sees ``log``, the command's options and the generated shared ones
    (:class:`~workbench.cli.request_options.RequestCommand`), so every incident command finds
    incidents, and so ids, the same way. ``check`` (see :func:`with_checked_incidents`) sees
    the command's own options first, so a bad choice fails before the drive is evaluated.
    ``find=False``: ``report`` is the ``IncidentRequest`` and the command finds the incidents
    in a pass of its own (``review`` with a viewer: one pass streams the drive and finds them).
    """
    return RequestCommand(command, inject="report", incidents=True, check=check, find=find)


def with_requests(command: Callable[..., None]) -> Callable[..., None]:
    """Give a command the incident options as ``requests``: drive path -> ``IncidentRequest``.

    Like :func:`with_incidents`, but nothing is evaluated: the command (``workbench batch``)
    builds one request per drive, each with the same settings.
    """
    return RequestCommand(command, inject="requests", incidents=True)


def with_checked_incidents(
    check: Callable[..., None],
) -> Callable[[Callable[..., None]], Callable[..., None]]:
    """:func:`with_incidents` whose ``check`` validates the command's own options first."""
    return functools.partial(with_incidents, check=check)
