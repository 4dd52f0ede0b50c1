"""``workbench conformance rss CASES.json``: evaluate RSS conformance cases as JSON lines."""

from __future__ import annotations

import json
from pathlib import Path  # noqa: TC003  (typer reads the annotations at runtime)
from typing import Annotated

import typer

from rss.conformance import evaluate_document
from rss.errors import RssCaseError
from workbench.outputs import json_text

__all__ = ["register"]

conformance_app = typer.Typer(
    help="Conformance runs against reference case files.", no_args_is_help=True
)


@conformance_app.command("rss")
def rss_cases(
    cases: Annotated[
        Path,
        typer.Argument(exists=True, dir_okay=False, help="Case file (rss-cases-format.md)."),
    ],
) -> None:
    """Evaluate every case (and sequence step) and print one JSON object per line."""
    try:
        document = json.loads(cases.read_text())
    except json.JSONDecodeError as err:
        raise RssCaseError(str(cases), f"not valid JSON: {err}") from err
    for record in evaluate_document(document):
        typer.echo(json_text(record))


def register(app: typer.Typer) -> None:
    """Add the ``conformance`` command group to the CLI."""
    app.add_typer(conformance_app, name="conformance")
