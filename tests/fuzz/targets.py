"""Fuzz targets: one loader entry point each, fed a file made of the fuzzer's bytes.

Every target writes the input bytes where its entry point expects a file (a name with the
right suffix; for a rosbag2 directory, ``metadata.yaml`` beside a valid storage file) and
reads it to the end the way the workbench does. The only acceptable failures are the
target's typed errors with a one-line message naming the file; anything else is a finding.

| target | input bytes are | entry point |
|---|---|---|
| ``mcap-ros2``, ``-ros1``, ``-json``, ``-protobuf``, ``-osi`` | an ``.mcap`` | drive |
| ``osi-trace`` | an ASAM OSI ``.osi`` trace | drive |
| ``ros1-bag`` | a ROS 1 ``.bag`` | drive |
| ``rosbag2-sqlite3`` | ``metadata.yaml`` of a rosbag2 directory | drive |
| ``db3`` | a bare rosbag2 ``.db3`` | drive |
| ``commonroad`` | a CommonRoad scenario ``.xml`` | drive |
| ``lanelet2``, ``opendrive``, ``commonroad-map`` | an ``.osm``, ``.xodr``, ``.xml`` map | map |
| ``scenario-architect`` (``-scn``) | a ``.saa`` archive (a ``.scn`` text) | drive |
| ``openlabel`` | an OpenLABEL JSON file | ``import_openlabel`` |

drive: ``open_drive``, its ``info`` and ``lane_map``, every frame; map: ``read_map``;
``import_openlabel`` into a new label store.
"""

from __future__ import annotations

import shutil
from contextlib import closing
from dataclasses import dataclass
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from collections.abc import Callable
    from pathlib import Path

__all__ = ["BASE_DB3", "TARGETS", "Target", "UntypedFailureError", "run_input"]

#: Name of the storage file the ``rosbag2-sqlite3`` target's ``metadata.yaml`` lies beside.
BASE_DB3 = "fuzz_0.db3"
#: OSI trace name by the trace naming convention (``gt``: GroundTruth messages).
_OSI_NAME = "20240101T000000Z_gt_3.8.0_7.0.0_5_fuzz.osi"


class UntypedFailureError(AssertionError):
    """A typed error whose message is not one line naming the input file."""


@dataclass(frozen=True, slots=True)
class Target:
    """One fuzz target.

    Attributes:
        name: Target name (``make fuzz`` and ``tests/fuzz/corpus/<name>/``).
        file_name: Name the input bytes are written as.
        read: Entry point on the placed path; returns how many frames (or labels) it read.
        errors: The only exception types the entry point may raise (imported when called,
            so that the fuzzer imports the loaders under its instrumentation).
        instrument: Top-level packages whose code the coverage-guided fuzzer instruments.
        storage: Whether the input is ``metadata.yaml`` beside :data:`BASE_DB3`.
    """

    name: str
    file_name: str
    read: Callable[[Path], int]
    errors: Callable[[], tuple[type[BaseException], ...]]
    instrument: tuple[str, ...]
    storage: bool = False

    def place(self, data: bytes, directory: Path, assets: Path | None) -> Path:
        """Write ``data`` into the empty ``directory``; return the path the entry point opens."""
        if not self.storage:
            path = directory / self.file_name
            path.write_bytes(data)
            return path
        if assets is None:
            msg = f"target {self.name} needs the assets directory holding {BASE_DB3}"
            raise ValueError(msg)
        bag = directory / "bag"
        bag.mkdir()
        shutil.copyfile(assets / BASE_DB3, bag / BASE_DB3)
        (bag / self.file_name).write_bytes(data)
        return bag


def _drive(path: Path) -> int:
    from loaders import open_drive  # noqa: PLC0415 - imported under the fuzzer's instrumentation

    with closing(open_drive(path)) as drive:
        _ = (drive.info, drive.lane_map)
        return sum(1 for _ in drive.frames())


def _map(path: Path) -> int:
    from loaders.message_logs.mapsource import read_map  # noqa: PLC0415 - instrumented import

    return len(read_map(path, str(path)).lanes)


def _openlabel(path: Path) -> int:
    from workbench.annotations.openlabel_import import import_openlabel  # noqa: PLC0415
    from workbench.annotations.store import LabelStore  # noqa: PLC0415

    with LabelStore(path.with_name("labels.sqlite")) as store:
        return len(import_openlabel(path, store).outcomes)


def _loader_errors() -> tuple[type[BaseException], ...]:
    from loaders.errors import LoaderError  # noqa: PLC0415

    return (LoaderError,)


def _label_errors() -> tuple[type[BaseException], ...]:
    from workbench.annotations.errors import OpenLabelError, StoreError  # noqa: PLC0415

    return (OpenLabelError, StoreError)


_MCAP = ("loaders", "mcap", "mcap_protobuf", "rosbags")
_ROS = ("loaders", "rosbags")
_XML = ("loaders",)


def _targets() -> dict[str, Target]:
    loader = _loader_errors
    rows = [
        ("mcap-ros2", "drive.mcap", _drive, _MCAP),
        ("mcap-ros1", "drive.mcap", _drive, _MCAP),
        ("mcap-json", "drive.mcap", _drive, _MCAP),
        ("mcap-protobuf", "drive.mcap", _drive, _MCAP),
        ("mcap-osi", "drive.mcap", _drive, (*_MCAP, "betterosi")),
        ("osi-trace", _OSI_NAME, _drive, ("loaders", "betterosi")),
        ("ros1-bag", "drive.bag", _drive, _ROS),
        ("db3", "drive.db3", _drive, _ROS),
        ("commonroad", "scenario.xml", _drive, _XML),
        ("lanelet2", "map.osm", _map, _XML),
        ("opendrive", "map.xodr", _map, _XML),
        ("commonroad-map", "map.xml", _map, _XML),
        ("scenario-architect", "drive.saa", _drive, _XML),
        ("scenario-architect-scn", "drive.scn", _drive, _XML),
    ]
    out = {name: Target(name, file, read, loader, inst) for name, file, read, inst in rows}
    out["rosbag2-sqlite3"] = Target(
        "rosbag2-sqlite3", "metadata.yaml", _drive, loader, (*_ROS, "ruamel"), storage=True
    )
    out["openlabel"] = Target(
        "openlabel", "labels.json", _openlabel, _label_errors, ("workbench.annotations",)
    )
    return dict(sorted(out.items()))


#: Target name -> target.
TARGETS: dict[str, Target] = _targets()


def run_input(target: Target, data: bytes, directory: Path, assets: Path | None) -> str:
    """Feed one input to ``target`` in the empty ``directory``.

    Returns:
        ``"ok: N"`` (frames or labels read) or ``"typed: <message>"``.

    Raises:
        UntypedFailureError: A typed error whose message spans lines or names no file.
        Exception: Any error that is not one of ``target.errors()`` (a finding).
    """
    path = target.place(data, directory, assets)
    try:
        count = target.read(path)
    except target.errors() as err:
        text = str(err)
        if "\n" in text or (path.name not in text and str(directory) not in text):
            msg = f"{target.name}: {type(err).__name__} is not one line naming the file: {text!r}"
            raise UntypedFailureError(msg) from err
        return f"typed: {text}"
    return f"ok: {count}"
