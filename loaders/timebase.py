"""Nanoseconds <-> seconds: the one place that converts (DESIGN.md: time is integer ns).

Every layer keeps time as integer nanoseconds (``*_ns``) and converts only to show or to
compute a rate. These helpers are the conversions, with the arithmetic of the inline
expressions they replace, so results stay bit-identical::

    ns_to_s(t_ns)  ==  t_ns / 1e9        (a division: ``t_ns * 1e-9`` differs in the last bits)
    s_to_ns(t_s)   ==  round(t_s * 1e9)  (an int, rounded half to even)

``ns_to_s`` takes a Python number or a numpy array of any shape and returns the same shape.
The pure engines (``rss``, ``reachsets``) keep seconds and never see nanoseconds.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, overload

if TYPE_CHECKING:
    import numpy as np
    from numpy.typing import NDArray

__all__ = ["NS_PER_S", "ns_to_s", "s_to_ns"]

#: Nanoseconds per second, as the float every conversion divides or multiplies by.
NS_PER_S = 1e9


@overload
def ns_to_s(t_ns: float) -> float: ...
@overload
def ns_to_s(t_ns: NDArray[np.integer] | NDArray[np.floating]) -> NDArray[np.float64]: ...
def ns_to_s(
    t_ns: float | NDArray[np.integer] | NDArray[np.floating],
) -> float | NDArray[np.floating]:
    """Seconds of ``t_ns`` nanoseconds (a time span or a stamp), ``t_ns / 1e9``."""
    return t_ns / NS_PER_S


def s_to_ns(t_s: float) -> int:
    """Integer nanoseconds of ``t_s`` seconds, ``round(t_s * 1e9)``."""
    return round(t_s * NS_PER_S)
