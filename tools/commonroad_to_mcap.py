r"""Convert CommonRoad scenarios to ROS 2 MCAP logs and, optionally, check them with the CLI.

For each ``X.xml`` it writes ``OUT/X.mcap`` (``workbench.samples.drive_mcap``: the drive
``workbench evaluate X.xml`` sees, as ``nav_msgs/Odometry`` + ``derived_object_msgs/
ObjectArray`` + ``autoware_planning_msgs/Trajectory``) and ``OUT/X.ego-size`` (the ego's
size as ``L,W,H``, which ``Odometry`` does not carry). The map is the scenario itself:
``--map X.xml``.

``--check ENGINES`` then runs, per log::

    workbench evaluate OUT/X.mcap --map X.xml --ego-size $(cat OUT/X.ego-size) \
        --engines ENGINES --per-frame OUT/X.jsonl

and requires exit 0, no traceback, one JSON line per written frame and a record of every
engine in every line. Run::

    PYTHONPATH=$PWD .venv/bin/python tools/commonroad_to_mcap.py \
        ../shared/external/commonroad_ngsim/*.xml --out /tmp/ngsim \
        --check rss,unstructured,reachsets
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from loaders import open_drive  # noqa: E402
from workbench.samples.drive_mcap import ego_size_option, write_drive_mcap  # noqa: E402

#: The ``workbench`` console script, run by this interpreter from the checkout.
_CLI = "from workbench.cli.main import main; main()"


def convert(xml: Path, out: Path, ego_id: str | None) -> tuple[Path, Path, int]:
    """Write ``out/<stem>.mcap`` and ``out/<stem>.ego-size``; return them and the frames."""
    out.mkdir(parents=True, exist_ok=True)
    mcap, toml = out / f"{xml.stem}.mcap", out / f"{xml.stem}.ego-size"
    drive = open_drive(xml, ego_id=ego_id)
    try:
        frames = write_drive_mcap(drive, mcap, map_name=xml.name)
        first = next(iter(drive.frames()))
    finally:
        drive.close()
    toml.write_text(ego_size_option(first.ego))
    return mcap, toml, frames


def check(xml: Path, mcap: Path, toml: Path, frames: int, engines: str) -> str:
    """Evaluate the log with the CLI; return a one-line result (``FAIL ...`` on a problem)."""
    lines = mcap.with_suffix(".jsonl")
    cmd = [sys.executable, "-c", _CLI, "evaluate", str(mcap), "--map", str(xml)]
    cmd += ["--ego-size", toml.read_text(), "--engines", engines, "--per-frame", str(lines)]
    start = time.perf_counter()
    done = subprocess.run(cmd, capture_output=True, text=True, check=False, cwd=ROOT)  # noqa: S603
    seconds = time.perf_counter() - start
    names = engines.split(",")
    text = lines.read_text() if lines.is_file() else ""
    records = [json.loads(line) for line in text.splitlines()]
    missing = sum(1 for r in records for name in names if name not in r)
    unsafe = {name: sum(1 for r in records if not r[name]["is_safe"]) for name in names}
    problems = []
    if done.returncode != 0:
        problems.append(f"exit {done.returncode}: {done.stderr.strip()[-300:]}")
    if "Traceback" in done.stdout + done.stderr:
        problems.append("traceback")
    if len(records) != frames or missing:
        problems.append(f"{len(records)} lines for {frames} frames, {missing} records missing")
    verdict = "FAIL " + "; ".join(problems) if problems else "ok"
    counts = " ".join(f"{name} {n}" for name, n in unsafe.items())
    return f"{verdict}: {len(records)} frames, unsafe {counts}, {seconds:.1f} s"


def main() -> int:
    """Convert (and check) every scenario given; exit 1 when a check failed."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenarios", nargs="+", type=Path, help="CommonRoad .xml files")
    parser.add_argument("--out", type=Path, required=True, help="output directory")
    parser.add_argument("--ego-id", help="obstacle promoted to ego (default: longest-lived)")
    parser.add_argument("--check", metavar="ENGINES", help="evaluate each log with the CLI")
    args = parser.parse_args()
    failed = 0
    for xml in args.scenarios:
        mcap, toml, frames = convert(xml, args.out, args.ego_id)
        line = f"{xml.stem}: {frames} frames -> {mcap} ({mcap.stat().st_size} bytes)"
        if args.check:
            result = check(xml, mcap, toml, frames, args.check)
            failed += result.startswith("FAIL")
            line += f"; {result}"
        print(line)
    return 1 if failed else 0


if __name__ == "__main__":
    raise SystemExit(main())
