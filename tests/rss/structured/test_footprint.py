"""Footprint kernels against plain numpy formulations (lane lookup, tolerant reductions)."""

import numpy as np
import pytest

from rss.structured.footprint import _MIN_MAX_SIGN, _find_lanes, _merge, _reduce


@pytest.mark.parametrize("seed", [0, 5, 99])
def test_find_lanes_is_the_first_match(seed):
    rng = np.random.default_rng(seed)
    table = rng.integers(-1, 6, size=(40, 7))  # (C, W), duplicates and -1 included
    lane = rng.integers(-1, 6, size=(40, 3))  # (C, K)
    match = (table[:, None, :] == lane[:, :, None]) & (lane >= 0)[:, :, None]
    hit, idx = _find_lanes(lane, np.ascontiguousarray(table.T))
    assert hit.tolist() == match.any(axis=2).tolist()
    assert idx.tolist() == match.argmax(axis=2).tolist()


def test_reduce_is_a_tolerant_running_min_max_with_nan_to_num():
    rng = np.random.default_rng(3)
    values = rng.choice([0.0, 1.0, 1.0005, 2.0, np.inf, -np.inf, np.nan], size=(2, 30, 4, 3))
    valid = rng.random((30, 4, 3)) < 0.6
    with np.errstate(invalid="ignore"):  # inf - inf
        got = _reduce(values, valid)
        merged = _merge(values.reshape(2, 120, 3), valid.reshape(120, 3), _MIN_MAX_SIGN)
    want = np.nan_to_num(merged, nan=0.0).reshape(2, 30, 4)
    assert got.tobytes() == want.tobytes()
    # the running min keeps the first value unless a later one is 1 mm smaller
    first = np.array([[[[1.0005, 1.0, 0.0]]], [[[1.0, 1.0005, 2.0]]]])
    assert _reduce(first, np.ones((1, 1, 3), dtype=bool)).ravel().tolist() == [0.0, 2.0]
    close = np.array([[[[1.0005, 1.0]]], [[[1.0, 1.0005]]]])
    assert _reduce(close, np.ones((1, 1, 2), dtype=bool)).ravel().tolist() == [1.0005, 1.0]
