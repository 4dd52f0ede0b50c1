"""``workbench batch`` with ``file://`` URLs (read where the task runs); other URLs refused."""

from __future__ import annotations

import shutil
from typing import TYPE_CHECKING

import pytest

from tests.workbench.batch.conftest import ENGINES
from tests.workbench.batch.drives import GOOD, drive_rows, incident_rows
from tests.workbench.cli_runs import run_workbench
from workbench.batch import BatchError, expand_logs

if TYPE_CHECKING:
    from pathlib import Path


def test_file_urls_name_the_same_logs_as_paths(fleet: Path, tmp_path: Path) -> None:
    folder = tmp_path / "with space %"  # percent-encoded in the URL
    shutil.copytree(fleet, folder)
    assert expand_logs([(folder / GOOD[0]).as_uri()]) == [folder / GOOD[0]]
    assert expand_logs([folder.as_uri()]) == expand_logs([str(folder)])
    local = f"file://localhost{(folder / GOOD[1]).as_uri().removeprefix('file://')}"
    assert expand_logs([local]) == [folder / GOOD[1]]


@pytest.mark.parametrize("url", ["memory://fleet/a.mcap", "s3://bucket/a.mcap", "file://host/a"])
def test_other_urls_are_refused_in_one_line(url: str) -> None:
    with pytest.raises(BatchError, match="only file:// URLs") as err:
        expand_logs([url])
    assert url in str(err.value)
    assert "\n" not in str(err.value)


def test_a_batch_of_a_file_url_gives_the_rows_of_its_path(
    fleet: Path, reference: Path, tmp_path: Path
) -> None:
    out = tmp_path / "url"
    log = fleet / GOOD[0]
    args = ["batch", log.as_uri(), "--out", str(out), "--jobs", "1", "--engines", ENGINES]
    assert run_workbench(args) == 0
    drive = drive_rows(out)[GOOD[0]]
    assert drive["status"] == "ok"
    assert drive["path"] == str(log)
    expected = [r for r in incident_rows(reference) if r["drive_path"] == str(log)]
    assert expected
    assert incident_rows(out) == expected
