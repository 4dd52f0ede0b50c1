"""Round every float a sample writer emits to a fixed grid, so the files are machine-independent.

numpy's SIMD kernels (``sin``, ``cos``, ``arctan2``, ``hypot``, ...) and libm may differ in
the last bit between CPUs and library versions, and derivatives (yaw rate, acceleration)
amplify that by ``1 / DT_S``: the raw trajectory floats differ by up to ~1e-14 between
machines. Every writer therefore rounds each float to an integer multiple of a grid far
above that noise and far below anything an engine can notice:

- :data:`STEPS_PER_UNIT` = 1e6: metres, m/s, m/s^2, rad/s, probabilities (1 micrometre),
  at least 1e6 times the noise of a float64 coordinate up to 10 km (ulp 1.8e-12 m);
- :data:`ANGLE_STEPS` = 1e9: angles (rad) and quaternion components (about 2e-9 rad of
  yaw), 1e6 times the noise of a component in ``[-1, 1]`` (ulp 1.1e-16).

Coarser formatting (4 decimals in JSON, millimetres in OSM) is applied to the quantised
value, never to the raw one: synthetic kinematics often land exactly on a decimal tie
(``20.59625`` at 4 decimals), where one ulp of noise would flip the raw value's rounding.

The rounded value is ``round(x * steps) / steps``: a product, a rounding to an integer and
a division, each correctly rounded by IEEE 754, so the result is the same double on every
machine whenever the input's noise does not straddle a rounding midpoint (probability
about ``noise * steps`` per value, below 1e-7). ``-0.0`` becomes ``0.0``.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, TypeVar, cast

import numpy as np

if TYPE_CHECKING:
    from numpy.typing import NDArray

__all__ = ["ANGLE_STEPS", "STEPS_PER_UNIT", "quantise", "quantise_array", "quantise_field"]

_T = TypeVar("_T")

#: Grid of metric values (m, m/s, m/s^2, rad/s, probabilities): 1e-6 of the unit.
STEPS_PER_UNIT = 1e6
#: Grid of angles (rad) and quaternion components: 1e-9.
ANGLE_STEPS = 1e9


def quantise(value: float, steps: float = STEPS_PER_UNIT) -> float:
    """``value`` rounded to the nearest multiple of ``1 / steps`` (ties to even), never -0.0."""
    return round(float(value) * steps) / steps


def quantise_array(
    values: NDArray[np.floating[Any]], steps: float = STEPS_PER_UNIT
) -> NDArray[np.floating[Any]]:
    """:func:`quantise` element-wise; same shape and dtype as ``values``."""
    return np.asarray(np.rint(values * steps) / steps + 0.0, dtype=values.dtype)


def quantise_field(value: _T, steps: float = STEPS_PER_UNIT) -> _T:
    """Quantise a message field: a float or a float array; anything else is returned as is."""
    if isinstance(value, float):
        return cast("_T", quantise(value, steps))
    if isinstance(value, np.ndarray) and np.issubdtype(value.dtype, np.floating):
        return cast("_T", quantise_array(value, steps))
    return value
