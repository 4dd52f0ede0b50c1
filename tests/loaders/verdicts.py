"""The RSS per-frame records of ``workbench evaluate`` on a log, for same-drive comparisons."""

from __future__ import annotations

import json
from typing import TYPE_CHECKING, Any

from typer.testing import CliRunner

from workbench.cli.main import app

if TYPE_CHECKING:
    from pathlib import Path

#: Frames compared (the first 7.5 s of a 20 Hz sample: the cut-in included).
VERDICT_FRAMES = 150
#: Record keys holding one entry per object id.
_PER_OBJECT = ("responsibility", "severity", "compliance")
#: Record keys whose numbers follow the objects' velocities (safe distances, measured
#: accelerations): they differ where a message type carries no velocity and it is estimated.
VELOCITY_FACTS = ("severity", "compliance")


def _id_free(rss: dict[str, Any]) -> dict[str, Any]:
    """Object ids differ by message type (UUID hex, ``det<k>``, ``ns/id``): keep counts and
    the per-object values in a canonical order instead."""
    for key in ("dangerous_objects", "invalid_objects"):
        rss[key] = len(rss[key])
    for key in _PER_OBJECT:
        if key in rss:
            rss[key] = sorted(json.dumps(v, sort_keys=True) for v in rss[key].values())
    return rss


def rss_verdicts(
    path: Path, out: Path, *extra: str, id_free: bool = False, drop: tuple[str, ...] = ()
) -> list[dict[str, Any]]:
    """RSS records of the first :data:`VERDICT_FRAMES` frames (``extra``: more CLI options;
    ``drop``: record keys left out)."""
    args = ["evaluate", str(path), "--engines", "rss", "--end", str(VERDICT_FRAMES / 20)]
    result = CliRunner().invoke(app, [*args, *extra, "--per-frame", str(out)])
    assert result.exit_code == 0, result.output
    records = [json.loads(line)["rss"] for line in out.read_text().splitlines()]
    for record in records:
        for key in drop:
            record.pop(key, None)
    return [_id_free(r) for r in records] if id_free else records
