"""Proper-response compliance on the recorded motion (docs/rss.md, "Proper-response compliance").

For every object some party must act towards (:meth:`RssVerdict.responsibility`), and for
each such party (ego, object): since when it had to act without a break (``since``), when
its response was due (``since + rho`` of that party's dynamics: the RSS response time), the
longitudinal restriction of its proper response (``brake_min`` for ``BrakeMin``,
``brake_min_correct`` for ``BrakeMinCorrect``: its acceleration must stay at or below it),
its measured longitudinal acceleration, and once due the shortfall [m/s²] (0: complied). A
response that restricts only laterally is listed with no requirement (lateral acceleration
is not measured).

Measured on filtered motion, only while the response is due and the danger lasts: a
constant-acceleration least-squares fit of the party's **positions** over the samples of
the current duty since its response was due, at most the last :data:`FIT_WINDOW_NS` (1 s):
``p(tau) = p0 + v tau + a tau^2 / 2`` in x and y (a causal second-order Savitzky-Golay
filter). The recorded speed is not used: on real traffic it disagrees with the positions
(docs/data_quality.md), and its noise made shortfalls of 8-10 m/s² out of nothing. The
measurement is the fitted acceleration along the fitted direction of motion; it needs
:data:`MIN_SAMPLES` samples over at least :data:`MIN_SPAN_NS` (``None`` before: the first
half second after the response was due is not judged). Shortfall ``max(0, measured -
required)``, where a party cannot be asked to brake harder than stopping within the fit
allows (``required`` raised to ``-v_start / span``, ``v_start`` the fitted speed at the
fit's start: a creeping or stopping party complies by standing); a party whose fitted speed
is below :data:`STOPPED_MPS` has complied.
"""

from __future__ import annotations

import collections
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from loaders.records import ObjectClass as FrameClass
from loaders.timebase import ns_to_s, s_to_ns
from rss.params import ObjectClass
from rss.structured.responsibility import Responsible
from rss.structured.states import LongitudinalResponse
from workbench.engines.classes import dynamics_class
from workbench.engines.rss.verdict import Obligation

if TYPE_CHECKING:
    from collections.abc import Sequence

    from numpy.typing import NDArray

    from loaders.records import Frame
    from rss.params import RssParams
    from workbench.engines.rss.verdict import RssVerdict

__all__ = [
    "FIT_WINDOW_NS",
    "MIN_SAMPLES",
    "MIN_SPAN_NS",
    "STOPPED_MPS",
    "WINDOW_NS",
    "ComplianceTracker",
    "FittedMotion",
    "Obligation",
    "fit_motion",
    "shortfall_of",
    "slope",
]

#: Window of the speed-slope estimate :func:`slope` [ns] (tools/ngsim_accelerations.py).
WINDOW_NS = 500_000_000
#: Longest stretch of positions the compliance fit uses [ns].
FIT_WINDOW_NS = 1_000_000_000
#: Shortest stretch (since the response was due) the compliance fit judges [ns].
MIN_SPAN_NS = 500_000_000
#: Fewest samples the compliance fit judges.
MIN_SAMPLES = 5
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
    t = ns_to_s(t_ns - t_ns[-1])
    dt = t - t.mean()
    denominator = float(np.dot(dt, dt))
    if denominator <= 0.0:
        return None
    return float(np.dot(dt, speed_mps - speed_mps.mean()) / denominator)


@dataclass(frozen=True, slots=True)
class FittedMotion:
    """A constant-acceleration fit of positions.

    Attributes:
        accel_mps2: Fitted acceleration along the fitted direction of motion (at the middle
            of the fit) [m/s²].
        speed_start_mps: Fitted speed at the first sample (the middle's, changed at the
            acceleration along the path).
        speed_end_mps: Fitted speed at the last sample (likewise).
        span_s: Last minus first sample time [s].
    """

    accel_mps2: float
    speed_start_mps: float
    speed_end_mps: float
    span_s: float


def fit_motion(
    t_ns: NDArray[np.int64], x_m: NDArray[np.float64], y_m: NDArray[np.float64]
) -> FittedMotion | None:
    """Least-squares ``p(tau) = p0 + v tau + a tau^2 / 2`` in x and y; ``None`` when too short.

    Args:
        t_ns: ``(K,)`` sample times, increasing.
        x_m: ``(K,)`` positions x (map frame).
        y_m: ``(K,)`` positions y.

    Returns:
        The fit, or ``None`` with fewer than :data:`MIN_SAMPLES` samples or a span shorter
        than :data:`MIN_SPAN_NS`.
    """
    if t_ns.size < MIN_SAMPLES or int(t_ns[-1] - t_ns[0]) < MIN_SPAN_NS:
        return None
    tau = ns_to_s(t_ns - t_ns[0])
    mid = 0.5 * float(tau[-1])
    tau = tau - mid
    design = np.column_stack((np.ones_like(tau), tau, 0.5 * tau * tau))
    coef, *_ = np.linalg.lstsq(design, np.column_stack((x_m, y_m)), rcond=None)
    v_mid, accel = coef[1], coef[2]
    speed = float(np.hypot(*v_mid))
    along = float(np.dot(accel, v_mid) / speed) if speed > 0.0 else 0.0
    return FittedMotion(
        accel_mps2=along,
        speed_start_mps=max(0.0, speed - along * mid),
        speed_end_mps=max(0.0, speed + along * mid),
        span_s=2.0 * mid,
    )


class ComplianceTracker:
    """Keeps the last :data:`FIT_WINDOW_NS` of positions and the runs of duties."""

    def __init__(self, params: RssParams) -> None:
        """Start with no history (a fresh replay)."""
        self._params = params
        self._frames: collections.deque[
            tuple[int, float, float, NDArray[np.str_], NDArray[np.float64], NDArray[np.float64]]
        ]
        self._frames = collections.deque()
        self._since: dict[tuple[str, Responsible], int] = {}

    def _push(self, frame: Frame) -> None:
        actors = frame.actors
        x = np.where(actors.valid, actors.x_m, np.nan)
        y = np.where(actors.valid, actors.y_m, np.nan)
        self._frames.append((frame.t_ns, frame.ego.x_m, frame.ego.y_m, actors.ids, x, y))
        while self._frames and self._frames[0][0] < frame.t_ns - FIT_WINDOW_NS:
            self._frames.popleft()

    def _positions(
        self, label: str | None, from_ns: int
    ) -> tuple[NDArray[np.int64], NDArray[np.float64], NDArray[np.float64]]:
        """Times and positions of the ego (``None``) or an object from ``from_ns`` on."""
        times: list[int] = []
        xs: list[float] = []
        ys: list[float] = []
        for t_ns, ego_x, ego_y, ids, x, y in self._frames:
            if t_ns < from_ns:
                continue
            if label is None:
                times.append(t_ns)
                xs.append(ego_x)
                ys.append(ego_y)
                continue
            rows = np.flatnonzero(ids == label)
            if rows.size and np.isfinite(x[rows[0]]):
                times.append(t_ns)
                xs.append(float(x[rows[0]]))
                ys.append(float(y[rows[0]]))
        return (
            np.asarray(times, dtype=np.int64),
            np.asarray(xs, dtype=np.float64),
            np.asarray(ys, dtype=np.float64),
        )

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
            if party is Responsible.EGO:
                dyn = self._params.for_class(ObjectClass.EGO)
            else:
                code = classes.get(label)
                cls = ObjectClass.UNKNOWN if code is None else dynamics_class(FrameClass(code))
                dyn = self._params.for_class(cls)
            since = self._since[(label, party)]
            due = since + s_to_ns(dyn.response_time_s)
            required = (
                dyn.brake_min_mps2
                if response == _BRAKE_MIN
                else dyn.brake_min_correct_mps2
                if response == _BRAKE_MIN_CORRECT
                else None
            )
            motion = fit_motion(*self._positions(None if party is Responsible.EGO else label, due))
            measured = None if motion is None else motion.accel_mps2
            shortfall = None
            if required is not None and motion is not None and frame.t_ns >= due:
                shortfall = shortfall_of(motion, required)
            out.append((label, Obligation(party, since, due, required, measured, shortfall)))
        return tuple(out)


def shortfall_of(motion: FittedMotion, required_mps2: float) -> float:
    """``max(0, measured - required)``; a party may stop instead of braking (0 at standstill)."""
    if motion.speed_end_mps < STOPPED_MPS:
        return 0.0
    reachable = max(required_mps2, -motion.speed_start_mps / motion.span_s)
    return max(0.0, motion.accel_mps2 - reachable)


def _duties(verdict: RssVerdict) -> dict[tuple[str, Responsible], int]:
    """The duties of a frame: ``(label, party)`` to the most severe longitudinal response.

    Every party that must act in some constellation of the frame is listed.
    """
    result = verdict.result
    if result is None or result.responsibility is None:
        return {}
    side = result.responsibility
    ego_lon = result.states.lon_response.tolist()
    obj_lon = side.object_states.lon_response.tolist()
    out: dict[tuple[str, Responsible], int] = {}
    for k, label in enumerate(verdict.labels):
        if label.startswith("road_boundary"):
            continue
        if side.ego_must_act[k]:
            ego = (label, Responsible.EGO)
            out[ego] = max(out.get(ego, 0), ego_lon[k])
        if side.object_must_act[k]:
            obj = (label, Responsible.OBJECT)
            out[obj] = max(out.get(obj, 0), obj_lon[k])
    return out
