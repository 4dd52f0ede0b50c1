"""``python -m tests.goldens.update`` (``make goldens``): rewrite the goldens, report the change.

The one update switch of the golden harness. It refuses to run under ``CI=true`` (exit 2):
CI compares the goldens and never writes them. The tests never write a golden file, so a
run that updates cannot pass by comparing a file with itself: this tool writes, and
says per file what it changed; ``pytest tests/goldens`` then compares as always.

Usage::

    python -m tests.goldens.update [--variant NAME]... [--engine NAME]... [--log NAME]...

For every variant, registered engine and sample log (or those named), it evaluates the log
(:mod:`tests.goldens.samples`), compares the records with the golden file within the
tolerance of :mod:`tests.goldens.compare` and rewrites only files that differ beyond it
(or are missing or unreadable). Per file it prints ``new``, ``unchanged`` or ``updated``
with the changed frames, the record keys that changed in how many frames, the safe/unsafe
flips and the first difference; then the counts per variant and the size of all golden
files. Without a filter it also removes golden files of variants, engines or logs that no
longer exist.
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
    VARIANTS,
    EvaluateError,
    evaluate_log,
    golden_path,
    sample_logs,
)
from workbench.engines.registry import names

if TYPE_CHECKING:
    from pathlib import Path

    from tests.goldens.golden_file import FrameRecord

__all__ = ["main", "summary", "update"]

#: Exit code of a refused or failed update.
_FAILED = 2
#: The outcomes of a golden file, in the order the summary lists them.
_OUTCOMES = ("updated", "new", "removed", "unchanged")


def _indented(text: str) -> str:
    return "".join(f"    {line}\n" for line in text.splitlines())


def _one(
    variant: str, engine: str, log: str, got: list[FrameRecord], *, root: Path, out: TextIO
) -> str:
    """Compare, write when changed, report; the outcome's name."""
    path = golden_path(variant, engine, log, root)
    name = str(path.relative_to(root))
    text = golden_text(variant, engine, log, got)
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


def _stale(root: Path, wanted: set[Path], counts: dict[str, Counter[str]], out: TextIO) -> None:
    """Remove the golden files not ``wanted`` (variant, engine or log gone); count them."""
    for path in sorted(root.rglob("*.jsonl")):
        if path not in wanted:
            rel = path.relative_to(root)
            out.write(f"{rel}: removed (no such variant, engine or sample log)\n")
            path.unlink()
            counts.setdefault(rel.parts[0], Counter())["removed"] += 1


def update(
    variants: tuple[str, ...],
    engines: tuple[str, ...],
    logs: list[Path],
    *,
    root: Path = GOLDEN_DIR,
    prune: bool = False,
    out: TextIO = sys.stdout,
) -> dict[str, Counter[str]]:
    """Rewrite the golden files of ``variants`` x ``engines`` x ``logs`` that changed.

    Args:
        variants: Keys of :data:`~tests.goldens.samples.VARIANTS`.
        engines: Engine names.
        logs: Sample logs.
        root: The golden directory.
        prune: Also remove every other golden file under ``root``.
        out: Where the report goes.

    Returns:
        The outcomes counted per variant (``new``, ``updated``, ``unchanged``, ``removed``).

    Raises:
        EvaluateError: A log could not be evaluated.
    """
    counts: dict[str, Counter[str]] = {variant: Counter() for variant in variants}
    for variant in variants:
        for log in logs:
            records = evaluate_log(log, engines, variant)
            for engine in engines:
                got = records[engine]
                counts[variant][_one(variant, engine, log.name, got, root=root, out=out)] += 1
    if prune:
        wanted = {
            golden_path(v, e, log.name, root) for v in variants for e in engines for log in logs
        }
        _stale(root, wanted, counts, out)
    return counts


def summary(counts: dict[str, Counter[str]], root: Path = GOLDEN_DIR) -> str:
    """The last lines of the report: the outcomes per variant, the golden files' total size."""
    lines = [
        f"{variant}: " + ", ".join(f"{counted[k]} {k}" for k in _OUTCOMES)
        for variant, counted in counts.items()
    ]
    files = list(root.rglob("*.jsonl"))
    size_kb = sum(path.stat().st_size for path in files) / 1000
    lines.append(f"{len(files)} golden files, {size_kb:.0f} kB in all")
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    """Run the update; the exit code (2 under ``CI=true`` or on a failure)."""
    parser = argparse.ArgumentParser(prog="python -m tests.goldens.update", description=__doc__)
    parser.add_argument("--variant", action="append", default=[], help="only this variant")
    parser.add_argument("--engine", action="append", default=[], help="only this engine")
    parser.add_argument("--log", action="append", default=[], help="only this sample log")
    args = parser.parse_args(argv)
    if running_in_ci():
        sys.stderr.write(
            "error: goldens are never updated under CI=true; run `make goldens` locally "
            "and commit the files after reviewing the report\n"
        )
        return _FAILED
    variants = tuple(args.variant) or tuple(VARIANTS)
    engines = tuple(args.engine) or names()
    logs = list(sample_logs())
    unknown = (
        sorted(set(args.variant) - set(VARIANTS))
        + sorted(set(args.engine) - set(names()))
        + sorted(set(args.log) - {log.name for log in logs})
    )
    if unknown:
        sys.stderr.write(
            f"error: no such variant, engine or log in {SAMPLE_DIR}: {', '.join(unknown)}\n"
        )
        return _FAILED
    if args.log:
        logs = [log for log in logs if log.name in args.log]
    try:
        counts = update(
            variants, engines, logs, prune=not (args.variant or args.engine or args.log)
        )
    except EvaluateError as err:
        sys.stderr.write(f"error: {err}\n")
        return _FAILED
    sys.stdout.write(summary(counts))
    return 0


if __name__ == "__main__":
    sys.exit(main())
