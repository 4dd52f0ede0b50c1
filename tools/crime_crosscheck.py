r"""Independent criticality cross-check of the NGSIM scenarios with commonroad-crime (CriMe).

For each CommonRoad scenario, with the ego our loader picks by default (the longest-lived
vehicle), CriMe 0.4.5 computes TTC and the required deceleration for every other vehicle and
time step within 150 m (rotated scenario, rebuilt lane index, reference path from the ego's
trajectory, accelerations 0, our in-path gate: tests/workbench/triage/crime_side.py), and a
plain numpy recompute does the same. Real conflicts (TTC <= 1.5 s or required deceleration >=
3.4 m/s² while closing in path, flagged by both) are written per drive to
``out/crime/<scenario>.json`` with the agreement of the two; an existing file is reused unless
``--force``. Needs the side venv of ``make oracle-crime``::

    PROTOCOL_BUFFERS_PYTHON_IMPLEMENTATION=python .venv-oracle-crime/bin/python \
        tools/crime_crosscheck.py ../shared/external/commonroad_ngsim/*.xml [--near-path]

``--near-path`` computes CriMe only where the recompute finds the other vehicle ahead within
the in-path gate plus 1 m (what the acceptance test does; same conflicts, a fraction of the
time).
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from tests.workbench.triage.crime_side import drive_verdict  # noqa: E402

#: Where the per-drive verdicts are cached (not committed).
OUT_DIR = ROOT / "out" / "crime"


def cached(xml: Path, out_dir: Path = OUT_DIR) -> Path:
    """The cache file of one scenario's verdict."""
    return out_dir / f"{xml.stem}.json"


def main() -> int:
    """Compute (or reuse) each scenario's verdict and print a one-line summary per drive."""
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("scenarios", nargs="+", type=Path)
    parser.add_argument("--out-dir", type=Path, default=OUT_DIR)
    parser.add_argument("--near-path", action="store_true", help="CriMe near the path only")
    parser.add_argument("--force", action="store_true", help="recompute cached drives")
    args = parser.parse_args()
    args.out_dir.mkdir(parents=True, exist_ok=True)
    started = time.perf_counter()
    for xml in sorted(args.scenarios):
        path = cached(xml, args.out_dir)
        if path.exists() and not args.force:
            verdict = json.loads(path.read_text())
        else:
            verdict = drive_verdict(xml, full=not args.near_path)
            path.write_text(json.dumps(verdict, indent=1, allow_nan=False) + "\n")
        agreement = verdict["agreement"]
        print(
            f"{xml.stem}: ego {verdict['ego']}, {len(verdict['conflicts'])} conflict(s) "
            f"{[(c['object'], c['frames']) for c in verdict['conflicts']]}, "
            f"CriMe only {[(c['object'], c['frames']) for c in verdict['crime_only']]}, "
            f"agree {agreement['agree']:.4f} on {agreement['compared']} pair-steps, "
            f"errors {verdict['crime_errors']}, CriMe {verdict['seconds']['crime']:.1f} s"
        )
    print(f"total {time.perf_counter() - started:.1f} s", file=sys.stderr)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
