"""Acceptance of issue 27 on the 11 NGSIM scenarios, with the commands' defaults.

What ``workbench incidents FILE`` lists by default (events or incidents, read from its JSON
output: ``listing.py``) is held against facts computed independently of our engines:

(a) every real conflict of the independent measure (commonroad-crime's TTC and required
    deceleration, confirmed by a plain recompute: ``crime_side.drive_verdict``) is in the top
    three of its drive: an entry among the first three has the conflict's object and a time
    span within ``listing.SPAN_TOLERANCE_S`` of the conflict's;
(b) no entry in a drive's top five is benign throughout (at every step one of: both parties
    stand, the gap is over 15 m and opening, laterally clear by 1.5 m and not converging;
    ``benign.py``, from the scenario's states);
(c) no incident anywhere (every incident of every entry) in which both parties stand
    throughout.

(a) needs commonroad-crime, which lives in the side venv of ``make oracle-crime``: it skips
in the project venv and fails there when missing. The module is marked ``acceptance`` and
``make pytest`` deselects it; ``make acceptance`` runs it whole in the side venv.
"""

from __future__ import annotations

import functools
import os
from typing import TYPE_CHECKING, Any

import pytest

from loaders.commonroad_scenario import load_scenario
from tests.conftest import EXTERNAL_DIR
from tests.workbench.triage import crime_side
from tests.workbench.triage.benign import pair_facts
from tests.workbench.triage.conflicts import default_ego
from tests.workbench.triage.listing import Entry, default_listing

if TYPE_CHECKING:
    from pathlib import Path

pytestmark = [pytest.mark.external, pytest.mark.acceptance]

SCENARIO_DIR = EXTERNAL_DIR / "commonroad_ngsim"
SCENARIOS = sorted(p.name for p in SCENARIO_DIR.glob("*.xml")) or ["(none found)"]
IN_CRIME_ENV = os.environ.get("WORKBENCH_ORACLE_ENV") == "crime"


def _scenario(external_dir: Path, name: str) -> Path:
    path = external_dir / "commonroad_ngsim" / name
    if not path.is_file():
        pytest.fail(f"{path} is missing")
    return path


@functools.cache
def _verdict(xml: Path) -> dict[str, Any]:
    return crime_side.drive_verdict(xml)


@pytest.mark.oracle
@pytest.mark.parametrize("name", SCENARIOS)
def test_real_conflicts_in_top_three(external_dir: Path, name: str) -> None:
    if not crime_side.available():
        if IN_CRIME_ENV:
            pytest.fail("commonroad-crime is missing from the side venv (make oracle-crime)")
        pytest.skip("commonroad-crime lives in the side venv: make acceptance")
    xml = _scenario(external_dir, name)
    verdict = _verdict(xml)
    dt_ns = load_scenario(xml).dt_ns
    listing = default_listing(xml)
    missed = [
        f"object {c['object']} frames {c['frames']} (TTC {c['min_ttc_s']} s, "
        f"decel {c['max_required_decel_mps2']} m/s², gap {c['min_gap_m']} m); listed at "
        + (", ".join(e.describe() for e in listing if e.covers(c, dt_ns)) or "nowhere")
        for c in verdict["conflicts"]
        if not any(e.covers(c, dt_ns) for e in listing[:3])
    ]
    assert not missed, f"{name}: real conflicts not in the top three: {missed}"


def _benign_reasons(xml: Path, entry: Entry) -> list[str] | None:
    """Per object, why the pair is benign at every step of the span; ``None`` if it is not."""
    scenario = load_scenario(xml)
    ego = default_ego(scenario)
    tracks = {t.id: t for t in scenario.tracks}
    if not entry.objects:
        return None
    span = (entry.start_ns // scenario.dt_ns, entry.end_ns // scenario.dt_ns, scenario.dt_ns / 1e9)
    reasons = []
    for obj in entry.objects:
        facts = pair_facts(ego, tracks[obj], span)
        if not facts or not all(f.benign for f in facts):
            return None
        closest = min(facts, key=lambda f: f.gap_m)
        reasons.append(
            f"{obj}: "
            + ", ".join(sorted({f.reason() for f in facts}))
            + f" (min gap {closest.gap_m:.1f} m, lateral {closest.lateral_clear_m:.1f} m there)"
        )
    return reasons


@pytest.mark.parametrize("name", SCENARIOS)
def test_no_benign_entry_in_top_five(external_dir: Path, name: str) -> None:
    xml = _scenario(external_dir, name)
    benign = [
        f"{entry.describe()}: {reasons}"
        for entry in default_listing(xml)[:5]
        if (reasons := _benign_reasons(xml, entry)) is not None
    ]
    assert not benign, f"{name}: benign throughout, yet in the top five: {benign}"


@pytest.mark.parametrize("name", SCENARIOS)
def test_no_incident_where_both_stand_throughout(external_dir: Path, name: str) -> None:
    xml = _scenario(external_dir, name)
    scenario = load_scenario(xml)
    ego = default_ego(scenario)
    tracks = {t.id: t for t in scenario.tracks}
    standing = []
    for entry in default_listing(xml):
        for incident in entry.incidents:
            first = int(incident["start_ns"]) // scenario.dt_ns
            last = int(incident["end_ns"]) // scenario.dt_ns
            for obj in incident.get("objects", ()):
                facts = pair_facts(ego, tracks[str(obj)], (first, last, scenario.dt_ns / 1e9))
                if facts and all(f.both_stand for f in facts):
                    standing.append(f"{incident.get('id')} object {obj} steps {first}-{last}")
    assert not standing, f"{name}: incidents in which both parties stand throughout: {standing}"
