"""Entry point of the ``workbench`` CLI.

Each command lives in its own module and registers itself on ``app``. Library errors that
come from the user's input are printed as one line with exit code 2; ``--debug`` shows the
traceback instead.
"""

from __future__ import annotations

import sys
from typing import Annotated

import typer

from workbench.cli import commands
from workbench.engines.registry import user_errors

__all__ = ["app", "main"]

app = typer.Typer(
    name="workbench",
    help="Replay, re-evaluate and review recorded drives for automated-driving safety.",
    no_args_is_help=True,
    pretty_exceptions_enable=False,
    add_completion=False,
)


@app.callback()
def _root(
    *,
    debug: Annotated[
        bool, typer.Option("--debug", help="Show full tracebacks instead of one-line errors.")
    ] = False,
) -> None:
    """Replay, re-evaluate and review recorded drives for automated-driving safety."""
    del debug  # read in main() before typer runs


commands.register_all(app)


def main(argv: list[str] | None = None) -> None:
    """Run the CLI, turning user-input errors into one line and exit code 2."""
    args = sys.argv[1:] if argv is None else argv
    debug = "--debug" in args
    try:
        app(args=args, standalone_mode=True)
    except user_errors() as err:
        if debug:
            raise
        typer.secho(f"error: {err}", err=True, fg=typer.colors.RED)
        sys.exit(2)
    except KeyboardInterrupt:
        typer.secho("interrupted", err=True)
        sys.exit(130)
