"""``python -m tests.goldens.update`` (``make goldens``): rewrite the goldens, report the change.

The one update switch of the golden harness. It refuses to run under ``CI=true`` (exit 2):
CI compares the goldens and never writes them. The tests never write a golden file, so a
run that updates cannot pass by comparing a file with itself: this tool writes, and
says per file what it changed; ``pytest tests/goldens`` then compares as always.

Usage::

    python -m tests.goldens.update [--engine NAME]... [--log NAME]...

For every registered engine and every sample log (or those named), it evaluates the log
(:mod:`tests.goldens.samples`), compares the records with the golden file within the
tolerance of :mod:`tests.goldens.compare` and rewrites only files that differ beyond it
(or are missing or unreadable). Per file it prints ``new``, ``unchanged`` or ``updated``
with the changed frames, the record keys that changed in how many frames, the safe/unsafe
flips and the first difference. Without ``--engine``/``--log`` it also removes golden files
of engines or logs that no longer exist.
"""

from __future__ import annotations

import argparse
import sys
from collections import Counter
from typing import TYPE_CHECKING, TextIO

from tests.conftest import running_in_ci
from tests.goldens.compare import compare
from tests.goldens.golden_file import GoldenFileError, golden_text, read_golden
from tests.goldens.samples import (
    GOLDEN_DIR,
    SAMPLE_DIR,
    EvaluateError,
    evaluate_log,
    golden_path,
    sample_logs,
)
from workbench.engines.registry import names

if TYPE_CHECKING:
    from pathlib import Path

    from tests.goldens.golden_file import FrameRecord

__all__ = ["main", "update"]

#: Exit code of a refused or failed update.
_FAILED = 2


def _indented(text: str) -> str:
    return "".join(f"    {line}\n" for line in text.splitlines())


def _one(engine: str, log: str, got: list[FrameRecord], root: Path, out: TextIO) -> str:
    """Compare, write when changed, report; the outcome's name."""
    path = golden_path(engine, log, root)
    name = str(path.relative_to(root))
    text = golden_text(engine, log, got)
    try:
        stored = read_golden(path).frames if path.is_file() else None
    except GoldenFileError as err:
        out.write(f"{name}: rewritten, the file was unreadable ({err})\n")
        stored, outcome = None, "updated"
    else:
        outcome = "new"
        if stored is None:
            out.write(f"{name}: new ({len(got)} frames)\n")
    if stored is not None:
        changes = compare(stored, got)
        if not changes:
            out.write(f"{name}: unchanged\n")
            return "unchanged"
        outcome = "updated"
        out.write(f"{name}: updated\n{_indented(changes.summary())}")
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)
    return outcome


def _stale(root: Path, engines: tuple[str, ...], logs: list[str], out: TextIO) -> int:
    """Remove golden files of engines or logs that are gone; how many."""
    wanted = {golden_path(e, log, root) for e in engines for log in logs}
    removed = 0
    for path in sorted(root.glob("*/*.jsonl")):
        if path not in wanted:
            out.write(f"{path.relative_to(root)}: removed (no such engine or sample log)\n")
            path.unlink()
            removed += 1
    return removed


def update(
    engines: tuple[str, ...],
    logs: list[Path],
    *,
    root: Path = GOLDEN_DIR,
    prune: bool = False,
    out: TextIO = sys.stdout,
) -> Counter[str]:
    """Rewrite the golden files of ``engines`` x ``logs`` that changed; count the outcomes.

    Args:
        engines: Engine names.
        logs: Sample logs.
        root: The golden directory.
        prune: Also remove golden files of other engines or logs.
        out: Where the report goes.

    Raises:
        EvaluateError: A log could not be evaluated.
    """
    counts: Counter[str] = Counter()
    for log in logs:
        records = evaluate_log(log, engines)
        for engine in engines:
            counts[_one(engine, log.name, records[engine], root, out)] += 1
    if prune:
        counts["removed"] += _stale(root, engines, [log.name for log in logs], out)
    return counts


def main(argv: list[str] | None = None) -> int:
    """Run the update; the exit code (2 under ``CI=true`` or on a failure)."""
    parser = argparse.ArgumentParser(prog="python -m tests.goldens.update", description=__doc__)
    parser.add_argument("--engine", action="append", default=[], help="only this engine")
    parser.add_argument("--log", action="append", default=[], help="only this sample log")
    args = parser.parse_args(argv)
    if running_in_ci():
        sys.stderr.write(
            "error: goldens are never updated under CI=true; run `make goldens` locally "
            "and commit the files after reviewing the report\n"
        )
        return _FAILED
    engines = tuple(args.engine) or names()
    logs = list(sample_logs())
    unknown = sorted(set(args.engine) - set(names())) + sorted(
        set(args.log) - {log.name for log in logs}
    )
    if unknown:
        sys.stderr.write(f"error: no such engine or log in {SAMPLE_DIR}: {', '.join(unknown)}\n")
        return _FAILED
    if args.log:
        logs = [log for log in logs if log.name in args.log]
    try:
        counts = update(engines, logs, prune=not (args.engine or args.log))
    except EvaluateError as err:
        sys.stderr.write(f"error: {err}\n")
        return _FAILED
    order = ("updated", "new", "removed", "unchanged")
    sys.stdout.write(", ".join(f"{counts[k]} {k}" for k in order) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
