"""One integer id space per drive: ``"7"`` and ``"007"`` are two objects in every engine."""

from __future__ import annotations

import dataclasses
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from loaders import open_drive
from loaders.records import ActorTable
from workbench.engines import build_runners
from workbench.engines.ids import EGO_OBJECT_ID, FIRST_LABEL_ID, ActorIds
from workbench.engines.rss.verdict import RssVerdict

if TYPE_CHECKING:
    from loaders.records import Frame

SAMPLE = Path(__file__).resolve().parents[3] / "sample_logs" / "pedestrian_crossing.mcap"
ENGINES = ["rss", "unstructured", "reachsets"]
#: Frames of the sample where every engine names a culprit.
WINDOW = range(96, 112)


def _relabel(label: str) -> str:
    """``"1"`` -> ``"7"``: a canonical decimal label of its own for each sample actor."""
    return str(int(label) + 6)


def _doubled(frame: Frame) -> Frame:
    """``frame`` with every actor twice: as ``"7"`` and as ``"007"`` (same box, same motion)."""
    a = frame.actors
    labels = [_relabel(str(x)) for x in a.ids]
    columns = {
        f.name: np.concatenate([getattr(a, f.name), getattr(a, f.name)])
        for f in dataclasses.fields(a)
    }
    columns["ids"] = np.array([*labels, *(f"00{x}" for x in labels)], dtype=np.str_)
    return dataclasses.replace(frame, actors=ActorTable(**columns))


def test_leading_zeros_and_names_get_ids_of_their_own():
    ids = ActorIds()
    labels = ["7", "007", "car_3", "7", "0", "\u0667", "123456789012"]
    values = [ids.to_int(x) for x in labels]
    assert values[0] == 7
    assert values[3] == values[0]
    assert values[4] == 0
    assert len(set(values)) == len(values) - 1
    assert all(FIRST_LABEL_ID <= v < EGO_OBJECT_ID for v in (values[1], values[2], *values[5:]))
    assert [ids.label(v) for v in values] == labels
    assert ids.label(12) == "12"


def test_7_and_007_in_one_frame_are_reported_under_their_own_ids_by_every_engine():
    drive = open_drive(SAMPLE)
    try:
        frames = [f for f in drive.frames() if f.index in WINDOW]
        plain = build_runners(ENGINES, drive.lane_map)
        doubled = build_runners(ENGINES, drive.lane_map)
        expected = {r.name: r.step_many(frames) for r in plain}
        found = {r.name: r.step_many([_doubled(f) for f in frames]) for r in doubled}
    finally:
        drive.close()
    named = 0
    for name in ENGINES:
        for before, after in zip(expected[name], found[name], strict=True):
            want = {_relabel(c) for c in before.culprits}
            want |= {f"00{c}" for c in want}
            assert set(after.culprits) == want, name
            assert after.is_safe == before.is_safe
            named += bool(before.culprits)
        assert any(v.culprits for v in expected[name]), f"{name} names no culprit in the window"
    assert named >= len(ENGINES)
    labels = [v.labels for v in found["rss"] if isinstance(v, RssVerdict)]
    assert len(labels) == len(WINDOW)
    assert all(len(set(k)) == len(k) for k in labels)
    assert any({"7", "007"} <= set(k) for k in labels)
