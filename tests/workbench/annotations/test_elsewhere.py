"""Labels made under other settings are named by the commands that read labels, never dropped."""

from __future__ import annotations

import json
from pathlib import Path
from typing import TYPE_CHECKING

from tests.workbench.cli_runs import run_workbench
from workbench.annotations import LabelStore
from workbench.incidents import drive_content_hash

if TYPE_CHECKING:
    import pytest

LOG = Path(__file__).resolve().parents[3] / "sample_logs" / "hard_braking_lead.mcap"

#: The reference profile flags hard_braking_lead's car-following early; ``auto`` (highway)
#: only the lead's hard braking: the first profile's incidents are not all the second's.
REFERENCE = ["--engines", "rss", "--rss-profile", "adrss-5.0"]
REVIEW = ["--engines", "rss"]


def _ids(tmp_path: Path, options: list[str]) -> list[str]:
    out = tmp_path / "ids.json"
    assert run_workbench(["incidents", str(LOG), *options, "--out", str(out)]) == 0
    return [row["id"] for row in json.loads(out.read_text())]


def test_labels_of_other_settings_are_named_and_kept(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    store = tmp_path / "labels.sqlite"
    reference, review = _ids(tmp_path, REFERENCE), _ids(tmp_path, REVIEW)
    away = [i for i in reference if i not in review]
    assert away
    for incident_id in reference:
        label = ["label", str(LOG), incident_id, *REFERENCE, "--verdict", "confirmed"]
        assert run_workbench([*label, "--store", str(store)]) == 0
    capsys.readouterr()
    doc = tmp_path / "doc.json"
    export = ["labels", "export", str(LOG), *REVIEW, "--store", str(store), "--out", str(doc)]
    assert run_workbench(export) == 0
    err = capsys.readouterr().err
    assert f"{len(away)} label(s) of this drive are for incidents these settings do not" in err
    assert "rss_profile adrss-5.0 (now auto)" in err
    # nothing is deleted: every label is still in the store
    with LabelStore(store) as labels:
        assert set(labels.labels(drive_content_hash(LOG))) == set(reference)
    # under the settings they were made with, the note is silent
    assert run_workbench([*export[:3], *REFERENCE, *export[5:]]) == 0
    assert "label(s) of this drive" not in capsys.readouterr().err
