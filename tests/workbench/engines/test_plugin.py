"""An engine added in one file is seen by every command, the settings file and the blueprint.

The toy engine below is the whole plugin: its runner, typed verdict, record, Rerun sink,
view and one option of its own (``--toy-near``) live here; registering its spec is the only
step (no other module is touched).
"""

from __future__ import annotations

import dataclasses
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

from workbench.cli.main import app, main
from workbench.engines import EngineSpec, names, register
from workbench.engines.options import option
from workbench.engines.registry import unregister
from workbench.incidents import IncidentRequest, find_incidents
from workbench.incidents.whatif import variants, what_if
from workbench.replay.blueprint import replay_blueprint
from workbench.replay.sink import time_index

if TYPE_CHECKING:
    from collections.abc import Iterator, Sequence

    from loaders.maps.model import LaneMap
    from loaders.records import Frame
    from workbench.engines.ids import ActorIds
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


@dataclass(frozen=True, slots=True)
class ToyOptions:
    near_m: float = option(NEAR_M, flag="--toy-near", help="Toy: unsafe nearer than this [m].")

    def __post_init__(self) -> None:
        if not self.near_m > 0.0:
            msg = f"--toy-near {self.near_m}: give a distance > 0 m"
            raise ValueError(msg)


class ToyRunner:
    name = "toy"

    def __init__(self, options: ToyOptions) -> None:
        self.options = options

    def step_many(self, frames: Sequence[Frame]) -> list[ToyVerdict]:
        out = []
        for f in frames:
            d = np.hypot(f.actors.x_m - f.ego.x_m, f.actors.y_m - f.ego.y_m)
            near = tuple(sorted(str(a) for a in f.actors.ids[d < self.options.near_m]))
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


def _build(
    lane_map: LaneMap | None, options: ToyOptions, *, full_geometry: bool, actor_ids: ActorIds
) -> ToyRunner:
    del lane_map, full_geometry
    return ToyRunner(options)


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
    options=ToyOptions,
    what_if=lambda o: [("toy-near-5", dataclasses.replace(o, near_m=5.0))],
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


def _unsafe_toy_frames(tmp_path: Path, *extra: str) -> int:
    lines = tmp_path / "toy.jsonl"
    args = ["evaluate", str(SAMPLE), "--engines", "toy", "--end", "2", "--per-frame", str(lines)]
    result = CliRunner().invoke(app, [*args, *extra])
    assert result.exit_code == 0, result.output
    return sum(not json.loads(line)["toy"]["is_safe"] for line in lines.read_text().splitlines())


@pytest.mark.parametrize(
    "command", ["evaluate", "replay", "incidents", "review", "export", "demo", "info", "batch"]
)
def test_the_toy_option_is_in_every_command_help(toy, command: str) -> None:
    del toy
    result = CliRunner().invoke(app, [command, "--help"])
    assert result.exit_code == 0, result.output
    assert "--toy-near" in result.output


def test_the_toy_option_changes_the_verdicts_from_the_cli_and_the_settings(toy, tmp_path):
    del toy
    default = _unsafe_toy_frames(tmp_path)
    near = _unsafe_toy_frames(tmp_path, "--toy-near", "1")
    settings = tmp_path / "settings.toml"
    settings.write_text("[toy]\nnear_m = 1.0\n")
    from_file = _unsafe_toy_frames(tmp_path, "--settings", str(settings))
    cli_wins = _unsafe_toy_frames(tmp_path, "--settings", str(settings), "--toy-near", "30")
    assert default > 0
    assert near < default
    assert from_file == near
    assert cli_wins == default


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--toy-near", "-1"], "--toy-near -1.0: give a distance > 0 m"),
        (["--settings", "{settings}"], "[toy]: unknown option 'near' (known: near_m)"),
        (["--settings", "{other}"], "[nothing] names no engine"),
        (["--engines", "toy,toy"], "'toy' named twice"),
    ],
)
def test_bad_toy_options_are_one_line_errors(toy, tmp_path, capsys, args, message):
    del toy
    settings, other = tmp_path / "s.toml", tmp_path / "o.toml"
    settings.write_text("[toy]\nnear = 1.0\n")
    other.write_text("[nothing]\nnear_m = 1.0\n")
    args = [a.format(settings=settings, other=other) for a in args]
    with pytest.raises(SystemExit) as exit_:
        main(["evaluate", str(SAMPLE), "--engines", "toy", "--end", "1", *args])
    assert exit_.value.code == 2
    err = capsys.readouterr().err
    assert message in err
    assert len(err.strip().splitlines()) == 1


def test_the_toy_option_reaches_incidents_and_review(toy, tmp_path, monkeypatch):
    del toy
    seen = []
    monkeypatch.setattr("workbench.review.loop.run_review", lambda s: seen.append(s.report))
    settings = tmp_path / "settings.toml"
    settings.write_text("[toy]\nnear_m = 1.0\n")
    store = str(tmp_path / "labels.sqlite")
    base = [str(SAMPLE), "--engines", "toy", "--store", store]
    for extra in (["--toy-near", "2.5"], ["--settings", str(settings)], []):
        result = CliRunner().invoke(app, ["review", *base, *extra])
        assert result.exit_code == 0, result.output
    requests = [report.request for report in seen]
    assert [r.options_of("toy").near_m for r in requests] == [2.5, 1.0, NEAR_M]
    assert [report.settings["toy_near"] for report in seen] == [2.5, 1.0, NEAR_M]
    assert len(seen[0].incidents) <= len(seen[2].incidents)
    listed = tmp_path / "incidents.json"
    args = ["incidents", str(SAMPLE), "--engines", "toy", "--toy-near", "2.5", "--out", str(listed)]
    result = CliRunner().invoke(app, args)
    assert result.exit_code == 0, result.output
    assert len(json.loads(listed.read_text())) == len(seen[0].incidents)


def test_the_toy_what_if_is_its_own(toy):
    del toy
    request = IncidentRequest(SAMPLE, engines=("toy",))
    report = find_incidents(request, window=(None, None))
    incident = report.incidents[0]
    assert variants(request, incident) == ("toy-near-5",)
    outcome = what_if(request, incident, "toy-near-5")
    assert outcome.line().startswith("what-if toy-near-5: ")
