"""``workbench engines``: the registered engines, their options, viewer tabs and causes."""

from __future__ import annotations

from typing import TYPE_CHECKING

from rich.table import Table

from workbench.cli.tables import print_table

if TYPE_CHECKING:
    import typer

__all__ = ["register"]


def engines() -> None:
    """List the engines ``--engines`` accepts (built-ins and installed plugins)."""
    from workbench.engines.options import declared  # noqa: PLC0415 - start-up light
    from workbench.engines.registry import engine, names  # noqa: PLC0415

    table = Table(title="engines")
    for column in ("name", "options (--settings key: flag)", "viewer tab", "violation causes"):
        table.add_column(column)
    for name in names():
        spec = engine(name)
        options = "\n".join(f"{d.name}: {d.meta.flag}" for d in declared(spec)) or "-"
        table.add_row(spec.name, options, spec.title, ", ".join(spec.causes))
    print_table(table)


def register(app: typer.Typer) -> None:
    """Add ``engines`` to the CLI."""
    app.command("engines")(engines)
