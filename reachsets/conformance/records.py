"""The per-case records of the reach-set case format (``docs/reachset-cases.md``).

JSON numbers are rounded to 1e-6; nothing non-finite reaches a record (the parser rejects
non-finite inputs and the engine's times and outlines are finite).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np
import shapely

if TYPE_CHECKING:
    from collections.abc import Callable, Mapping

    from numpy.typing import NDArray

    from reachsets.engine import ReachResult
    from reachsets.reduce import CellRings

__all__ = ["check_expected", "result_record", "set_outlines"]

#: Decimals of every number in a record (1e-6 m, 1e-6 s).
DECIMALS = 6
#: Tolerance of an expected ``t_offset_s``.
T_TOLERANCE_S = 1e-6
#: Rounded grid stamps by the grid's bytes (a document's cases share a few grids).
_TIMES: dict[bytes, list[float]] = {}
_TIMES_MAX = 64


def set_outlines(result: ReachResult, name: Callable[[str], str]) -> dict[str, Any]:
    """The reduced sets as outlines, the reference's ``rrese_<object>_<t>`` equivalent.

    Each checked object gets one entry per grid stamp: the exterior rings of the parts of
    its reduced set (``[]`` where nothing is left), each ring closed and written as the
    reference writes an outline, ``[[x0, x1, ...], [y0, y1, ...]]``. Where every set of the
    frame is the clipper's rings as they are (``ReachResult.rings``, the common case) the
    outlines are read from those points, else taken apart from the shapely geometries: the
    same points either way (``tests/reachsets/conformance/test_fast_paths.py``).

    Args:
        result: A full-geometry result (``ReachParams.full_geometry``).
        name: Maps the engine's object ids to the document's.

    Returns:
        ``{"t_s": [...], "objects": [{"object_id": ..., "outlines": [[ring, ...], ...]}]}``.
    """
    steps = len(result.occupancy.t_s)
    rings = result.rings
    if rings is not None and rings.cells.exact[rings.start : rings.stop].all():
        cells = _ring_outlines(rings.cells, rings.start, rings.stop)
    else:
        cells = _geometry_outlines(result.reach_sets.reshape(-1))
    objects = [
        {"object_id": name(i), "outlines": cells[k * steps : (k + 1) * steps]}
        for k, i in enumerate(result.object_ids.tolist())
    ]
    return {"t_s": _times(result.occupancy.t_s), "objects": objects}


def _times(t_s: NDArray[np.float64]) -> list[float]:
    """The grid stamps rounded to 1e-6 (Python's ``round``), remembered per grid."""
    key = t_s.tobytes()
    times = _TIMES.get(key)
    if times is None:
        if len(_TIMES) >= _TIMES_MAX:
            _TIMES.clear()
        times = _TIMES[key] = [round(t, DECIMALS) for t in t_s.tolist()]
    return list(times)  # the record's own list


def _ring_outlines(rings: CellRings, start: int, stop: int) -> list[list[list[list[float]]]]:
    """Per cell ``start:stop`` its rings as ``[xs, ys]``, read from the clipper's points."""
    first = rings.first[start : stop + 1]
    r0, r1 = int(first[0]), int(first[-1])
    ends = rings.ends[r0 : r1 + 1]
    p0 = int(ends[0])
    coords = np.round(rings.xy[p0 : int(ends[-1])], DECIMALS)
    return _split(coords, (ends[1:] - p0).tolist(), (first[1:] - r0).tolist())


def _geometry_outlines(flat: NDArray[np.object_]) -> list[list[list[list[float]]]]:
    """Per cell of ``flat`` (shapely geometries or ``None``) its parts' exterior rings."""
    parts, owner = shapely.get_parts(flat, return_index=True)
    rings = shapely.get_exterior_ring(parts)
    coords = np.round(shapely.get_coordinates(rings), DECIMALS)
    ends = np.cumsum(shapely.get_num_coordinates(rings)).tolist()
    # parts come cell by cell, in cell order: each cell's rings are one slice
    last = np.cumsum(np.bincount(owner, minlength=flat.size)).tolist()
    return _split(coords, ends, last)


def _split(
    coords: NDArray[np.float64], ends: list[int], last: list[int]
) -> list[list[list[list[float]]]]:
    """Rounded points ``(P, 2)`` as rings ``[xs, ys]`` grouped by cell.

    ``ends``: each ring's end point; ``last``: each cell's end ring.
    """
    xs, ys = coords[:, 0].tolist(), coords[:, 1].tolist()
    per_ring = [[xs[a:b], ys[a:b]] for a, b in zip([0, *ends], ends, strict=False)]
    return [per_ring[a:b] for a, b in zip([0, *last], last, strict=False)]


def result_record(
    result: ReachResult, name: Callable[[str], str], *, full_sets: bool
) -> dict[str, Any]:
    """The verdict keys of one frame's record.

    Args:
        result: The engine's result of the frame.
        name: Maps the engine's object ids to the document's.
        full_sets: Add the reduced sets' outlines (``sets``).

    Returns:
        ``safe``, ``collisions``, ``checked_objects``, ``checked_ids``, ``skipped_ids``,
        ``patches`` (and ``sets``).
    """
    record: dict[str, Any] = {
        "safe": bool(result.is_safe),
        "collisions": [
            {
                "object_id": name(c.object_id),
                "t_offset_s": round(c.t_offset_s, DECIMALS),
                "step": c.step,
            }
            for c in result.collisions
        ],
        "checked_objects": len(result.object_ids),
        "checked_ids": [name(str(i)) for i in result.object_ids],
        "skipped_ids": [name(i) for i in result.skipped_ids],
        "patches": [
            {"object_id": name(p.object_id), "rule": p.rule, "step": p.step} for p in result.patches
        ],
    }
    if full_sets:
        record["sets"] = set_outlines(result, name)
    return record


def check_expected(record: Mapping[str, Any], expected: Mapping[str, Any]) -> dict[str, Any]:
    """Compare a record with its ``expected`` block.

    ``safe`` is compared as is; ``object_id``, ``t_offset_s`` (within 1e-6 s) and ``step``
    with the first collision (earliest step, then object order).

    Returns:
        ``{"passed": bool, "failures": ["<key>: got ..., expected ...", ...]}``.
    """
    failures = []
    if "safe" in expected and record["safe"] != expected["safe"]:
        failures.append(f"safe: got {record['safe']!r}, expected {expected['safe']!r}")
    wanted = [k for k in ("object_id", "t_offset_s", "step") if k in expected]
    collisions = record["collisions"]
    if wanted and not collisions:
        failures.append(f"{', '.join(wanted)}: no collision")
    elif wanted:
        first = min(collisions, key=lambda c: c["step"])
        for key in wanted:
            got, want = first[key], expected[key]
            same = (
                math.isclose(got, want, rel_tol=0.0, abs_tol=T_TOLERANCE_S)
                if key == "t_offset_s"
                else str(got) == str(want)
            )
            if not same:
                failures.append(f"first collision {key}: got {got!r}, expected {want!r}")
    return {"passed": not failures, "failures": failures}
