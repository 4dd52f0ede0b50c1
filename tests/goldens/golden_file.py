"""The golden file format: one engine's per-frame records of one log, run-length encoded.

``expected/<variant>/<engine>/<log>.jsonl``, one JSON object per line (compact separators)::

    {"variant": "default", "engine": "rss", "log": "highway_cut_in.mcap", "frames": 401,
     "time": [[first_frame, first_t_ns, count, step_ns], ...]}
    {"frames": [first, last], "rss": {<the record of frames first..last>}}
    ...

The first line names the variant, the engine and the log and holds the frame index and time of every
frame as arithmetic runs (frame ``+1``, time ``+step_ns``; a sample log is one run). Each
further line is one run of consecutive frames whose records are identical, keyed by the
engine's name as in ``workbench evaluate --per-frame``. A changed frame therefore changes
(and splits) only the lines of its run, so a regenerated file reviews as a short diff.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from collections.abc import Sequence
    from pathlib import Path

__all__ = ["FrameRecord", "Golden", "GoldenFileError", "golden_text", "read_golden"]


class GoldenFileError(Exception):
    """A golden file that does not hold what the format says (message names the file)."""


@dataclass(frozen=True)
class FrameRecord:
    """One frame's record of one engine (a ``--per-frame`` line, one engine's part)."""

    frame: int
    t_ns: int
    record: Any


@dataclass(frozen=True)
class Golden:
    """The content of one golden file."""

    variant: str
    engine: str
    log: str
    frames: tuple[FrameRecord, ...]


def _dumps(value: Any) -> str:
    return json.dumps(value, separators=(",", ":"), allow_nan=False)


def _time_runs(frames: Sequence[FrameRecord]) -> list[list[int]]:
    runs: list[list[int]] = []
    for f in frames:
        if runs:
            first, t0, count, step = runs[-1]
            if f.frame == first + count and (count == 1 or f.t_ns == t0 + count * step):
                runs[-1] = [first, t0, count + 1, f.t_ns - t0 if count == 1 else step]
                continue
        runs.append([f.frame, f.t_ns, 1, 0])
    return runs


def golden_text(variant: str, engine: str, log: str, frames: Sequence[FrameRecord]) -> str:
    """The file text of ``frames`` (deterministic: equal records give equal text)."""
    head = {
        "variant": variant,
        "engine": engine,
        "log": log,
        "frames": len(frames),
        "time": _time_runs(frames),
    }
    lines = [_dumps(head)]
    start = 0
    for k in range(1, len(frames) + 1):
        if k == len(frames) or _dumps(frames[k].record) != _dumps(frames[start].record):
            span = [frames[start].frame, frames[k - 1].frame]
            lines.append(_dumps({"frames": span, engine: frames[start].record}))
            start = k
    return "\n".join(lines) + "\n"


def _expand(time: list[list[int]]) -> list[tuple[int, int]]:
    return [(first + k, t0 + k * step) for first, t0, count, step in time for k in range(count)]


def read_golden(path: Path) -> Golden:
    """Parse a golden file.

    Raises:
        GoldenFileError: Not JSON lines of this format, or runs that do not cover the frames.
    """
    try:
        head, *runs = (json.loads(line) for line in path.read_text().splitlines())
        variant, engine, log = str(head["variant"]), str(head["engine"]), str(head["log"])
        times = _expand(head["time"])
        out: list[FrameRecord] = []
        for run in runs:
            first, last = run["frames"]
            if times[len(out)][0] != first:
                should = times[len(out)][0]
                raise GoldenFileError(f"{path}: run {run['frames']} should start at {should}")
            while True:
                frame, t_ns = times[len(out)]
                out.append(FrameRecord(frame, t_ns, run[engine]))
                if frame == last:
                    break
    except (ValueError, KeyError, TypeError, IndexError) as err:
        raise GoldenFileError(f"{path}: not a golden file ({err})") from err
    if len(out) != head["frames"] or len(out) != len(times):
        raise GoldenFileError(f"{path}: {len(out)} frames in the runs, {len(times)} in the header")
    return Golden(variant, engine, log, tuple(out))
