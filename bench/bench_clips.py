"""Clip export from a large log: one pass for all clips, flat memory.

A ROS 2 MCAP of about 1 GiB (``--quick``: 100 MiB) is generated: the ``highway_cut_in``
sample's messages repeated back to back, plus a 10 Hz camera topic of incompressible 160 KiB
``sensor_msgs/CompressedImage`` payloads (about 11 minutes of drive per GiB), the kind of
topic that makes real logs large. Twenty windows of up to 9 s (an incident of 3 s with 3 s of
margin on each side; at most half their spacing, so they do not overlap) spread over the drive
are cut with ``loaders.clips.write_clips``. The reference is one plain read of the same file
with the ``mcap`` reader, every payload touched. Each side runs in a fresh interpreter, so
its peak RSS is its own, and the page cache is emptied before each when we may (root).
"""

from __future__ import annotations

import json
import os
import tempfile
import time
from pathlib import Path
from typing import Any

from bench.child import peak_rss_mib, run_json
from loaders.timebase import ns_to_s

_MIB = 2**20
_CLIPS = 20
_WINDOW_S = 9
_IMAGE_BYTES = 160 * 2**10
_IMAGE_PERIOD_NS = 100_000_000
_DROP_CACHES = Path("/proc/sys/vm/drop_caches")
_CHILD = (
    "import json, sys; from bench import bench_clips as b; print(json.dumps(b.{}(*sys.argv[1:])))"
)


def generate(target: str, mib: str) -> dict[str, int]:
    """Write the large log to ``target`` (about ``mib`` MiB); return its size and time span."""
    import numpy as np  # noqa: PLC0415 - child-process entry point
    from mcap.reader import make_reader  # noqa: PLC0415
    from mcap.writer import CompressionType, Writer  # noqa: PLC0415

    from loaders.typestore import typestore  # noqa: PLC0415

    store = typestore(2)
    image_t = "sensor_msgs/msg/CompressedImage"
    header_t = store.types["std_msgs/msg/Header"]
    time_t = store.types["builtin_interfaces/msg/Time"]
    with Path("sample_logs/highway_cut_in.mcap").open("rb") as f:
        records = list(make_reader(f).iter_messages())
    t0 = records[0][2].log_time
    span = records[-1][2].log_time - t0 + 50_000_000
    rng = np.random.default_rng(0)
    written = laps = 0
    with Path(target).open("wb") as out:
        writer = Writer(out, compression=CompressionType.ZSTD)
        writer.start(profile="ros2", library="bench")
        ids: dict[int, int] = {}
        for schema, channel, _ in records:
            if channel.id not in ids and schema is not None:
                sid = writer.register_schema(schema.name, schema.encoding, schema.data)
                ids[channel.id] = writer.register_channel(
                    channel.topic, channel.message_encoding, sid, channel.metadata
                )
        text = store.generate_msgdef(image_t, ros_version=2)[0]
        camera_schema = writer.register_schema(image_t, "ros2msg", text.encode())
        camera = writer.register_channel("/camera/image/compressed", "cdr", camera_schema, {})
        while written < int(mib) * _MIB:
            base = laps * span
            for _, channel, message in records:
                t = message.log_time + base
                writer.add_message(ids[channel.id], t, message.data, t)
            for t in range(t0 + base, t0 + base + span, _IMAGE_PERIOD_NS):
                stamp = time_t(sec=t // 10**9, nanosec=t % 10**9)
                pixels = rng.integers(0, 256, _IMAGE_BYTES, dtype=np.uint8)
                image = store.types[image_t](header_t(stamp, "camera"), "jpeg", pixels)
                data = store.serialize_cdr(image, image_t)
                writer.add_message(camera, t, bytes(data), t)
                written += len(data)
            laps += 1
        writer.finish()  # type: ignore[no-untyped-call]
    return {"bytes": Path(target).stat().st_size, "start": t0, "end": t0 + laps * span}


def read_once(log: str) -> dict[str, float]:
    """Read every message of ``log`` with the ``mcap`` reader; wall time and peak RSS."""
    from mcap.reader import make_reader  # noqa: PLC0415 - child-process entry point

    started = time.perf_counter()
    count = size = 0
    with Path(log).open("rb") as f:
        for _, _, message in make_reader(f).iter_messages():
            count += 1
            size += len(message.data)
    return {"s": time.perf_counter() - started, "messages": count, "rss_mib": peak_rss_mib()}


def cut(log: str, out: str, start: str, end: str) -> dict[str, float]:
    """Cut the twenty windows of ``[start, end]`` from ``log`` into ``out``."""
    from loaders.clips import ClipRequest, write_clips  # noqa: PLC0415 - child entry point

    step = (int(end) - int(start)) // _CLIPS
    window = min(_WINDOW_S * 10**9, step // 2)
    first = int(start)
    requests = [
        ClipRequest(
            Path(out) / f"clip_{i:02d}.mcap",
            first + i * step,
            first + i * step + window,
            {"id": str(i)},
        )
        for i in range(_CLIPS)
    ]
    started = time.perf_counter()
    outcomes = write_clips(Path(log), requests, map_file=("map.osm", "text/xml", b"<osm/>", 0))
    elapsed = time.perf_counter() - started
    return {
        "s": elapsed,
        "written": sum(o.written for o in outcomes),
        "messages": sum(o.messages for o in outcomes),
        "window_s": ns_to_s(window),
        "out_mib": sum(p.stat().st_size for p in Path(out).iterdir()) / _MIB,
        "rss_mib": peak_rss_mib(),
    }


def export_cli(log: str, out: str) -> dict[str, float]:
    """``workbench export LOG --all`` (RSS incidents, MCAP clips only): wall time, peak RSS."""
    from workbench.cli.main import main  # noqa: PLC0415 - child-process entry point

    started = time.perf_counter()
    args = ["export", log, "--all", "--engines", "rss", "--no-rrd", "--no-thumbnails"]
    args += ["--map", "sample_logs/highway_cut_in.osm", "--out", out]
    args += ["--store", str(Path(out).parent / "labels.sqlite")]
    try:
        main(args)
    except SystemExit as done:
        if done.code not in (None, 0):
            raise
    elapsed = time.perf_counter() - started
    index = json.loads((Path(out) / "clips.json").read_text())
    return {"s": elapsed, "clips": len(index), "rss_mib": peak_rss_mib()}


def _drop_caches() -> bool:
    """Empty the page cache so both sides read from disk (needs root; else warm cache)."""
    try:
        os.sync()
        _DROP_CACHES.write_text("3\n")
    except OSError:
        return False
    return True


def run(*, quick: bool) -> str:
    """Generate the large log, cut the clips, and return the Markdown section."""
    with tempfile.TemporaryDirectory(prefix="bench_clips_") as tmp:
        log = Path(tmp) / "large.mcap"
        size = "100" if quick else "1024"
        made: dict[str, Any] = run_json(_CHILD.format("generate"), str(log), size)
        cold = _drop_caches()
        read = run_json(_CHILD.format("read_once"), str(log))
        out = Path(tmp) / "clips"
        out.mkdir()
        cold = _drop_caches() and cold
        clips = run_json(
            _CHILD.format("cut"), str(log), str(out), str(made["start"]), str(made["end"])
        )
        _drop_caches()
        whole = run_json(_CHILD.format("export_cli"), str(log), str(Path(tmp) / "export"))
    ratio = clips["s"] / read["s"]
    cache = "emptied before each step (both read from disk)" if cold else "warm (not root)"
    rows = [
        "| step | wall time (s) | peak RSS (MiB) | messages |",
        "|---|---:|---:|---:|",
        (
            f"| read the log once (`mcap` reader) | {read['s']:.2f} | {read['rss_mib']:.0f} | "
            f"{read['messages']} |"
        ),
        (
            f"| cut {clips['written']} clips in one pass (`write_clips`) | {clips['s']:.2f} | "
            f"{clips['rss_mib']:.0f} | {clips['messages']} |"
        ),
        (
            "| `workbench export --all --engines rss --no-rrd --no-thumbnails` (finds the "
            f"incidents, then writes {whole['clips']:.0f} MCAP clips) | {whole['s']:.2f} | "
            f"{whole['rss_mib']:.0f} | |"
        ),
    ]
    facts = json.dumps({"read": read, "cut": clips, "export": whole}, sort_keys=True)
    return (
        "## Clip export from a large log\n\n"
        f"Log: {made['bytes'] / _MIB:.0f} MiB ROS 2 MCAP (sample drive repeated, 10 Hz 160 KiB "
        f"camera payloads). {_CLIPS} clips of {clips['window_s']:.1f} s, "
        f"{clips['out_mib']:.0f} MiB written. Page cache: {cache}.\n\n"
        + "\n".join(rows)
        + f"\n\nCut time / read time: **{ratio:.2f}** (target: at most 2); "
        "peak RSS target: under 400 MB. The whole command also evaluates every frame to find "
        "the incidents (its own pass, the cost of `workbench incidents`); the clips then take "
        "the one pass measured above.\n\n"
        f"<!-- {facts} -->\n"
    )
