"""What the goldens cover: every registered engine on every sample log, as ``evaluate`` runs it.

The records are those of ``workbench evaluate LOG --engines <every engine> --per-frame FILE``
with the command's defaults (run in this process), split by engine: the goldens pin exactly
what a user gets. Engines are independent of each other within a run, so one run per log
serves all of them.
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
    "EvaluateError",
    "evaluate_log",
    "golden_path",
    "sample_logs",
]

SAMPLE_DIR = Path(__file__).resolve().parents[2] / "sample_logs"
#: Where the golden files live: ``<engine>/<log>.jsonl``.
GOLDEN_DIR = Path(__file__).resolve().parent / "expected"
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


def golden_path(engine: str, log: str, root: Path = GOLDEN_DIR) -> Path:
    """The golden file of ``engine`` on the log named ``log``."""
    return root / engine / f"{log}.jsonl"


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


def evaluate_log(log: Path, engines: tuple[str, ...] | None = None) -> dict[str, list[FrameRecord]]:
    """Each engine's per-frame records of ``log`` (default: every registered engine).

    Raises:
        EvaluateError: The command failed (its message in the error).
    """
    engines = names() if engines is None else engines
    with tempfile.TemporaryDirectory(prefix="goldens-") as tmp:
        out = Path(tmp) / "frames.jsonl"
        args = ["evaluate", str(log), "--engines", ",".join(engines), "--per-frame", str(out)]
        code, err = _run(args)
        if code != 0 or not out.is_file():
            last = err.strip().splitlines()[-1:] or ["no message"]
            raise EvaluateError(f"{log.name}: workbench evaluate exited {code}: {last[0]}")
        lines = [json.loads(line) for line in out.read_text().splitlines()]
    return {
        name: [FrameRecord(line["frame"], line["t_ns"], line[name]) for line in lines]
        for name in engines
    }
