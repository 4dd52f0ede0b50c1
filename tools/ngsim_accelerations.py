"""Longitudinal accelerations of every vehicle of NGSIM scenarios (naturalistic data).

The check behind the ``highway`` (US-101) and ``urban`` (Lankershim, Peachtree: ``--glob
'USA_[LP]*.xml'``) RSS profiles' acceleration values (docs/rss.md, "Parameter
profiles"): each vehicle's speed series (the ego's and every object's, per CommonRoad
scenario) is turned into accelerations the way proper-response compliance measured them —
the least-squares slope of the speed over the last 0.5 s (it now fits positions)
(:func:`workbench.engines.rss.compliance.slope`) — and the percentiles over all vehicles are
printed::

    .venv/bin/python tools/ngsim_accelerations.py [--dir ../shared/external/commonroad_ngsim] \
        [--glob G]
"""

from __future__ import annotations

import argparse
import sys
from collections import defaultdict
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from loaders import open_drive  # noqa: E402
from workbench.engines.rss.compliance import WINDOW_NS, slope  # noqa: E402

PERCENTILES = (0.1, 1.0, 5.0, 50.0, 95.0, 99.0, 99.9)


def accelerations(path: Path) -> tuple[int, np.ndarray]:
    """Vehicles of one scenario and their 0.5 s least-squares accelerations [m/s²]."""
    series: dict[str, list[tuple[int, float]]] = defaultdict(list)
    drive = open_drive(path)
    try:
        for frame in drive.frames():
            a = frame.actors
            speeds = np.hypot(a.vx_mps, a.vy_mps)
            for oid, v in zip(a.ids.tolist(), speeds.tolist(), strict=True):
                series[oid].append((frame.t_ns, v))
            series["ego"].append((frame.t_ns, frame.ego.speed_mps))
    finally:
        drive.close()
    out: list[float] = []
    for samples in series.values():
        t = np.array([s[0] for s in samples], dtype=np.int64)
        v = np.array([s[1] for s in samples], dtype=np.float64)
        for k in range(len(t)):
            window = (t >= t[k] - WINDOW_NS) & (t <= t[k])
            value = slope(t[window], v[window])
            if value is not None and t[k] - t[0] >= WINDOW_NS:
                out.append(value)
    return len(series), np.array(out)


def main() -> int:
    """Print the percentiles per scenario and over all of them."""
    ap = argparse.ArgumentParser()
    ap.add_argument("--dir", type=Path, default=ROOT.parent / "shared/external/commonroad_ngsim")
    ap.add_argument(
        "--glob",
        default="USA_US101*.xml",
        help="scenario files in --dir (urban: 'USA_Lanker*.xml', 'USA_Peach*.xml')",
    )
    args = ap.parse_args()
    paths = sorted(args.dir.glob(args.glob))
    if not paths:
        print(f"no {args.glob} in {args.dir}", file=sys.stderr)
        return 2
    head = " ".join(f"p{p:g}".rjust(7) for p in PERCENTILES)
    print(f"{'scenario':26} {'vehicles':>8} {'samples':>8} {head}")
    every = []
    vehicles = 0
    for path in paths:
        n, acc = accelerations(path)
        vehicles += n
        every.append(acc)
        row = " ".join(f"{v:7.2f}" for v in np.percentile(acc, PERCENTILES))
        print(f"{path.stem:26} {n:8d} {len(acc):8d} {row}")
    acc = np.concatenate(every)
    row = " ".join(f"{v:7.2f}" for v in np.percentile(acc, PERCENTILES))
    print(f"{'all':26} {vehicles:8d} {len(acc):8d} {row}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
