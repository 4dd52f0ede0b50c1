"""An engine added in one file is seen by ``evaluate``, ``replay`` and the blueprint.

The toy engine below is the whole plugin: its runner, typed verdict, record, Rerun sink and
view live here; registering its spec is the only step (no other module is touched).
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
import pytest
import rerun as rr
import rerun.blueprint as rrb
from rerun.chunk import RrdReader
from typer.testing import CliRunner

from workbench.cli.main import app
from workbench.engines import EngineSpec, names, register
from workbench.engines.registry import unregister
from workbench.replay.blueprint import replay_blueprint
from workbench.replay.sink import time_index

if TYPE_CHECKING:
    from collections.abc import Iterator, Sequence

    from loaders.maps.model import LaneMap
    from loaders.records import Frame
    from workbench.engines.base import EngineSettings
    from workbench.replay.layout import ChunkLayout
    from workbench.replay.short_labels import ShortLabels

SAMPLE = Path(__file__).resolve().parents[3] / "sample_logs" / "highway_cut_in.mcap"
#: Actors nearer than this to the ego make a toy frame unsafe [m].
NEAR_M = 30.0


@dataclass(frozen=True, slots=True)
class ToyVerdict:
    is_safe: bool
    culprits: tuple[str, ...]
    cause: str
    margin: float
    nearest_m: float


class ToyRunner:
    name = "toy"

    def step_many(self, frames: Sequence[Frame]) -> list[ToyVerdict]:
        out = []
        for f in frames:
            d = np.hypot(f.actors.x_m - f.ego.x_m, f.actors.y_m - f.ego.y_m)
            near = tuple(sorted(str(a) for a in f.actors.ids[d < NEAR_M]))
            nearest = float(d.min()) if len(d) else float("inf")
            out.append(ToyVerdict(not near, near, "toy: near" if near else "", nearest, nearest))
        return out


class ToySink:
    def __init__(self, recording: rr.RecordingStream, labels: ShortLabels) -> None:
        self.recording = recording
        self.labels = labels  # the drive's short labels, for any object label it would draw

    def send_chunk(
        self, frames: Sequence[Frame], layout: ChunkLayout, verdicts: Sequence[ToyVerdict]
    ) -> None:
        del frames
        states = np.array(["safe" if v.is_safe else "near" for v in verdicts], dtype=str)
        self.recording.send_columns(
            "toy/state",
            indexes=time_index(layout.frame, layout.t_ns),
            columns=rr.StateChange.columns(state=states),
        )


def _record(verdict: ToyVerdict) -> dict[str, Any]:
    return {"is_safe": verdict.is_safe, "near": list(verdict.culprits)}


def _build(lane_map: LaneMap | None, settings: EngineSettings) -> ToyRunner:
    del lane_map, settings
    return ToyRunner()


TOY = EngineSpec(
    name="toy",
    title="toy",
    short="toy",
    state_origin="/toy",
    causes=("toy: near",),
    build=_build,
    record=_record,
    sink=ToySink,
    views=lambda: [rrb.TimeSeriesView(name="toy plot", origin="/plots/toy")],
)


@pytest.fixture
def toy() -> Iterator[EngineSpec]:
    register(TOY)
    yield TOY
    unregister("toy")


def _views(container: Any) -> Iterator[Any]:
    for item in container.contents:
        if isinstance(item, rrb.Container):
            yield from _views(item)
        else:
            yield item


def test_a_registered_engine_is_evaluated_by_the_cli(toy, tmp_path):
    assert "toy" in names()
    lines = tmp_path / "frames.jsonl"
    args = [
        "evaluate",
        str(SAMPLE),
        "--engines",
        "toy,rss",
        "--end",
        "2",
        "--per-frame",
        str(lines),
    ]
    result = CliRunner().invoke(app, args)
    assert result.exit_code == 0, result.output
    records = [json.loads(line) for line in lines.read_text().splitlines()]
    assert len(records) == 40
    assert all(list(r) == ["t_ns", "frame", "toy", "rss"] for r in records)
    assert any(not r["toy"]["is_safe"] and r["toy"]["near"] for r in records)


def test_a_registered_engine_is_replayed_with_its_sink_and_views(toy, tmp_path):
    out = tmp_path / "toy.rrd"
    result = CliRunner().invoke(
        app, ["replay", str(SAMPLE), "--engines", "toy", "--end", "2", "--out", str(out)]
    )
    assert result.exit_code == 0, result.output
    assert "toy:" in result.output
    store = RrdReader(str(out)).store().stream().collect()
    table = store.reader(index="frame", contents="/toy/state").to_arrow_table()
    assert table.num_rows == 40
    blueprint = replay_blueprint((0.0, 0.0), engines=["toy"])
    origins = {str(v.origin) for v in _views(blueprint.root_container)}
    assert "/plots/toy" in origins
    assert "/toy" in origins
    assert "/rss/structured" in origins
    listed = CliRunner().invoke(app, ["engines"])
    assert "toy: near" in listed.output
