"""Read the reach-set case format (``docs/reachset-cases.md``) into engine inputs.

Pure: a parsed JSON document in, :class:`CaseDefaults` and :class:`ParsedCase` out. Every
malformed value raises :class:`~reachsets.conformance.errors.ReachCaseError` naming the
document, the case, the field and the value.
"""

from __future__ import annotations

import dataclasses
import itertools
import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from reachsets.conformance.errors import ReachCaseError
from reachsets.engine import RuleState
from reachsets.errors import ParamsError, ReachSetError
from reachsets.inputs import (
    REFERENCE_EGO_LENGTH_M,
    REFERENCE_EGO_WIDTH_M,
    EgoTrajectory,
    ObjectStates,
    ReachInputs,
    TrackBounds,
)
from reachsets.params import ReachMethod, ReachParams
from reachsets.track import build_track

if TYPE_CHECKING:
    from collections.abc import Mapping

__all__ = ["CaseDefaults", "ParsedCase", "ParsedStep", "parse_case", "parse_defaults"]

#: Keys of an ``expected`` block.
EXPECTED_KEYS = frozenset({"safe", "object_id", "t_offset_s", "step"})
#: ``ReachParams`` fields a document may not set (the command sets them).
_FIXED_PARAMS = frozenset({"method", "full_geometry"})
_EGO_ARRAYS = ("x", "y", "heading", "speed")
#: Keys allowed in a step (``time_s`` and ``note`` are informational), a case, an ego plan
#: and an object.
_STEP_KEYS = frozenset({"ego", "objects", "expected", "time_s", "note"})
_CASE_KEYS = _STEP_KEYS | {"id", "method", "sequence"}
_EGO_KEYS = frozenset({*_EGO_ARRAYS, "t_s", "length", "width"})
_OBJECT_KEYS = frozenset({"id", "x", "y", "yaw", "speed", "length", "width"})
#: ``ObjectStates`` fields, in the order ``_inputs`` builds them.
_OBJECT_FIELDS = ("ids", "x_m", "y_m", "yaw_rad", "speed_mps", "length_m", "width_m")
#: The element types of a list of floats only (the fast path of ``numbers``).
_FLOAT_ONLY = frozenset({float})


@dataclass(frozen=True)
class CaseDefaults:
    """What all cases of a document share, prepared once (the command's start-up).

    Attributes:
        source: The document's name, for messages.
        method: Method of a case that names none.
        params: Engine parameters per method (``full_geometry`` as the command asks).
        ego_length_m: Ego length of a case that gives none.
        ego_width_m: Ego width of a case that gives none.
        track: The track bounds shared by every case (``None``: no track).
        start: The rule state every case and sequence starts from: empty memory, the
            track's geometry already built.
    """

    source: str
    method: ReachMethod
    params: Mapping[ReachMethod, ReachParams]
    ego_length_m: float
    ego_width_m: float
    track: TrackBounds | None
    start: RuleState


@dataclass(frozen=True)
class ParsedStep:
    """One frame to evaluate: the engine inputs and the optional expectation.

    Attributes:
        inputs: Ego plan, objects and the shared track.
        expected: The ``expected`` block (keys of :data:`EXPECTED_KEYS`), or ``None``.
    """

    inputs: ReachInputs
    expected: Mapping[str, Any] | None


@dataclass(frozen=True)
class ParsedCase:
    """A case: one step, or the steps of a ``sequence`` sharing the rule memory.

    Attributes:
        case_id: The case's ``id``.
        method: Its method.
        steps: Its frames, in time order.
        is_sequence: Written as a ``sequence`` (its records carry ``sequence_id``/``step``).
    """

    case_id: str
    method: ReachMethod
    steps: tuple[ParsedStep, ...]
    is_sequence: bool


@dataclass(frozen=True)
class _Where:
    """Where a value sits (for messages)."""

    source: str
    case_id: str

    def error(self, field: str, value: object, reason: str) -> ReachCaseError:
        return ReachCaseError(self.source, self.case_id, field, value, reason)

    def number(self, field: str, value: object) -> float:
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise self.error(field, value, "expected a number")
        try:
            number = float(value)
        except OverflowError:
            number = math.inf
        if not math.isfinite(number):
            raise self.error(field, value, "expected a finite number")
        return number

    def size(self, field: str, value: object) -> float:
        size = self.number(field, value)
        if size <= 0:
            raise self.error(field, value, "expected a positive size")
        return size

    def numbers(self, field: str, value: object) -> list[float]:
        if not isinstance(value, list) or not value:
            raise self.error(field, value, "expected a non-empty list of numbers")
        if set(map(type, value)) == _FLOAT_ONLY and math.isfinite(sum(value)):
            return value  # the common case at once: a finite sum of floats has finite terms
        return [self.number(f"{field}.{k}", v) for k, v in enumerate(value)]

    def mapping(self, field: str, value: object) -> dict[str, Any]:
        if not isinstance(value, dict):
            raise self.error(field, value, "expected a JSON object")
        return value

    def points(self, field: str, value: object) -> list[list[float]]:
        if not isinstance(value, list) or len(value) < 2:  # noqa: PLR2004
            raise self.error(field, value, "expected a list of at least two [x, y] points")
        out = []
        for k, point in enumerate(value):
            if not isinstance(point, list) or len(point) != 2:  # noqa: PLR2004
                raise self.error(f"{field}.{k}", point, "expected an [x, y] point")
            out.append([self.number(f"{field}.{k}.{i}", c) for i, c in enumerate(point)])
        return out

    def known(self, field: str, value: dict[str, Any], keys: frozenset[str]) -> dict[str, Any]:
        for key, item in value.items():
            if key not in keys:
                dot = f"{field}." if field else ""
                raise self.error(f"{dot}{key}", item, f"unknown key ({', '.join(sorted(keys))})")
        return value

    def method(self, field: str, value: object) -> ReachMethod:
        try:
            return ReachMethod(str(value))
        except ValueError:
            names = ", ".join(m.value for m in ReachMethod)
            raise self.error(field, value, f"expected one of {names}") from None


def _typed(where: _Where, field: str, value: object, annotation: str) -> object:
    """``value`` checked against a ``ReachParams`` field's annotation."""
    if annotation == "bool":
        if not isinstance(value, bool):
            raise where.error(field, value, "expected true or false")
        return value
    if annotation == "int":
        if isinstance(value, bool) or not isinstance(value, int):
            raise where.error(field, value, "expected an integer")
        return value
    if annotation.startswith("tuple"):
        return tuple(where.numbers(field, value))
    return where.number(field, value)


def _overrides(where: _Where, target: Any, values: dict[str, Any], prefix: str) -> Any:
    """``target`` (a params dataclass) with the document's overrides."""
    known = {f.name: f for f in dataclasses.fields(target)}
    changes: dict[str, object] = {}
    for key, value in values.items():
        field = f"{prefix}.{key}"
        spec = known.get(key)
        if spec is None or (prefix == "params" and key in _FIXED_PARAMS):
            raise where.error(field, value, "not a settable ReachParams field")
        current = getattr(target, key)
        if dataclasses.is_dataclass(current):
            changes[key] = _overrides(where, current, where.mapping(field, value), field)
        else:
            changes[key] = _typed(where, field, value, str(spec.type))
    try:
        return dataclasses.replace(target, **changes)
    except ParamsError as err:
        raise where.error(f"{prefix}.{err.name}", err.value, str(err)) from err


def parse_defaults(
    document: Mapping[str, Any], source: str = "<document>", *, full_sets: bool = False
) -> CaseDefaults:
    """The document's shared settings, with the track prepared once.

    Args:
        document: The parsed JSON document.
        source: Its name, for messages (the CLI passes the file name).
        full_sets: Reduce every set (the records then carry the outlines); else verdict only.

    Raises:
        ReachCaseError: A malformed ``defaults`` block.
    """
    where = _Where(source, "<defaults>")
    raw = where.mapping("defaults", document.get("defaults", {}))
    unknown = set(raw) - {"method", "params", "ego", "track"}
    if unknown:
        key = min(unknown)
        raise where.error(key, raw[key], "unknown key (method, params, ego, track)")
    method = where.method("method", raw.get("method", ReachMethod.TURN.value))
    base = _overrides(
        where, ReachParams(), where.mapping("params", raw.get("params", {})), "params"
    )
    params = {m: dataclasses.replace(base, method=m, full_geometry=full_sets) for m in ReachMethod}
    ego = where.mapping("ego", raw.get("ego", {}))
    length = where.size("ego.length", ego.get("length", REFERENCE_EGO_LENGTH_M))
    width = where.size("ego.width", ego.get("width", REFERENCE_EGO_WIDTH_M))
    track = None
    start = RuleState()
    if "track" in raw:
        bounds = where.mapping("track", raw["track"])
        left = where.points("track.left", bounds.get("left"))
        right = where.points("track.right", bounds.get("right"))
        try:
            track = TrackBounds(left, right)  # type: ignore[arg-type]
            geometry = build_track(track, base.closed_track_gap_m)
        except (ReachSetError, ValueError) as err:
            raise where.error("track", getattr(err, "value", None), str(err)) from err
        start = RuleState(track_bounds=track, track=geometry)
    return CaseDefaults(source, method, params, length, width, track, start)


def _expected(where: _Where, field: str, value: object) -> dict[str, Any]:
    raw = where.mapping(field, value)
    for key, want in raw.items():
        if key not in EXPECTED_KEYS:
            raise where.error(f"{field}.{key}", want, f"expected one of {sorted(EXPECTED_KEYS)}")
    if "safe" in raw and not isinstance(raw["safe"], bool):
        raise where.error(f"{field}.safe", raw["safe"], "expected true or false")
    if "t_offset_s" in raw:
        where.number(f"{field}.t_offset_s", raw["t_offset_s"])
    step = raw.get("step", 0)
    if isinstance(step, bool) or not isinstance(step, int):
        raise where.error(f"{field}.step", step, "expected an integer")
    return raw


def _step(where: _Where, raw: object, field: str, defaults: CaseDefaults) -> ParsedStep:
    """One frame: ``ego``, ``objects`` and ``expected`` of a case or a sequence step."""
    step = where.known(
        field, where.mapping(field or "case", raw), _STEP_KEYS if field else _CASE_KEYS
    )
    dot = f"{field}." if field else ""
    ego = where.known(f"{dot}ego", where.mapping(f"{dot}ego", step.get("ego")), _EGO_KEYS)
    arrays = {k: where.numbers(f"{dot}ego.{k}", ego.get(k)) for k in _EGO_ARRAYS}
    count = len(arrays["x"])
    times = where.numbers(f"{dot}ego.t_s", ego["t_s"]) if "t_s" in ego else None
    if times is not None and any(b < a for a, b in itertools.pairwise(times)):
        raise where.error(f"{dot}ego.t_s", times, "expected non-decreasing times")
    for key, values in [*arrays.items(), ("t_s", times or arrays["x"])]:
        if len(values) != count:
            raise where.error(f"{dot}ego.{key}", values, f"expected {count} values (as ego.x)")
    raw_objects = step.get("objects", [])
    if not isinstance(raw_objects, list):
        raise where.error(f"{dot}objects", raw_objects, "expected a list of objects")
    columns: dict[str, list[Any]] = {k: [] for k in ("id", "x", "y", "yaw", "speed", "l", "w")}
    for k, value in enumerate(raw_objects):
        obj = where.mapping(f"{dot}objects.{k}", value)
        where.known(f"{dot}objects.{k}", obj, _OBJECT_KEYS)
        name = obj.get("id")
        if isinstance(name, bool) or not isinstance(name, str | int) or str(name) in columns["id"]:
            raise where.error(f"{dot}objects.{k}.id", name, "expected a unique string or integer")
        columns["id"].append(str(name))
        for key in ("x", "y", "yaw", "speed"):
            columns[key].append(where.number(f"{dot}objects.{k}.{key}", obj.get(key)))
        for key, short, default in (("length", "l", math.nan), ("width", "w", math.nan)):
            size = obj.get(key)
            columns[short].append(
                default if size is None else where.size(f"{dot}objects.{k}.{key}", size)
            )
    length = where.size(f"{dot}ego.length", ego.get("length", defaults.ego_length_m))
    width = where.size(f"{dot}ego.width", ego.get("width", defaults.ego_width_m))
    ego_rows = [arrays[k] for k in _EGO_ARRAYS]
    inputs = _inputs(ego_rows, times, (length, width), columns, defaults.track)
    expected = step.get("expected")
    return ParsedStep(
        inputs, None if expected is None else _expected(where, f"{dot}expected", expected)
    )


def _inputs(
    ego: list[list[float]],
    times: list[float] | None,
    size: tuple[float, float],
    columns: dict[str, list[Any]],
    track: TrackBounds | None,
) -> ReachInputs:
    """``reach_inputs_from_arrays`` of values ``_step`` has checked, without checking again.

    Every number is finite, the ego's lists have one length, sizes are positive or NaN
    (missing: the ego's). The arrays are the adapter's (same dtypes and values, read-only);
    ``tests/reachsets/conformance`` compares the two.

    Args:
        ego: The ego's x, y, heading and speed lists.
        times: Its ``t_s`` (``None``: from the speeds).
        size: The ego's length and width.
        columns: The objects' ``id``, ``x``, ``y``, ``yaw``, ``speed``, ``l``, ``w`` lists.
        track: The shared track bounds.
    """
    k = len(ego[0])
    block = np.array([*ego, [math.nan] * k if times is None else times], dtype=np.float64)
    block.flags.writeable = False
    x, y, yaw, speed, t = block
    trajectory = object.__new__(EgoTrajectory)
    for name, value in (("x_m", x), ("y_m", y), ("yaw_rad", yaw), ("speed_mps", speed)):
        object.__setattr__(trajectory, name, value)
    object.__setattr__(trajectory, "t_s", t)
    object.__setattr__(trajectory, "length_m", size[0])
    object.__setattr__(trajectory, "width_m", size[1])
    ids = columns["id"]
    rows = np.array([columns[c] for c in ("x", "y", "yaw", "speed", "l", "w")], dtype=np.float64)
    rows = rows.reshape(6, len(ids))
    rows[3] = np.clip(rows[3], 0.0, None)  # as ObjectStates: negative speeds read as 0
    for row, default in ((4, size[0]), (5, size[1])):
        rows[row] = np.where(np.isnan(rows[row]), default, rows[row])
    names = np.array(ids, dtype=np.str_) if ids else np.zeros(0, "<U1")
    names.flags.writeable = False
    rows.flags.writeable = False
    objects = ObjectStates.of_frozen(dict(zip(_OBJECT_FIELDS, [names, *rows], strict=True)))
    return ReachInputs(ego=trajectory, objects=objects, track=track)


def parse_case(raw: object, defaults: CaseDefaults, index: int) -> ParsedCase:
    """Read case number ``index`` of the document.

    Raises:
        ReachCaseError: A malformed case (the message names the field and value).
    """
    fallback = f"#{index}"
    case_id = str(raw.get("id", fallback)) if isinstance(raw, dict) else fallback
    where = _Where(defaults.source, case_id)
    case = where.known("", where.mapping("case", raw), _CASE_KEYS)
    method = where.method("method", case.get("method", defaults.method.value))
    if "sequence" not in case:
        return ParsedCase(case_id, method, (_step(where, case, "", defaults),), is_sequence=False)
    steps = case["sequence"]
    if not isinstance(steps, list) or not steps:
        raise where.error("sequence", steps, "expected a non-empty list of steps")
    parsed = tuple(_step(where, s, f"sequence.{k}", defaults) for k, s in enumerate(steps))
    return ParsedCase(case_id, method, parsed, is_sequence=True)
