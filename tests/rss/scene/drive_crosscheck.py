"""Drive-level cross-check against ad-rss map integration 5.0: both sides, per frame.

The reference (``adrss_drive_oracle.py`` under ``RSS_MAP_ORACLE_PYTHON``) and ours
(:func:`rss.evaluate_frames` over the whole drive, memory carried across its frames) see
the same drives of ``town01_drives``. Oracle answers are cached in one JSON file (by the
caller, e.g. under ``out/``) together with the drives they answer, and asked again when
the drives differ. Used by ``test_crosscheck_drives.py`` and ``tools/drive_crosscheck.py``.
"""

from __future__ import annotations

import dataclasses
import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from rss import evaluate_frames
from rss.params import (
    DEFAULT_EGO_DYNAMICS,
    DEFAULT_VEHICLE_DYNAMICS,
    RestrictSpeedLimitMode,
    RssParams,
    SceneSettings,
)
from rss.scene import SceneEgo, SceneMemo, SceneObjects
from tests.rss.scene.oracle_processes import ask_in_parallel

if TYPE_CHECKING:
    from rss.scene import PreparedGraph

__all__ = [
    "DRIVE_ORACLE",
    "EGO_ID",
    "Agreement",
    "compare_drives",
    "oracle_drives",
    "our_drive",
]

DRIVE_ORACLE = Path(__file__).with_name("adrss_drive_oracle.py")
#: The ego's id on both sides (the oracle's ``EGO_ID``).
EGO_ID = 1000


def frame_inputs(frame: dict[str, Any]) -> tuple[SceneEgo, SceneObjects]:
    """Scene inputs of one drive frame (the oracle builds the same vehicles)."""
    e, objs = frame["ego"], frame["objects"]
    ego = SceneEgo(
        EGO_ID, e["x"], e["y"], e["yaw"], e["v"], e["length"], e["width"], DEFAULT_EGO_DYNAMICS
    )

    def col(key: str) -> np.ndarray:
        return np.array([o[key] for o in objs], dtype=float)

    v, yaw = col("v"), col("yaw")
    objects = SceneObjects(
        ids=np.array([o["id"] for o in objs], dtype=np.int64),
        object_type=np.full(len(objs), 2, dtype=np.int64),
        x_m=col("x"),
        y_m=col("y"),
        yaw_rad=yaw,
        vx_mps=v * np.cos(yaw),
        vy_mps=v * np.sin(yaw),
        length_m=col("length"),
        width_m=col("width"),
        dynamics=(DEFAULT_VEHICLE_DYNAMICS,) * len(objs),
    )
    return ego, objects


def our_drive(
    prep: PreparedGraph,
    drive: dict[str, Any],
    settings: SceneSettings,
    memo: SceneMemo | None = None,
) -> list[dict[str, Any]]:
    """Our frames of one drive in the oracle's answer format (memory across the frames).

    ``memo``: the map's scene memo, shared across drives (``None``: a fresh one). A drive's
    ``speed_limit_mode`` (as the oracle reads it) replaces the settings' one.
    """
    frames = [frame_inputs(f) for f in drive["frames"]]
    if "speed_limit_mode" in drive:
        mode = RestrictSpeedLimitMode(drive["speed_limit_mode"])
        settings = dataclasses.replace(settings, restrict_speed_limit_mode=mode)
    params = RssParams(scene=settings)
    verdicts, _ = evaluate_frames(frames, params, None, graph=prep, memo=memo)
    out = []
    for verdict in verdicts:
        answer: dict[str, Any] = {"ok": True, "dangerous": [], "situations": []}
        if verdict.result is not None:
            r = verdict.result
            answer["dangerous"] = sorted({int(x) for x in verdict.object_id[r.dangerous]})
            for i, c in enumerate(verdict.scene.constellations):
                answer["situations"].append(
                    {
                        "id": int(verdict.object_id[i]),
                        "type": c.constellation_type.name,
                        "lon_d": float(r.relative.lon_distance_m[i]),
                        "lat_d": float(r.relative.lat_distance_m[i]),
                        "dangerous": bool(r.dangerous[i]),
                    }
                )
        out.append(answer)
    return out


def _ask(python: str, town: Path, drives: list[dict[str, Any]]) -> list[list[dict[str, Any]]]:
    """The oracle's frames of ``drives``, two processes (one per core) over alternate drives."""
    chunks = [drives[0::2], drives[1::2]]
    parts = []
    for code, out, err in ask_in_parallel(python, DRIVE_ORACLE, town, chunks, 3600):
        if code != 0 or not out.strip():
            msg = f"drive oracle failed: {err[-2000:]}"
            raise RuntimeError(msg)
        parts.append(json.loads(out.strip().splitlines()[-1]))
    answers: list[list[dict[str, Any]]] = [[] for _ in drives]
    answers[0::2], answers[1::2] = parts[0], parts[1]
    return answers


def oracle_drives(
    drives: list[dict[str, Any]], python: str, town: Path, cache: Path | None
) -> list[list[dict[str, Any]]]:
    """The oracle's frames of every drive, from ``cache`` when it answers these drives."""
    if cache is not None and cache.exists():
        cached = json.loads(cache.read_text())
        if isinstance(cached, dict) and cached.get("drives") == drives:
            answers: list[list[dict[str, Any]]] = cached["answers"]
            return answers
    answers = _ask(python, town, drives)
    if cache is not None:
        cache.parent.mkdir(parents=True, exist_ok=True)
        cache.write_text(json.dumps({"drives": drives, "answers": answers}))
    return answers


@dataclass
class Agreement:
    """Per-frame agreement of one mode.

    Attributes:
        frames: Frames compared.
        agree: Frames with the same verdict (any dangerous object).
        reference_dangerous: Frames the reference calls dangerous.
        missed: ``(drive, frame)`` the reference calls dangerous and we call safe.
        extra: ``(drive, frame)`` we call dangerous and the reference safe.
        failed: ``(drive, frame)`` where the reference's check failed (not compared).
    """

    frames: int = 0
    agree: int = 0
    reference_dangerous: int = 0
    missed: list[tuple[int, int]] = field(default_factory=list)
    extra: list[tuple[int, int]] = field(default_factory=list)
    failed: list[tuple[int, int]] = field(default_factory=list)

    @property
    def rate(self) -> float:
        """Share of agreeing frames."""
        return self.agree / max(self.frames, 1)

    def summary(self) -> str:
        """One line: agreement, reference-dangerous frames, both kinds of disagreement."""
        return (
            f"{self.agree}/{self.frames} frames agree ({100 * self.rate:.1f} %), reference "
            f"dangerous {self.reference_dangerous}, safe-for-us {len(self.missed)}, "
            f"dangerous-for-us {len(self.extra)}, reference failed {len(self.failed)}"
        )


def compare_drives(
    mine: list[list[dict[str, Any]]], theirs: list[list[dict[str, Any]]]
) -> Agreement:
    """Frame-by-frame verdict agreement (frames where the reference failed are left out)."""
    stats = Agreement()
    for d, (ours_d, theirs_d) in enumerate(zip(mine, theirs, strict=True)):
        for k, (a, b) in enumerate(zip(ours_d, theirs_d, strict=True)):
            if not b["ok"]:
                stats.failed.append((d, k))
                continue
            stats.frames += 1
            ref, us = bool(b["dangerous"]), bool(a["dangerous"])
            stats.reference_dangerous += ref
            stats.agree += ref == us
            if ref and not us:
                stats.missed.append((d, k))
            elif us and not ref:
                stats.extra.append((d, k))
    return stats
