"""``workbench conformance rss CASES.json``: evaluate RSS conformance cases as JSON lines."""

from __future__ import annotations

import json
from pathlib import Path  # noqa: TC003  (typer reads the annotations at runtime)
from typing import Annotated, Any

import typer

from rss.conformance import evaluate_document
from rss.errors import RssCaseError
from workbench.driver import engine_gc
from workbench.errors import WorkbenchError
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
    with engine_gc():  # the drive pipeline's collector threshold (docs/rss_scene.md)
        for record in evaluate_document(document):
            typer.echo(json_text(record))


def _read_reach_cases(path: Path) -> Any:
    from reachsets.conformance import ReachCaseError  # noqa: PLC0415 - light start-up

    try:
        return json.loads(path.read_text())
    except json.JSONDecodeError as err:
        raise ReachCaseError(str(path), "<document>", "json", err.msg, "not valid JSON") from err
    except (OSError, UnicodeDecodeError) as err:
        raise ReachCaseError(str(path), "<document>", "file", str(path), str(err)) from err


@conformance_app.command("reachsets")
def reach_cases(
    cases: Annotated[
        Path,
        typer.Argument(exists=True, dir_okay=False, help="Case file (docs/reachset-cases.md)."),
    ],
    *,
    full_sets: Annotated[
        bool,
        typer.Option(
            "--full-sets", help="Reduce every reachable set and write its outlines (`sets`)."
        ),
    ] = False,
) -> None:
    """Rate every reach-set case (and sequence step); print one JSON object per line."""
    from reachsets.conformance import evaluate_cases, prepare_document  # noqa: PLC0415

    prepared = prepare_document(_read_reach_cases(cases), str(cases), full_sets=full_sets)
    with engine_gc():
        for record in evaluate_cases(prepared):
            typer.echo(json_text(record))


@conformance_app.command("reachsets-cases")
def make_reach_cases(
    out: Annotated[Path, typer.Argument(dir_okay=False, help="Case file to write (JSON).")],
    *,
    random: Annotated[
        int | None, typer.Option("--random", min=1, help="Write this many random cases.")
    ] = None,
    seed: Annotated[int, typer.Option("--seed", help="Seed of the random cases.")] = 0,
    sequences: Annotated[
        int, typer.Option("--sequences", min=0, help="Random sequences (4 steps) to add.")
    ] = 0,
    log: Annotated[
        Path | None,
        typer.Option(
            "--log", dir_okay=True, help="A drive on a track: one sequence of its frames."
        ),
    ] = None,
    method: Annotated[
        list[str] | None,
        typer.Option(
            "--method",
            help="simple, turn or bound (repeat to cycle; default: all three, turn for --log).",
        ),
    ] = None,
) -> None:
    """Write a reach-set case file: seeded random cases (--random N) or a drive (--log FILE)."""
    import numpy as np  # noqa: PLC0415 - light start-up

    from reachsets import ReachMethod  # noqa: PLC0415
    from reachsets.conformance import random_document  # noqa: PLC0415

    if (random is None) == (log is None):
        msg = "reachsets-cases: give exactly one of --random N and --log FILE"
        raise WorkbenchError(msg)
    names = method or (["turn"] if log is not None else [m.value for m in ReachMethod])
    for name in names:
        if name not in {m.value for m in ReachMethod}:
            msg = f"--method {name!r}: expected simple, turn or bound"
            raise WorkbenchError(msg)
    if log is not None:
        from workbench.drives import open_log  # noqa: PLC0415
        from workbench.engines.registry import engine  # noqa: PLC0415

        to_cases = engine("reachsets").case_document
        assert to_cases is not None  # the reach-set engine writes its case documents
        drive = open_log(log, map_path=None, profile=None, ego_id=None)
        try:
            document = to_cases(drive, name=log.stem, method=names[0], source=str(log))
        finally:
            drive.close()
    else:
        assert random is not None
        rng = np.random.default_rng(seed)
        document = random_document(rng, random, methods=names, sequences=sequences)
    out.write_text(json_text(document, compact=True) + "\n")
    typer.echo(f"wrote {len(document['cases'])} cases to {out}", err=True)
    # a drive's steps carry a note only where objects were left out (non-finite values)
    left = sum(1 for case in document["cases"] for s in case.get("sequence", []) if "note" in s)
    if left and log is not None:
        typer.echo(
            f"{log}: {left} step(s) leave out objects with a non-finite pose, speed or size"
            " (named in each step's note)",
            err=True,
        )


def register(app: typer.Typer) -> None:
    """Add the ``conformance`` command group to the CLI."""
    app.add_typer(conformance_app, name="conformance")
