"""Evaluate a conformance case file into the records of ``conformance/rss-cases-format.md``.

Pure: the CLI does the file I/O and prints one JSON line per record.
"""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING, Any

import numpy as np

from rss.conformance.cases import (
    OTHER_ID,
    CaseDefaults,
    ParsedCase,
    other_dynamics_for,
    parse_case,
    parse_defaults,
)
from rss.conformance.records import frame_record, json_number
from rss.conformance.unstructured import unstructured_record, unstructured_records
from rss.errors import RssCaseError, RssError
from rss.model import ObjectType
from rss.physics import stated_braking_longitudinal, stopping_distance
from rss.structured.batch import stack_dynamics
from rss.structured.engine import check_frame, check_frames
from rss.structured.formulas import (
    safe_lateral_distance,
    safe_longitudinal_distance_opposite,
    safe_longitudinal_distance_same,
)
from rss.structured.memory import RssMemory
from rss.structured.stacking import stack_constellations
from rss.structured.states import InvalidReason

if TYPE_CHECKING:
    from collections.abc import Iterator, Mapping, Sequence

    from rss.structured.batch import ConstellationBatch
    from rss.structured.engine import FrameResult
    from rss.unstructured.memory import UnstructuredMemory

__all__ = [
    "BATCH_CASES",
    "BATCH_MIN_CASES",
    "check_expected",
    "evaluate_document",
    "evaluate_formula",
    "structured_record",
]

#: Cases read (and independent structured cases batched) at a time.
BATCH_CASES = 1024
#: Independent structured cases from which a chunk's are batched (fewer: one by one).
BATCH_MIN_CASES = 8
#: Renumbered ego ids of batched cases (never the other's id :data:`OTHER_ID`).
FIRST_EGO_ID = OTHER_ID + 1
#: Tolerance of list-valued expectations (e.g. acceleration ranges).
_LIST_TOLERANCE = 1e-5
#: An expected ``[value, tol]`` pair.
_VALUE_AND_TOLERANCE = 2


def _formula_object(
    case_id: str, obj: Mapping[str, Any], defaults: CaseDefaults
) -> tuple[Any, dict[str, float]]:
    if not isinstance(obj, dict):
        raise RssCaseError(case_id, "formula objects must be JSON objects")
    try:
        dyn = other_dynamics_for(defaults, ObjectType.OtherVehicle).with_overrides(
            obj.get("dynamics", {})
        )
    except RssError as err:
        raise RssCaseError(case_id, str(err)) from err
    speeds = {}
    for name in ("v_lon", "v_lat"):
        low = obj.get(name, obj.get(f"{name}_min", 0.0))
        high = obj.get(name, obj.get(f"{name}_max", 0.0))
        speeds[f"{name}_min"], speeds[f"{name}_max"] = (
            _as_float(case_id, low),
            _as_float(case_id, high),
        )
    return stack_dynamics([dyn]), speeds


def _as_float(case_id: str, value: object) -> float:
    if not isinstance(value, int | float) or isinstance(value, bool):
        raise RssCaseError(case_id, f"expected a number, got {value!r}")
    return float(value)


def evaluate_formula(case: Mapping[str, Any], defaults: CaseDefaults, case_id: str) -> float:
    """Value of a ``kind: formula`` case.

    Raises:
        RssCaseError: Unknown function or malformed arguments.
    """
    function = case.get("function")
    arr = np.array

    def arg(key: str) -> Any:
        if key not in case:
            raise RssCaseError(case_id, f"formula {function!r} needs {key!r}")
        return arr([float(case[key])])

    if function == "stated_braking_lon":
        value = stated_braking_longitudinal(
            arg("speed"),
            arg("max_speed_on_acceleration"),
            arg("response_time"),
            arg("accel"),
            arg("decel"),
        )
    elif function == "stopping_distance":
        value = stopping_distance(arg("speed"), arg("decel"))
    elif function in {"lon_same_direction", "lon_opposite_direction", "lateral"}:
        names = {
            "lon_same_direction": ("following", "leading"),
            "lon_opposite_direction": ("correct", "opposite"),
            "lateral": ("left", "right"),
        }[function]
        (d_a, v_a), (d_b, v_b) = (
            _formula_object(case_id, case.get(n, {}), defaults) for n in names
        )
        if function == "lon_same_direction":
            value = safe_longitudinal_distance_same(
                d_a, arr([v_a["v_lon_max"]]), d_b, arr([v_b["v_lon_min"]])
            )
        elif function == "lon_opposite_direction":
            value = safe_longitudinal_distance_opposite(
                d_a, arr([v_a["v_lon_max"]]), d_b, arr([v_b["v_lon_max"]])
            )
        else:
            value = safe_lateral_distance(
                d_a, arr([v_a["v_lat_max"]]), d_b, arr([v_b["v_lat_min"]])
            )
    else:
        raise RssCaseError(case_id, f"unknown formula function {function!r}")
    return float(np.asarray(value).reshape(-1)[0])


def _resolve_path(record: Mapping[str, Any], path: str) -> Any:
    node: Any = record
    for part in path.split("."):
        if isinstance(node, list) and part.isdigit() and int(part) < len(node):
            node = node[int(part)]
        elif isinstance(node, dict) and part in node:
            node = node[part]
        else:
            raise KeyError(path)
    return node


def _matches(actual: Any, expected: Any) -> bool:
    if isinstance(actual, list) and isinstance(expected, list):
        return len(actual) == len(expected) and all(
            _matches(a, e)
            if not isinstance(a, int | float) or isinstance(a, bool)
            else a is not None and abs(a - e) <= _LIST_TOLERANCE
            for a, e in zip(actual, expected, strict=True)
        )
    if (
        isinstance(expected, list)
        and len(expected) == _VALUE_AND_TOLERANCE
        and isinstance(actual, int | float)
        and not isinstance(actual, bool)
    ):
        return bool(abs(actual - expected[0]) <= expected[1])
    return bool(actual == expected)


def check_expected(record: Mapping[str, Any], expected: Mapping[str, Any]) -> dict[str, Any]:
    """Compare a record against ``expected`` dotted paths (``[value, tol]`` = tolerance)."""
    failures = []
    for path, want in expected.items():
        try:
            got = _resolve_path(record, path)
        except KeyError:
            failures.append(f"{path}: missing (expected {want!r})")
            continue
        if not _matches(got, want):
            failures.append(f"{path}: got {got!r}, expected {want!r}")
    return {"passed": not failures, "failures": failures}


def _evaluate(
    parsed: ParsedCase,
    defaults: CaseDefaults,
    memory: RssMemory,
    unstructured: UnstructuredMemory | None = None,
) -> tuple[dict[str, Any], RssMemory, UnstructuredMemory | None]:
    record: dict[str, Any] = {"id": parsed.case_id, "kind": parsed.kind}
    if parsed.sequence_id is not None:
        record |= {"sequence_id": parsed.sequence_id, "step": parsed.step}
    if parsed.kind == "unstructured":
        values, unstructured = unstructured_record(
            parsed.raw, defaults, parsed.case_id, unstructured, json_number
        )
        record |= values
    elif parsed.kind == "formula":
        record |= {
            "ok": True,
            "value": json_number(evaluate_formula(parsed.raw, defaults, parsed.case_id)),
        }
    else:
        assert parsed.constellation is not None
        try:
            batch = stack_constellations([parsed.constellation])
        except RssError as err:
            return record | {"ok": False, "error": str(err)}, memory, unstructured
        result, memory = check_frame(batch, parsed.default_ego, memory)
        return structured_record(parsed, result, batch, 0), memory, unstructured
    return _with_check(record, parsed), memory, unstructured


def _with_check(record: dict[str, Any], parsed: ParsedCase) -> dict[str, Any]:
    if parsed.expected:
        record["expected_check"] = check_expected(record, parsed.expected)
    return record


def structured_record(
    parsed: ParsedCase, result: FrameResult, batch: ConstellationBatch, index: int
) -> dict[str, Any]:
    """The record of a structured case evaluated as frame ``index`` of ``result``."""
    assert parsed.constellation is not None
    record: dict[str, Any] = {"id": parsed.case_id, "kind": parsed.kind}
    if parsed.sequence_id is not None:
        record |= {"sequence_id": parsed.sequence_id, "step": parsed.step}
    record |= {"ok": True, "constellation_type": parsed.constellation.constellation_type.name}
    record |= frame_record(result, batch, index)
    invalid = result.invalid[result.frame == index]
    if invalid.any():
        record |= {"ok": False, "error": f"invalid input: {InvalidReason(int(invalid[0])).name}"}
    return _with_check(record, parsed)


def _batched(parsed: Sequence[ParsedCase]) -> dict[int, dict[str, Any]]:
    """Records of independent structured cases from one batched engine call (``id(case)``).

    Each case is its own frame, its ego renumbered (:data:`FIRST_EGO_ID` on) so that no
    memory key meets another case's: every case starts with a fresh memory, as evaluated
    alone. Fewer than :data:`BATCH_MIN_CASES` cases, or one the stacking rejects, are left
    to the per-case path (empty answer), which reports the error of that case alone.
    """
    if len(parsed) < BATCH_MIN_CASES:
        return {}
    constellations = []
    for k, case in enumerate(parsed):
        c = case.constellation
        assert c is not None
        ego = dataclasses.replace(c.ego, object_id=FIRST_EGO_ID + k)
        constellations.append(dataclasses.replace(c, ego=ego))
    try:
        batch = stack_constellations(constellations)
    except RssError:
        return {}
    count = len(parsed)
    result, _ = check_frames(batch, np.arange(count), count, parsed[0].default_ego)
    return {id(case): structured_record(case, result, batch, k) for k, case in enumerate(parsed)}


def _batched_unstructured(
    parsed: Sequence[ParsedCase], defaults: CaseDefaults
) -> dict[int, dict[str, Any]]:
    """Records of independent unstructured cases from one batched engine call (``id(case)``).

    :func:`rss.conformance.unstructured.unstructured_records` (fresh memory per case);
    malformed cases, and fewer than :data:`BATCH_MIN_CASES`, are left to the per-case path.
    """
    if len(parsed) < BATCH_MIN_CASES:
        return {}
    values = unstructured_records([(p.raw, p.case_id) for p in parsed], defaults, json_number)
    out = {}
    for case, keys in zip(parsed, values, strict=True):
        if keys is not None:
            record: dict[str, Any] = {"id": case.case_id, "kind": case.kind}
            out[id(case)] = _with_check(record | keys, case)
    return out


def _sequence(
    case: Mapping[str, Any], case_id: str, defaults: CaseDefaults
) -> Iterator[dict[str, Any]]:
    """The records of a sequence's steps, the memory carried from step to step."""
    memory = RssMemory.empty()
    unstructured: UnstructuredMemory | None = None
    for step, raw_step in enumerate(case.get("steps", [])):
        step_id = f"{case_id}#{step}"
        try:
            parsed = parse_case(raw_step, defaults, step_id, case_id, step)
            record, memory, unstructured = _evaluate(parsed, defaults, memory, unstructured)
        except RssError as err:
            record = {
                "id": step_id,
                "sequence_id": case_id,
                "step": step,
                "ok": False,
                "error": str(err),
            }
        yield record


def _chunk(cases: Sequence[Any], first: int, defaults: CaseDefaults) -> Iterator[dict[str, Any]]:
    """The records of consecutive cases; their independent structured cases batched."""
    items: list[tuple[str, Any, ParsedCase | dict[str, Any] | None]] = []
    for index, case in enumerate(cases, start=first):
        case_id = str(case.get("id", f"#{index}")) if isinstance(case, dict) else f"#{index}"
        if isinstance(case, dict) and case.get("kind") == "sequence":
            items.append((case_id, case, None))
            continue
        try:
            items.append((case_id, case, parse_case(case, defaults, case_id)))
        except RssError as err:
            kind = case.get("kind") if isinstance(case, dict) else None
            items.append(
                (case_id, case, {"id": case_id, "kind": kind, "ok": False, "error": str(err)})
            )
    batched = _batched(
        [p for _, _, p in items if isinstance(p, ParsedCase) and p.kind == "structured"]
    )
    batched |= _batched_unstructured(
        [p for _, _, p in items if isinstance(p, ParsedCase) and p.kind == "unstructured"],
        defaults,
    )
    for case_id, case, item in items:
        if item is None:
            yield from _sequence(case, case_id, defaults)
        elif isinstance(item, dict):
            yield item
        elif id(item) in batched:
            yield batched[id(item)]
        else:
            try:
                record, _, _ = _evaluate(item, defaults, RssMemory.empty())
            except RssError as err:
                record = {"id": case_id, "kind": item.kind, "ok": False, "error": str(err)}
            yield record


def evaluate_document(document: Mapping[str, Any]) -> Iterator[dict[str, Any]]:
    """Yield one record per case and per sequence step.

    A malformed case yields ``ok: false`` with its error and the run continues. Cases are
    read :data:`BATCH_CASES` at a time; the independent structured cases of each chunk are
    evaluated in one batched engine call, its independent unstructured cases in another
    (each case with a fresh memory, as the drive pipeline batches frames), sequences step
    by step with their memory; the records are the same and come in document order.

    Raises:
        RssCaseError: The document itself is malformed (no ``cases`` list).
        RssParameterError: Invalid ``defaults``.
    """
    cases = document.get("cases") if isinstance(document, dict) else None
    if not isinstance(cases, list):
        raise RssCaseError("<document>", "needs a 'cases' list")
    defaults = parse_defaults(document)
    for first in range(0, len(cases), BATCH_CASES):
        yield from _chunk(cases[first : first + BATCH_CASES], first, defaults)
