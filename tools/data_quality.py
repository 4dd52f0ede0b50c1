"""Data-quality findings per drive, and what the checks cost per frame against the RSS path.

Runs :mod:`workbench.quality` on the NGSIM CommonRoad scenarios, the real logs and the
samples (docs/data_quality.md) and prints one markdown row per drive: objects, findings per
kind, the check's time per frame and, with ``--cost``, the RSS engine's time per frame on
the same frames (the drive's ``auto`` profile)::

    .venv/bin/python tools/data_quality.py [--external ../shared/external] [--cost]
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from collections.abc import Callable

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from loaders import open_drive  # noqa: E402
from workbench.drives import load_rss_params  # noqa: E402
from workbench.engines.rss.runner import RssRunner  # noqa: E402
from workbench.quality import Kind, check_tracks, tracks_from_frames  # noqa: E402
from workbench.quality.summary import kind_counts  # noqa: E402

REPEATS = 3


def drives(external: Path) -> list[Path]:
    """The drives checked: NGSIM scenarios, real logs, sample MCAPs."""
    found = sorted((external / "commonroad_ngsim").glob("*.xml"))
    found += [
        external / "real_logs" / "test2.bag",
        external / "real_logs" / "bag_ego_trajectory.db3",
    ]
    found += sorted((ROOT / "sample_logs").glob("*.mcap"))
    return [p for p in found if p.exists()]


def _best_ms(fn: Callable[[], object], frames: int) -> float:
    best = float("inf")
    for _ in range(REPEATS):
        start = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - start)
    return 1e3 * best / max(frames, 1)


def row(path: Path, *, cost: bool) -> str:
    """One markdown row for a drive."""
    drive = open_drive(path)
    try:
        frames = list(drive.frames())
        lane_map = drive.lane_map
    finally:
        drive.close()
    tracks = tracks_from_frames(frames)
    findings = check_tracks(tracks)
    counts = kind_counts(findings)
    check_ms = _best_ms(lambda: check_tracks(tracks_from_frames(frames)), len(frames))
    cells = [path.stem, str(len(frames)), str(len(tracks.ids))]
    cells += [str(counts[str(k)]) for k in Kind]
    cells.append(f"{check_ms:.3f}")
    if cost:
        runner = RssRunner(lane_map, load_rss_params(None, None, lane_map))
        start = time.perf_counter()
        for k in range(0, len(frames), 32):
            runner.step_many(frames[k : k + 32])
        rss_ms = 1e3 * (time.perf_counter() - start) / max(len(frames), 1)
        others = len(tracks.ids) > 1  # RSS has nothing to evaluate without objects
        cells += [f"{rss_ms:.2f}", f"{100 * check_ms / rss_ms:.1f} %" if others else "-"]
    return "| " + " | ".join(cells) + " |"


def main() -> None:
    """Print the table."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--external", type=Path, default=ROOT / ".." / "shared" / "external")
    parser.add_argument("--cost", action="store_true", help="time the RSS engine too")
    args = parser.parse_args()
    head = ["drive", "frames", "objects", *(str(k) for k in Kind), "checks ms/frame"]
    if args.cost:
        head += ["RSS ms/frame", "checks / RSS"]
    print("| " + " | ".join(head) + " |")
    print("|" + "---|" * len(head))
    for path in drives(args.external):
        print(row(path, cost=args.cost), flush=True)


if __name__ == "__main__":
    main()
