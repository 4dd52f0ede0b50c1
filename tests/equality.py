"""Deep equality of engine outputs for "batched path equals step by step" tests."""

from __future__ import annotations

import dataclasses
from typing import Any

import numpy as np

__all__ = ["assert_same"]


def assert_same(got: Any, expected: Any, where: str = "") -> None:
    """Deep equality of dataclasses, tuples, dicts and arrays (NaN equals NaN)."""
    if isinstance(expected, np.ndarray):
        assert isinstance(got, np.ndarray), where
        assert got.dtype == expected.dtype, where
        assert got.shape == expected.shape, where
        assert np.array_equal(got, expected, equal_nan=expected.dtype.kind == "f"), where
    elif dataclasses.is_dataclass(expected) and not isinstance(expected, type):
        assert type(got) is type(expected), where
        for f in dataclasses.fields(expected):
            assert_same(getattr(got, f.name), getattr(expected, f.name), f"{where}.{f.name}")
    elif isinstance(expected, (tuple, list)):
        assert isinstance(got, type(expected)), where
        assert len(got) == len(expected), where
        for k, (g, e) in enumerate(zip(got, expected, strict=True)):
            assert_same(g, e, f"{where}[{k}]")
    elif isinstance(expected, dict):
        assert got.keys() == expected.keys(), where
        for key, value in expected.items():
            assert_same(got[key], value, f"{where}[{key!r}]")
    else:
        assert got == expected, where
