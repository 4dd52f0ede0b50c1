"""sha256 digests of map matching and scene creation on fixed inputs (Town01).

A guard for speed work on ``rss.scene.matching``: the digests must not move when only the
speed changes. Three input sets, each digested on its own::

    bench      the frames of ``bench/bench_scene.py`` (full run: 10 drives x 40 frames):
               ``match_boxes`` per frame, ``match_frames`` per pipeline chunk, and
               ``create_scene`` on the batched matches
    crosscheck the seeded pairs of ``tests/rss/scene/test_crosscheck_adrss_map.py``
               (``match_boxes`` and ``create_scene`` per pair)
    random     seeded boxes of random size and heading near random lanes (``match_boxes``)

Run (pure Python, so that the sources are what runs)::

    RSS_WORKBENCH_PURE_PYTHON=1 .venv/bin/python tools/matching_digest.py [--quick]
"""

from __future__ import annotations

import argparse
import hashlib
import sys
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from bench.bench_scene import TOWN01, _drives  # noqa: E402
from loaders.maps.opendrive import read_opendrive  # noqa: E402
from rss.params import SceneSettings  # noqa: E402
from rss.scene import PreparedGraph, SceneMemo, create_scene, match_boxes, prepare  # noqa: E402
from rss.scene.chunked import match_frames  # noqa: E402
from rss.scene.create import scene_boxes  # noqa: E402
from rss.scene.match_records import BoxArrays  # noqa: E402
from tests.rss.scene.test_crosscheck_adrss_map import (  # noqa: E402
    N_PAIRS,
    SETTINGS,
    pair_inputs,
    placements,
)
from workbench.driver import CHUNK_FRAMES  # noqa: E402
from workbench.engines.rss.adapter import lane_graph_from_map  # noqa: E402

if TYPE_CHECKING:
    from rss.scene import Matches
    from rss.scene.inputs import Scene

_N_RANDOM = 4000


def _add_matches(h: hashlib._Hash, m: Matches) -> None:
    for name in (
        "box",
        "lane",
        "lon_min",
        "lon_max",
        "lat_min",
        "lat_max",
        "anchor",
        "anchor_s",
        "anchor_heading_rad",
        "heading_rad",
    ):
        h.update(np.ascontiguousarray(getattr(m, name)).tobytes())
    h.update(repr(m.starts).encode())


def _add_scene(h: hashlib._Hash, scene: Scene) -> None:
    text = repr(scene)
    if "..." in text:  # a truncated numpy repr would hide differences
        raise SystemExit("scene repr is truncated")
    h.update(text.encode())


def bench_digest(prep: PreparedGraph, quick: bool) -> str:  # noqa: FBT001
    """Digest of the bench frames (see module docstring)."""
    h = hashlib.sha256()
    settings = SceneSettings()
    memo = SceneMemo()
    for drive in _drives(prep, *((3, 10) if quick else (10, 40))):
        for ego, objects in drive:
            _add_matches(h, match_boxes(prep, scene_boxes(ego, objects)))
        for lo in range(0, len(drive), CHUNK_FRAMES):
            chunk = drive[lo : lo + CHUNK_FRAMES]
            matches = match_frames(prep, [scene_boxes(e, o) for e, o in chunk])
            for (ego, objects), m in zip(chunk, matches, strict=True):
                _add_matches(h, m)
                _add_scene(h, create_scene(prep, ego, objects, settings, matches=m, memo=memo))
    return h.hexdigest()


def crosscheck_digest(prep: PreparedGraph, n: int) -> str:
    """Digest of the cross-check pairs (see module docstring)."""
    h = hashlib.sha256()
    for pair in placements(prep, seed=1, n=n):
        ego, objects = pair_inputs(pair)
        _add_matches(h, match_boxes(prep, scene_boxes(ego, objects)))
        _add_scene(h, create_scene(prep, ego, objects, SETTINGS))
    return h.hexdigest()


def random_boxes(prep: PreparedGraph, n: int, seed: int = 3) -> BoxArrays:
    """``n`` boxes near random lane vertices, random heading and size (seeded)."""
    rng = np.random.default_rng(seed)
    lanes = rng.integers(0, len(prep.graph), n)
    centres = np.array(
        [prep.graph.centre_m[k][rng.integers(len(prep.graph.centre_m[k]))] for k in lanes]
    )
    centres += rng.normal(0.0, 2.0, (n, 2))
    return BoxArrays(
        x_m=centres[:, 0],
        y_m=centres[:, 1],
        yaw_rad=rng.uniform(-np.pi, np.pi, n),
        length_m=rng.uniform(0.3, 12.0, n),
        width_m=rng.uniform(0.3, 3.0, n),
    )


def random_digest(prep: PreparedGraph, n: int) -> str:
    """Digest of :func:`random_boxes`, matched 50 at a time."""
    h = hashlib.sha256()
    boxes = random_boxes(prep, n)
    for lo in range(0, n, 50):
        part = BoxArrays(
            *(
                getattr(boxes, f)[lo : lo + 50]
                for f in ("x_m", "y_m", "yaw_rad", "length_m", "width_m")
            )
        )
        _add_matches(h, match_boxes(prep, part))
    return h.hexdigest()


def main() -> int:
    """Print the three digests."""
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args()
    prep = prepare(lane_graph_from_map(read_opendrive(TOWN01)))
    print("bench     ", bench_digest(prep, args.quick))
    print("crosscheck", crosscheck_digest(prep, 100 if args.quick else N_PAIRS))
    print("random    ", random_digest(prep, 500 if args.quick else _N_RANDOM))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
