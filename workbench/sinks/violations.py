"""Merge unsafe frames into violation intervals, one row per interval with a stable id."""

from __future__ import annotations

import csv
import hashlib
import json
from dataclasses import asdict, dataclass, field
from typing import TYPE_CHECKING

from workbench.errors import WorkbenchError

if TYPE_CHECKING:
    from collections.abc import Iterable
    from pathlib import Path

    from workbench.evaluate.pipeline import FrameResult

__all__ = ["Violation", "detect_violations", "write_violations"]


@dataclass(slots=True)
class Violation:
    """A run of consecutive unsafe frames of one engine.

    Attributes:
        id: Stable id: hash of the log name, engine and first frame.
        log: Log file name.
        engine: Engine name.
        label: Rule or response that fired (first frame's label; others are in ``labels``).
        objects: Ids of the objects involved over the whole interval, sorted.
        start_frame: First unsafe frame.
        end_frame: Last unsafe frame (inclusive).
        start_ns: Time of the first unsafe frame.
        end_ns: Time of the last unsafe frame.
        worst_margin: Smallest engine margin within the interval.
        labels: Every label seen within the interval, sorted.
    """

    id: str
    log: str
    engine: str
    label: str
    objects: list[str]
    start_frame: int
    end_frame: int
    start_ns: int
    end_ns: int
    worst_margin: float
    labels: list[str] = field(default_factory=list)

    @property
    def frames(self) -> int:
        """Number of frames in the interval."""
        return self.end_frame - self.start_frame + 1


def _stable_id(log: str, engine: str, start_frame: int) -> str:
    digest = hashlib.sha256(f"{log}\0{engine}\0{start_frame}".encode()).hexdigest()
    return f"{engine}-{start_frame:06d}-{digest[:8]}"


def detect_violations(results: Iterable[FrameResult], log: str) -> list[Violation]:
    """Merge consecutive unsafe frames of each engine into intervals.

    A frame gap (a frame the engine rated safe) ends an interval.

    Args:
        results: Frame results in frame order.
        log: Log name recorded in each violation (and part of its id).

    Returns:
        Violations ordered by start frame, then engine.
    """
    open_: dict[str, Violation] = {}
    done: list[Violation] = []
    for res in results:
        for engine, out in res.outputs.items():
            current = open_.get(engine)
            if out.is_safe:
                if current is not None:
                    done.append(open_.pop(engine))
                continue
            if current is None or current.end_frame != res.frame - 1:
                if current is not None:
                    done.append(current)
                current = Violation(
                    id=_stable_id(log, engine, res.frame),
                    log=log,
                    engine=engine,
                    label=out.label,
                    objects=[],
                    start_frame=res.frame,
                    end_frame=res.frame,
                    start_ns=res.t_ns,
                    end_ns=res.t_ns,
                    worst_margin=out.margin,
                )
                open_[engine] = current
            current.end_frame = res.frame
            current.end_ns = res.t_ns
            current.worst_margin = min(current.worst_margin, out.margin)
            current.objects = sorted(set(current.objects) | set(out.culprits))
            if out.label:
                current.labels = sorted(set(current.labels) | {out.label})
    done.extend(open_.values())
    done.sort(key=lambda v: (v.start_frame, v.engine))
    return done


def write_violations(violations: list[Violation], path: Path) -> None:
    """Write the violations table as JSON (``.json``) or CSV (``.csv``), atomically.

    Raises:
        WorkbenchError: For any other suffix.
    """
    rows = [asdict(v) for v in violations]
    tmp = path.with_name(f".{path.name}.tmp")
    if path.suffix == ".json":
        tmp.write_text(json.dumps(rows, indent=2) + "\n")
    elif path.suffix == ".csv":
        names = list(Violation.__dataclass_fields__)
        with tmp.open("w", newline="") as fh:
            writer = csv.DictWriter(fh, fieldnames=names)
            writer.writeheader()
            for row in rows:
                row["objects"] = " ".join(row["objects"])
                row["labels"] = " ".join(row["labels"])
                writer.writerow(row)
    else:
        msg = f"{path}: violations file must end in .json or .csv, not {path.suffix!r}"
        raise WorkbenchError(msg)
    tmp.replace(path)
