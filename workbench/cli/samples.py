"""``workbench samples OUTDIR``: write the deterministic sample drives and their maps."""

from __future__ import annotations

from pathlib import Path  # noqa: TC003  (typer resolves annotations at runtime)

import typer

from workbench.samples.generate import SCENARIOS, generate

__all__ = ["register"]


def samples(
    outdir: Path = typer.Argument(..., help="Directory to write the sample logs into."),  # noqa: B008
    scenario: list[str] = typer.Option(  # noqa: B008
        [], "--scenario", "-s", help="Only these scenarios (repeatable); default: all."
    ),
) -> None:
    """Generate the sample drives (MCAP, ROS 1 bag, rosbag2, Lanelet2 maps) into OUTDIR."""
    unknown = sorted(set(scenario) - set(SCENARIOS))
    if unknown:
        msg = f"unknown scenario(s) {', '.join(unknown)}; choose from {', '.join(SCENARIOS)}"
        raise typer.BadParameter(msg, param_hint="--scenario")
    for path in generate(outdir, scenario or None):
        typer.echo(str(path))


def register(app: typer.Typer) -> None:
    """Add the ``samples`` command to ``app``."""
    app.command("samples")(samples)
