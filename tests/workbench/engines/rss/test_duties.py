"""Responsibility and compliance in the viewer: duty lanes and allowed-vs-measured plots."""

from pathlib import Path

import numpy as np
import pytest
from rerun.chunk import RrdReader

from loaders.records import Frame
from rss.structured.responsibility import Responsible
from tests.workbench.engines.helpers import forward_fill, open_window, rrd_states, rss_window
from tests.workbench.fakes import bound
from workbench.engines.rss.duties import NO_DUTY, layout_duties
from workbench.engines.rss.runner import RssRunner
from workbench.engines.rss.sink import duty_path
from workbench.engines.rss.verdict import RssVerdict
from workbench.viewer.replay import replay_drive

SAMPLES = Path(__file__).resolve().parents[4] / "sample_logs"
#: docs/samples.md: the lead brakes hard from 5 s; the ego must respond.
LOG = SAMPLES / "hard_braking_lead.mcap"
WINDOW_S = (4.0, 8.0)
LEAD = "00000000000000000000000000000001"


@pytest.fixture(scope="module")
def braking() -> tuple[list[Frame], list[RssVerdict]]:
    return rss_window(LOG, WINDOW_S)


def test_duty_lanes_name_who_must_act_in_every_frame(braking):
    _, verdicts = braking
    cols = layout_duties(verdicts)
    assert LEAD in cols.duty_states
    assert "ego must act" in cols.duty_states[LEAD]
    for row, verdict in enumerate(verdicts):
        who = verdict.responsibility()
        for label, states in cols.duty_states.items():
            want = {
                Responsible.EGO: "ego must act",
                Responsible.OBJECT: "object must act",
                Responsible.BOTH: "both must act",
            }
            assert states[row] == want.get(who.get(label, Responsible.NONE), NO_DUTY)


def test_compliance_series_hold_each_obligation(braking):
    _, verdicts = braking
    cols = layout_duties(verdicts)
    allowed_rows, allowed = cols.compliance[f"{LEAD}/ego_allowed"]
    measured_rows, measured = cols.compliance[f"{LEAD}/ego_measured"]
    expected = [
        (row, duty)
        for row, verdict in enumerate(verdicts)
        for label, duty in verdict.obligations
        if label == LEAD and duty.party is Responsible.EGO
    ]
    assert expected
    want_allowed = [
        (r, d.required_max_mps2) for r, d in expected if d.required_max_mps2 is not None
    ]
    assert list(zip(allowed_rows.tolist(), allowed.tolist(), strict=True)) == want_allowed
    want_measured = [(r, d.measured_mps2) for r, d in expected if d.measured_mps2 is not None]
    assert list(zip(measured_rows.tolist(), measured.tolist(), strict=True)) == want_measured
    # the lead brakes at 7 m/s²: the ego's allowed acceleration is a braking limit
    assert (allowed < 0).any()


def test_replay_logs_duty_lanes_and_compliance_plots(tmp_path, braking):
    frames, verdicts = braking
    path = tmp_path / "duties.rrd"
    drive = open_window(LOG, WINDOW_S)
    replay_drive(drive, out=path, send_frames=7, engines=[bound(RssRunner(drive.lane_map))])
    drive.close()
    cols = layout_duties(verdicts)
    index = [f.index for f in frames]
    # duty lanes carry only changes, also across chunk boundaries (7 frames)
    for label, states in cols.duty_states.items():
        changes = rrd_states(path, "/" + duty_path(label))
        first = next(k for k, s in enumerate(states) if s != NO_DUTY)
        assert forward_fill(changes, index)[first:] == states[first:]
    store = RrdReader(path).store().stream().collect()
    for key, (rows, values) in cols.compliance.items():
        label, kind = key.rsplit("/", 1)
        entity = f"/plots/rss/compliance/{label}/{kind}"
        table = store.reader(index="frame", contents=entity).to_arrow_table().to_pydict()
        got = dict(zip(table["frame"], table[f"{entity}:Scalars:scalars"], strict=True))
        want = {index[r]: v for r, v in zip(rows.tolist(), values.tolist(), strict=True)}
        assert {f: float(np.asarray(v)[0]) for f, v in got.items() if v} == want
