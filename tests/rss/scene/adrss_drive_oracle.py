"""ad-rss map integration 5.0 over whole drives: drives (JSON, stdin) -> frames (JSON, stdout).

Runs under the oracle interpreter of ``adrss_map_oracle.py`` (same vehicles, dynamics and
scene settings: unit-test dynamics, no speed-limit mode, no ego route, no green lights).
Usage: ``python adrss_drive_oracle.py MAP.xodr < drives.json > answers.json``; a drive is
``town01_drives``' JSON (its optional ``speed_limit_mode``, an ``RssRestrictSpeedLimitMode``
name, is passed to ``appendConstellations``; default none). Each drive gets one
``ad.rss.core.RssCheck`` that sees its frames in order with time indices 1, 2, ... (the
memory of ad-rss across frames); each frame's world model is built with one
``appendConstellations`` per object. The answer per frame:
``{"ok", "dangerous": [object ids], "situations": [{"id", "type", "lon_d", "lat_d",
"dangerous"}]}``.
"""

import json
import os
import sys
from typing import Any

import ad_rss_map_integration as ad  # type: ignore[import-not-found]
from adrss_map_oracle import (  # type: ignore[import-not-found]
    EGO_ID,
    _dynamics,
    _object_data,
    _value,
    append_structured,
    init_map,
)


def _frame(
    check: Any, time_index: int, frame: dict[str, Any], speed_limit_mode: str
) -> dict[str, Any]:
    creation = ad.rss.map.RssWorldModelCreation(time_index, _dynamics(1.0))
    e = frame["ego"]
    ego = _object_data(EGO_ID, ad.rss.world.ObjectType.EgoVehicle, e, e["length"], e["width"], 1.0)
    ok = True
    for o in frame["objects"]:
        other = _object_data(
            o["id"], ad.rss.world.ObjectType.OtherVehicle, o, o["length"], o["width"], 2.0
        )
        ok &= append_structured(creation, ego, other, speed_limit_mode)
    answer: dict[str, Any] = {"ok": ok, "dangerous": [], "situations": []}
    snapshot = ad.rss.core.RssSituationSnapshot()
    states = ad.rss.state.RssStateSnapshot()
    response = ad.rss.state.ProperResponse()
    if not check.calculateProperResponse(creation.getWorldModel(), snapshot, states, response):
        answer["ok"] = False
        return answer
    danger = {
        int(s.constellation_id): bool(ad.rss.state.isDangerous(s))
        for s in states.individual_responses
    }
    for c in snapshot.constellations:
        rp = c.relative_position
        answer["situations"].append(
            {
                "id": int(c.object_id),
                "type": str(c.constellation_type).split("::")[-1].split(".")[-1],
                "lon_d": _value(rp.longitudinal_distance),
                "lat_d": _value(rp.lateral_distance),
                "dangerous": danger.get(int(c.constellation_id), False),
            }
        )
    answer["dangerous"] = sorted(int(x) for x in response.dangerous_objects)
    return answer


def _drive(drive: dict[str, Any]) -> list[dict[str, Any]]:
    check = ad.rss.core.RssCheck()
    mode = drive.get("speed_limit_mode", "None")
    return [_frame(check, k + 1, frame, mode) for k, frame in enumerate(drive["frames"])]


def main() -> None:
    content = open(sys.argv[1]).read()  # noqa: PTH123, SIM115
    drives = json.load(sys.stdin)
    real_stdout = os.dup(1)
    os.dup2(os.open(os.devnull, os.O_WRONLY), 1)
    try:
        init_map(content)
        result = [_drive(d) for d in drives]
    finally:
        os.dup2(real_stdout, 1)
    sys.stdout.write(json.dumps(result) + "\n")


if __name__ == "__main__":
    main()
