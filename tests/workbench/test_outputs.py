"""The shared output writers: whole files or none, and JSON that strict parsers accept."""

from __future__ import annotations

import json
import math
import re
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from workbench.annotations.openlabel import write_openlabel
from workbench.errors import WorkbenchError
from workbench.incidents import write_incidents
from workbench.incidents.model import Incident, Severity
from workbench.outputs import atomic_output, finite, json_text, write_json
from workbench.sinks.violations import Violation, write_violations

ROOT = Path(__file__).resolve().parents[2]
NON_FINITE = (math.inf, -math.inf, math.nan)


def _strict(text: str) -> Any:
    """JSON as a browser parses it: ``NaN``/``Infinity`` are errors."""

    def refuse(token: str) -> None:
        msg = f"non-finite number {token} in JSON"
        raise AssertionError(msg)

    return json.loads(text, parse_constant=refuse)


def test_every_json_writer_goes_through_the_shared_encoder() -> None:
    encoder = re.compile(r"\bjson\.dumps?\(")
    found = [
        f"{path.relative_to(ROOT)}"
        for package in ("workbench", "loaders", "rss", "reachsets")
        for path in sorted((ROOT / package).rglob("*.py"))
        if encoder.search(path.read_text()) and path != ROOT / "workbench" / "outputs.py"
    ]
    assert found == []


@pytest.mark.parametrize("bad", NON_FINITE)
def test_non_finite_numbers_become_null(bad: float) -> None:
    value = {"a": bad, "b": [1.5, bad, (np.float64(bad), np.float32(2.0))], "c": np.int64(3)}
    assert _strict(json_text(value)) == {"a": None, "b": [1.5, None, [None, 2.0]], "c": 3}
    assert finite(-0.0) == 0.0
    assert finite("inf") == "inf"


def _incident(bad: float) -> Incident:
    severity = Severity(bad, 3, 0.1, facts={"ttc_s": bad, "name": "x"})
    return Incident("rss-000001-x", "rss", ("7",), "RSS lon", 1, 3, 10, 30, severity)


@pytest.mark.parametrize("bad", NON_FINITE)
def test_file_writers_write_no_non_finite_number(tmp_path: Path, bad: float) -> None:
    violation = Violation("v", "log", "rss", "lon", ["7"], 1, 3, 10, 30, bad, ["lon"], "")
    write_violations([violation], tmp_path / "v.json")
    assert _strict((tmp_path / "v.json").read_text())[0]["worst_margin"] is None
    write_incidents([_incident(bad)], tmp_path / "i.json")
    (record,) = _strict((tmp_path / "i.json").read_text())
    assert record["severity"]["ttc_s"] is None
    assert record["severity"]["worst_margin"] is None
    write_openlabel({"openlabel": {"metadata": {"x": bad}}}, tmp_path / "o.json")
    assert _strict((tmp_path / "o.json").read_text())["openlabel"]["metadata"]["x"] is None
    write_json(tmp_path / "w.json", [bad], "a test file")
    assert _strict((tmp_path / "w.json").read_text()) == [None]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["i.json", "o.json", "v.json", "w.json"]


def test_a_failed_write_leaves_neither_file_nor_part(tmp_path: Path) -> None:
    target = tmp_path / "out.json"

    def write_half() -> None:
        with atomic_output(target, "a test file") as part:
            part.write_text("half")
            raise RuntimeError

    with pytest.raises(RuntimeError):
        write_half()
    assert list(tmp_path.iterdir()) == []


def test_an_unwritable_target_is_one_line_naming_it(tmp_path: Path) -> None:
    (tmp_path / "file").write_text("")
    with pytest.raises(WorkbenchError) as info:
        write_json(tmp_path / "file" / "out.json", {}, "the clip index")
    assert str(info.value).startswith(f"{tmp_path / 'file' / 'out.json'}: cannot write")
    assert "\n" not in str(info.value)
    with pytest.raises(WorkbenchError, match="Is a directory"):
        write_json(tmp_path, {}, "OpenLABEL")


@pytest.mark.parametrize(
    "value",
    [
        {"a": 1.5, "b": [1, 2.25, "x", None, True], "c": (3, 4.0)},
        {"f64": np.float64(0.1), "neg": -0.0, "big": 1e300},
        {"i64": np.int64(3), "b": np.bool_(True), "nan": math.nan},
        [np.float32(2.5), {"inf": math.inf}],
    ],
)
@pytest.mark.parametrize("compact", [False, True])
def test_the_strict_shortcut_writes_what_the_walk_writes(value: Any, compact: bool) -> None:
    separators = (",", ":") if compact else None
    walked = json.dumps(finite(value), separators=separators, allow_nan=False)
    assert json_text(value, compact=compact) == walked
