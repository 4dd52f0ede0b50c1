"""Generate every sample drive into a directory (``workbench samples OUTDIR``)."""

from __future__ import annotations

from typing import TYPE_CHECKING

from workbench.samples.foxglove_writer import write_foxglove_mcap
from workbench.samples.lanelet2_writer import to_osm_bytes
from workbench.samples.racing import write_racing_sample
from workbench.samples.ros_writers import write_bag, write_mcap, write_rosbag2
from workbench.samples.scenarios_roads import hard_braking_lead, highway_cut_in, wrong_way_oncoming
from workbench.samples.scenarios_urban import parking_lot, pedestrian_crossing, urban_intersection

if TYPE_CHECKING:
    from collections.abc import Callable, Iterable
    from pathlib import Path

    from workbench.samples.scenario import Scenario

__all__ = ["FOXGLOVE_SCENARIO", "SCENARIOS", "generate", "generate_scenario"]

#: Scenario builders by name, in generation order.
SCENARIOS: dict[str, Callable[[], Scenario]] = {
    "highway_cut_in": highway_cut_in,
    "hard_braking_lead": hard_braking_lead,
    "wrong_way_oncoming": wrong_way_oncoming,
    "urban_intersection": urban_intersection,
    "pedestrian_crossing": pedestrian_crossing,
    "parking_lot": parking_lot,
}
#: The scenario that also gets a Foxglove protobuf/JSON MCAP variant.
FOXGLOVE_SCENARIO = "pedestrian_crossing"


def generate_scenario(sc: Scenario, outdir: Path) -> list[Path]:
    """Write the map and every log variant of one scenario; return the written paths."""
    outdir.mkdir(parents=True, exist_ok=True)
    osm = to_osm_bytes(sc.lane_map)
    paths = [
        outdir / f"{sc.name}.osm",
        outdir / f"{sc.name}.mcap",
        outdir / f"{sc.name}.bag",
        outdir / f"{sc.name}_rosbag2",
    ]
    paths[0].write_bytes(osm)
    write_mcap(sc, paths[1], osm)
    write_bag(sc, paths[2])
    write_rosbag2(sc, paths[3], osm)
    if sc.name == FOXGLOVE_SCENARIO:
        paths.append(outdir / f"{sc.name}_foxglove.mcap")
        write_foxglove_mcap(sc, paths[-1], osm)
    return paths


def generate(outdir: Path, names: Iterable[str] | None = None) -> list[Path]:
    """Generate the named scenarios (default: all, plus the racing sample) into ``outdir``.

    Raises:
        KeyError: for an unknown scenario name.
    """
    written: list[Path] = []
    for name in names if names is not None else SCENARIOS:
        written += generate_scenario(SCENARIOS[name](), outdir)
    if names is None:
        written += write_racing_sample(outdir)
    return written
