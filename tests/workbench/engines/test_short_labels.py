"""Every engine labels objects by the drive's short label (``#1``), the scene's own table.

Read back from the ``.rrd`` with the dataframe API: the ids of ``derived_object_msgs`` (32
digits) never appear in a drawn label; each label's ``object_id`` component keeps the full id.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import pytest
from rerun.chunk import RrdReader

from workbench.incidents import IncidentReport, IncidentRequest, find_incidents
from workbench.replay.incidents import short_labels
from workbench.replay.short_labels import ShortLabels
from workbench.replay.sink import OBJECT_ID
from workbench.viewer.replay import replay_drive

if TYPE_CHECKING:
    from collections.abc import Mapping

SAMPLES = Path(__file__).resolve().parents[3] / "sample_logs"
#: ``derived_object_msgs``: the lead car's id fills 32 columns.
LOG = SAMPLES / "hard_braking_lead.mcap"
LEAD = "00000000000000000000000000000001"
ENGINES = ("rss", "reachsets", "unstructured")
#: Entity -> archetype of the engines' labelled geometry.
LABELLED = {
    "/world/rss/constellations": "LineStrips3D",
    "/world/reach/collisions": "Points3D",
    "/world/actors": "Boxes3D",  # the scene's actors, from the same table
}


@pytest.fixture(scope="module")
def report() -> IncidentReport:
    return find_incidents(IncidentRequest(LOG, engines=ENGINES))


def _replay(out: Path, labels: ShortLabels | None) -> None:
    request = IncidentRequest(LOG, engines=ENGINES)
    drive = request.open_drive()
    try:
        runners, ego = request.engines_for(drive, full_geometry=True)
        replay_drive(
            drive,
            out=out,
            engines=runners,
            ego_size=ego,
            incident_settings=request.settings,
            labels=labels,
        )
    finally:
        drive.close()


def _labelled(path: Path, entity: str, archetype: str) -> list[tuple[str, str]]:
    """``(label, full id)`` of every instance of ``entity`` over all frames."""
    store = RrdReader(path).store().stream().collect()
    table = store.reader(index="frame", contents=entity).to_arrow_table()
    labels = table.column(f"{entity}:{archetype}:labels").to_pylist()
    ids = table.column(f"{entity}:{OBJECT_ID}").to_pylist()
    pairs: list[tuple[str, str]] = []
    for frame_labels, frame_ids in zip(labels, ids, strict=True):
        assert len(frame_labels or []) == len(frame_ids or [])
        pairs.extend(zip(frame_labels or [], frame_ids or [], strict=True))
    return pairs


def _highlight_labels(path: Path) -> set[str]:
    store = RrdReader(path).store().stream().collect()
    table = store.reader(index="frame", contents="/world/incidents/**").to_arrow_table()
    shown: set[str] = set()
    for name in table.column_names:
        if name.endswith(":Boxes3D:labels"):
            for row in table.column(name).to_pylist():
                shown.update(row or [])
    return shown


def _check_engines(path: Path, table: Mapping[str, str]) -> set[str]:
    """Every engine label names its object by ``table``'s short label; the ids it labels."""
    seen: set[str] = set()
    for entity, archetype in LABELLED.items():
        pairs = _labelled(path, entity, archetype)
        assert pairs, entity
        for label, object_id in pairs:
            assert len(object_id) == len(LEAD)  # the full id is kept beside the label
            assert object_id not in label, (entity, label)
            short = label.split(":", 1)[0] if ":" in label else label.split(" @ ", 1)[0]
            assert short == table[object_id], (entity, label, object_id)
            seen.add(object_id)
    return seen


def test_engines_use_the_review_table_and_keep_the_full_ids(report, tmp_path):
    table = short_labels(report.incidents)
    assert table[LEAD] == "#1"
    out = tmp_path / "review.rrd"
    _replay(out, table)
    assert LEAD in _check_engines(out, table)
    # the scene's highlights use the same table: the lead car is #1 everywhere
    assert _highlight_labels(out) == {table[o] for i in report.incidents for o in i.objects}
    # the plots keep the full id in the path and name the series by the short label
    store = RrdReader(out).store().stream().collect()
    static = store.reader(index=None, contents="/plots/rss/**").to_arrow_table().to_pydict()
    names = {k: v for k, v in static.items() if k.endswith(":SeriesLines:names")}
    assert names[f"/plots/rss/distances/{LEAD}/lon_m:SeriesLines:names"] == [["#1 lon_m"]]
    for column, (value,) in names.items():
        object_id = column.split("/")[-2]
        assert value == [f"{table[object_id]} {column.split('/')[-1].split(':')[0]}"]


def test_without_a_table_the_replay_numbers_culprits_first_and_scene_and_engines_agree(
    report, tmp_path
):
    out = tmp_path / "replay.rrd"
    _replay(out, None)
    culprits = {o for i in report.incidents for o in i.objects}
    shown = _highlight_labels(out)
    assert shown
    # rebuild the replay's table from what the engines drew: one label per id, one id per label
    drawn: dict[str, str] = {}
    for entity, archetype in LABELLED.items():
        for label, object_id in _labelled(out, entity, archetype):
            short = label.split(":", 1)[0] if ":" in label else label.split(" @ ", 1)[0]
            assert drawn.setdefault(object_id, short) == short
    assert len(set(drawn.values())) == len(drawn)
    assert {drawn[o] for o in culprits if o in drawn} <= shown
    assert drawn[LEAD] == "#1"  # the first culprit of the drive


def test_a_table_numbers_objects_in_order_and_keeps_them():
    table = ShortLabels(["b", "a"])
    assert table.label("a") == "#2"
    assert table.label("c") == "#3"
    assert list(table) == ["b", "a", "c"]
    assert dict(table) == {"b": "#1", "a": "#2", "c": "#3"}
    assert "d" not in table
    assert table.get("d", "d") == "d"
