"""What a labelled clip carries: its label everywhere, the drive's frames and ids in its
``.rrd``, a reproducible MCAP; a used directory refused or replaced whole."""

from __future__ import annotations

import csv
import json
from pathlib import Path
from typing import Any

import pytest
from mcap.reader import make_reader

from loaders.clips import EVENT_TOPIC
from tests.workbench.cli_runs import run_workbench
from tests.workbench.engines.helpers import rrd_states
from workbench.annotations import LabelStore
from workbench.incidents import IncidentRequest, find_incidents

SAMPLES = Path(__file__).resolve().parents[3] / "sample_logs"
LOG = SAMPLES / "urban_intersection.mcap"
TAGS = ["cut-in, late", "x,y"]  # commas inside tags: a list, never joined


@pytest.fixture(scope="module")
def labelled(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Any]:
    """A drive with one confirmed incident, exported twice (the second with ``--force``)."""
    root = tmp_path_factory.mktemp("labelled")
    store = root / "labels.sqlite"
    report = find_incidents(IncidentRequest(LOG, engines=("rss",)))
    target = report.incidents[1]
    args = ["label", str(LOG), target.id, "--verdict", "confirmed", "--engines", "rss"]
    args += ["--note", "brakes late", "--reviewer", "ann", "--store", str(store)]
    for tag in TAGS:
        args += ["--tag", tag]
    assert run_workbench(args) == 0
    export = ["export", str(LOG), "--engines", "rss", "--store", str(store), "--no-thumbnails"]
    export += ["--incident", target.id, "--incident", report.incidents[0].id]
    for name in ("a", "b"):
        assert run_workbench([*export, "--out", str(root / name)]) == 0
    return {"root": root, "report": report, "target": target, "store": store, "args": export}


def _clip(out: Path, incident_id: str) -> dict[str, Any]:
    clips: list[dict[str, Any]] = json.loads((out / "clips.json").read_text())
    (clip,) = [c for c in clips if c["id"] == incident_id]
    return clip


def test_the_index_holds_the_label_and_the_source(labelled) -> None:
    out, target, report = labelled["root"] / "a", labelled["target"], labelled["report"]
    clip = _clip(out, target.id)
    assert (clip["verdict"], clip["tags"], clip["note"], clip["reviewer"]) == (
        "confirmed",
        sorted(TAGS),
        "brakes late",
        "ann",
    )
    assert clip["source"] == str(LOG)
    assert clip["drive_sha256"] == report.drive_hash
    assert clip["severity"]["unsafe_frames"] == target.severity.unsafe_frames
    with (out / "clips.csv").open() as f:
        (row,) = [r for r in csv.DictReader(f) if r["id"] == target.id]
    assert json.loads(row["tags"]) == sorted(TAGS)
    assert (row["note"], row["reviewer"], row["drive_sha256"]) == (
        "brakes late",
        "ann",
        report.drive_hash,
    )
    assert int(row["severity.unsafe_frames"]) == target.severity.unsafe_frames


def test_tags_are_a_json_list_in_the_clip(labelled) -> None:
    out, target = labelled["root"] / "a", labelled["target"]
    with (out / _clip(out, target.id)["files"]["mcap"]).open("rb") as f:
        reader = make_reader(f)
        metadata = {m.name: m.metadata for m in reader.iter_metadata()}
        topics = [c.topic for _, c, _ in reader.iter_messages()]
    assert json.loads(metadata["incident"]["tags"]) == sorted(TAGS)
    assert metadata["incident"]["verdict"] == "confirmed"
    assert EVENT_TOPIC in topics


def test_mcap_clips_are_byte_reproducible(labelled) -> None:
    root, target = labelled["root"], labelled["target"]
    name = _clip(root / "a", target.id)["files"]["mcap"]
    assert (root / "a" / name).read_bytes() == (root / "b" / name).read_bytes()


def test_the_recording_uses_the_drive_frames_id_and_verdict(labelled) -> None:
    out, target = labelled["root"] / "a", labelled["target"]
    rrd = out / _clip(out, target.id)["files"]["rrd"]
    states = rrd_states(rrd, f"/incidents/lanes/rss/{target.id}")
    assert states  # the drive's incident id, found again from the warm engines
    assert min(states) == target.start_frame
    assert states[target.start_frame] == "confirmed"


def test_the_clip_openlabel_imports_onto_the_source_drive(labelled, tmp_path: Path) -> None:
    out, target, report = labelled["root"] / "a", labelled["target"], labelled["report"]
    doc = out / _clip(out, target.id)["files"]["openlabel"]
    meta = json.loads(doc.read_text())["openlabel"]["metadata"]
    assert (meta["drive_sha256"], meta["clip"]["incident_id"]) == (report.drive_hash, target.id)
    fresh = tmp_path / "fresh.sqlite"
    assert run_workbench(["labels", "import", str(doc), "--store", str(fresh)]) == 0
    with LabelStore(fresh) as store:
        label = store.label(report.drive_hash, target.id)
    assert label is not None
    assert (label.verdict, list(label.tags), label.reviewer) == ("confirmed", sorted(TAGS), "ann")


def test_a_used_directory_is_refused_or_replaced_whole(labelled, capsys) -> None:
    root, target = labelled["root"], labelled["target"]
    args = ["export", str(LOG), "--engines", "rss", "--store", str(labelled["store"]), "--no-rrd"]
    args += ["--no-thumbnails", "--incident", target.id, "--out", str(root / "a")]
    before = sorted(p.name for p in (root / "a").iterdir())
    assert run_workbench(args) == 2
    assert "holds an earlier export" in capsys.readouterr().err
    assert sorted(p.name for p in (root / "a").iterdir()) == before
    (root / "a" / "keep.txt").write_text("not ours")
    assert run_workbench([*args, "--force"]) == 0
    (clip,) = json.loads((root / "a" / "clips.json").read_text())
    named = {n for n in clip["files"].values() if n} | {"clips.json", "clips.csv", "keep.txt"}
    assert {p.name for p in (root / "a").iterdir()} == named  # no stale clip left
