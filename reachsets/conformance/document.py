"""Evaluate a reach-set case document into records (``docs/reachset-cases.md``).

Pure: the CLI reads the file and prints one JSON line per record. Start-up
(:func:`prepare_document`: the defaults and the shared track, built once) is separate from
the per-case work (:func:`evaluate_cases`: parse, evaluate, records), so a benchmark can
time the cases alone.

Independent cases of one method are evaluated together, as the drive pipeline batches
frames: one ``evaluate_frames`` call over up to :data:`BATCH_CASES` of them, each case a
frame whose object ids are made unique (``<k>/<id>``), so no rule memory passes from one
case to another and each case is rated as if alone (tested against one call per case). A
sequence is one ``evaluate_frames`` call over its steps, the memory carried from step to step.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from reachsets.conformance.cases import CaseDefaults, ParsedCase, parse_case, parse_defaults
from reachsets.conformance.errors import ReachCaseError
from reachsets.conformance.records import check_expected, result_record
from reachsets.engine import evaluate_frames
from reachsets.errors import ReachSetError
from reachsets.inputs import ObjectStates

if TYPE_CHECKING:
    from collections.abc import Iterator, Mapping, Sequence

    from reachsets.conformance.cases import ParsedStep
    from reachsets.engine import ReachResult
    from reachsets.inputs import ReachInputs

__all__ = [
    "BATCH_CASES",
    "PreparedDocument",
    "evaluate_cases",
    "evaluate_document",
    "prepare_document",
    "unique_ids",
]

#: Independent cases evaluated in one engine call.
BATCH_CASES = 64


@dataclass(frozen=True)
class PreparedDocument:
    """A document after start-up: its defaults (track built) and its raw cases.

    Attributes:
        defaults: Shared settings and the prepared track.
        cases: The ``cases`` list as read (parsed one by one by :func:`evaluate_cases`).
        full_sets: The records carry the reduced sets' outlines.
    """

    defaults: CaseDefaults
    cases: Sequence[Any]
    full_sets: bool


def prepare_document(
    document: object, source: str = "<document>", *, full_sets: bool = False
) -> PreparedDocument:
    """Start-up: read the defaults and prepare the shared track once.

    Args:
        document: The parsed JSON document.
        source: Its name, for messages.
        full_sets: Reduce every set and write the outlines (else verdict only).

    Raises:
        ReachCaseError: No ``cases`` list, or malformed ``defaults``.
    """
    if not isinstance(document, dict):
        kind = type(document).__name__
        raise ReachCaseError(source, "<document>", "document", kind, "expected a JSON object")
    cases = document.get("cases")
    if not isinstance(cases, list):
        raise ReachCaseError(source, "<document>", "cases", cases, "expected a list of cases")
    defaults = parse_defaults(document, source, full_sets=full_sets)
    return PreparedDocument(defaults, cases, full_sets)


def unique_ids(inputs: ReachInputs, prefix: str) -> ReachInputs:
    """``inputs`` with every object id prefixed (no memory is shared with another case).

    Args:
        inputs: One case's frame.
        prefix: Its prefix within the engine call, e.g. ``"3/"``.
    """
    objects = inputs.objects
    columns = {f.name: getattr(objects, f.name) for f in dataclasses.fields(objects)}
    ids = np.array([f"{prefix}{i}" for i in objects.ids.tolist()], dtype=np.str_)
    ids.flags.writeable = False
    columns["ids"] = ids
    # the columns are the checked object's (read-only): shared, no second validation
    return dataclasses.replace(inputs, objects=ObjectStates.of_frozen(columns))


def _record(
    case: ParsedCase, index: int, result: ReachResult, prefix: str, *, full_sets: bool
) -> dict[str, Any]:
    """The record of step ``index`` of ``case``."""
    record: dict[str, Any] = {"id": case.case_id}
    if case.is_sequence:
        record = {
            "id": f"{case.case_id}#{index}",
            "sequence_id": case.case_id,
            "step": index,
        }
    cut = len(prefix)
    record |= {"ok": True, "method": case.method.value}
    record |= result_record(result, lambda i: i[cut:], full_sets=full_sets)
    step: ParsedStep = case.steps[index]
    if step.expected is not None:
        record["expected_check"] = check_expected(record, step.expected)
    return record


def _failed(case_id: str, err: Exception) -> dict[str, Any]:
    return {"id": case_id, "ok": False, "error": str(err)}


def _alone(case: ParsedCase, prepared: PreparedDocument) -> list[dict[str, Any]]:
    """The records of one case (or sequence) from its own ``evaluate_frames`` call."""
    params = prepared.defaults.params[case.method]
    try:
        results, _ = evaluate_frames(
            [s.inputs for s in case.steps], params, prepared.defaults.start
        )
    except ReachSetError as err:
        return [_failed(case.case_id, err)]
    return [_record(case, k, r, "", full_sets=prepared.full_sets) for k, r in enumerate(results)]


def _together(cases: Sequence[ParsedCase], prepared: PreparedDocument) -> dict[int, dict[str, Any]]:
    """Records of independent one-step cases of one method from one engine call (by ``id``).

    A chunk the engine rejects is left to :func:`_alone` (empty answer), which reports the
    error of the one case that caused it.
    """
    if len(cases) < 2:  # noqa: PLR2004
        return {}
    params = prepared.defaults.params[cases[0].method]
    prefixes = [f"{k}/" for k in range(len(cases))]
    inputs = [unique_ids(c.steps[0].inputs, p) for c, p in zip(cases, prefixes, strict=True)]
    try:
        results, _ = evaluate_frames(inputs, params, prepared.defaults.start)
    except ReachSetError:
        return {}
    return {
        id(c): _record(c, 0, r, p, full_sets=prepared.full_sets)
        for c, r, p in zip(cases, results, prefixes, strict=True)
    }


def _chunk(
    cases: Sequence[Any], first: int, prepared: PreparedDocument
) -> Iterator[dict[str, Any]]:
    """The records of consecutive cases, their independent cases batched by method."""
    items: list[ParsedCase | dict[str, Any]] = []
    for index, raw in enumerate(cases, start=first):
        try:
            items.append(parse_case(raw, prepared.defaults, index))
        except ReachCaseError as err:
            items.append(_failed(err.case_id, err))
    single = [p for p in items if isinstance(p, ParsedCase) and not p.is_sequence]
    done: dict[int, dict[str, Any]] = {}
    for method in sorted({p.method for p in single}):
        done |= _together([p for p in single if p.method is method], prepared)
    for item in items:
        if isinstance(item, dict):
            yield item
        elif id(item) in done:
            yield done[id(item)]
        else:
            yield from _alone(item, prepared)


def evaluate_cases(prepared: PreparedDocument) -> Iterator[dict[str, Any]]:
    """Yield one record per case and per sequence step, in document order.

    A malformed case yields ``ok: false`` with its one-line error and the run continues.
    """
    cases = prepared.cases
    for first in range(0, len(cases), BATCH_CASES):
        yield from _chunk(cases[first : first + BATCH_CASES], first, prepared)


def evaluate_document(
    document: Mapping[str, Any] | object, source: str = "<document>", *, full_sets: bool = False
) -> Iterator[dict[str, Any]]:
    """:func:`prepare_document` then :func:`evaluate_cases`.

    Raises:
        ReachCaseError: The document itself is malformed (before any record).
    """
    prepared = prepare_document(document, source, full_sets=full_sets)
    return evaluate_cases(prepared)
