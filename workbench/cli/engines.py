"""``workbench engines``: the registered engines, their viewer tabs and violation causes."""

from __future__ import annotations

from typing import TYPE_CHECKING

from rich.table import Table

from workbench.cli.tables import print_table

if TYPE_CHECKING:
    import typer

__all__ = ["register"]


def engines() -> None:
    """List the engines ``--engines`` accepts (built-ins and installed plugins)."""
    from workbench.engines.registry import engine, names  # noqa: PLC0415 - start-up light

    table = Table(title="engines")
    for column in ("name", "viewer tab", "violation causes"):
        table.add_column(column)
    for name in names():
        spec = engine(name)
        table.add_row(spec.name, spec.title, ", ".join(spec.causes))
    print_table(table)


def register(app: typer.Typer) -> None:
    """Add ``engines`` to the CLI."""
    app.command("engines")(engines)
