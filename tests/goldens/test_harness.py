"""The harness itself: the tolerance, the file format, the change report and the update switch."""

from __future__ import annotations

import io
import json

import pytest

from tests.goldens import update
from tests.goldens.compare import ABS_TOL, compare, first_difference, spans
from tests.goldens.golden_file import FrameRecord, GoldenFileError, golden_text, read_golden
from tests.goldens.samples import SAMPLE_DIR, VARIANTS, evaluate_log
from tests.workbench.engines.test_plugin import TOY
from workbench.engines.registry import names, register, unregister

# --- tolerance ----------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("expected", "got"),
    [
        (0.427863, 0.427864),  # one step of the records' 1e-6 rounding (a tie moved)
        (0.1 + 0.2, 0.3),  # last bits
        (1e12, 1e12 * (1 + 5e-10)),  # relative
        ({"a": [1, 2.5, None]}, {"a": [1, 2.5 + 1e-12, None]}),
    ],
)
def test_floats_equal_within_the_tolerance(expected, got):
    assert first_difference(expected, got) is None


@pytest.mark.parametrize(
    ("expected", "got", "where"),
    [
        (0.427863, 0.427866, "."),  # three quanta
        (5, 6, "."),
        (2, 2.0, "."),  # another text in the per-frame line
        (True, 1, "."),
        (None, 0.0, "."),
        ("Brake", "DriveAway", "."),
        ({"a": 1}, {"a": 1, "b": 2}, ".b"),
        ({"a": [1, 2]}, {"a": [1]}, ".a"),
        ({"a": 1, "b": 2}, {"b": 2, "a": 1}, " key order"),
        ({"s": {"1": {"ttc_s": 1.0}}}, {"s": {"1": {"ttc_s": 1.1}}}, ".s.1.ttc_s"),
    ],
)
def test_anything_else_differs(expected, got, where):
    found = first_difference(expected, got)
    assert found is not None
    assert found.startswith(f"{where}:")


def test_the_absolute_tolerance_is_one_record_quantum_and_a_bit():
    assert first_difference(1.0, 1.0 + ABS_TOL * 0.99) is None
    assert first_difference(1.0, 1.0 + ABS_TOL * 1.5) is not None


# --- file format --------------------------------------------------------------------------


def _frames(records: list[dict[str, object]], times: list[int] | None = None) -> list[FrameRecord]:
    times = times or [1_000 + 50 * k for k in range(len(records))]
    return [FrameRecord(k, t, r) for k, (t, r) in enumerate(zip(times, records, strict=True))]


SAFE = {"is_safe": True, "dangerous_objects": [], "x": 1.5}
UNSAFE = {"is_safe": False, "dangerous_objects": ["7"], "x": 0.25}


def test_file_round_trips_and_runs_share_a_line(tmp_path):
    times = [0, 50, 100, 175, 250, 400]  # two time runs
    frames = _frames([SAFE, SAFE, UNSAFE, UNSAFE, SAFE, SAFE], times)
    text = golden_text("default", "toy", "a.mcap", frames)
    lines = text.splitlines()
    assert json.loads(lines[0]) == {
        "variant": "default",
        "engine": "toy",
        "log": "a.mcap",
        "frames": 6,
        "time": [[0, 0, 3, 50], [3, 175, 2, 75], [5, 400, 1, 0]],
    }
    assert [json.loads(line)["frames"] for line in lines[1:]] == [[0, 1], [2, 3], [4, 5]]
    path = tmp_path / "g.jsonl"
    path.write_text(text)
    golden = read_golden(path)
    assert (golden.variant, golden.engine, golden.log) == ("default", "toy", "a.mcap")
    assert list(golden.frames) == frames


def test_one_changed_frame_changes_only_the_lines_of_its_run():
    before = golden_text("v", "toy", "a.mcap", _frames([SAFE] * 10)).splitlines()
    changed = _frames([SAFE] * 4 + [UNSAFE] + [SAFE] * 5)
    after = golden_text("v", "toy", "a.mcap", changed).splitlines()
    assert before[0] == after[0]
    assert len(before) == 2
    assert [json.loads(line)["frames"] for line in after[1:]] == [[0, 3], [4, 4], [5, 9]]


@pytest.mark.parametrize(
    "body",
    [
        '{"frames":[0,1],"toy":{}}',  # one frame short of the header
        '{"frames":[1,2],"toy":{}}',  # does not start at the first frame
        '{"frames":[0,5],"toy":{}}',  # beyond the last frame
        '{"frames":[0,2],"other":{}}',  # another engine's key
        "not json",
    ],
)
def test_malformed_files_are_named(tmp_path, body):
    path = tmp_path / "g.jsonl"
    head = '{"variant":"v","engine":"toy","log":"a.mcap","frames":3,"time":[[0,0,3,50]]}\n'
    path.write_text(head + body)
    with pytest.raises(GoldenFileError, match=r"g\.jsonl"):
        read_golden(path)


# --- change report ------------------------------------------------------------------------


def test_report_names_frames_keys_and_flips():
    old = _frames([SAFE] * 6)
    new = _frames([SAFE, UNSAFE, UNSAFE, SAFE, {**SAFE, "x": 1.75}, SAFE, SAFE])
    changes = compare(old, new)
    assert changes
    assert changes.changed == [1, 2, 4]
    assert changes.added == [6]
    assert changes.keys == {"is_safe": 2, "dangerous_objects": 2, "x": 3}
    assert (changes.safe_to_unsafe, changes.unsafe_to_safe) == (2, 0)
    text = changes.summary()
    assert "3 of 7 frames changed: 1-2, 4" in text
    assert "safe -> unsafe 2, unsafe -> safe 0" in text
    assert "first: frame 1: is_safe: True -> False" in text
    assert not compare(old, old)


def test_spans_are_short():
    assert spans([7, 3, 4, 5, 12]) == "3-5, 7, 12"
    assert spans(range(0, 40, 2)).endswith("… (12 more)")


# --- the update switch --------------------------------------------------------------------


def test_update_refuses_under_ci(monkeypatch, capsys):
    monkeypatch.setenv("CI", "true")
    assert update.main([]) == 2
    assert "never updated under CI=true" in capsys.readouterr().err


@pytest.mark.parametrize("option", ["--log", "--engine", "--variant"])
def test_update_rejects_an_unknown_name(monkeypatch, capsys, option):
    monkeypatch.delenv("CI", raising=False)
    assert update.main([option, "nope"]) == 2
    assert "nope" in capsys.readouterr().err


def test_update_writes_reports_and_restores_a_changed_frame(tmp_path):
    log = SAMPLE_DIR / "racing_overtake.saa"
    engines = ("reachsets",)
    (tmp_path / "gone").mkdir()
    (tmp_path / "gone" / "old.mcap.jsonl").write_text("{}\n")
    report = io.StringIO()
    counts = update.update(("default",), engines, [log], root=tmp_path, prune=True, out=report)
    assert counts == {"default": {"new": 1}, "gone": {"removed": 1}}
    assert "default/reachsets/racing_overtake.saa.jsonl: new (81 frames)" in report.getvalue()
    assert "gone/old.mcap.jsonl: removed" in report.getvalue()
    path = tmp_path / "default" / "reachsets" / "racing_overtake.saa.jsonl"
    clean = path.read_text()
    assert list(read_golden(path).frames) == evaluate_log(log, engines)["reachsets"]
    assert update.summary(counts, tmp_path) == (
        "default: 0 updated, 1 new, 0 removed, 0 unchanged\n"
        "gone: 0 updated, 0 new, 1 removed, 0 unchanged\n"
        f"1 golden files, {len(clean.encode()) / 1000:.0f} kB in all\n"
    )

    # tamper with frame 10 as a wrong golden would: the update names it, flips it back
    frames = list(read_golden(path).frames)
    record = frames[10].record
    frames[10] = FrameRecord(10, frames[10].t_ns, {**record, "is_safe": not record["is_safe"]})
    path.write_text(golden_text("default", "reachsets", log.name, frames))
    report = io.StringIO()
    counts = update.update(("default",), engines, [log], root=tmp_path, out=report)
    assert counts == {"default": {"updated": 1}}
    text = report.getvalue()
    assert "default/reachsets/racing_overtake.saa.jsonl: updated" in text
    assert "1 of 81 frames changed: 10" in text
    assert "keys: is_safe (1)" in text
    assert path.read_text() == clean

    report = io.StringIO()
    counts = update.update(("default",), engines, [log], root=tmp_path, out=report)
    assert counts == {"default": {"unchanged": 1}}
    assert path.read_text() == clean

    path.write_text("not a golden file\n")
    report = io.StringIO()
    counts = update.update(("default",), engines, [log], root=tmp_path, out=report)
    assert counts == {"default": {"updated": 1}}
    assert "rewritten, the file was unreadable" in report.getvalue()
    assert path.read_text() == clean


def test_a_registered_engine_gets_goldens_without_new_test_code(tmp_path):
    log = SAMPLE_DIR / "racing_overtake.saa"
    register(TOY)
    try:
        assert "toy" in names()
        records = evaluate_log(log)  # every registered engine, as the golden tests run
        report = io.StringIO()
        counts = update.update(("default",), names(), [log], root=tmp_path, out=report)
    finally:
        unregister("toy")
    assert counts == {"default": {"new": len(names()) + 1}}
    assert "default/toy/racing_overtake.saa.jsonl: new (81 frames)" in report.getvalue()
    golden = read_golden(tmp_path / "default" / "toy" / "racing_overtake.saa.jsonl")
    assert golden.engine == "toy"
    assert list(golden.frames) == records["toy"]
    assert {tuple(f.record) for f in golden.frames} == {("is_safe", "near")}


def test_a_variant_is_one_table_entry_whose_arguments_reach_evaluate(tmp_path, monkeypatch):
    log = SAMPLE_DIR / "racing_overtake.saa"
    # any evaluate option works; --start makes the arguments' effect visible in the frames
    monkeypatch.setitem(VARIANTS, "from-2s", ("--start", "2"))
    report = io.StringIO()
    counts = update.update(tuple(VARIANTS), ("reachsets",), [log], root=tmp_path, out=report)
    assert counts == {variant: {"new": 1} for variant in VARIANTS}
    full = read_golden(tmp_path / "default" / "reachsets" / "racing_overtake.saa.jsonl")
    late = read_golden(tmp_path / "from-2s" / "reachsets" / "racing_overtake.saa.jsonl")
    assert (late.variant, late.engine, late.log) == ("from-2s", "reachsets", log.name)
    assert list(late.frames) == evaluate_log(log, ("reachsets",), "from-2s")["reachsets"]
    assert 0 < len(late.frames) < len(full.frames) == 81
    assert late.frames[0].t_ns - full.frames[0].t_ns >= 2_000_000_000


def test_a_file_without_its_variant_is_not_a_golden_file(tmp_path):
    path = tmp_path / "g.jsonl"
    path.write_text('{"engine":"toy","log":"a.mcap","frames":1,"time":[[0,0,1,0]]}\n')
    path.write_text(path.read_text() + '{"frames":[0,0],"toy":{}}\n')
    with pytest.raises(GoldenFileError, match="variant"):
        read_golden(path)
