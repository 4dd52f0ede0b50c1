"""The standstill rule on real traffic: USA_Lanker-1_4, where the ego and its neighbours stand."""

from __future__ import annotations

from typing import TYPE_CHECKING

from workbench.engines.registry import engine_options
from workbench.incidents import IncidentRequest, find_incidents

if TYPE_CHECKING:
    from pathlib import Path


def test_lankershim_queue_standing_throughout_has_no_rss_incident(external_dir: Path) -> None:
    """Every vehicle stands (a red light); the reference flags the queue, ``auto`` does not."""
    log = external_dir / "commonroad_ngsim" / "USA_Lanker-1_4_T-1.xml"
    reference = find_incidents(
        IncidentRequest(log, ("rss",), options=engine_options({"rss_profile": "adrss-5.0"}))
    )
    # ad-rss' assumption: standing cars start at 3.5 m/s^2 during rho (object 1680 is 0.23 m
    # behind the ego, 1687 6.5 m behind, 1690 beside it)
    assert {o for i in reference.incidents for o in i.objects} >= {"1680", "1687"}
    review = find_incidents(IncidentRequest(log, ("rss",)))
    assert review.settings["rss_profile"] == "auto"
    assert review.incidents == ()
