"""Times ad-rss map integration 5.0 on scene-bench frames (runs in the oracle interpreter).

Run by ``bench/scene_reference.py`` as ``python -m bench.scene_reference_oracle MAP.xodr``
from the repository root under ``.venv-oracle-adrss-map`` (§8.4 work-around). Reads
``{"frames": [...]}`` as JSON on stdin (frame format: ``bench/scene_reference.py``) and
writes one JSON line on stdout: CPU time (``time.process_time``) per phase in ms per frame,
constellation counts per frame and the number of frames ad-rss rejected. Per frame:

* ``matching``: ``RssObjectData`` of the ego and every object, each with its
  ``getMapMatchedBoundingBox`` (0.1 m sampling);
* ``append``: ``appendConstellations`` of every object into one ``RssWorldModelCreation``;
* ``world_model``: ``getWorldModel``;
* ``extraction``, ``checking``, ``resolving``: the ad-rss core chain (``RssCheck``'s three
  steps), one instance each per scene so the memories carry from frame to frame.

Frame 0 is run once untimed beforehand (warm-up, own instances). The library logs to the
C-level stdout, so file descriptor 1 is redirected while it runs.
"""

import json
import os
import sys
import time
from collections import Counter
from pathlib import Path
from typing import Any

import ad_rss_map_integration as ad  # type: ignore[import-not-found]

from tests.rss.scene import adrss_map_oracle as oracle

PHASES = ("matching", "append", "world_model", "extraction", "checking", "resolving")


class _Core:
    """The ad-rss core chain of one scene (memories carried between its frames)."""

    def __init__(self) -> None:
        self.extraction = ad.rss.core.RssSituationExtraction()
        self.checking = ad.rss.core.RssSituationChecking()
        self.resolving = ad.rss.core.RssResponseResolving()


def _object_data(vehicle: dict[str, Any], object_type: Any) -> Any:
    return oracle._object_data(  # noqa: SLF001
        int(vehicle["id"]),
        object_type,
        vehicle,
        float(vehicle["length"]),
        float(vehicle["width"]),
        float(vehicle["response_time"]),
    )


def _kind(constellation: Any) -> str:
    return str(constellation.constellation_type).split("::")[-1]


def run_frame(frame: dict[str, Any], time_index: int, core: _Core) -> dict[str, Any]:
    """Run one frame through map matching, world creation and the core chain.

    Args:
        frame: one frame (``ego`` and ``objects``, see ``bench/scene_reference.py``).
        time_index: ad-rss time index (>= 1, increasing per ``core``).
        core: the scene's core chain.

    Returns:
        ``{"s": {phase: CPU s}, "constellations": int, "relevant": int,
        "situations": int, "types": [constellation type per constellation], "ok": bool}``.
    """
    clock = [time.process_time()]

    def lap() -> float:
        clock.append(time.process_time())
        return clock[-1] - clock[-2]

    vehicle = ad.rss.world.ObjectType
    ego = _object_data(frame["ego"], vehicle.EgoVehicle)
    others = [_object_data(o, vehicle.OtherVehicle) for o in frame["objects"]]
    s = {"matching": lap()}
    creation = ad.rss.map.RssWorldModelCreation(time_index, oracle._dynamics(1.0))  # noqa: SLF001
    appended = [oracle.append_structured(creation, ego, other) for other in others]
    ok = all(appended)
    s["append"] = lap()
    world = creation.getWorldModel()
    s["world_model"] = lap()
    situations = ad.rss.core.RssSituationSnapshot()
    ok &= bool(core.extraction.extractSituation(world, situations))
    s["extraction"] = lap()
    states = ad.rss.state.RssStateSnapshot()
    ok &= bool(core.checking.checkSituation(situations, states))
    s["checking"] = lap()
    ok &= bool(core.resolving.provideProperResponse(states, ad.rss.state.ProperResponse()))
    s["resolving"] = lap()
    kinds = [_kind(c) for c in world.constellations]
    return {
        "s": s,
        "constellations": len(kinds),
        "relevant": sum(k != "NotRelevant" for k in kinds),
        "situations": sum(_kind(c) != "NotRelevant" for c in situations.constellations),
        "types": kinds,
        "ok": ok,
    }


def time_frames(frames: list[dict[str, Any]]) -> dict[str, Any]:
    """Time every frame (after one untimed warm-up run of the first).

    Returns:
        ``{"frames": n, "ms_per_frame": {phase: ms}, "constellations_per_frame": float,
        "relevant_per_frame": float, "situations_per_frame": float,
        "types_per_frame": {type: float}, "failed_frames": int}``; ``relevant`` counts
        the world model's constellations other than ``NotRelevant``.
    """
    run_frame(frames[0], 1, _Core())
    total = dict.fromkeys(PHASES, 0.0)
    counts = {"constellations": 0, "relevant": 0, "situations": 0}
    types: Counter[str] = Counter()
    failed = 0
    core, scene = _Core(), frames[0].get("scene", 0)
    for k, frame in enumerate(frames):
        if frame.get("scene", 0) != scene:
            core, scene = _Core(), frame.get("scene", 0)
        out = run_frame(frame, k + 1, core)
        for phase, seconds in out["s"].items():
            total[phase] += seconds
        for key in counts:
            counts[key] += out[key]
        types.update(out["types"])
        failed += not out["ok"]
    n = len(frames)
    return {
        "frames": n,
        "ms_per_frame": {phase: total[phase] / n * 1e3 for phase in PHASES},
        **{f"{key}_per_frame": value / n for key, value in counts.items()},
        "types_per_frame": {kind: count / n for kind, count in sorted(types.items())},
        "failed_frames": failed,
    }


def main() -> None:
    """Read the map path (argv) and the frames (stdin); print the timings as one JSON line."""
    content = Path(sys.argv[1]).read_text()
    frames = json.load(sys.stdin)["frames"]
    real_stdout = os.dup(1)
    os.dup2(os.open(os.devnull, os.O_WRONLY), 1)
    try:
        oracle.init_map(content)
        result = time_frames(frames)
    finally:
        os.dup2(real_stdout, 1)
    sys.stdout.write(json.dumps(result) + "\n")


if __name__ == "__main__":
    main()
