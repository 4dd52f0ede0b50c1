r"""Seeded random reach-set case documents (``docs/reachset-cases.md``).

One track strip per document: a straight, a constant-radius curve (60-150 m, turning
40-110 degrees left or right) and another straight, 10-16 m wide. Each case puts the ego
somewhere on it with a plan along the strip (constant speed or braking, 0.2 s waypoints over
4 s, with or without ``t_s``) and 1-3 objects ahead, alongside or behind it at 0-50 m/s,
heading along the strip within a few degrees. Methods cycle through the ones asked for. A
sequence advances the same scene by 0.1 s per step::

        right bound  ___________
                                \\       straight - curve - straight
        centre ---> ego  obj     )
        left bound   ___________/

Pure: the generator takes a ``numpy.random.Generator`` and returns a JSON-ready dict.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from reachsets.params import ReachMethod

if TYPE_CHECKING:
    from collections.abc import Sequence

    from numpy.typing import NDArray

__all__ = ["random_document"]

#: Length of each straight of the strip [m].
STRAIGHT_M = 150.0
#: Spacing of the bound points [m] (as on the TUM logs' Modena track).
POINT_STEP_M = 3.0
#: Plan waypoint spacing and horizon [s].
PLAN_DT_S, PLAN_HORIZON_S = 0.2, 4.0
#: Time between the steps of a sequence [s].
SEQUENCE_DT_S = 0.1
#: Objects start within this arc-length window around the ego [m] (behind .. ahead).
OBJECT_WINDOW_M = (-30.0, 60.0)
#: Digits kept in the document (1 mm, 1 mrad).
_DIGITS = 3


@dataclass(frozen=True)
class _Strip:
    """The strip's centre line sampled every 0.5 m: arc length, position, heading."""

    s_m: NDArray[np.float64]
    x_m: NDArray[np.float64]
    y_m: NDArray[np.float64]
    heading_rad: NDArray[np.float64]
    width_m: float

    def pose(self, s_m: Any, offset_m: Any) -> tuple[Any, Any, Any]:
        """Points at arc length ``s_m`` and ``offset_m`` left of the centre, and the heading."""
        s = np.clip(s_m, 0.0, self.s_m[-1])
        heading = np.interp(s, self.s_m, self.heading_rad)
        x = np.interp(s, self.s_m, self.x_m) - np.sin(heading) * offset_m
        y = np.interp(s, self.s_m, self.y_m) + np.cos(heading) * offset_m
        return x, y, heading


def _strip(rng: np.random.Generator) -> _Strip:
    radius = rng.uniform(60.0, 150.0)
    turn = math.radians(rng.uniform(40.0, 110.0)) * rng.choice([-1.0, 1.0])
    curve = radius * abs(turn)
    s = np.arange(0.0, 2 * STRAIGHT_M + curve, 0.5)
    # heading: 0 on the first straight, rising linearly through the curve, then held
    heading = np.clip((s - STRAIGHT_M) / curve, 0.0, 1.0) * turn
    step = np.diff(s)
    mid = (heading[1:] + heading[:-1]) / 2
    x = np.concatenate([[0.0], np.cumsum(np.cos(mid) * step)])
    y = np.concatenate([[0.0], np.cumsum(np.sin(mid) * step)])
    return _Strip(s, x, y, heading, float(rng.uniform(10.0, 16.0)))


def _bounds(strip: _Strip) -> dict[str, list[list[float]]]:
    s = np.arange(0.0, strip.s_m[-1], POINT_STEP_M)
    half = strip.width_m / 2
    out = {}
    for name, side in (("left", half), ("right", -half)):
        x, y, _ = strip.pose(s, side)
        out[name] = np.round(np.stack([x, y], axis=1), _DIGITS).tolist()
    return out


@dataclass(frozen=True)
class _Scene:
    """A case's scene at its first step (arc lengths, offsets, speeds)."""

    ego_s_m: float
    ego_offset_m: float
    ego_speed_mps: float
    ego_brake_mps2: float
    timed: bool
    objects: tuple[tuple[str, float, float, float, float, float, float], ...]


def _scene(rng: np.random.Generator, strip: _Strip) -> _Scene:
    half = strip.width_m / 2
    objects = [
        (
            f"veh_{k + 1}",
            float(rng.uniform(*OBJECT_WINDOW_M)),  # arc length relative to the ego
            float(rng.uniform(-half + 1.5, half - 1.5)),
            float(rng.normal(0.0, 0.05)),  # heading error
            float(rng.uniform(0.0, 50.0)),
            float(rng.uniform(4.0, 5.0)),
            float(rng.uniform(1.8, 2.2)),
        )
        for k in range(int(rng.integers(1, 4)))
    ]
    return _Scene(
        ego_s_m=float(rng.uniform(40.0, strip.s_m[-1] - 200.0)),
        ego_offset_m=float(rng.uniform(-half + 2.0, half - 2.0)),
        ego_speed_mps=float(rng.uniform(5.0, 45.0)),
        ego_brake_mps2=float(rng.choice([0.0, rng.uniform(2.0, 9.0)])),
        timed=bool(rng.integers(0, 2)),
        objects=tuple(objects),
    )


def _r(values: Any) -> Any:
    return np.round(np.asarray(values, dtype=np.float64), _DIGITS).tolist()


def _step(scene: _Scene, strip: _Strip, t0_s: float) -> dict[str, Any]:
    """The scene ``t0_s`` after its start (everyone moved along the strip)."""
    v0, a = scene.ego_speed_mps, scene.ego_brake_mps2
    t = np.arange(0.0, PLAN_HORIZON_S + 1e-9, PLAN_DT_S) + t0_s
    t_stop = v0 / a if a > 0 else math.inf
    moved = np.where(t < t_stop, v0 * t - a * t**2 / 2, v0 * t_stop / 2)
    speed = np.maximum(v0 - a * t, 0.0)
    x, y, heading = strip.pose(scene.ego_s_m + moved, scene.ego_offset_m)
    ego: dict[str, Any] = {"x": _r(x), "y": _r(y), "heading": _r(heading), "speed": _r(speed)}
    if scene.timed:
        ego["t_s"] = _r(t - t0_s)
    objects = []
    for name, ds, offset, dyaw, v, length, width in scene.objects:
        ox, oy, oh = strip.pose(scene.ego_s_m + ds + v * t0_s, offset)
        objects.append(
            {
                "id": name,
                "x": _r(ox),
                "y": _r(oy),
                "yaw": _r(oh + dyaw),
                "speed": _r(v),
                "length": _r(length),
                "width": _r(width),
            }
        )
    return {"ego": ego, "objects": objects}


def random_document(
    rng: np.random.Generator,
    count: int,
    *,
    methods: Sequence[ReachMethod | str] = tuple(ReachMethod),
    sequences: int = 0,
    sequence_steps: int = 4,
) -> dict[str, Any]:
    """A case document of ``count`` random cases and ``sequences`` random sequences.

    Args:
        rng: The random generator (seed it for a reproducible document).
        count: Number of one-step cases (``r0``, ``r1``, ...).
        methods: Methods the cases cycle through (case ``k`` gets ``methods[k % len]``).
        sequences: Number of sequences (``q0``, ...), appended after the cases.
        sequence_steps: Steps per sequence, 0.1 s apart.

    Returns:
        The JSON-ready document (track in ``defaults``, no ``expected`` blocks).
    """
    names = [ReachMethod(m).value for m in methods]
    strip = _strip(rng)
    cases: list[dict[str, Any]] = []
    for k in range(count):
        scene = _scene(rng, strip)
        cases.append({"id": f"r{k}", "method": names[k % len(names)], **_step(scene, strip, 0.0)})
    for k in range(sequences):
        scene = _scene(rng, strip)
        steps = [_step(scene, strip, j * SEQUENCE_DT_S) for j in range(sequence_steps)]
        cases.append({"id": f"q{k}", "method": names[k % len(names)], "sequence": steps})
    return {"defaults": {"track": _bounds(strip)}, "cases": cases}
