"""A corpus of damaged files for every container, made in the test from the sample logs.

Damage: truncation, a zeroed 4 KiB block, 64 overwritten bytes inside a compressed chunk
and a file of random bytes. Reading must never end in a traceback: every frame before the
damage is yielded (the frames read are a prefix of the undamaged drive's frames) and then
a typed ``LoaderError`` names the file and, where known, the offset or time.
"""

from __future__ import annotations

import random
import shutil
from contextlib import closing
from pathlib import Path
from typing import TYPE_CHECKING

import pytest
from mcap.reader import make_reader

from loaders import open_drive
from loaders.errors import LoaderError
from tests.loaders import containers
from tests.loaders.ego_logs import reference_frames
from tests.loaders.osi_logs import write_osi

if TYPE_CHECKING:
    from collections.abc import Callable

    from loaders.records import Frame

SAMPLES = Path(__file__).resolve().parents[2] / "sample_logs"
_Key = tuple[int, float, float, float, tuple[str, ...]]


def _key(frame: Frame) -> _Key:
    """What must not change in a frame read before the damage (kinematics of the last
    frame may: its next ego message is gone)."""
    ego = frame.ego
    return (frame.t_ns, ego.x_m, ego.y_m, ego.yaw_rad, tuple(str(i) for i in frame.actors.ids))


def _drain(path: Path) -> tuple[list[_Key], LoaderError | None]:
    keys: list[_Key] = []
    try:
        with closing(open_drive(path)) as drive:
            keys.extend(_key(f) for f in drive.frames())
    except LoaderError as err:
        return keys, err
    return keys, None


def _mcap_chunk(path: Path) -> int:
    """Offset of the middle of the second chunk's compressed records (the first if one)."""
    with path.open("rb") as f:
        summary = make_reader(f).get_summary()
    assert summary is not None
    chunks = sorted(summary.chunk_indexes, key=lambda c: c.chunk_start_offset)
    chunk = chunks[min(1, len(chunks) - 1)]
    return chunk.chunk_start_offset + chunk.chunk_length // 2


def _copy(name: str) -> Callable[[Path], Path]:
    """Writer copying the sample ``name`` into a directory."""

    def write(directory: Path) -> Path:
        src = SAMPLES / name
        if src.is_dir():
            return Path(shutil.copytree(src, directory / "x"))
        return Path(shutil.copy(src, directory / f"x{src.suffix}"))

    return write


def _middle(path: Path) -> int:
    return path.stat().st_size // 2


#: Container -> (writer of the undamaged file from the samples, offset inside compressed data).
_CONTAINERS: dict[str, tuple[Callable[[Path], Path], Callable[[Path], int]]] = {
    "ros1-bag": (_copy("highway_cut_in.bag"), _middle),
    "ros2-mcap": (
        _copy("highway_cut_in.mcap"),
        _mcap_chunk,
    ),
    "mcap-protobuf": (
        _copy("pedestrian_crossing_foxglove.mcap"),
        _mcap_chunk,
    ),
    "ros1-mcap": (
        lambda d: containers.ros1_mcap(SAMPLES / "highway_cut_in.bag", d / "x.mcap"),
        _mcap_chunk,
    ),
    "rosbag2-sqlite3": (
        _copy("highway_cut_in_rosbag2"),
        lambda p: _middle(next(p.glob("*.db3"))),
    ),
    "bare-db3": (lambda d: containers.bare_db3(SAMPLES / "highway_cut_in_rosbag2", d), _middle),
    "osi-trace": (lambda d: write_osi(reference_frames(SAMPLES.parent), d, "gt_osi"), _middle),
    "osi-mcap": (lambda d: write_osi(reference_frames(SAMPLES.parent), d, "sv_mcap"), _mcap_chunk),
}


def _target(path: Path) -> Path:
    """The file to damage: the log itself or the storage file of a rosbag2 directory."""
    return next(path.glob("*.db3")) if path.is_dir() else path


def _damage(kind: str, data: bytes, offset: int) -> bytes:
    rng = random.Random(18)  # noqa: S311 - reproducible damage, not cryptography
    out = bytearray(data)
    if kind == "truncated-half":
        return data[: len(data) // 2]
    if kind == "truncated-end":
        return data[: len(data) - 100]
    if kind == "zeroed-block":
        out[offset : offset + 4096] = bytes(len(out[offset : offset + 4096]))
    elif kind == "overwritten-chunk-bytes":
        out[offset : offset + 64] = rng.randbytes(64)
    else:
        return rng.randbytes(8192)
    return bytes(out)


@pytest.fixture(scope="module")
def undamaged(tmp_path_factory: pytest.TempPathFactory) -> dict[str, tuple[Path, list[_Key]]]:
    out = {}
    for name, (write, _) in _CONTAINERS.items():
        path = Path(write(tmp_path_factory.mktemp(name)))
        keys, err = _drain(path)
        assert err is None
        assert keys
        out[name] = (path, keys)
    return out


@pytest.mark.parametrize(
    "kind", ["truncated-half", "truncated-end", "zeroed-block", "overwritten-chunk-bytes", "random"]
)
@pytest.mark.parametrize("container", list(_CONTAINERS))
def test_damaged_file_keeps_readable_frames_and_fails_typed(
    undamaged: dict[str, tuple[Path, list[_Key]]], tmp_path: Path, container: str, kind: str
) -> None:
    src, reference = undamaged[container]
    path = tmp_path / src.name
    if src.is_dir():
        shutil.copytree(src, path)
    else:
        shutil.copy(src, path)
    target = _target(path)
    offset = _CONTAINERS[container][1](path)
    target.write_bytes(_damage(kind, target.read_bytes(), offset))
    keys, err = _drain(path)
    assert keys == reference[: len(keys)]
    assert err is not None, f"{kind} {container}: damage went unnoticed"
    assert str(path) in str(err) or str(target) in str(err)
    assert "\n" not in str(err)
    assert err.offset is not None or err.t_ns is not None, str(err)
