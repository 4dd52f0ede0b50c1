"""What a directory argument of ``workbench batch`` contributes: every file the loaders
open (``loaders.open.LOG_SUFFIXES``, any case), locally and at a URL alike."""

from __future__ import annotations

from typing import TYPE_CHECKING

import fsspec

from loaders.open import LOG_SUFFIXES, is_drive_path
from workbench.batch import expand_logs

if TYPE_CHECKING:
    from pathlib import Path

#: Relative names written into the folder, and whether a batch of it takes them.
LAYOUT = {
    "a.mcap": True,
    "B.MCAP": True,  # the loaders take any case
    "trace.osi": True,  # an OSI trace: a single-drive command reads it, so a batch does
    "deep/scenario.xml": True,
    "deep/race.SAA": True,
    ".hidden.mcap": False,
    "notes.txt": False,
    "map.osm": False,  # a sidecar, not a drive
    "bag2/metadata.yaml": False,  # the directory is one drive ...
    "bag2/bag2_0.db3": False,  # ... its .db3 is not listed again
}


def _write(root: Path) -> None:
    for name in LAYOUT:
        (root / name).parent.mkdir(parents=True, exist_ok=True)
        (root / name).write_bytes(b"")


def test_a_folder_gives_every_file_the_loaders_open(tmp_path: Path) -> None:
    _write(tmp_path)
    found = expand_logs([str(tmp_path)])
    expected = sorted(
        [tmp_path / name for name, taken in LAYOUT.items() if taken] + [tmp_path / "bag2"],
        key=str,
    )
    assert found == expected
    assert all(is_drive_path(p) for p in found if not isinstance(p, str))
    suffixes = {p.suffix.lower() for p in expected if p.suffix}
    assert suffixes <= set(LOG_SUFFIXES)


def test_a_folder_at_a_url_gives_the_same_names(tmp_path: Path) -> None:
    fs = fsspec.filesystem("memory")
    root = "/expand_dirs"
    for name in LAYOUT:
        fs.pipe(f"{root}/{name}", b"")
    try:
        urls = expand_logs([f"memory://{root}/"])
    finally:
        fs.rm(root, recursive=True)
    _write(tmp_path)
    local = expand_logs([str(tmp_path)])
    assert [u.rsplit(root + "/", 1)[1] for u in map(str, urls)] == [
        str(p.relative_to(tmp_path)) for p in local if not isinstance(p, str)
    ]
