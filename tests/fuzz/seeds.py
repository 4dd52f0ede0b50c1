"""Small valid inputs every fuzz target starts from, written by the tests' own writers.

Seeds are made from ``sample_logs/`` and the loader tests' synthetic drive, never from
``../shared/external``. They are cut short (a few frames) and written uncompressed where
the container allows, so that the fuzzer's mutations reach the decoders instead of dying
in a checksum or a decompressor; one compressed seed per container keeps that path covered.
"""

from __future__ import annotations

import io
import json
import shutil
import zipfile
from pathlib import Path
from typing import TYPE_CHECKING

from mcap.reader import make_reader
from mcap.writer import CompressionType
from mcap.writer import Writer as McapWriter
from rosbags.rosbag1 import Writer as Bag1Writer
from ruamel.yaml import YAML

from loaders.typestore import typestore
from tests.fuzz.targets import BASE_DB3
from tests.loaders import containers
from tests.loaders.fixtures import (
    ODOM,
    ros_entries,
    write_mcap_json,
    write_mcap_protobuf,
    write_ros1_bag,
    write_ros2_mcap,
    write_rosbag2,
)
from tests.loaders.maps.commonroad_xml import scenario
from workbench.samples.racing import write_racing_sample

if TYPE_CHECKING:
    from collections.abc import Callable

    from tests.loaders.fixtures import Entry

__all__ = ["SEEDS", "write_assets", "write_seeds"]

SAMPLES = Path(__file__).resolve().parents[2] / "sample_logs"
#: Messages kept in a seed log (ego at 10 Hz: a few frames with objects and a plan).
_HEAD = 14


def _entries(version: int, objects: str, plan: str) -> list[Entry]:
    return ros_entries(version, ODOM, objects, plan)[:_HEAD]


def mcap_head(src: Path, dst: Path, count: int = _HEAD, *, schema_data: bool = True) -> Path:
    """The first ``count`` messages of an MCAP, uncompressed, without attachments.

    ``schema_data=False`` empties the schemas' data (the OSI decoder goes by the schema name;
    the descriptor set would make the seed 1 MB).
    """
    with src.open("rb") as f, dst.open("wb") as g:
        reader = make_reader(f)
        header = reader.get_header()
        writer = McapWriter(g, compression=CompressionType.NONE, chunk_size=4096)
        writer.start(profile=header.profile, library="rss-workbench fuzz seeds")
        schemas: dict[int, int] = {}
        channels: dict[int, int] = {}
        for k, (schema, channel, message) in enumerate(reader.iter_messages()):
            if k >= count:
                break
            sid = 0
            if schema is not None:
                if schema.id not in schemas:
                    schemas[schema.id] = writer.register_schema(
                        schema.name, schema.encoding, schema.data if schema_data else b""
                    )
                sid = schemas[schema.id]
            if channel.id not in channels:
                channels[channel.id] = writer.register_channel(
                    channel.topic, channel.message_encoding, sid, channel.metadata
                )
            writer.add_message(
                channels[channel.id], message.log_time, message.data, message.publish_time
            )
        writer.finish()  # type: ignore[no-untyped-call]
    return dst


def _ros2_mcap(d: Path) -> list[Path]:
    entries = _entries(
        2, "vision_msgs/msg/Detection3DArray", "autoware_planning_msgs/msg/Trajectory"
    )
    return [
        write_ros2_mcap(d / "synthetic.mcap", entries, compression=CompressionType.NONE),
        mcap_head(SAMPLES / "highway_cut_in.mcap", d / "highway_cut_in.mcap"),
    ]


def _ros1_mcap(d: Path) -> list[Path]:
    full = containers.ros1_mcap(SAMPLES / "hard_braking_lead.bag", d / "full.mcap")
    return [mcap_head(full, d / "hard_braking_lead.mcap")]


def _json_mcap(d: Path) -> list[Path]:
    full = write_mcap_json(d / "full.mcap")
    return [mcap_head(full, d / "synthetic.mcap")]


def _protobuf_mcap(d: Path) -> list[Path]:
    full = write_mcap_protobuf(d / "full.mcap")
    return [
        mcap_head(full, d / "synthetic.mcap"),
        mcap_head(SAMPLES / "pedestrian_crossing_foxglove.mcap", d / "foxglove.mcap"),
    ]


def _osi(d: Path, variant: str) -> list[Path]:
    from tests.loaders.ego_logs import reference_frames  # noqa: PLC0415 - reads a sample
    from tests.loaders.osi_logs import write_osi  # noqa: PLC0415 - imports betterosi

    path = write_osi(reference_frames(SAMPLES.parent)[:4], d, variant)
    if path.suffix == ".mcap":
        return [mcap_head(path, d / "sensor_view.mcap", schema_data=False)]
    return [path]


def _bag_uncompressed(path: Path, entries: list[Entry]) -> Path:
    store = typestore(1)
    with Bag1Writer(path) as writer:
        types = {e.topic: e.msgtype for e in entries}
        conns = {t: writer.add_connection(t, m, typestore=store) for t, m in types.items()}
        for e in entries:
            writer.write(conns[e.topic], e.t_ns, store.serialize_ros1(e.msg, e.msgtype))
    return path


def _bag(d: Path) -> list[Path]:
    entries = _entries(1, "derived_object_msgs/msg/ObjectArray", "nav_msgs/msg/Path")
    return [
        _bag_uncompressed(d / "synthetic.bag", entries),
        write_ros1_bag(d / "synthetic_lz4.bag", entries),
    ]


def _rosbag2(d: Path) -> Path:
    """A small rosbag2 sqlite3 directory whose storage file is :data:`BASE_DB3`."""
    entries = _entries(
        2, "autoware_perception_msgs/msg/PredictedObjects", "autoware_planning_msgs/msg/Trajectory"
    )
    bag = write_rosbag2(d / "bag", entries, "sqlite3")
    next(bag.glob("*.db3")).rename(bag / BASE_DB3)
    yaml = YAML(typ="safe")
    doc = yaml.load(bag / "metadata.yaml")
    info = doc["rosbag2_bagfile_information"]
    info["relative_file_paths"] = [BASE_DB3]
    for entry in info.get("files", []):
        entry["path"] = BASE_DB3
    yaml.dump(doc, bag / "metadata.yaml")
    return bag


def _db3(d: Path) -> list[Path]:
    return [shutil.copyfile(_rosbag2(d) / BASE_DB3, d / "synthetic.db3")]


def _metadata(d: Path) -> list[Path]:
    return [_rosbag2(d) / "metadata.yaml"]


def _commonroad_body(version: str) -> str:
    def state(tag: str, step: int, x: float, y: float, v: float) -> str:
        return (
            f"<{tag}><position><point><x>{x}</x><y>{y}</y></point></position>"
            f"<orientation><exact>0.0</exact></orientation><time><exact>{step}</exact></time>"
            f"<velocity><exact>{v}</exact></velocity></{tag}>"
        )

    def obstacle(oid: int, kind: str, y: float, v: float) -> str:
        states = "".join(state("state", k, v * k * 0.1, y, v) for k in range(1, 4))
        body = (
            f"<type>{kind}</type><shape><rectangle><length>4.0</length><width>2.0</width>"
            f"</rectangle></shape>{state('initialState', 0, 0.0, y, v)}"
            f"<trajectory>{states}</trajectory>"
        )
        if version == "2018b":
            return f'<obstacle id="{oid}"><role>dynamic</role>{body}</obstacle>'
        return f'<dynamicObstacle id="{oid}">{body}</dynamicObstacle>'

    return obstacle(10, "car", 1.5, 10.0) + obstacle(30, "pedestrian", -5.0, 1.0)


def _commonroad(d: Path) -> list[Path]:
    out = []
    for version in ("2018b", "2020a"):
        path = d / f"scenario_{version}.xml"
        path.write_bytes(scenario(version, _commonroad_body(version)))
        out.append(path)
    return out


def _commonroad_map(d: Path) -> list[Path]:
    path = d / "network_2020a.xml"
    path.write_bytes(scenario("2020a", ""))
    return [path]


def _lanelet2(d: Path) -> list[Path]:
    from tests.loaders.ego_logs import write_origin_map  # noqa: PLC0415

    return [write_origin_map(d / "one_lanelet.osm")]


def _opendrive(d: Path) -> list[Path]:
    road = (
        '<road id="1" length="50" junction="-1"><link/>'
        '<type s="0" type="town"><speed max="50" unit="km/h"/></type><planView>'
        '<geometry s="0" x="0" y="0" hdg="0" length="20"><line/></geometry>'
        '<geometry s="20" x="20" y="0" hdg="0" length="15"><arc curvature="0.02"/></geometry>'
        '<geometry s="35" x="35" y="2" hdg="0.3" length="15">'
        '<spiral curvStart="0.02" curvEnd="0.0"/></geometry></planView>'
        '<lanes><laneSection s="0"><left><lane id="1" type="driving">'
        '<width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane></left>'
        '<center><lane id="0" type="none"/></center><right><lane id="-1" type="driving">'
        '<width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane></right></laneSection></lanes>'
        "</road>"
    )
    path = d / "one_road.xodr"
    path.write_text(f"<?xml version='1.0'?><OpenDRIVE><header/>{road}</OpenDRIVE>")
    return [path]


def _short_scn(text: str, rows: int = 4, points: int = 4) -> str:
    """The header and first ``rows`` rows of a ``.scn``, every JSON list cut to ``points``."""
    out = []
    data_rows = 0
    for line in text.splitlines():
        if line.startswith("# bound_"):
            key, _, value = line.partition(":")
            out.append(f"{key}:{json.dumps(json.loads(value)[:points])}")
        elif line.startswith(("#", "time;")) or not line.strip():
            out.append(line)
        elif data_rows < rows:
            fields = [
                json.dumps(json.loads(f)[:points]) if f.startswith("[") else f
                for f in line.split(";")
            ]
            out.append(";".join(fields))
            data_rows += 1
    return "\n".join(out) + "\n"


def _scenario_architect(d: Path, archive: bool) -> list[Path]:
    sample = write_racing_sample(d / "sample")[0]
    with zipfile.ZipFile(sample) as zf:
        name = next(n for n in zf.namelist() if n.endswith(".scn"))
        text = _short_scn(zf.read(name).decode())
    if not archive:
        path = d / "short.scn"
        path.write_text(text)
        return [path]
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w") as zf:
        zf.writestr(zipfile.ZipInfo("short.scn", (2024, 1, 1, 0, 0, 0)), text)
    path = d / "short.saa"
    path.write_bytes(buf.getvalue())
    return [path]


def _openlabel(d: Path) -> list[Path]:
    def action(name: str, verdict: str, tags: list[str]) -> dict[str, object]:
        text = {
            "engine": "rss",
            "cause": "longitudinal",
            "verdict": verdict,
            "note": "seen in review",
            "reviewer": "fuzz",
            "labelled_ns": "1700000000000000000",
        }
        return {
            "name": name,
            "type": "incident/rss",
            "frame_intervals": [{"frame_start": 3, "frame_end": 7}],
            "action_data": {
                "text": [{"name": k, "val": v} for k, v in text.items()],
                "vec": [{"name": "objects", "val": ["11"]}, {"name": "tags", "val": tags}],
            },
        }

    doc = {
        "openlabel": {
            "metadata": {
                "schema_version": "1.0.0",
                "drive_sha256": "ab" * 32,
                "tagged_file": "drive.mcap",
                "settings": {"profile": "adrss-5.0"},
            },
            "actions": {
                "0": action("rss-11-longitudinal-3", "confirmed", ["late"]),
                "1": action("rss-12-lateral-5", "false_positive", []),
            },
        }
    }
    path = d / "labels.json"
    path.write_text(json.dumps(doc, indent=1))
    return [path]


#: Target name -> writer of its seeds into an empty directory.
SEEDS: dict[str, Callable[[Path], list[Path]]] = {
    "commonroad": _commonroad,
    "commonroad-map": _commonroad_map,
    "db3": _db3,
    "lanelet2": _lanelet2,
    "mcap-json": _json_mcap,
    "mcap-osi": lambda d: _osi(d, "sv_mcap"),
    "mcap-protobuf": _protobuf_mcap,
    "mcap-ros1": _ros1_mcap,
    "mcap-ros2": _ros2_mcap,
    "opendrive": _opendrive,
    "openlabel": _openlabel,
    "osi-trace": lambda d: _osi(d, "gt_osi"),
    "ros1-bag": _bag,
    "rosbag2-sqlite3": _metadata,
    "scenario-architect": lambda d: _scenario_architect(d, archive=True),
    "scenario-architect-scn": lambda d: _scenario_architect(d, archive=False),
}


def write_seeds(target: str, out_dir: Path) -> list[Path]:
    """Write the seeds of ``target`` into ``out_dir`` (flat: one file per seed).

    Returns:
        The seed files, named ``seed-<name>``.
    """
    out_dir.mkdir(parents=True, exist_ok=True)
    work = out_dir / ".work"
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir()
    seeds = []
    for path in SEEDS[target](work):
        seed = out_dir / f"seed-{path.name}"
        seed.write_bytes(path.read_bytes())
        seeds.append(seed)
    shutil.rmtree(work)
    return seeds


def write_assets(out_dir: Path) -> Path:
    """Write the storage file the ``rosbag2-sqlite3`` target's inputs lie beside."""
    out_dir.mkdir(parents=True, exist_ok=True)
    work = out_dir / ".work"
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir()
    shutil.copyfile(_rosbag2(work) / BASE_DB3, out_dir / BASE_DB3)
    shutil.rmtree(work)
    return out_dir
