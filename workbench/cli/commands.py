"""Registry of CLI command modules; each module exposes ``register(app)``."""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import typer

__all__ = ["COMMAND_MODULES", "register_all"]

#: Modules whose ``register(app)`` adds commands, in help order.
COMMAND_MODULES: tuple[str, ...] = (
    "workbench.cli.info",
    "workbench.cli.replay",
    "workbench.cli.evaluate",
    "workbench.cli.demo",
    "workbench.cli.incidents",
    "workbench.cli.label",
    "workbench.cli.labels",
    "workbench.cli.review",
    "workbench.cli.export",
    "workbench.cli.batch",
    "workbench.cli.engines",
    "workbench.cli.conformance",
    "workbench.cli.samples",
)


def register_all(app: typer.Typer) -> None:
    """Import every command module and let it add its commands to ``app``."""
    for name in COMMAND_MODULES:
        importlib.import_module(name).register(app)
