"""The 11 NGSIM scenarios as ROS 2 MCAP logs give the frames and verdicts of their XML.

Issue 17 acceptance: each CommonRoad scenario is converted in a temporary directory
(``write_drive_mcap``, whole drive) and opened with the scenario as ``--map``. Every frame
must equal the XML drive's (tolerances in ``drive_compare``), and the per-frame JSON records
of rss, unstructured and reachsets must be identical (their margins within 1e-9 relative) over
the first
``WINDOW_FRAMES`` frames (the whole drives take about 75 s per format, so the suite checks a
window; ``tools/commonroad_to_mcap.py --check`` runs the whole drives through the CLI, see
``docs/maps.md``). The ego's size is given to both runs as ``--rss-params`` would.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import pytest

from loaders import open_drive
from tests.reachsets.test_real_maps import NGSIM
from tests.workbench.samples.drive_compare import (
    ENGINES,
    assert_same_frames,
    assert_same_verdicts,
    ego_size_of,
    verdict_records,
)
from workbench.samples.drive_mcap import write_drive_mcap

if TYPE_CHECKING:
    from pathlib import Path

pytestmark = pytest.mark.external

#: Frames whose verdicts are compared, from the start of each drive (0.3 s of NGSIM).
WINDOW_FRAMES = 3


@pytest.mark.parametrize("name", NGSIM)
def test_mcap_drive_equals_xml_drive(external_dir: Path, tmp_path: Path, name: str) -> None:
    xml = external_dir / "commonroad_ngsim" / f"{name}.xml"
    log = tmp_path / f"{name}.mcap"
    source = open_drive(xml)
    written = write_drive_mcap(source, log, map_name=xml.name)
    expected = list(source.frames())
    converted = open_drive(log, map=xml)
    got = list(converted.frames())
    assert written == len(expected) == source.info.frame_count
    assert_same_frames(expected, got)

    size = ego_size_of(expected[0])
    end_ns = expected[WINDOW_FRAMES].t_ns
    records, margins = verdict_records(source, size, (None, end_ns))
    assert len(records) == WINDOW_FRAMES
    assert all(name in r for r in records for name in ENGINES)
    assert_same_verdicts(verdict_records(converted, size, (None, end_ns)), (records, margins))
