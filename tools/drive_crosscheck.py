"""Per-frame disagreements between our structured RSS and ad-rss map integration on drives.

Diagnostic companion of ``tests/rss/scene/test_crosscheck_drives.py`` (same seeded Town01
drives of ``tests/rss/scene/town01_drives.py``, same comparison). The oracle's answers are
cached in ``out/`` per (seed, n), so iterating on our side takes seconds::

    .venv/bin/python tools/drive_crosscheck.py [--n 20] [--seed 1] [--show 20]
        [--oracle .venv-oracle-adrss-map/bin/python] [--mode default|compat|both]
        [--frames 3:0,3:1] [--min-gap 6] [--town ../shared/external/maps/Town01.xodr]
        [--junction-routes]

``--junction-routes``: the drives with random routes through junction lanes and vehicles
on the ego's own lane route, checked with ad-rss' ``IncreasedSpeedLimit10``
(``town01_drives``' module docstring; cached apart).

Prints, per mode, the agreement line, then every disagreeing frame (``drive:frame``) with
both sides' constellations of the objects involved: type, longitudinal / lateral distance,
``!`` for dangerous.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from loaders.maps.opendrive import read_opendrive  # noqa: E402
from rss.params import RestrictSpeedLimitMode, SceneSettings  # noqa: E402
from rss.scene import SceneMemo, prepare  # noqa: E402
from tests.rss.scene.drive_crosscheck import (  # noqa: E402
    compare_drives,
    oracle_drives,
    our_drive,
)
from tests.rss.scene.town01_drives import drives as make_drives  # noqa: E402
from workbench.engines.rss.adapter import lane_graph_from_map  # noqa: E402

TOWN = (ROOT / ".." / "shared" / "external" / "maps" / "Town01.xodr").resolve()
MODES = {
    "default": SceneSettings(restrict_speed_limit_mode=RestrictSpeedLimitMode.NONE),
    "compat": SceneSettings(
        restrict_speed_limit_mode=RestrictSpeedLimitMode.NONE, reproduce_adrss_5_0_defects=True
    ),
}


def _fmt(answer: dict[str, Any], ids: set[int]) -> str:
    parts = [
        f"{s['id']}:{s['type'][:16]}({s['lon_d']:.2f},{s['lat_d']:.2f})"
        + ("!" if s["dangerous"] else "")
        for s in answer["situations"]
        if s["id"] in ids
    ]
    return " ".join(parts) or "-"


def main() -> int:
    """Run the comparison and print each mode's disagreeing frames."""
    ap = argparse.ArgumentParser()
    ap.add_argument("--n", type=int, default=20)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--show", type=int, default=60)
    ap.add_argument("--oracle", default=str(ROOT / ".venv-oracle-adrss-map" / "bin" / "python"))
    ap.add_argument("--mode", choices=[*MODES, "both"], default="both")
    ap.add_argument("--min-gap", type=float, default=6.0, help="objects' start gap (m)")
    ap.add_argument("--town", type=Path, default=TOWN, help="the Town01 OpenDRIVE map")
    ap.add_argument("--frames", default="", help="drive:frame,... to show whatever they say")
    ap.add_argument("--junction-routes", action="store_true", help="the junction-route drives")
    args = ap.parse_args()
    prep = prepare(lane_graph_from_map(read_opendrive(args.town)))
    drives = make_drives(
        prep, args.seed, args.n, args.min_gap, junction_routes=args.junction_routes
    )
    gap = "" if args.min_gap == 6.0 else f"_g{args.min_gap:g}"  # noqa: PLR2004 - the default
    gap += "_jr" if args.junction_routes else ""
    cache = ROOT / "out" / f"adrss_drive_oracle_s{args.seed}_n{args.n}{gap}.json"
    theirs = oracle_drives(drives, args.oracle, args.town, cache)
    for mode in MODES if args.mode == "both" else [args.mode]:
        memo = SceneMemo()
        mine = [our_drive(prep, d, MODES[mode], memo) for d in drives]
        stats = compare_drives(mine, theirs)
        print(f"\n######## {mode}: {stats.summary()}")
        picked = [(int(p.split(":")[0]), int(p.split(":")[1])) for p in args.frames.split(",") if p]
        rows: list[tuple[str, list[tuple[int, int]]]] = [
            ("missed", stats.missed),
            ("extra", stats.extra),
            ("picked", picked),
        ]
        for name, frames in rows:
            if frames:
                print(f"== {name}: {len(frames)}")
            for d, k in frames[: args.show]:
                a, b = mine[d][k], theirs[d][k]
                ids = {s["id"] for s in a["situations"] + b["situations"]}
                if name != "picked":
                    ids = set(a["dangerous"]) ^ set(b["dangerous"])
                print(f"  {d:3d}:{k:<3d} ours:   {_fmt(a, ids)}")
                print(f"          theirs: {_fmt(b, ids)}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
