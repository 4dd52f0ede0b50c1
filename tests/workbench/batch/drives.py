"""A small fleet for the batch tests: two good sample drives and every kind of bad log.

| name | what | expected status |
|---|---|---|
| ``racing_overtake.saa`` | sample drive | ``ok`` |
| ``hard_braking_lead.mcap`` (+ its ``.osm``) | sample drive | ``ok`` |
| ``half.mcap`` | the MCAP cut at 60 % of its bytes | ``partial`` |
| ``truncated.mcap`` | its first 3000 bytes (no whole message) | ``failed`` |
| ``random.mcap`` | 4 kB of seeded random bytes | ``failed`` |
| ``empty.bag`` | 0 bytes | ``failed`` |
| ``wrong.xml`` | a Lanelet2 map where a drive is expected | ``failed`` |
"""

from __future__ import annotations

import os
import random
import shutil
import signal
import socket
from pathlib import Path
from typing import TYPE_CHECKING, Any

import pyarrow.parquet as pq

from workbench.batch import evaluate_log

if TYPE_CHECKING:
    from workbench.incidents import IncidentRequest

__all__ = [
    "BAD",
    "GOOD",
    "ROOT",
    "die_once",
    "drive_rows",
    "free_port",
    "incident_rows",
    "make_fleet",
]

ROOT = Path(__file__).resolve().parents[3]
SAMPLES = ROOT / "sample_logs"
#: Good drives (file names in the fleet directory).
GOOD = ("hard_braking_lead.mcap", "racing_overtake.saa")
#: Bad logs by name: expected status.
BAD = {
    "half.mcap": "partial",
    "truncated.mcap": "failed",
    "random.mcap": "failed",
    "empty.bag": "failed",
    "wrong.xml": "failed",
}


def make_fleet(folder: Path, *, bad: bool = True) -> list[Path]:
    """Write the fleet into ``folder``; return the logs (good first)."""
    folder.mkdir(parents=True, exist_ok=True)
    for name in (*GOOD, "hard_braking_lead.osm"):
        shutil.copy(SAMPLES / name, folder / name)
    logs = [folder / name for name in GOOD]
    if not bad:
        return logs
    data = (SAMPLES / "hard_braking_lead.mcap").read_bytes()
    (folder / "half.mcap").write_bytes(data[: len(data) * 6 // 10])
    shutil.copy(SAMPLES / "hard_braking_lead.osm", folder / "half.osm")
    (folder / "truncated.mcap").write_bytes(data[:3000])
    noise = random.Random(30).randbytes(4096)  # noqa: S311 - seeded test data
    (folder / "random.mcap").write_bytes(noise)
    (folder / "empty.bag").write_bytes(b"")
    shutil.copy(SAMPLES / "hard_braking_lead.osm", folder / "wrong.xml")
    return [*logs, *(folder / name for name in BAD)]


def incident_rows(results: Path) -> list[dict[str, Any]]:
    """``incidents.parquet`` as rows."""
    rows: list[dict[str, Any]] = pq.read_table(results / "incidents.parquet").to_pylist()
    return rows


def drive_rows(results: Path) -> dict[str, dict[str, Any]]:
    """``drives.parquet`` by file name."""
    rows = pq.read_table(results / "drives.parquet").to_pylist()
    return {Path(r["path"]).name: r for r in rows}


def die_once(marker: str, request: IncidentRequest) -> dict[str, Any]:
    """The first call anywhere kills its own worker process (SIGKILL); later ones evaluate."""
    try:
        fd = os.open(marker, os.O_CREAT | os.O_EXCL | os.O_WRONLY)
    except FileExistsError:
        return evaluate_log(request)
    os.close(fd)
    os.kill(os.getpid(), signal.SIGKILL)
    raise AssertionError("unreachable")


def free_port() -> int:
    """A TCP port free on 127.0.0.1 now."""
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return int(sock.getsockname()[1])
