"""What a drive left out: one line (or details) after ``info``, ``evaluate`` and ``replay``."""

from __future__ import annotations

from typing import Annotated

import typer

__all__ = ["VerboseOption", "echo_losses"]

#: ``--verbose``: one line per kind of loss instead of the summary line.
VerboseOption = Annotated[
    bool, typer.Option("--verbose", help="Detail every dropped or ignored message kind.")
]


def echo_losses(notes: dict[str, str], *, verbose: bool) -> None:
    """Print the loss summary line (or the detail lines with ``verbose``); nothing if none."""
    from loaders.losses import loss_details, loss_summary  # noqa: PLC0415 - light start-up

    if verbose:
        for line in loss_details(notes):
            typer.echo(f"lost: {line}")
        return
    summary = loss_summary(notes)
    if summary is not None:
        typer.echo(summary)
