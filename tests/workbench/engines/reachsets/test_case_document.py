"""A drive as a reach-set case document: ``workbench conformance reachsets`` on it gives the
drive pipeline's verdicts frame for frame (the racing sample, and both TUM logs from
``shared/external``, as ``tests/reachsets/test_external_saa.py`` evaluates them)."""

from __future__ import annotations

import dataclasses
import json
from functools import cache
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from typer.testing import CliRunner

from loaders import open_drive
from reachsets import ReachMethod, ReachParams, evaluate_frames
from reachsets.conformance import evaluate_document
from reachsets.inputs import ObjectStates
from workbench.cli.main import app, main
from workbench.engines.reachsets import adapter
from workbench.engines.reachsets.adapter import frame_to_reach_inputs
from workbench.engines.reachsets.cases import drive_case_document

SAMPLE = Path(__file__).resolve().parents[4] / "sample_logs" / "racing_overtake.saa"
#: labelled steps per TUM log (as in test_external_saa)
TUM = {"modena_T1_cutin_collision.saa": 23, "modena_T3_T4_catchingup_collision.saa": 88}


@cache
def _pipeline(path: Path, method: ReachMethod) -> tuple[Any, ...]:
    """The drive pipeline's results, frame by frame with the memory carried along."""
    drive = open_drive(path)
    params = ReachParams(method=method)
    state = None
    out = []
    for frame in drive.frames():
        (result,), state = evaluate_frames(
            [frame_to_reach_inputs(frame, drive.lane_map)], params, state
        )
        out.append(result)
    drive.close()
    return tuple(out)


@cache
def _document(path: Path, method: ReachMethod) -> str:
    drive = open_drive(path)
    try:
        document = drive_case_document(drive, name=path.stem, method=method.value)
    finally:
        drive.close()
    return json.dumps(document, allow_nan=False)


def _check(path: Path, method: ReachMethod) -> list[dict[str, Any]]:
    records = list(evaluate_document(json.loads(_document(path, method)), path.name))
    results = _pipeline(path, method)
    assert len(records) == len(results)
    for k, (record, result) in enumerate(zip(records, results, strict=True)):
        assert (record["sequence_id"], record["step"], record["ok"]) == (path.stem, k, True)
        assert record["safe"] is result.is_safe
        assert [(c["object_id"], c["step"]) for c in record["collisions"]] == [
            (c.object_id, c.step) for c in result.collisions
        ]
        assert record["checked_ids"] == [str(i) for i in result.object_ids]
        assert [p["rule"] for p in record["patches"]] == [p.rule for p in result.patches]
    return records


@pytest.mark.parametrize("method", list(ReachMethod))
def test_racing_sample_verdicts_equal_the_pipeline(method: ReachMethod) -> None:
    records = _check(SAMPLE, method)
    assert any(not r["safe"] for r in records)
    assert any(r["safe"] for r in records)


@pytest.mark.external
@pytest.mark.parametrize("method", list(ReachMethod))
@pytest.mark.parametrize("name", sorted(TUM))
def test_tum_logs_verdicts_equal_the_pipeline(
    external_dir: Path, name: str, method: ReachMethod
) -> None:
    records = _check(external_dir / "trajectory_supervisor" / name, method)
    checked = [r["expected_check"] for r in records if "expected_check" in r]
    assert len(checked) == TUM[name]  # every safety_dyn label became an expected verdict
    assert all(c["passed"] for c in checked), [c for c in checked if not c["passed"]]


def test_log_option_writes_the_document(tmp_path: Path) -> None:
    out = tmp_path / "racing.json"
    runner = CliRunner()
    made = runner.invoke(app, ["conformance", "reachsets-cases", str(out), "--log", str(SAMPLE)])
    assert made.exit_code == 0, made.output
    document = json.loads(out.read_text())
    assert document == json.loads(_document(SAMPLE, ReachMethod.TURN))
    assert document["defaults"]["method"] == "turn"
    rated = runner.invoke(app, ["conformance", "reachsets", str(out)])
    assert rated.exit_code == 0, rated.output
    safe = [json.loads(line)["safe"] for line in rated.stdout.splitlines()]
    assert safe == [r.is_safe for r in _pipeline(SAMPLE, ReachMethod.TURN)]


def test_a_road_drive_is_a_one_line_error(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    log = SAMPLE.with_name("highway_cut_in.mcap")
    with pytest.raises(SystemExit) as info:
        main(["conformance", "reachsets-cases", str(tmp_path / "x.json"), "--log", str(log)])
    err = capsys.readouterr().err
    assert info.value.code == 2
    assert (
        err
        == f"error: {log}: the drive has a road map; reach-set case files hold track bounds only\n"
    )
    assert not (tmp_path / "x.json").exists()


def test_objects_left_out_are_named(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """A non-finite object is left out of its step and named in the step's note and on stderr."""
    from workbench.engines.reachsets import cases  # noqa: PLC0415

    real = adapter.reach_inputs_and_kind

    def with_a_nan(frame: Any, *args: Any) -> Any:
        inputs, kind = real(frame, *args)
        o = inputs.objects
        if frame.index != 3 or not len(o):
            return inputs, kind
        x = np.array(o.x_m)
        x[0] = np.nan
        x.flags.writeable = False
        columns = {f.name: getattr(o, f.name) for f in dataclasses.fields(o)}
        objects = ObjectStates.of_frozen({**columns, "x_m": x})
        return dataclasses.replace(inputs, objects=objects), kind

    monkeypatch.setattr(cases, "reach_inputs_and_kind", with_a_nan)
    out = tmp_path / "racing.json"
    made = CliRunner().invoke(
        app, ["conformance", "reachsets-cases", str(out), "--log", str(SAMPLE)]
    )
    assert made.exit_code == 0, made.output
    steps = json.loads(out.read_text())["cases"][0]["sequence"]
    noted = [k for k, s in enumerate(steps) if "note" in s]
    assert noted == [3]
    left = steps[3]["note"].removeprefix(f"{cases.LEFT_OUT}: ").split(", ")
    assert left
    assert not set(left) & {o["id"] for o in steps[3]["objects"]}
    assert "1 step(s) leave out objects" in made.stderr
    records = list(evaluate_document(json.loads(out.read_text()), out.name))
    assert records[3]["ok"] is True  # a note is informational: the step is rated
