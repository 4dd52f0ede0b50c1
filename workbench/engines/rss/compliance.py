"""Proper-response compliance on the recorded motion (docs/rss.md, "Proper-response compliance").

For every object some party must act towards (:meth:`RssVerdict.responsibility`), and for
each such party (ego, object): since when it had to act without a break (``since``), when
its response was due (``since + rho`` of that party's dynamics: the RSS response time), the
longitudinal restriction of its proper response (``brake_min`` for ``BrakeMin``,
``brake_min_correct`` for ``BrakeMinCorrect``: its acceleration must stay at or below it),
its measured longitudinal acceleration, and once due the shortfall
``max(0, measured - required)`` [m/s²] (0: complied; a party at standstill, below
:data:`STOPPED_MPS`, has complied). A response that restricts only laterally is listed with
no requirement (lateral acceleration is not measured).

Measured acceleration: the least-squares slope of the recorded speed over the samples of
the last :data:`WINDOW_NS` (0.5 s) up to and including the frame — a causal first-order
Savitzky-Golay derivative: it averages the finite differences of the window (noise down by
about the square root of the sample count) and lags the true acceleration by about 0.25 s.
The ego's speed is the log's ``EgoState.speed_mps``; an object's is the magnitude of its
map-frame velocity (its acceleration along its path, not along the lane). ``None`` with
fewer than two samples in the window.
"""

from __future__ import annotations

import collections
from typing import TYPE_CHECKING

import numpy as np

from loaders.records import ObjectClass as FrameClass
from rss.params import ObjectClass
from rss.structured.states import LongitudinalResponse
from workbench.engines.classes import dynamics_class
from workbench.engines.rss.verdict import Obligation

if TYPE_CHECKING:
    from collections.abc import Sequence

    from numpy.typing import NDArray

    from loaders.records import Frame
    from rss.params import RssParams
    from workbench.engines.rss.verdict import RssVerdict

__all__ = ["STOPPED_MPS", "WINDOW_NS", "ComplianceTracker", "Obligation", "slope"]

#: Window of the acceleration estimate [ns].
WINDOW_NS = 500_000_000
#: Below this speed a party is at standstill: its braking duty is fulfilled [m/s].
STOPPED_MPS = 0.1
_BRAKE_MIN = int(LongitudinalResponse.BrakeMin)
_BRAKE_MIN_CORRECT = int(LongitudinalResponse.BrakeMinCorrect)


def slope(t_ns: NDArray[np.int64], speed_mps: NDArray[np.float64]) -> float | None:
    """Least-squares slope of speed over time [m/s²]; ``None`` with fewer than two samples.

    Args:
        t_ns: ``(K,)`` sample times.
        speed_mps: ``(K,)`` speeds.
    """
    if t_ns.size < 2:  # noqa: PLR2004 - a slope needs two samples
        return None
    t = (t_ns - t_ns[-1]) / 1e9
    dt = t - t.mean()
    denominator = float(np.dot(dt, dt))
    if denominator <= 0.0:
        return None
    return float(np.dot(dt, speed_mps - speed_mps.mean()) / denominator)


class ComplianceTracker:
    """Keeps the last :data:`WINDOW_NS` of recorded speeds and the runs of duties."""

    def __init__(self, params: RssParams) -> None:
        """Start with no history (a fresh replay)."""
        self._params = params
        self._frames: collections.deque[tuple[int, float, NDArray[np.str_], NDArray[np.float64]]]
        self._frames = collections.deque()
        self._since: dict[tuple[str, str], int] = {}

    def _push(self, frame: Frame) -> None:
        actors = frame.actors
        speed = np.where(actors.valid, np.hypot(actors.vx_mps, actors.vy_mps), np.nan)
        self._frames.append((frame.t_ns, abs(frame.ego.speed_mps), actors.ids, speed))
        while self._frames and self._frames[0][0] < frame.t_ns - WINDOW_NS:
            self._frames.popleft()

    def _speeds(self, label: str | None) -> tuple[NDArray[np.int64], NDArray[np.float64]]:
        times: list[int] = []
        speeds: list[float] = []
        for t_ns, ego_speed, ids, actor_speed in self._frames:
            if label is None:
                times.append(t_ns)
                speeds.append(ego_speed)
                continue
            rows = np.flatnonzero(ids == label)
            if rows.size and np.isfinite(actor_speed[rows[0]]):
                times.append(t_ns)
                speeds.append(float(actor_speed[rows[0]]))
        return np.asarray(times, dtype=np.int64), np.asarray(speeds, dtype=np.float64)

    def obligations(
        self, frames: Sequence[Frame], verdicts: Sequence[RssVerdict]
    ) -> list[tuple[tuple[str, Obligation], ...]]:
        """Each frame's ``(object label, obligation)`` pairs, in label and party order."""
        return [self._frame(f, v) for f, v in zip(frames, verdicts, strict=True)]

    def _frame(self, frame: Frame, verdict: RssVerdict) -> tuple[tuple[str, Obligation], ...]:
        self._push(frame)
        duties = _duties(verdict)
        self._since = {k: self._since.get(k, frame.t_ns) for k in duties}
        if not duties:
            return ()
        classes = dict(
            zip(frame.actors.ids.tolist(), frame.actors.object_class.tolist(), strict=True)
        )
        out = []
        for (label, party), response in sorted(duties.items()):
            if party == "ego":
                dyn = self._params.for_class(ObjectClass.EGO)
                t, v = self._speeds(None)
            else:
                code = classes.get(label)
                cls = ObjectClass.UNKNOWN if code is None else dynamics_class(FrameClass(code))
                dyn = self._params.for_class(cls)
                t, v = self._speeds(label)
            since = self._since[(label, party)]
            due = since + round(dyn.response_time_s * 1e9)
            required = (
                dyn.brake_min_mps2
                if response == _BRAKE_MIN
                else dyn.brake_min_correct_mps2
                if response == _BRAKE_MIN_CORRECT
                else None
            )
            measured = slope(t, v)
            shortfall = None
            if required is not None and measured is not None and frame.t_ns >= due:
                stopped = v.size > 0 and v[-1] < STOPPED_MPS
                shortfall = 0.0 if stopped else max(0.0, measured - required)
            out.append((label, Obligation(party, since, due, required, measured, shortfall)))
        return tuple(out)


def _duties(verdict: RssVerdict) -> dict[tuple[str, str], int]:
    """The duties of a frame: ``(label, party)`` to the most severe longitudinal response.

    Every party that must act in some constellation of the frame is listed.
    """
    result = verdict.result
    if result is None or result.responsibility is None:
        return {}
    side = result.responsibility
    ego_lon = result.states.lon_response.tolist()
    obj_lon = side.object_states.lon_response.tolist()
    out: dict[tuple[str, str], int] = {}
    for k, label in enumerate(verdict.labels):
        if label.startswith("road_boundary"):
            continue
        if side.ego_must_act[k]:
            out[(label, "ego")] = max(out.get((label, "ego"), 0), ego_lon[k])
        if side.object_must_act[k]:
            out[(label, "object")] = max(out.get((label, "object"), 0), obj_lon[k])
    return out
