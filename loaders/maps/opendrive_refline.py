"""OpenDRIVE reference lines: exact plan-view poses and the stations ad-map samples them at.

A road's reference line is a chain of plan-view records (``line``, ``arc``, ``spiral``,
``poly3``, ``paramPoly3``), each starting at its own ``s``; ``laneOffset`` shifts it
sideways and ``elevation`` lifts it. :class:`ReferenceLine` evaluates the shifted line at
any ``s`` (lines and arcs in closed form, spirals by Gauss-Legendre quadrature of the
heading, cubic polynomials at the parameter of the requested arc length) and chooses the
stations where lane borders are sampled, with the rule of ad-map's OpenDRIVE reader
(``ad_map_opendrive_reader``, the map behind ad-rss-map-integration 5.0):

1. every record's start and the road's end; inside an arc of curvature ``k`` that turns
   by at least 0.01 rad, ``floor(length / d)`` equal pieces with
   ``d = 2 / k · acos(1 - k · e)`` (chord sagitta ``e``); inside a flatter arc its middle;
2. then, recursively, the middle of every interval of at least ``e`` in ``s`` whose
   shifted centre point (x, y, z) lies more than ``e`` from the middle of its chord,

with ``e = MAX_SAMPLING_ERROR_M`` = 5 cm. Lanes refine these stations further
(:mod:`loaders.maps.opendrive_borders`).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from loaders.errors import MapError

if TYPE_CHECKING:
    import xml.etree.ElementTree as ET
    from collections.abc import Callable

    from numpy.typing import NDArray

    _F = NDArray[np.float64]

__all__ = [
    "MAX_SAMPLING_ERROR_M",
    "ReferenceLine",
    "bisect_stations",
    "float_attr",
    "piecewise_cubic",
]

#: ad-map's sampling tolerance: chord sagitta and shortest refined interval (m).
MAX_SAMPLING_ERROR_M = 0.05
#: Arcs turning by less than this (rad) get only their middle as an extra station.
_FLAT_ARC_RAD = 1e-2
#: Arcs with a smaller curvature (1/m) are evaluated as lines.
_STRAIGHT_CURVATURE = 1e-15
_GAUSS_NODES, _GAUSS_WEIGHTS = np.polynomial.legendre.leggauss(8)
#: Panel length of the spiral quadrature (m); 8 nodes per panel keep errors < 1e-9 m.
_PANEL_M = 2.0
#: Parameter samples per cubic record for the arc-length table.
_POLY_TABLE = 4001


def float_attr(elem: ET.Element, key: str, default: float = 0.0) -> float:
    """A numeric XML attribute, ``default`` when absent."""
    value = elem.get(key)
    return default if value is None else float(value)


def piecewise_cubic(starts: _F, coeffs: _F, at: _F) -> _F:
    """Evaluate piecewise cubic records (OpenDRIVE ``a b c d``).

    Each record applies from its start to the next record's start.

    Args:
        starts: Record starts, ``(R,)`` ascending (metres along ``s`` or section offset).
        coeffs: ``a, b, c, d`` per record, ``(R, 4)``.
        at: Evaluation positions, ``(N,)``; before the first start the first record applies.

    Returns:
        Values, ``(N,)``; zeros when there are no records.
    """
    if len(starts) == 0:
        return np.zeros_like(at)
    if len(starts) == 1:
        d = at - starts[0]
        a, b, c, e = coeffs[0]
    else:
        idx = np.maximum(np.searchsorted(starts, at, side="right") - 1, 0)
        d = at - starts[idx]
        a, b, c, e = coeffs[idx].T
    out: _F = a + d * (b + d * (c + d * e))
    return out


def _records(elems: list[ET.Element], key: str) -> tuple[_F, _F]:
    starts = np.array([float_attr(e, key) for e in elems], dtype=np.float64)
    coeffs = np.array([[float_attr(e, k) for k in "abcd"] for e in elems], dtype=np.float64)
    order = np.argsort(starts, kind="stable")
    return starts[order], coeffs[order].reshape(-1, 4)


def _spiral(k0: float, k1: float, length: float, d: _F) -> tuple[_F, _F, _F]:
    """Local ``(u, v, heading)`` of a clothoid from curvature ``k0`` to ``k1`` at ``d``."""
    rate = (k1 - k0) / length if length > 0 else 0.0  # a zero-length record: no curvature change

    def heading(x: _F) -> _F:
        out: _F = k0 * x + 0.5 * rate * x * x
        return out

    panels = max(1, math.ceil(float(np.max(d, initial=0.0)) / _PANEL_M))
    edges = np.linspace(0.0, 1.0, panels + 1)
    half = np.diff(edges) / 2
    mid = (edges[:-1] + edges[1:]) / 2
    frac = (mid[:, None] + half[:, None] * _GAUSS_NODES[None]).ravel()  # (P*8,) in [0, 1]
    weights = (half[:, None] * _GAUSS_WEIGHTS[None]).ravel()
    x = d[:, None] * frac[None]
    h = heading(x)
    u = d * (np.cos(h) @ weights)
    v = d * (np.sin(h) @ weights)
    return u, v, heading(d)


def _cubic(kind: ET.Element, length: float, d: _F) -> tuple[_F, _F, _F]:
    """Local ``(u, v, heading)`` of a ``poly3`` / ``paramPoly3`` at arc length ``d``."""
    if kind.tag == "poly3":
        cu = np.array([0.0, 1.0, 0.0, 0.0])
        cv = np.array([float_attr(kind, k) for k in "abcd"])
        p_max = 1.5 * length  # u never exceeds the arc length; the table is cut there
    else:
        cu = np.array([float_attr(kind, f"{k}U") for k in "abcd"])
        cv = np.array([float_attr(kind, f"{k}V") for k in "abcd"])
        p_max = length if kind.get("pRange") == "arcLength" else 1.0
    table = np.linspace(0.0, p_max, _POLY_TABLE)
    du = np.polynomial.polynomial.polyval(table, np.polynomial.polynomial.polyder(cu))
    dv = np.polynomial.polynomial.polyval(table, np.polynomial.polynomial.polyder(cv))
    speed = np.hypot(du, dv)
    arc = np.concatenate([[0.0], np.cumsum((speed[1:] + speed[:-1]) / 2 * np.diff(table))])
    p = np.interp(d, arc, table)
    u = np.polynomial.polynomial.polyval(p, cu)
    v = np.polynomial.polynomial.polyval(p, cv)
    hu = np.polynomial.polynomial.polyval(p, np.polynomial.polynomial.polyder(cu))
    hv = np.polynomial.polynomial.polyval(p, np.polynomial.polynomial.polyder(cv))
    return u, v, np.arctan2(hv, hu)


class ReferenceLine:
    """The laterally shifted reference line of one ``<road>``.

    Attributes:
        length_m: The road's ``length`` attribute (m).
        starts_m: Start ``s`` of each plan-view record, ``(G,)`` metres.
    """

    def __init__(self, road: ET.Element) -> None:
        """Read the plan view, ``laneOffset`` and ``elevation`` records of ``road``.

        Raises:
            MapError: No plan view, or an unknown geometry record.
        """
        self._geos = road.findall("planView/geometry")
        if not self._geos:
            raise MapError("<xodr>", f"road {road.get('id')} has no plan view")
        rows = np.array(
            [[float_attr(g, k) for k in ("s", "x", "y", "hdg", "length")] for g in self._geos],
            dtype=np.float64,
        )
        self.starts_m = rows[:, 0]
        self._x0, self._y0, self._h0, self._len = rows[:, 1], rows[:, 2], rows[:, 3], rows[:, 4]
        self.length_m = float_attr(road, "length", float(self.starts_m[-1] + self._len[-1]))
        self._offset = _records(road.findall("lanes/laneOffset"), "s")
        self._elevation = _records(road.findall("elevationProfile/elevation"), "s")
        self._tags = [g[0].tag if len(g) else "line" for g in self._geos]
        for tag in self._tags:
            if tag not in {"line", "arc", "spiral", "poly3", "paramPoly3"}:
                raise MapError("<xodr>", f"unsupported geometry {tag!r}")
        self._curv = np.array(
            [
                float_attr(g[0], "curvature") if tag == "arc" else 0.0
                for g, tag in zip(self._geos, self._tags, strict=True)
            ]
        )
        self._curved = [i for i, tag in enumerate(self._tags) if tag not in {"line", "arc"}]

    def poses(self, s_m: _F) -> tuple[_F, _F, _F]:
        """Unshifted reference-line poses.

        Args:
            s_m: Stations, ``(N,)`` metres; negative ones are evaluated at 0, ones past the
                last record extend it.

        Returns:
            ``x``, ``y`` (metres) and heading (rad), each ``(N,)``.
        """
        s = np.maximum(np.asarray(s_m, dtype=np.float64), 0.0)
        idx = np.maximum(np.searchsorted(self.starts_m, s, side="right") - 1, 0)
        d = s - self.starts_m[idx]
        k = self._curv[idx]
        bent = np.abs(k) >= _STRAIGHT_CURVATURE
        kd = k * d
        safe_k = np.where(bent, k, 1.0)
        u = np.where(bent, np.sin(kd) / safe_k, d)
        v = np.where(bent, (1.0 - np.cos(kd)) / safe_k, 0.0)
        dh = kd
        for g in self._curved:
            sel = idx == g
            if sel.any():
                u[sel], v[sel], dh[sel] = self._local(g, d[sel])
        h0 = self._h0[idx]
        c, sn = np.cos(h0), np.sin(h0)
        return self._x0[idx] + c * u - sn * v, self._y0[idx] + sn * u + c * v, h0 + dh

    def _local(self, g: int, d: _F) -> tuple[_F, _F, _F]:
        kind = self._geos[g][0]
        if kind.tag == "spiral":
            return _spiral(
                float_attr(kind, "curvStart"), float_attr(kind, "curvEnd"), float(self._len[g]), d
            )
        return _cubic(kind, float(self._len[g]), d)

    def frame(self, s_m: _F) -> tuple[_F, _F, _F]:
        """Shifted centre points and their left normals.

        Args:
            s_m: Stations, ``(N,)`` metres.

        Returns:
            Centre points ``(N, 3)`` (x, y, elevation z, metres), unit left normals
            ``(N, 2)`` of the unshifted line's heading, and the lane offset ``(N,)`` metres
            already applied to the centre points.
        """
        s = np.asarray(s_m, dtype=np.float64)
        x, y, h = self.poses(s)
        normal = np.stack([-np.sin(h), np.cos(h)], axis=1)
        offset = piecewise_cubic(*self._offset, s)
        z = piecewise_cubic(*self._elevation, s)
        centre = np.stack([x + offset * normal[:, 0], y + offset * normal[:, 1], z], axis=1)
        return centre, normal, offset

    def stations(self) -> _F:
        """ad-map's stations along the road (rule in the module docstring), ``(S,)`` m."""
        seeds = [self.length_m]
        for g, s0 in enumerate(self.starts_m):
            seeds.append(float(s0))
            if self._tags[g] != "arc":
                continue
            length, k = float(self._len[g]), abs(float(self._curv[g]))
            if k * length < _FLAT_ARC_RAD:
                seeds.append(float(s0) + 0.5 * length)
                continue
            step = 2.0 / k * math.acos(1.0 - k * MAX_SAMPLING_ERROR_M)
            pieces = int(length / step)
            seeds.extend(float(s0) + j / pieces * length for j in range(1, pieces))
        base = np.unique(np.array(seeds, dtype=np.float64))

        def points(s: _F) -> _F:
            return self.frame(s)[0][:, None, None, :]

        extra = bisect_stations(base, points, strict=True)[0]
        return np.unique(np.concatenate([base, extra]))


def bisect_stations(
    base_m: _F, points: Callable[[_F], _F], *, strict: bool
) -> tuple[_F, NDArray[np.intp], _F, _F]:
    """Recursive interval halving of ad-map's samplers, for several polylines at once.

    Each of ``L`` polylines owns ``E`` points per station (a lane's two borders, or one
    centre point). An interval ``[a, b]`` of one polyline at least ``MAX_SAMPLING_ERROR_M``
    long gets its middle ``m`` as a new station of that polyline when any of its points at
    ``m`` lies more than (``strict``) or at least ``MAX_SAMPLING_ERROR_M`` from the middle
    of its chord; both halves are then examined again.

    Args:
        base_m: Stations shared by every polyline, ``(S,)`` ascending metres.
        points: ``points(s) -> (N, L, E, 3)``: the polylines' points (x, y, z metres) at
            stations ``s`` ``(N,)``.
        strict: Compare with ``>`` (the centre line) rather than ``>=`` (lane borders).

    Returns:
        New stations ``(M,)`` metres, the polyline each belongs to ``(M,)``, that
        polyline's points there ``(M, E, 3)`` and the points at ``base_m``
        ``(S, L, E, 3)``.
    """
    tol = MAX_SAMPLING_ERROR_M
    at = points(base_m)
    n_lines = at.shape[1]
    line = np.repeat(np.arange(n_lines), len(base_m) - 1)
    k = np.tile(np.arange(len(base_m) - 1), n_lines)
    a, b = base_m[k], base_m[k + 1]
    pa, pb = at[k, line], at[k + 1, line]
    found_s: list[_F] = [np.zeros(0)]
    found_line: list[NDArray[np.intp]] = [np.zeros(0, dtype=np.intp)]
    found_points: list[_F] = [np.zeros((0, *at.shape[2:]))]
    while True:
        long = b - a >= tol
        a, b, line, pa, pb = a[long], b[long], line[long], pa[long], pb[long]
        if len(a) == 0:
            break
        m = 0.5 * (a + b)
        unique, inverse = np.unique(m, return_inverse=True)
        pm = points(unique)[inverse, line]
        err2 = np.max(np.sum((pm - 0.5 * (pa + pb)) ** 2, axis=-1), axis=-1)
        split = err2 > tol * tol if strict else err2 >= tol * tol
        found_s.append(m[split])
        found_line.append(line[split])
        found_points.append(pm[split])
        a = np.concatenate([a[split], m[split]])
        b = np.concatenate([m[split], b[split]])
        line = np.concatenate([line[split], line[split]])
        pa, pb = np.concatenate([pa[split], pm[split]]), np.concatenate([pm[split], pb[split]])
    return (
        np.concatenate(found_s),
        np.concatenate(found_line),
        np.concatenate(found_points),
        at,
    )
