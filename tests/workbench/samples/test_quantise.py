"""Rounding of written floats to fixed grids (machine-independent sample files)."""

from __future__ import annotations

import numpy as np

from workbench.samples.quantise import (
    ANGLE_STEPS,
    quantise,
    quantise_array,
    quantise_field,
)


def test_rounds_to_the_micrometre_and_keeps_short_decimals_exact():
    assert quantise(1.23456789) == 1.234568
    assert quantise(4.6) == 4.6
    assert quantise(-1750.0000000000002) == -1750.0


def test_last_bit_neighbours_round_to_the_same_double():
    for x in (0.1, 123.456789123, -987.654321987, 3.0e3 + 1e-7):
        assert quantise(np.nextafter(x, np.inf)) == quantise(np.nextafter(x, -np.inf))


def test_negative_zero_becomes_zero():
    assert str(quantise(-1e-17)) == "0.0"
    assert str(quantise_array(np.array([-1e-17]))[0]) == "0.0"


def test_array_matches_scalar_and_keeps_dtype():
    values = np.array([0.5e-6, 1.5e-6, -2.4999999e-3, 7.123456789], dtype=np.float64)
    got = quantise_array(values)
    assert got.dtype == np.float64
    assert got.tolist() == [quantise(float(v)) for v in values]


def test_quaternion_grid_is_finer():
    assert quantise(0.123456789123, ANGLE_STEPS) == 0.123456789


def test_field_quantises_floats_only():
    assert quantise_field(2.0000000001) == 2.0
    assert quantise_field(3) == 3
    assert quantise_field(True) is True
    assert quantise_field("x") == "x"
    ints = np.array([1, 2], dtype=np.uint8)
    assert quantise_field(ints) is ints
    floats = quantise_field(np.array([1.0000001, 2.0]))
    assert isinstance(floats, np.ndarray)
    assert floats.tolist() == [1.0, 2.0]
