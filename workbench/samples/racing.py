"""Racing sample: a small track and two cars overtaking, written as a ScenarioArchitect ``.saa``.

The track is a 250 m straight, a 90 degree left-hander of 150 m radius and a 110 m straight,
12 m wide. The ego starts 40 m behind ``veh_2`` at 38 m/s, moves to the left half between
1 s and 3 s, passes the 32 m/s ``veh_2`` (which holds the right half) and stays left. Every row
carries a 3 s performance trajectory (constant speed) and an emergency trajectory (10 m/s^2
to standstill), 30 points each, in TUM north-0 headings like the tool's own logs. The
``safety_dyn`` label is ``true`` while the cars are more than 20 m apart and ``null``
otherwise; there is no ``.sas`` member (that one is a pickle of the GUI state).
"""

from __future__ import annotations

import io
import math
import zipfile
from typing import TYPE_CHECKING

import numpy as np

from workbench.outputs import json_text
from workbench.samples.quantise import quantise

if TYPE_CHECKING:
    from pathlib import Path

    from numpy.typing import NDArray

__all__ = ["RACING_SAMPLE_NAME", "racing_centre", "write_racing_sample"]

RACING_SAMPLE_NAME = "racing_overtake"
_STRAIGHT_1_M = 250.0
_RADIUS_M = 150.0
_STRAIGHT_2_M = 110.0
_HALF_WIDTH_M = 6.0
_DT_S = 0.1
_DURATION_S = 8.0
_PLAN_POINTS = 30
_EGO_V_MPS = 38.0
_OBJ_V_MPS = 32.0
_OBJ_S0_M = 40.0
_BRAKE_MPS2 = 10.0
_ZIP_DATE = (2024, 1, 1, 0, 0, 0)
_COLUMNS = "time;x;y;heading;curv;vel;acc;ego_traj;ego_traj_em;object_array;safety_dyn;safety_stat"


def racing_centre(s_m: NDArray[np.float64]) -> tuple[NDArray[np.float64], ...]:
    """Centre-line pose at arc lengths ``s_m`` (clipped to the track): ``x, y, yaw, kappa``."""
    arc = _RADIUS_M * math.pi / 2
    s = np.clip(s_m, 0.0, _STRAIGHT_1_M + arc + _STRAIGHT_2_M)
    on_arc = np.clip(s - _STRAIGHT_1_M, 0.0, arc)
    phi = on_arc / _RADIUS_M
    x = np.minimum(s, _STRAIGHT_1_M) + _RADIUS_M * np.sin(phi)
    y = _RADIUS_M * (1 - np.cos(phi))
    after = np.maximum(s - _STRAIGHT_1_M - arc, 0.0)
    y = y + after
    kappa = np.where((s > _STRAIGHT_1_M) & (s < _STRAIGHT_1_M + arc), 1 / _RADIUS_M, 0.0)
    return x, y, phi, kappa


def _pose(s_m: NDArray[np.float64], lat_m: NDArray[np.float64]) -> tuple[NDArray[np.float64], ...]:
    """Position and ENU yaw at arc length ``s`` and lateral offset ``lat`` (right positive)."""
    x, y, yaw, kappa = racing_centre(s_m)
    return x + np.sin(yaw) * lat_m, y - np.cos(yaw) * lat_m, yaw, kappa


def _ego_lat(t_s: NDArray[np.float64]) -> NDArray[np.float64]:
    """Ego lateral offset: 0 until 1 s, smoothly to -3 m (left) by 3 s, then held."""
    u = np.clip((t_s - 1.0) / 2.0, 0.0, 1.0)
    return -3.0 * (3 * u**2 - 2 * u**3)


def _rows(t0: float, v0: float, s0: float, *, ego: bool, brake: bool) -> list[list[float]]:
    """30 trajectory rows ``[x, y, psi_north0, kappa, v, a]`` starting at ``t0``."""
    t_stop = v0 / _BRAKE_MPS2
    tau = np.linspace(0.0, t_stop if brake else 3.0, _PLAN_POINTS)
    if brake:
        v = v0 - _BRAKE_MPS2 * tau
        s = s0 + v0 * tau - 0.5 * _BRAKE_MPS2 * tau**2
        a = np.full_like(tau, -_BRAKE_MPS2)
    else:
        v = np.full_like(tau, v0)
        s = s0 + v0 * tau
        a = np.zeros_like(tau)
    lat = _ego_lat(np.full_like(tau, t0) + (0 if brake else tau)) if ego else np.full_like(tau, 1.5)
    x, y, yaw, kappa = _pose(s, lat)
    psi = (yaw - math.pi / 2 + math.pi) % (2 * math.pi) - math.pi
    return [[_q4(c) for c in row] for row in np.stack([x, y, psi, kappa, v, a], axis=1)]


def _q4(value: float) -> float:
    """A written number: on the 1e-6 grid of :mod:`workbench.samples.quantise`, then 4 decimals.

    Rounding the raw value to 4 decimals directly would let last-bit noise flip a value
    lying on a decimal tie (synthetic kinematics hit those); the quantised value is the same
    double on every machine, so its 4-decimal rounding is too.
    """
    return round(quantise(value), 4)


def _scn_text() -> str:
    s_b = np.linspace(0.0, _STRAIGHT_1_M + _RADIUS_M * math.pi / 2 + _STRAIGHT_2_M, 120)
    zeros = np.zeros_like(s_b)
    lx, ly, _, _ = _pose(s_b, zeros - _HALF_WIDTH_M)
    rx, ry, _, _ = _pose(s_b, zeros + _HALF_WIDTH_M)
    left = [[_q4(a), _q4(b)] for a, b in zip(lx, ly, strict=True)]
    right = [[_q4(a), _q4(b)] for a, b in zip(rx, ry, strict=True)]
    lines = [f"# bound_l:{json_text(left)}", f"# bound_r:{json_text(right)}", _COLUMNS]
    for k in range(round(_DURATION_S / _DT_S) + 1):
        t = round(k * _DT_S, 1)
        s_ego = _EGO_V_MPS * t
        s_obj = _OBJ_S0_M + _OBJ_V_MPS * t
        perf = _rows(t, _EGO_V_MPS, s_ego, ego=True, brake=False)
        emerg = _rows(t, _EGO_V_MPS, s_ego, ego=True, brake=True)
        obj = _rows(t, _OBJ_V_MPS, s_obj, ego=False, brake=False)[0]
        obj_state = [obj[0], obj[1], obj[2], _OBJ_V_MPS, 4.7, 2.0]
        label = "true" if abs(s_obj - s_ego) > 20.0 else "null"  # noqa: PLR2004
        ego_row = perf[0]
        cols = [
            str(t),
            *(str(v) for v in ego_row[:4]),
            str(_EGO_V_MPS),
            "0.0",
            json_text(perf),
            json_text(emerg),
            json_text([["veh_2", obj_state]]),
            label,
            "null",
        ]
        lines.append(";".join(cols))
    return "\n".join(lines) + "\n"


def _member(zf: zipfile.ZipFile, name: str, text: str) -> None:
    info = zipfile.ZipInfo(name, date_time=_ZIP_DATE)
    info.compress_type = zipfile.ZIP_DEFLATED
    zf.writestr(info, text)


def write_racing_sample(out_dir: Path) -> list[Path]:
    """Write ``racing_overtake.saa`` (deterministic, < 300 KB) into ``out_dir``.

    Args:
        out_dir: Target directory (created if missing).

    Returns:
        The written paths.
    """
    out_dir.mkdir(parents=True, exist_ok=True)
    ggv = "# v_mps, ax_max_mps2, ay_max_mps2\n" + "".join(
        f"{v:.1f}, 13.0, 13.0\n" for v in range(0, 73, 8)
    )
    ax = "# v_mps, ax_max_machines_mps2\n0.0, 6.0\n36.0, 6.0\n48.0, 4.8\n72.0, 2.5\n"
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w") as zf:
        _member(zf, f"{RACING_SAMPLE_NAME}.scn", _scn_text())
        _member(zf, f"{RACING_SAMPLE_NAME}_ggv.csv", ggv)
        _member(zf, f"{RACING_SAMPLE_NAME}_ax_max_machines.csv", ax)
    path = out_dir / f"{RACING_SAMPLE_NAME}.saa"
    path.write_bytes(buf.getvalue())
    return [path]
