"""Per-pair disagreements between our scene creation and ad-rss map integration (Town01).

Diagnostic companion of ``tests/rss/scene/test_crosscheck_adrss_map.py`` (same seeded
pairs, same comparison). The oracle's answers are cached in ``out/`` per (seed, n), so
iterating on our side takes seconds::

    .venv/bin/python tools/scene_crosscheck.py [--n 500] [--seed 1] [--show 20]
        [--oracle .venv-oracle-adrss-map/bin/python] [--refresh] [--pairs 3,17]

(the cache is renewed by itself when the pairs change, e.g. after a map-reader change).

Prints, for each mode, the summary rates, then the disagreeing pairs grouped by class
(``ours types -> theirs types``), with the pair index, distances and verdicts. The modes:
``default`` (ad-rss' two documented defects not reproduced; the pairs where they are in
play counted apart) and ``compat`` (``[scene] reproduce_adrss_5_0_defects``: raw
agreement); ``--mode`` picks one (``--explain`` shows our internals in that mode).
"""

from __future__ import annotations

import argparse
import functools
import json
import logging
import sys
from collections import defaultdict
from pathlib import Path
from typing import TYPE_CHECKING, Any

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))


from loaders.maps.opendrive import read_opendrive  # noqa: E402
from rss.scene import PreparedGraph, create_scene, prepare  # noqa: E402
from tests.rss.scene.oracle_processes import ask_in_parallel  # noqa: E402
from tests.rss.scene.test_crosscheck_adrss_map import (  # noqa: E402
    COMPAT_SETTINGS,
    ORACLE,
    SETTINGS,
    admap_lane_id,
    compare,
    ours,
    pair_inputs,
    placements,
    turn_defect,
)
from workbench.engines.rss.adapter import lane_graph_from_map  # noqa: E402

if TYPE_CHECKING:
    from rss.params import SceneSettings

TOWN = (ROOT / ".." / "shared" / "external" / "maps" / "Town01.xodr").resolve()


def oracle_answers(
    pairs: list[dict[str, Any]], python: str, cache: Path, *, refresh: bool
) -> list[dict[str, Any]]:
    """The oracle's answers, from ``cache`` unless missing, made for other pairs, or ``refresh``.

    The pairs follow our lane centre lines, so a change of the map reader moves them: the
    cache keeps the pairs it answers and is refreshed when they differ.
    """
    if cache.exists() and not refresh:
        cached = json.loads(cache.read_text())
        if isinstance(cached, dict) and cached.get("pairs") == pairs:
            answers: list[dict[str, Any]] = cached["answers"]
            return answers
    half = len(pairs) // 2
    chunks = [pairs[:half], pairs[half:]]
    answers = []
    for _, out, err in ask_in_parallel(python, ORACLE, TOWN, chunks, None):
        if not out.strip():
            raise SystemExit(err[-2000:])
        answers += json.loads(out.strip().splitlines()[-1])
    cache.parent.mkdir(exist_ok=True)
    cache.write_text(json.dumps({"pairs": pairs, "answers": answers}))
    return answers


def explain(prep: PreparedGraph, pair: dict[str, Any], settings: SceneSettings) -> None:
    """Print our side's internals for one pair (lane ids in ad-map's numbering)."""
    ego, objects = pair_inputs(pair)
    lid = functools.partial(admap_lane_id, prep)
    logging.basicConfig(format="   %(message)s")
    logging.getLogger("rss.scene").setLevel(logging.DEBUG)
    scene = create_scene(prep, ego, objects, settings)
    logging.getLogger("rss.scene").setLevel(logging.WARNING)
    for c in scene.constellations:
        print("   ", c.constellation_type.name)
        for name, road in (("ego road", c.ego_road), ("obj road", c.intersecting_road)):
            if road:
                segs = [
                    (
                        f"b{seg.min_length_before_intersecting_area_m:.2f}"
                        f" a{seg.min_length_after_intersecting_area_m:.2f}:"
                        if seg.segment_type.name == "Intersection"
                        else ""
                    )
                    + ",".join(
                        f"{lid(ln.lane_id % len(prep.graph))}({ln.length_min_m:.2f}/"
                        f"{ln.length_max_m:.2f})"
                        for ln in seg.lanes
                    )
                    for seg in road
                ]
                print(f"      {name}: {' > '.join(segs)}")
        for name, obj in (("ego", c.ego), ("obj", c.other)):
            regs = [
                f"{lid(r.lane_id % len(prep.graph))} lon[{r.lon_min:.3f},{r.lon_max:.3f}] "
                f"lat[{r.lat_min:.2f},{r.lat_max:.2f}]"
                for r in obj.regions
            ]
            sp = obj.speed
            print(
                f"      {name}: {'; '.join(regs)} v_lon[{sp.lon_min_mps:.2f},{sp.lon_max_mps:.2f}]"
                f" v_lat[{sp.lat_min_mps:.2f},{sp.lat_max_mps:.2f}]"
            )


def _fmt(side: dict[str, Any]) -> str:
    parts = [
        f"{s['type'][:14]}({s['lon_d']:.2f},{s['lat_d']:.2f}){'!' if d else ''}"
        f"[{s.get('ego_v_lon', 0):.1f},{s.get('ego_v_lat', 0):.1f}|"
        f"{s.get('other_v_lon', 0):.1f},{s.get('other_v_lat', 0):.1f}]"
        for s, d in zip(side["situations"], side["dangerous"] or [False] * 99, strict=False)
    ]
    return " ".join(parts) or "-"


def _classes(
    mine: dict[int, dict[str, Any]],
    theirs: list[dict[str, Any]],
    picked: list[int],
    defects: dict[int, bool] | None,
) -> tuple[list[tuple[str, list[int]]], list[tuple[float, int]]]:
    """Disagreement classes ``(name, pair indices)`` and ``(distance error, pair)`` rows.

    ``defects``: the pairs where ad-map's turn-direction defect is in play (default mode),
    listed apart among the verdict disagreements; ``None`` in compat mode.
    """
    classes: dict[str, list[int]] = defaultdict(list)
    verdict_only: list[int] = []
    turned: list[int] = []
    dist: list[tuple[float, int]] = []
    for k in picked:
        a, b = mine[k], theirs[k]
        ta = sorted({s["type"] for s in a["situations"]})
        tb = sorted({s["type"] for s in b["situations"]} - {"NotRelevant"})
        if ta != tb:
            classes[f"{'+'.join(ta) or '-'} -> {'+'.join(tb) or '-'}"].append(k)
        elif any(a["dangerous"]) != any(b["dangerous"]):
            verdict_only.append(k)
            if defects is not None and defects[k]:
                turned.append(k)
        if len(a["situations"]) == len(b["situations"]) == 1 and ta == tb:
            err = abs(a["situations"][0]["lon_d"] - b["situations"][0]["lon_d"])
            err += abs(a["situations"][0]["lat_d"] - b["situations"][0]["lat_d"])
            dist.append((err, k))
    rows = sorted(classes.items(), key=lambda kv: -len(kv[1]))
    rows.append(("same types, verdict differs", verdict_only))
    if defects is not None:
        rows.append(("... of which ad-map's turn-direction defect is in play", turned))
    return rows, dist


#: The two modes: name -> scene settings, and whether ad-rss' defects are counted apart.
MODES: dict[str, tuple[SceneSettings, bool]] = {
    "default": (SETTINGS, True),
    "compat": (COMPAT_SETTINGS, False),
}


def report(
    prep: PreparedGraph,
    pairs: list[dict[str, Any]],
    theirs: list[dict[str, Any]],
    picked: list[int],
    *,
    mode: str,
    args: argparse.Namespace,
) -> None:
    """Print one mode's summary (all pairs only), disagreement classes and extras."""
    settings, apart = MODES[mode]
    print(f"\n######## {mode} mode")
    mine = {k: ours(prep, pairs[k], settings) for k in picked}
    defects = {k: turn_defect(prep, pairs[k], theirs[k]) for k in picked} if apart else None
    if not args.pairs:
        flags = [defects[k] if defects is not None else False for k in picked]
        print(compare([mine[k] for k in picked], theirs, flags))
    rows, dist = _classes(mine, theirs, picked, defects)
    for name, ks in rows:
        print(f"\n== {name}: {len(ks)}  {ks}")
        for k in ks[: args.show]:
            print(f"  {k:4d} ours:   {_fmt(mine[k])}")
            print(f"       theirs: {_fmt(theirs[k])}   pair={json.dumps(pairs[k])}")
    if args.explain:
        for k in picked:
            print(f"\n===== pair {k}\n  ours:   {_fmt(mine[k])}\n  theirs: {_fmt(theirs[k])}")
            explain(prep, pairs[k], settings)
    if args.dist:
        print("\n== largest distance errors (lon+lat)")
        for err, k in sorted(dist, reverse=True)[: args.show]:
            print(f"  {k:4d} err={err:.3f} ours: {_fmt(mine[k])}  theirs: {_fmt(theirs[k])}")


def main() -> int:
    """Run the comparison and print the disagreement classes of each mode."""
    ap = argparse.ArgumentParser()
    ap.add_argument("--n", type=int, default=500)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--show", type=int, default=8)
    ap.add_argument("--oracle", default=str(ROOT / ".venv-oracle-adrss-map" / "bin" / "python"))
    ap.add_argument("--refresh", action="store_true")
    ap.add_argument("--pairs", default="")
    ap.add_argument("--mode", choices=[*MODES, "both"], default="both")
    ap.add_argument("--dist", action="store_true", help="list distance disagreements too")
    ap.add_argument("--dump", action="store_true", help="print [[k, pair], ...] of --pairs")
    ap.add_argument("--explain", action="store_true", help="our internals for --pairs")
    args = ap.parse_args()
    prep = prepare(lane_graph_from_map(read_opendrive(TOWN)))
    pairs = placements(prep, seed=args.seed, n=args.n)
    if args.dump:
        print(json.dumps([[int(k), pairs[int(k)]] for k in args.pairs.split(",")]))
        return 0
    cache = ROOT / "out" / f"adrss_map_oracle_s{args.seed}_n{args.n}.json"
    theirs = oracle_answers(pairs, args.oracle, cache, refresh=args.refresh)
    picked = [int(v) for v in args.pairs.split(",") if v] or list(range(len(pairs)))
    for mode in MODES if args.mode == "both" else [args.mode]:
        report(prep, pairs, theirs, picked, mode=mode, args=args)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
