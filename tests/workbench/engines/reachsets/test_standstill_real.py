"""``road.standstill`` on real traffic: USA_Lanker-1_4, the ego waiting at a red light."""

from __future__ import annotations

from typing import TYPE_CHECKING

from workbench.engines.registry import engine_options
from workbench.incidents import IncidentRequest, find_incidents

if TYPE_CHECKING:
    from pathlib import Path


def test_lankershim_standing_junction_has_no_reach_set_incident(external_dir: Path) -> None:
    """Standing cars across the junction "reach" the standing ego only with the reference rules."""
    log = external_dir / "commonroad_ngsim" / "USA_Lanker-1_4_T-1.xml"
    reference = find_incidents(
        IncidentRequest(log, ("reachsets",), options=engine_options({"reach_rules": "reference"}))
    )
    # oncoming cars standing 36-53 m ahead (1769, 1776, 1781, ...) given 13 m/s^2 from rest
    assert len(reference.incidents) >= 6
    review = find_incidents(IncidentRequest(log, ("reachsets",)))
    assert review.settings["reach_rules"] == "public_road"
    assert review.incidents == ()
