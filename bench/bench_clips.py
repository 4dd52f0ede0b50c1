"""Clip export from a large log: one pass for all clips, flat memory.

A ROS 2 MCAP of about 1 GiB (``--quick``: 100 MiB) is generated: the ``highway_cut_in``
sample's messages repeated back to back, plus a 10 Hz camera topic of incompressible 160 KiB
``sensor_msgs/CompressedImage`` payloads (about 11 minutes of drive per GiB), the kind of topic that makes real logs large.
Twenty windows of up to 8 s (at most half the spacing, so they do not overlap) spread over
the drive are cut with ``loaders.clips.write_clips``;
the reference is one plain read of the same file with the ``mcap`` reader (every message's
payload touched). Each side runs in a fresh interpreter, so peak RSS is its own.
"""

from __future__ import annotations

import json
import os
import tempfile
from pathlib import Path

from bench.child import run_json

_MIB = 2**20
_CLIPS = 20
_WINDOW_S = 9  # an incident of 3 s with 3 s of margin on each side

_GENERATE = """
import json, os, sys
from pathlib import Path
from mcap.reader import make_reader
from mcap.writer import CompressionType, Writer
from loaders.typestore import typestore

target, mib = Path(sys.argv[1]), int(sys.argv[2])
sample = Path("sample_logs/highway_cut_in.mcap")
store = typestore(2)
image_t = "sensor_msgs/msg/CompressedImage"
Header = store.types["std_msgs/msg/Header"]
Time = store.types["builtin_interfaces/msg/Time"]
with sample.open("rb") as f:
    reader = make_reader(f)
    records = [(s, c, m) for s, c, m in reader.iter_messages()]
t0 = records[0][2].log_time
span = records[-1][2].log_time - t0 + 50_000_000
written = 0
with target.open("wb") as out:
    w = Writer(out, compression=CompressionType.ZSTD)
    w.start(profile="ros2", library="bench")
    ids = {}
    for s, c, _ in records:
        if c.id not in ids:
            sid = w.register_schema(s.name, s.encoding, s.data)
            ids[c.id] = w.register_channel(c.topic, c.message_encoding, sid, c.metadata)
    text = store.generate_msgdef(image_t, ros_version=2)[0]
    cam = w.register_channel("/camera/image/compressed", "cdr",
                             w.register_schema(image_t, "ros2msg", text.encode()), {})
    lap = 0
    while written < mib * 2**20:
        base = lap * span
        for _, c, m in records:
            w.add_message(ids[c.id], m.log_time + base, m.data, m.log_time + base)
        t = t0 + base
        while t < t0 + base + span:
            msg = store.types[image_t](Header(Time(sec=t // 10**9, nanosec=t % 10**9), "cam"),
                                       "jpeg", __import__("numpy").frombuffer(os.urandom(160 * 2**10), dtype="uint8"))
            data = store.serialize_cdr(msg, image_t)
            w.add_message(cam, t, data, t)
            written += len(data)
            t += 100_000_000
        lap += 1
    w.finish()
print(json.dumps({"bytes": target.stat().st_size, "start": t0, "end": t0 + lap * span}))
"""

_DROP_CACHES = Path("/proc/sys/vm/drop_caches")


def _drop_caches() -> bool:
    """Empty the page cache so both sides read from disk (needs root; else warm cache)."""
    try:
        os.sync()
        _DROP_CACHES.write_text("3\n")
    except OSError:
        return False
    return True


_READ = """
import json, resource, sys, time
from mcap.reader import make_reader
t = time.perf_counter(); n = 0; size = 0
with open(sys.argv[1], "rb") as f:
    for _, _, m in make_reader(f).iter_messages():
        n += 1; size += len(m.data)
print(json.dumps({"s": time.perf_counter() - t, "messages": n,
                  "rss_mib": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024}))
"""

_CUT = """
import json, resource, sys, time
from pathlib import Path
from loaders.clips import ClipRequest, write_clips
log, out, start, end, clips, window = sys.argv[1], Path(sys.argv[2]), *map(int, sys.argv[3:7])
step = (end - start) // clips
window = min(window, step // 2)
requests = [ClipRequest(out / f"clip_{i:02d}.mcap", start + i * step, start + i * step + window,
                        {"id": str(i)}) for i in range(clips)]
t = time.perf_counter()
outcomes = write_clips(Path(log), requests, map_file=("map.osm", "text/xml", b"<osm/>"))
elapsed = time.perf_counter() - t
print(json.dumps({"s": elapsed, "written": sum(o.written for o in outcomes),
                  "messages": sum(o.messages for o in outcomes),
                  "out_mib": sum(p.stat().st_size for p in out.iterdir()) / 2**20,
                  "rss_mib": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024}))
"""


def run(*, quick: bool) -> str:
    """Generate the large log, cut the clips, and return the Markdown section."""
    mib = 100 if quick else 1024
    with tempfile.TemporaryDirectory(prefix="bench_clips_") as tmp:
        log = Path(tmp) / "large.mcap"
        made = run_json(_GENERATE, str(log), str(mib))
        cold = _drop_caches()
        read = run_json(_READ, str(log))
        out = Path(tmp) / "clips"
        out.mkdir()
        cold = _drop_caches() and cold
        cut = run_json(
            _CUT,
            str(log),
            str(out),
            str(made["start"]),
            str(made["end"]),
            str(_CLIPS),
            str(_WINDOW_S * 10**9),
        )
    ratio = cut["s"] / read["s"]
    rows = [
        "| step | wall time (s) | peak RSS (MiB) | messages |",
        "|---|---:|---:|---:|",
        f"| read the log once (`mcap` reader) | {read['s']:.2f} | {read['rss_mib']:.0f} | "
        f"{read['messages']} |",
        f"| cut {cut['written']} clips in one pass (`write_clips`) | {cut['s']:.2f} | "
        f"{cut['rss_mib']:.0f} | {cut['messages']} |",
    ]
    return (
        "## Clip export from a large log\n\n"
        f"Log: {made['bytes'] / _MIB:.0f} MiB ROS 2 MCAP (sample drive repeated + 10 Hz 160 KiB "
        f"camera payloads); {_CLIPS} clips of {_WINDOW_S} s, {cut['out_mib']:.0f} MiB written "
        "(zstd). Page cache: "
        + ("emptied before each step (both read from disk)" if cold else "warm (not root)")
        + ".\n\n"
        + "\n".join(rows)
        + f"\n\nCut / read time: **{ratio:.2f}×** "
        "(target ≤ 2×); peak RSS target < 400 MB.\n"
        + json.dumps({"read": read, "cut": cut}, sort_keys=True).join(["\n<!-- ", " -->\n"])
    )
