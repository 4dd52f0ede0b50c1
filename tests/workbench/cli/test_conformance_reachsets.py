"""``workbench conformance reachsets`` and ``reachsets-cases`` through the CLI: JSON lines,
the same records as the library, one-line errors without a traceback."""

from __future__ import annotations

import json
from typing import TYPE_CHECKING

import numpy as np
import pytest
from typer.testing import CliRunner

from reachsets.conformance import evaluate_document, random_document
from workbench.cli.main import app, main

if TYPE_CHECKING:
    from pathlib import Path


def _lines(text: str) -> list[dict[str, object]]:
    return [json.loads(line) for line in text.splitlines()]


@pytest.mark.parametrize("full_sets", [False, True])
def test_records_equal_the_library(tmp_path: Path, full_sets: bool) -> None:
    document = random_document(np.random.default_rng(3), 6, sequences=1)
    path = tmp_path / "cases.json"
    path.write_text(json.dumps(document))
    args = ["conformance", "reachsets", str(path)] + (["--full-sets"] if full_sets else [])
    result = CliRunner().invoke(app, args)
    assert result.exit_code == 0, result.output
    records = _lines(result.stdout)
    assert records == list(evaluate_document(document, str(path), full_sets=full_sets))
    assert [r["id"] for r in records] == [f"r{k}" for k in range(6)] + [f"q0#{k}" for k in range(4)]
    assert all(("sets" in r) is full_sets for r in records)


def test_random_file_round_trip(tmp_path: Path) -> None:
    path = tmp_path / "random.json"
    runner = CliRunner()
    made = runner.invoke(
        app,
        [
            *("conformance", "reachsets-cases", str(path), "--random", "4", "--seed", "9"),
            *("--method", "bound", "--sequences", "1"),
        ],
    )
    assert made.exit_code == 0, made.output
    document = json.loads(path.read_text())
    assert document == json.loads(
        json.dumps(random_document(np.random.default_rng(9), 4, methods=["bound"], sequences=1))
    )
    result = runner.invoke(app, ["conformance", "reachsets", str(path)])
    assert result.exit_code == 0, result.output
    assert {r["method"] for r in _lines(result.stdout)} == {"bound"}


def _run(args: list[str], capsys: pytest.CaptureFixture[str]) -> tuple[int, str]:
    with pytest.raises(SystemExit) as info:
        main(args)
    return int(info.value.code or 0), capsys.readouterr().err


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("{not json", "case '<document>', json="),
        ('{"cases": 3}', "case '<document>', cases=3: expected a list of cases"),
        ('{"cases": [], "defaults": {"method": "zz"}}', "case '<defaults>', method='zz'"),
        (
            '{"cases": [], "defaults": {"params": {"turn_radius_m": -1}}}',
            "params.turn_radius_m=-1.0: reach-set parameter turn_radius_m",
        ),
    ],
)
def test_bad_documents_are_one_line_errors(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], text: str, expected: str
) -> None:
    path = tmp_path / "bad.json"
    path.write_text(text)
    code, err = _run(["conformance", "reachsets", str(path)], capsys)
    assert code == 2
    assert err.count("\n") == 1
    assert err.startswith(f"error: reach-set cases {path}, ")
    assert expected in err
    assert "Traceback" not in err


def test_bad_case_is_a_record_and_the_run_goes_on(tmp_path: Path) -> None:
    document = random_document(np.random.default_rng(1), 2)
    document["cases"][0]["objects"][0]["speed"] = "fast"
    path = tmp_path / "cases.json"
    path.write_text(json.dumps(document))
    result = CliRunner().invoke(app, ["conformance", "reachsets", str(path)])
    assert result.exit_code == 0, result.output
    bad, good = _lines(result.stdout)
    assert bad == {
        "id": "r0",
        "ok": False,
        "error": f"reach-set cases {path}, case 'r0', objects.0.speed='fast': expected a number",
    }
    assert good["ok"] is True


def test_maker_needs_exactly_one_source(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = str(tmp_path / "x.json")
    code, err = _run(["conformance", "reachsets-cases", out], capsys)
    assert (code, err.count("\n")) == (2, 1)
    assert "exactly one of --random N and --log FILE" in err
    code, err = _run(
        ["conformance", "reachsets-cases", out, "--random", "2", "--method", "x"], capsys
    )
    assert code == 2
    assert "--method 'x'" in err
