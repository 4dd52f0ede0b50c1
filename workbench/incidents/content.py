"""The drive's content hash: what labels and incident ids are keyed by.

A streaming SHA-256 of the log's bytes (a rosbag2 directory: every file under it, by
relative path), read in chunks so memory stays flat; cached per process by path, size and
modification time, so every command of one run hashes a file once.
"""

from __future__ import annotations

import functools
import hashlib
from pathlib import Path

from workbench.errors import WorkbenchError

__all__ = ["CHUNK_BYTES", "drive_content_hash"]

#: Bytes read at a time.
CHUNK_BYTES = 1 << 20


def _files(path: Path) -> list[Path]:
    if path.is_dir():
        return sorted(p for p in path.rglob("*") if p.is_file())
    return [path]


def _stamp(path: Path) -> tuple[tuple[str, int, int], ...]:
    out = []
    for file in _files(path):
        st = file.stat()
        out.append((str(file), st.st_size, st.st_mtime_ns))
    return tuple(out)


@functools.lru_cache(maxsize=64)
def _hash(root: Path, stamp: tuple[tuple[str, int, int], ...]) -> str:
    digest = hashlib.sha256()
    for name, _size, _mtime in stamp:
        file = Path(name)
        if root.is_dir():
            digest.update(file.relative_to(root).as_posix().encode() + b"\0")
        with file.open("rb") as fh:
            while block := fh.read(CHUNK_BYTES):
                digest.update(block)
    return digest.hexdigest()


def drive_content_hash(path: Path) -> str:
    """Hex SHA-256 of a drive file's bytes, or of a directory's files and their names.

    Raises:
        WorkbenchError: The path cannot be read.
    """
    root = path.resolve()
    try:
        return _hash(root, _stamp(root))
    except OSError as err:
        raise WorkbenchError(f"{path}: cannot hash the drive ({err.strerror})") from err
