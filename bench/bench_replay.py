"""Replay throughput (frames/s) and peak memory of logging a drive into an ``.rrd`` file.

Workload: a 10 Hz drive with 30 actors and a 16-point plan per frame on a three-lane road.

- ``log``: layout + ``send_columns`` + file write, frames taken from a pre-built pool so that
  frame generation is not measured.
- ``synthetic load + log``: the same with frames built on the fly (``ActorTable`` per frame),
  the closest stand-in for a loader until real logs are measured.
- ``load_and_log(path)``: a real log opened with ``loaders.open_drive``; run on every log in
  ``sample_logs/`` once that entry point exists.
- memory: peak RSS of a fresh process logging N frames, for growing N (flat = streaming).
"""

from __future__ import annotations

import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from bench.child import run_json
from tests.workbench.fakes import DT_NS, T0_NS, FakeDrive, synthetic_frame
from workbench.viewer.replay import replay_drive

if TYPE_CHECKING:
    from collections.abc import Iterator

    from loaders.records import Frame

N_ACTORS = 30
POOL = 200
TARGET_FPS = 500


@dataclass
class PooledDrive(FakeDrive):
    """A ``FakeDrive`` that cycles a pre-built pool of frames (no per-frame construction)."""

    def frames(self, start_ns: int | None = None, end_ns: int | None = None) -> Iterator[Frame]:
        """Yield ``n_frames`` frames re-stamped from the pool; the window is ignored."""
        del start_ns, end_ns
        pool = [synthetic_frame(i, self.n_actors) for i in range(min(POOL, self.n_frames))]
        for i in range(self.n_frames):
            f = pool[i % len(pool)]
            yield type(f)(index=i, t_ns=T0_NS + i * DT_NS, ego=f.ego, actors=f.actors, plan=f.plan)


def _throughput(drive: FakeDrive, out: Path) -> tuple[float, float]:
    t0 = time.perf_counter()
    summary = replay_drive(drive, out=out)
    elapsed = time.perf_counter() - t0
    return summary.frames / elapsed, out.stat().st_size / 2**20


def load_and_log(path: Path, out: Path) -> tuple[int, float]:
    """Open a real log with ``loaders.open_drive`` and replay it; ``(frames, frames/s)``."""
    from loaders import open_drive  # type: ignore[attr-defined,unused-ignore]  # noqa: PLC0415

    drive = open_drive(path)
    try:
        t0 = time.perf_counter()
        summary = replay_drive(drive, out=out)
        return summary.frames, summary.frames / (time.perf_counter() - t0)
    finally:
        drive.close()


_CHILD = """
import json, sys
from pathlib import Path
from bench.bench_replay import PooledDrive
from bench.child import peak_rss_mib
from workbench.viewer.replay import replay_drive
n, out = int(sys.argv[1]), Path(sys.argv[2])
def rss_mib():
    return int(Path("/proc/self/statm").read_text().split()[1]) * 4096 / 2**20
marks = []
def progress(done):
    marks.append(rss_mib())
replay_drive(PooledDrive(n_frames=n, n_actors=30), out=out, progress=progress)
peak = peak_rss_mib()
print(json.dumps({"peak_mib": peak, "rss_first_mib": marks[0], "rss_last_mib": marks[-1]}))
"""


def _memory(n_frames: int, out: Path) -> dict[str, float]:
    result: dict[str, float] = run_json(_CHILD, str(n_frames), str(out))
    return result


def _sample_logs() -> list[Path]:
    from workbench.demo import find_sample_logs  # noqa: PLC0415

    samples = Path(__file__).resolve().parent.parent / "sample_logs"
    return find_sample_logs(samples) if samples.is_dir() else []


def _real_logs_section(tmp: Path) -> list[str]:
    try:
        from loaders import open_drive  # type: ignore[attr-defined,unused-ignore]  # noqa: F401, PLC0415
    except ImportError:
        return ["", "Real logs: `loaders.open_drive` not available yet; not measured."]
    lines = ["", "| sample log | frames | load + log frames/s |", "|---|---:|---:|"]
    for log in _sample_logs():
        frames, fps = load_and_log(log, tmp / f"{log.stem}.rrd")
        lines.append(f"| `{log.name}` | {frames} | {fps:,.0f} |")
    return lines


def run(quick: bool) -> str:  # noqa: FBT001 - the harness calls run(quick=...)
    """Measure and return the Markdown section."""
    n = 2_000 if quick else 10_000
    sizes = (2_000, 5_000) if quick else (2_000, 20_000)
    with tempfile.TemporaryDirectory() as tmp_name:
        tmp = Path(tmp_name)
        _throughput(PooledDrive(n_frames=200, n_actors=N_ACTORS), tmp / "warm.rrd")
        log_fps, log_mib = _throughput(PooledDrive(n_frames=n, n_actors=N_ACTORS), tmp / "a.rrd")
        gen_fps, _ = _throughput(FakeDrive(n_frames=n, n_actors=N_ACTORS), tmp / "b.rrd")
        mem = {k: _memory(k, tmp / f"m{k}.rrd") for k in sizes}
        real = _real_logs_section(tmp)
    lines = [
        "## Replay into Rerun",
        "",
        (
            f"10 Hz drive, {N_ACTORS} actors and a 16-point plan per frame, written to an "
            f"`.rrd` in chunks of 500 frames; {n:,} frames; one core. "
            f"Target: {TARGET_FPS} frames/s."
        ),
        "",
        "| stage | frames/s | output |",
        "|---|---:|---|",
        f"| log (layout + send_columns + file) | {log_fps:,.0f} | {log_mib:.1f} MiB |",
        f"| synthetic load + log | {gen_fps:,.0f} | |",
        "",
        "| frames logged | peak RSS | RSS after first chunk | RSS at the end |",
        "|---:|---:|---:|---:|",
    ]
    for k, m in mem.items():
        lines.append(
            f"| {k:,} | {m['peak_mib']:.0f} MiB | {m['rss_first_mib']:.0f} MiB | "
            f"{m['rss_last_mib']:.0f} MiB |"
        )
    return "\n".join(lines + real) + "\n"


if __name__ == "__main__":
    print(run(quick="--quick" in sys.argv))
