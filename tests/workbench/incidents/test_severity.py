"""Severity of an incident's own object: physical facts, the one order, finite JSON."""

from __future__ import annotations

import json
import math
from dataclasses import dataclass
from types import SimpleNamespace
from typing import TYPE_CHECKING

import numpy as np
import pytest

from rss.structured.states import LongitudinalResponse
from workbench.engines.base import VerdictSummary
from workbench.engines.registry import engine, names
from workbench.engines.rss.causes import RssCause
from workbench.incidents import Incident, IncidentDetector, Severity, severity_key
from workbench.incidents.kinematics import Box, box_gap_m, motion, time_to_contact_s
from workbench.incidents.order import TTC_REF_S, criticality

if TYPE_CHECKING:
    from pathlib import Path

    from workbench.incidents.model import Fact

T0 = 1_000_000_000
DT = 100_000_000

#: The registered engines' specs (what a chunk of the driver carries).
SPECS = tuple(engine(name) for name in names())


def test_a_stopped_car_ahead_gives_gap_closing_ttc_and_deceleration():
    ego = Box(0.0, 0.0, 0.0, 4.0, 2.0, vx_mps=10.0)
    lead = Box(20.0, 0.0, 0.0, 4.0, 2.0)
    found = motion(ego, lead)
    assert found.gap_m == pytest.approx(16.0)
    assert found.closing_speed_mps == pytest.approx(10.0)
    assert found.ttc_s == pytest.approx(1.6)
    assert found.decel_mps2 == pytest.approx(10.0**2 / (2 * 16.0))


def test_laterally_clear_parallel_or_opening_means_no_collision_course():
    ego = Box(0.0, 0.0, 0.0, 4.0, 2.0, vx_mps=10.0)
    beside = Box(-5.0, 3.5, 0.0, 4.0, 2.0, vx_mps=16.8)  # passing in the next lane
    assert time_to_contact_s(ego, beside) is None
    assert motion(ego, beside).decel_mps2 is None
    behind = Box(-30.0, 0.0, 0.0, 4.0, 2.0, vx_mps=8.0)  # falling back
    found = motion(ego, behind)
    assert found.ttc_s is None
    assert found.closing_speed_mps == pytest.approx(-2.0)


def test_overlapping_boxes_touch_now():
    ego = Box(0.0, 0.0, 0.3, 4.0, 2.0)
    other = Box(3.0, 0.5, -0.2, 4.0, 2.0)
    assert box_gap_m(ego, other) == 0.0
    assert time_to_contact_s(ego, other) == 0.0
    assert criticality(0.0, None) > criticality(TTC_REF_S / 2, None) > 1.0


def test_a_converging_car_beside_has_a_lateral_time_to_collision():
    ego = Box(0.0, 0.0, 0.0, 4.0, 2.0, vx_mps=10.0)
    heading = -0.1
    beside = Box(0.0, 3.5, heading, 4.0, 2.0, 10 * math.cos(heading), 10 * math.sin(heading))
    ttc = time_to_contact_s(ego, beside)
    assert ttc is not None
    # about 1.5 m of lateral gap closed at about 1 m/s (the corner reaches first)
    assert 0.5 < ttc < 1.6


BRAKE = RssCause(lon=LongitudinalResponse.BrakeMin)


@dataclass(frozen=True)
class _Frame:
    """What the detector reads of a frame: one verdict per object and the states."""

    is_safe: bool
    culprits: tuple[str, ...]
    cause: object
    margin: float
    margins: dict[str, float]

    def object_margin(self, object_id: str) -> float:
        return self.margins[object_id]


def _scene(ego_x: float, objects: dict[str, tuple[float, float, float]]) -> SimpleNamespace:
    ids = list(objects)

    def column(k: int) -> np.ndarray:
        return np.array([objects[i][k] for i in ids], dtype=float)

    n = len(ids)
    actors = SimpleNamespace(
        ids=np.array(ids),
        x_m=column(0),
        y_m=column(1),
        vx_mps=column(2),
        vy_mps=np.zeros(n),
        yaw_rad=np.zeros(n),
        length_m=np.full(n, 4.0),
        width_m=np.full(n, 1.8),
        valid=np.ones(n, dtype=bool),
    )
    ego = SimpleNamespace(
        x_m=ego_x, y_m=0.0, yaw_rad=0.0, speed_mps=10.0, length_m=4.0, width_m=1.8
    )
    return SimpleNamespace(ego=ego, actors=actors)


def test_each_incident_gets_its_own_objects_margin_and_facts():
    # US101-5_1 in small: a follower "476" far behind with a larger ratio and "462" close
    # ahead with the frame's smallest one; 476 used to carry 462's ratio and rank first
    detector = IncidentDetector("h", engines=SPECS)
    for k in range(5):
        verdict = _Frame(False, ("462", "476"), BRAKE, 0.37, {"462": 0.37, "476": 0.41})
        x = 10.0 * k * 0.1
        scene = _scene(x, {"462": (x + 8.0, 0.0, 8.0), "476": (x - 14.0, 0.0, 10.0)})
        detector.add(k, T0 + k * DT, {"rss": verdict}, scene)  # type: ignore[arg-type]
    found = {i.objects[0]: i for i in detector.incidents()}
    assert found["476"].severity.worst_margin == 0.41
    assert found["462"].severity.worst_margin == 0.37
    assert found["462"].severity.facts["gap_min_m"] == pytest.approx(4.0)
    assert found["462"].severity.facts["path_ttc_min_s"] == pytest.approx(2.0)
    assert found["476"].severity.facts["gap_min_m"] == pytest.approx(10.0)
    assert found["476"].severity.facts["path_ttc_min_s"] is None  # same speed: not closing
    assert [i.objects[0] for i in detector.incidents()] == ["462", "476"]


def _incident(
    name: str, facts: dict[str, Fact], *, suspect: tuple[str, ...] = (), margin: float = 0.0
) -> Incident:
    return Incident(
        id=f"rss-000000-{name}",
        engine="rss",
        objects=(name,),
        cause="RSS BrakeMin",
        start_frame=0,
        end_frame=3,
        start_ns=T0,
        end_ns=T0 + 3 * DT,
        severity=Severity(margin, 4, 0.3, facts),
        data_suspect=suspect,
    )


def test_the_order_clean_first_then_criticality_gap_shortfall():
    critical = _incident("critical", {"criticality": 2.0, "gap_min_m": 5.0})
    close = _incident("close", {"criticality": 0.0, "gap_min_m": 0.5})
    far = _incident("far", {"criticality": 0.0, "gap_min_m": 9.0, "shortfall_max_mps2": 4.0})
    far_calm = _incident("far_calm", {"criticality": 0.0, "gap_min_m": 9.0})
    suspect = _incident("suspect", {"criticality": 9.0, "gap_min_m": 0.1}, suspect=("teleport",))
    shuffled = [suspect, far_calm, far, close, critical]
    ordered = sorted(shuffled, key=severity_key)
    assert [i.objects[0] for i in ordered] == ["critical", "close", "far", "far_calm", "suspect"]


def test_records_hold_no_non_finite_number():
    never = _incident("never", {}, margin=math.inf)
    record = never.record()
    text = json.dumps(record, allow_nan=False)  # raises on inf/nan
    assert record["severity"]["worst_margin"] is None
    assert json.loads(text)["severity"]["severity_rank"]["gap_min_m"] is None


def test_summaries_without_states_have_no_physical_facts():
    detector = IncidentDetector("h", engines=SPECS)
    summary = VerdictSummary(False, ("a",), "unstructured: brake", 0.2)
    detector.add(0, T0, {"unstructured": summary})
    (only,) = detector.incidents()
    assert "gap_min_m" not in only.severity.facts
    assert only.severity.worst_margin == 0.2


@pytest.mark.parametrize("scenario", ["USA_US101-5_1_T-1.xml"])
def test_on_us101_5_1_each_incident_has_its_own_margin(external_dir: Path, scenario: str):
    from workbench.incidents import IncidentRequest, find_incidents  # noqa: PLC0415

    path = external_dir / "commonroad_ngsim" / scenario
    report = find_incidents(IncidentRequest(log=path, engines=("rss",)))
    found = {(i.objects[0], i.start_frame): i for i in report.incidents}
    follower, close = found["476", 0], found["462", 16]
    # each margin is the own object's worst ratio, no longer the frame's smallest
    for incident in (follower, close):
        assert incident.severity.worst_margin == pytest.approx(
            incident.severity.facts["distance_ratio_min"], abs=1e-6
        )
    assert follower.severity.worst_margin > close.severity.worst_margin
    assert report.incidents.index(close) < report.incidents.index(follower)
    json.dumps([i.record() for i in report.incidents], allow_nan=False)


def test_a_reach_set_incident_keeps_its_own_objects_collision_offset():
    from reachsets.engine import Collision  # noqa: PLC0415
    from workbench.engines.reachsets.verdict import ReachVerdict  # noqa: PLC0415

    hits = (Collision("a", 0.8, 8), Collision("b", 1.6, 16), Collision("a", 1.2, 12))
    result = SimpleNamespace(collisions=hits)
    verdict = ReachVerdict(False, ("a", "b"), "reach-set collision", 0.8, result)  # type: ignore[arg-type]
    detector = IncidentDetector("h", engines=SPECS)
    detector.add(0, T0, {"reachsets": verdict})
    margins = {i.objects[0]: i.severity.worst_margin for i in detector.incidents()}
    assert margins == {"a": 0.8, "b": 1.6}
