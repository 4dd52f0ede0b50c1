"""The pinned per-frame JSON lines of ``workbench evaluate --per-frame`` (DESIGN.md).

One line per frame: ``{"t_ns": int, "frame": int, <engine>: <record>, ...}``, the engines in
the order they ran, each record made by its engine's ``record`` function from the typed
verdict (``workbench/engines/<name>/record.py``). The file appears whole when the run ends:
it is written beside the target and renamed; a failed run leaves no file behind.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, Self, TextIO

from workbench.outputs import json_text, part_path

if TYPE_CHECKING:
    from pathlib import Path
    from types import TracebackType

    from workbench.driver.run import Chunk

__all__ = ["PerFrameJsonl", "frame_records"]


def frame_records(chunk: Chunk) -> list[dict[str, Any]]:
    """The per-frame JSON records of a chunk."""
    writers = {name: chunk.specs[name].record for name in chunk.verdicts}
    lines = []
    for k, frame in enumerate(chunk.frames):
        line: dict[str, Any] = {"t_ns": frame.t_ns, "frame": frame.index}
        for name, verdicts in chunk.verdicts.items():
            line[name] = writers[name](verdicts[k])
        lines.append(line)
    return lines


class PerFrameJsonl:
    """Writes the JSON lines of every chunk to ``path``, atomically (a context manager)."""

    def __init__(self, path: Path) -> None:
        """Remember the target; nothing is written before the block is entered."""
        self.path = path
        self._tmp = part_path(path)
        self._fh: TextIO | None = None

    def __enter__(self) -> Self:
        """Open the temporary file beside the target."""
        self._tmp.parent.mkdir(parents=True, exist_ok=True)
        self._fh = self._tmp.open("w")
        return self

    def add_chunk(self, chunk: Chunk) -> None:
        """Write the lines of one chunk."""
        assert self._fh is not None, "use PerFrameJsonl as a context manager"
        for line in frame_records(chunk):
            self._fh.write(json_text(line) + "\n")

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        """Rename the file into place, or remove it when the block failed."""
        if self._fh is not None:
            self._fh.close()
        if exc_type is None:
            self._tmp.replace(self.path)
        else:
            self._tmp.unlink(missing_ok=True)
