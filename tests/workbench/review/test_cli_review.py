import json
from pathlib import Path

from tests.workbench.cli_runs import run_workbench as _run
from workbench.review import loop

LOG = Path(__file__).resolve().parents[3] / "sample_logs" / "hard_braking_lead.mcap"
ARGS = ["--engines", "rss,reachsets", "--reach-method", "simple"]


def test_review_walks_the_filtered_incidents_worst_first(tmp_path, monkeypatch, capsys):
    seen = []
    monkeypatch.setattr(loop, "run_review", lambda session, viewer=None: seen.append(session))
    out = tmp_path / "i.json"
    assert _run(["incidents", str(LOG), *ARGS, "--engine", "reachsets", "--out", str(out)]) == 0
    store = tmp_path / "l.sqlite"
    assert _run(["review", str(LOG), *ARGS, "--engine", "reachsets", "--store", str(store)]) == 0
    (session,) = seen
    assert [i.id for i in session.incidents] == [r["id"] for r in json.loads(out.read_text())]
    assert {i.engine for i in session.incidents} == {"reachsets"}
    assert session.reviewer
    assert "0 of" in capsys.readouterr().out


def test_viewer_options_exclude_each_other(tmp_path, capsys):
    args = ["review", str(LOG), *ARGS, "--spawn", "--serve", "--store", str(tmp_path / "l.sqlite")]
    assert _run(args) == 2
    assert "mutually exclusive" in capsys.readouterr().err
