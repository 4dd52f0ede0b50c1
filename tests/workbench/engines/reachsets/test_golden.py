"""Golden per-frame reach-set verdicts of the samples with ``workbench evaluate``'s defaults.

Regenerate with ``REACH_GOLDEN_UPDATE=1 pytest tests/workbench/engines/reachsets/test_golden.py``
and review the diff against the scenario descriptions in docs/samples.md (the free-flow
stretches before the scripted events must stay safe: ``test_public_road.py``).
"""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Any

import pytest

from loaders import open_drive
from tests.workbench.engines.helpers import record
from workbench.engines import build_runners
from workbench.samples.generate import SCENARIOS as SAMPLE_BUILDERS

SAMPLES = Path(__file__).resolve().parents[4] / "sample_logs"
#: Every road sample, in generation order.
SCENARIOS = list(SAMPLE_BUILDERS)


def _frames(name: str) -> list[dict[str, Any]]:
    drive = open_drive(SAMPLES / f"{name}.mcap")
    try:
        (runner,) = build_runners(["reachsets"], drive.lane_map)
        frames = list(drive.frames())
    finally:
        drive.close()
    out = []
    for k in range(0, len(frames), 32):
        chunk = frames[k : k + 32]
        for frame, verdict in zip(chunk, runner.step_many(chunk), strict=True):
            rec = record(verdict)
            assert rec["is_safe"] == (not rec["collisions"])
            out.append(
                {
                    "frame": frame.index,
                    "t_ns": frame.t_ns,
                    "is_safe": rec["is_safe"],
                    "culprits": [c["object_id"] for c in rec["collisions"]],
                    "trajectory": rec["trajectory"],
                }
            )
    return out


@pytest.mark.parametrize("name", SCENARIOS)
def test_golden(name):
    path = SAMPLES / f"{name}.reachsets.expected.json"
    frames = _frames(name)
    if os.environ.get("REACH_GOLDEN_UPDATE"):
        doc = {
            "engine": "reachsets",
            "settings": "defaults",
            "log": f"{name}.mcap",
            "frames": frames,
        }
        path.write_text(json.dumps(doc, indent=None, separators=(",", ":")) + "\n")
    assert frames == json.loads(path.read_text())["frames"]
