"""What the goldens cover: every variant x registered engine x sample log, as ``evaluate`` runs it.

The records are those of ``workbench evaluate LOG --engines <every engine> --per-frame FILE
<the variant's arguments>`` (run in this process), split by engine: the goldens pin exactly
what a user gets. A variant is one entry of :data:`VARIANTS`: ``default`` (the command's
defaults) and ``adrss-5.0`` (the exact reference mode). Engines are independent of each
other within a run, so one run per variant and log serves all of them.
"""

from __future__ import annotations

import contextlib
import io
import json
import tempfile
from pathlib import Path

from tests.goldens.golden_file import FrameRecord
from workbench.cli.main import main as workbench_main
from workbench.engines.registry import names

__all__ = [
    "GOLDEN_DIR",
    "SAMPLE_DIR",
    "VARIANTS",
    "EvaluateError",
    "evaluate_log",
    "golden_path",
    "sample_logs",
]

SAMPLE_DIR = Path(__file__).resolve().parents[2] / "sample_logs"
#: Where the golden files live: ``<variant>/<engine>/<log>.jsonl``.
GOLDEN_DIR = Path(__file__).resolve().parent / "expected"
#: The pinned variants: name -> the ``evaluate`` arguments added to the common ones. One
#: entry adds a variant (its directory, its tests, its part of ``make goldens``). Every
#: engine is pinned in every variant: which settings an engine reads is its own business, so
#: the harness cannot tell which arguments leave its records alone.
VARIANTS: dict[str, tuple[str, ...]] = {
    # the command's defaults: the RSS profile chosen per drive (docs/rss.md)
    "default": (),
    # the exact reference mode: structured RSS identical to ad-rss 5.0
    "adrss-5.0": ("--rss-profile", "adrss-5.0"),
}
#: Container suffixes of the drive logs in ``sample_logs/``.
_LOG_SUFFIXES = (".mcap", ".bag", ".saa", ".xml", ".osi")
#: A rosbag2 directory of a sample holds its ``.mcap``'s messages in another container
#: (docs/samples.md); the loaders' contract test covers it, the goldens skip it.
_ROSBAG2_SUFFIX = "_rosbag2"


class EvaluateError(Exception):
    """``workbench evaluate`` failed on a sample (the message names the log and the error)."""


def sample_logs(root: Path = SAMPLE_DIR) -> tuple[Path, ...]:
    """Every drive log of ``root`` the goldens cover, sorted by name."""
    if not root.is_dir():
        return ()
    return tuple(
        sorted(p for p in root.iterdir() if p.is_file() and p.name.endswith(_LOG_SUFFIXES))
    )


def golden_path(variant: str, engine: str, log: str, root: Path = GOLDEN_DIR) -> Path:
    """The golden file of ``engine`` on the log named ``log`` in ``variant``."""
    return root / variant / engine / f"{log}.jsonl"


def _run(args: list[str]) -> tuple[int, str]:
    err = io.StringIO()
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(err):
        try:
            workbench_main(args)
        except SystemExit as done:
            code = done.code
        else:
            code = 0
    return (0 if code is None else int(code)), err.getvalue()


def evaluate_log(
    log: Path, engines: tuple[str, ...] | None = None, variant: str = "default"
) -> dict[str, list[FrameRecord]]:
    """Each engine's per-frame records of ``log`` (default: every registered engine).

    Args:
        log: The sample log.
        engines: Engine names (default: every registered engine).
        variant: A key of :data:`VARIANTS`: the ``evaluate`` arguments added.

    Raises:
        EvaluateError: The command failed (its message in the error).
    """
    engines = names() if engines is None else engines
    with tempfile.TemporaryDirectory(prefix="goldens-") as tmp:
        out = Path(tmp) / "frames.jsonl"
        args = ["evaluate", str(log), "--engines", ",".join(engines), "--per-frame", str(out)]
        code, err = _run([*args, *VARIANTS[variant]])
        if code != 0 or not out.is_file():
            last = err.strip().splitlines()[-1:] or ["no message"]
            where = f"{log.name} ({variant})"
            raise EvaluateError(f"{where}: workbench evaluate exited {code}: {last[0]}")
        lines = [json.loads(line) for line in out.read_text().splitlines()]
    return {
        name: [FrameRecord(line["frame"], line["t_ns"], line[name]) for line in lines]
        for name in engines
    }
