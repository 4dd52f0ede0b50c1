"""The one ns <-> s conversion keeps the arithmetic of the inline expressions it replaced."""

from __future__ import annotations

import numpy as np

from loaders.timebase import NS_PER_S, ns_to_s, s_to_ns


def test_ns_to_s_divides_by_1e9_for_numbers_and_arrays():
    stamps = [0, 1, 999_999_999, 1_700_000_000_050_000_000, -250_000_000]
    for t_ns in stamps:
        assert ns_to_s(t_ns) == t_ns / 1e9
    array = np.array(stamps, dtype=np.int64)
    got = ns_to_s(array)
    assert got.shape == array.shape
    assert np.array_equal(got, array / 1e9)
    assert NS_PER_S == 10**9


def test_s_to_ns_rounds_to_the_nearest_integer_nanosecond():
    for t_s in (0.0, 0.1, 2.5, 1e-9, 4.0000000005, -0.3):
        value = s_to_ns(t_s)
        assert isinstance(value, int)
        assert value == round(t_s * 1e9)
        assert abs(value - t_s * 1e9) <= 0.5
    assert s_to_ns(ns_to_s(123_456_789)) == 123_456_789
