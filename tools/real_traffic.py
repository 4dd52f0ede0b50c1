r"""Write docs/real_traffic.md: what each engine flags on the real NGSIM scenarios, per profile.

For every CommonRoad scenario given, every engine runs over the whole drive through
``workbench.incidents.find_incidents`` with the commands' defaults (RSS once per parameter
profile: ``adrss-5.0``, ``carla``, ``highway`` and ``auto``); the table gives the unsafe
frames, the incidents, for RSS how many of them the ego and the object had to respond in, and
the top-ranked incident's facts. Run::

    PYTHONPATH=$PWD .venv/bin/python tools/real_traffic.py \
        ../shared/external/commonroad_ngsim/*.xml --out docs/real_traffic_table.md
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from workbench.incidents import IncidentReport, IncidentRequest, find_incidents  # noqa: E402

#: ``(engine, RSS profile)`` runs per scenario.
RUNS = (
    ("rss", "adrss-5.0"),
    ("rss", "carla"),
    ("rss", "highway"),
    ("rss", "auto"),
    ("unstructured", "auto"),
    ("reachsets", "auto"),
)


def _unsafe_frames(report: IncidentReport) -> int:
    frames: set[int] = set()
    for incident in report.incidents:
        frames.update(range(incident.start_frame, incident.end_frame + 1))
    return len(frames)


def _top(report: IncidentReport) -> str:
    if not report.incidents:
        return "-"
    top = report.incidents[0]
    facts = top.severity.facts
    parts = [f"`{top.id}` object {','.join(top.objects) or '-'}", top.cause]
    parts.append(f"{top.duration_s:.1f} s, margin {top.severity.worst_margin:.2f}")
    if facts.get("responsible"):
        parts.append(f"{facts['responsible']} must act")
    if facts.get("shortfall_max_mps2"):
        parts.append(
            f"shortfall {facts['shortfall_max_mps2']:.1f} m/s² ({facts['shortfall_party']})"
        )
    return "; ".join(parts)


def _row(xml: Path, engine: str, profile: str) -> str:
    started = time.perf_counter()
    report = find_incidents(IncidentRequest(xml, engines=(engine,), rss_profile=profile))
    elapsed = time.perf_counter() - started
    frames = len(report.frame_times)
    unsafe = _unsafe_frames(report)
    ego = sum(i.severity.facts.get("responsible") in {"ego", "both"} for i in report.incidents)
    obj = sum(i.severity.facts.get("responsible") in {"object", "both"} for i in report.incidents)
    who = f"{ego} / {obj}" if engine == "rss" else "-"
    shown = profile if engine == "rss" else "-"
    share = 100 * unsafe / frames if frames else 0.0
    print(f"{xml.stem} {engine} {profile}: {unsafe}/{frames} in {elapsed:.1f} s", file=sys.stderr)
    return (
        f"| {xml.stem.removeprefix('USA_').removesuffix('_T-1')} | {engine} | {shown} | "
        f"{unsafe}/{frames} ({share:.0f} %) | {len(report.incidents)} | {who} | {_top(report)} |"
    )


def main() -> int:
    """Run every scenario and write the table."""
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("scenarios", nargs="+", type=Path)
    parser.add_argument("--out", type=Path, required=True)
    args = parser.parse_args()
    rows = [
        (
            "| scenario | engine | RSS profile | unsafe frames | incidents "
            "| RSS: ego / object must act | top-ranked incident |"
        ),
        "|---|---|---|---:|---:|---:|---|",
    ]
    for xml in sorted(args.scenarios):
        rows += [_row(xml, engine, profile) for engine, profile in RUNS]
    args.out.write_text("\n".join(rows) + "\n")
    print(f"wrote {args.out}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
