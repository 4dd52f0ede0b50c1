"""CommonRoad uncertain (interval) states: read at the interval's centre, noted in DriveInfo."""

from __future__ import annotations

from typing import TYPE_CHECKING

import pytest

from loaders.commonroad import open_commonroad
from tests.loaders.test_commonroad import obstacle, straight, write

if TYPE_CHECKING:
    from pathlib import Path

#: State 2 of the ego: a rectangle position, an orientation and a time interval.
RECTANGLE = (
    "<state><position><rectangle><length>2.0</length><width>1.0</width><orientation>0.0"
    "</orientation><center><x>2.0</x><y>0.5</y></center></rectangle></position>"
    "<orientation><intervalStart>-0.1</intervalStart><intervalEnd>0.3</intervalEnd></orientation>"
    "<time><intervalStart>1</intervalStart><intervalEnd>3</intervalEnd></time>"
    "<velocity><exact>10.0</exact></velocity></state>"
)
#: State 3: a polygon position (vertex mean (3.0, 0.0)) and a velocity interval.
POLYGON = (
    "<state><position><polygon><point><x>2.0</x><y>-1.0</y></point><point><x>4.0</x>"
    "<y>-1.0</y></point><point><x>4.0</x><y>1.0</y></point><point><x>2.0</x><y>1.0</y>"
    "</point></polygon></position><orientation><exact>0.0</exact></orientation>"
    "<time><exact>3</exact></time>"
    "<velocity><intervalStart>8.0</intervalStart><intervalEnd>12.0</intervalEnd></velocity></state>"
)


@pytest.mark.parametrize("version", ["2018b", "2020a"])
def test_interval_states_use_the_centre_and_are_noted(tmp_path: Path, version: str) -> None:
    ego = obstacle(version, 10, "car", straight(range(5)))
    exact_2 = ego[ego.index("<state>") :].split("</state>")
    # replace the exact states of steps 2 and 3 by uncertain ones
    states = [s + "</state>" for s in exact_2[:-1]]
    ego = ego.replace(states[1], RECTANGLE).replace(states[2], POLYGON)
    other = obstacle(version, 20, "car", straight(range(5), y=3.5))
    drive = open_commonroad(write(tmp_path, version, ego + other), ego_id="10")
    frames = list(drive.frames())
    assert [f.t_ns for f in frames] == [k * 100_000_000 for k in range(5)]
    assert (frames[2].ego.x_m, frames[2].ego.y_m) == pytest.approx((2.0, 0.5))
    assert frames[2].ego.yaw_rad == pytest.approx(0.1)
    assert (frames[3].ego.x_m, frames[3].ego.y_m) == pytest.approx((3.0, 0.0))
    assert frames[3].ego.speed_mps == pytest.approx(10.0)
    note = drive.info.notes["uncertain_states"]
    assert note == (
        "2 states of 1 obstacles (orientation, position, time, velocity): interval centres used"
    )


def test_exact_scenario_has_no_note(tmp_path: Path) -> None:
    body = obstacle("2020a", 10, "car", straight(range(3)))
    drive = open_commonroad(write(tmp_path, "2020a", body), ego_id="10")
    assert "uncertain_states" not in drive.info.notes
    assert len(list(drive.frames())) == 3
