"""ScenarioArchitect racing logs (``.saa`` ZIP archives or bare ``.scn`` text logs).

An ``.saa`` holds ``<name>.scn`` (text log), ``<name>.sas`` (a Python pickle of the GUI state,
never unpickled here), ``<name>_ggv.csv`` and ``<name>_ax_max_machines.csv``. The ``.scn``::

    # bound_l:[[x, y], ...]
    # bound_r:[[x, y], ...]
    time;x;y;heading;curv;vel;acc;ego_traj;ego_traj_em;object_array;safety_dyn;safety_stat
    0.0;16.1;147.6;-2.21;0.0005;33.4;0.16;[[x, y, psi, kappa, v, a], ...];[...];
        [["veh_2", [x, y, psi, v, length, width]]];null;null

Headings (``heading``, ``psi``) are TUM north-0 (``psi = 0`` points to +y, counter-clockwise
positive); this reader is the one boundary converting them to ENU yaw::

    yaw_enu = psi + pi/2        (psi = 0, north  ->  yaw = pi/2)

The ego's size is only in the pickle, so the reference's simulation values (4.7 m x 2.8 m)
are used. ``Frame.extras``: ``labels`` (``safety_dyn``/``safety_stat``: True, False or None),
``trajectories`` (``performance`` and ``emergency``, each a dict of ``(30,)`` arrays
``x_m, y_m, yaw_rad, curvature_inv_m, speed_mps, accel_mps2``). ``Frame.plan`` is the
trajectory chosen by ``plan`` and ``Frame.plan_kind`` says which (``emergency`` ->
``PlanKind.EMERGENCY``, ``performance`` -> ``PlanKind.NOMINAL``).
"""

from __future__ import annotations

import io
import json
import lzma
import math
import zipfile
import zlib
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, Self

import numpy as np

from loaders.drive import DriveInfo, TopicInfo, TopicRoles
from loaders.errors import CorruptLogError, EmptyLogError, InvalidValueError, UnsupportedFormatError
from loaders.maps.model import LaneMap
from loaders.records import ActorTable, EgoState, Frame, ObjectClass, Plan, PlanKind
from loaders.timebase import s_to_ns

if TYPE_CHECKING:
    from collections.abc import Iterator

    from numpy.typing import NDArray

__all__ = [
    "EGO_LENGTH_M",
    "EGO_WIDTH_M",
    "ScenarioArchitectDrive",
    "north0_to_enu",
    "open_scenario_architect",
]

EGO_LENGTH_M = 4.7
EGO_WIDTH_M = 2.8
_COLUMNS = "time;x;y;heading;curv;vel;acc;ego_traj;ego_traj_em;object_array;safety_dyn;safety_stat"
_PLANS = {"emergency": "ego_traj_em", "performance": "ego_traj"}
_PLAN_KINDS = {"emergency": PlanKind.EMERGENCY, "performance": PlanKind.NOMINAL}
_TRAJ_FIELDS = ("x_m", "y_m", "yaw_rad", "curvature_inv_m", "speed_mps", "accel_mps2")


#: What a damaged archive raises while its members are read: zlib/lzma errors in compressed
#: data, ``RuntimeError`` for an encrypted member, ``NotImplementedError`` for an unknown
#: compression method.
_ARCHIVE_ERRORS = (
    zipfile.BadZipFile,
    EOFError,
    OSError,
    zlib.error,
    lzma.LZMAError,
    RuntimeError,
    NotImplementedError,
)


def north0_to_enu(psi_rad: Any) -> Any:
    """Convert a TUM north-0 heading to ENU yaw, wrapped to ``[-pi, pi)``."""
    return (np.asarray(psi_rad, dtype=np.float64) + math.pi / 2 + math.pi) % (2 * math.pi) - math.pi


@dataclass(frozen=True, slots=True)
class _Header:
    bound_left: NDArray[np.float64]
    bound_right: NDArray[np.float64]
    first_row_line: int
    times_s: NDArray[np.float64]


def _traj(rows: Any) -> dict[str, NDArray[np.float64]]:
    arr = np.asarray(rows, dtype=np.float64).reshape(-1, 6)
    out = {name: arr[:, k].copy() for k, name in enumerate(_TRAJ_FIELDS)}
    out["yaw_rad"] = north0_to_enu(out["yaw_rad"])
    for v in out.values():
        v.flags.writeable = False
    return out


def _label(text: str) -> bool | None:
    value = json.loads(text)
    if value is None or isinstance(value, bool):
        return value
    msg = f"label {text!r} is not true/false/null"
    raise ValueError(msg)


class ScenarioArchitectDrive:
    """A ScenarioArchitect log as a ``Drive`` (see module docstring)."""

    def __init__(self, path: Path, plan: str) -> None:
        """Open ``path`` and scan its header and timestamps (rows are parsed lazily)."""
        if plan not in _PLANS:
            raise UnsupportedFormatError(path, f"plan must be one of {sorted(_PLANS)}", value=plan)
        self._path = path
        self._plan = plan
        self._csv: dict[str, str] = {}
        self._header = self._scan()
        left, right = self._header.bound_left, self._header.bound_right
        self._lane_map = LaneMap(
            lanes={}, source=str(path), format="track", boundaries_m=(left, right)
        )
        times = self._header.times_s
        n = len(times)
        notes = {
            "ego_size": f"{EGO_LENGTH_M} x {EGO_WIDTH_M} m (default; the size is only in .sas)",
            "csv_members": ", ".join(sorted(self._csv)),
        }
        topics = (
            TopicInfo("/ego", "scenario_architect/ego_state", n, "ego"),
            TopicInfo("/objects", "scenario_architect/object_array", n, "objects"),
            TopicInfo(f"/{_PLANS[plan]}", "scenario_architect/trajectory", n, "plan"),
        )
        self._info = DriveInfo(
            path=path,
            source_format="scenario-architect",
            start_ns=s_to_ns(times[0]),
            end_ns=s_to_ns(times[-1]),
            topics=topics,
            roles=TopicRoles(ego="/ego", objects=("/objects",), plan=f"/{_PLANS[plan]}"),
            frame_count=n,
            map_source="bound_l/bound_r header",
            notes=notes,
        )

    @property
    def info(self) -> DriveInfo:
        """What was detected about the drive."""
        return self._info

    @property
    def lane_map(self) -> LaneMap:
        """Track bounds as ``LaneMap(format="track", boundaries_m=(left, right))``."""
        return self._lane_map

    @property
    def csv_members(self) -> dict[str, str]:
        """Text of the archive's CSV members (``ggv``, ``ax_max_machines``), by suffix."""
        return dict(self._csv)

    def close(self) -> None:
        """Nothing stays open between calls."""

    def __enter__(self) -> Self:
        """Use the drive as a context manager."""
        return self

    def __exit__(self, *exc: object) -> None:
        """Close the drive."""
        self.close()

    def _open_text(self) -> io.TextIOBase:
        try:
            if zipfile.is_zipfile(self._path):
                zf = zipfile.ZipFile(self._path)
                names = [n for n in zf.namelist() if n.endswith(".scn")]
                if not names:
                    zf.close()
                    raise UnsupportedFormatError(self._path, "archive holds no .scn member")
                for name in zf.namelist():
                    for kind in ("ggv", "ax_max_machines"):
                        if name.endswith(f"_{kind}.csv"):
                            self._csv[kind] = zf.read(name).decode("utf-8")
                return io.TextIOWrapper(zf.open(names[0]), encoding="utf-8")
            if self._path.suffix == ".saa":
                raise CorruptLogError(self._path, "not a valid ZIP archive")
            return self._path.open(encoding="utf-8")
        except (*_ARCHIVE_ERRORS, UnicodeDecodeError) as err:
            raise CorruptLogError(self._path, f"cannot open: {err}") from err

    def _scan(self) -> _Header:
        bounds: dict[str, NDArray[np.float64]] = {}
        times: list[float] = []
        first = -1
        with self._open_text() as fh:
            try:
                for lineno, line in enumerate(fh):
                    if line.startswith("# bound_"):
                        key, _, value = line[2:].partition(":")
                        bounds[key] = np.asarray(json.loads(value), dtype=np.float64)
                    elif line.startswith("time;"):
                        if line.strip() != _COLUMNS:
                            raise UnsupportedFormatError(
                                self._path, "unexpected columns", offset=lineno, value=line.strip()
                            )
                        first = lineno + 1
                    elif first >= 0 and line.strip():
                        times.append(float(line.split(";", 1)[0]))
            except (*_ARCHIVE_ERRORS, ValueError) as err:
                if not times:
                    raise CorruptLogError(self._path, f"unreadable header: {err}") from err
        if "bound_l" not in bounds or "bound_r" not in bounds or first < 0:
            raise UnsupportedFormatError(self._path, "no bound_l/bound_r header or column line")
        if not times:
            raise EmptyLogError(self._path, "no rows")
        return _Header(bounds["bound_l"], bounds["bound_r"], first, np.asarray(times))

    def _frame(self, index: int, line: str) -> Frame:
        cols = line.rstrip("\n").split(";")
        t_s, x, y, heading, curv, vel, acc = (float(c) for c in cols[:7])
        t_ns = s_to_ns(t_s)
        if not all(math.isfinite(v) for v in (x, y, heading)):
            raise InvalidValueError(self._path, "non-finite ego pose", t_ns=t_ns, value=cols[:4])
        trajs = {"performance": _traj(json.loads(cols[7])), "emergency": _traj(json.loads(cols[8]))}
        ego = EgoState(
            x_m=x,
            y_m=y,
            z_m=0.0,
            yaw_rad=float(north0_to_enu(heading)),
            speed_mps=vel,
            accel_mps2=acc,
            yaw_rate_radps=curv * vel,
            length_m=EGO_LENGTH_M,
            width_m=EGO_WIDTH_M,
        )
        objects = json.loads(cols[9])
        state = np.asarray([o[1] for o in objects], dtype=np.float64).reshape(-1, 6)
        yaw = north0_to_enu(state[:, 2])
        actors = ActorTable.from_columns(
            ids=[str(o[0]) for o in objects],
            object_class=np.full(len(objects), ObjectClass.CAR),
            x_m=state[:, 0],
            y_m=state[:, 1],
            yaw_rad=yaw,
            vx_mps=state[:, 3] * np.cos(yaw),
            vy_mps=state[:, 3] * np.sin(yaw),
            length_m=state[:, 4],
            width_m=state[:, 5],
        )
        chosen = trajs[self._plan]
        plan = Plan(
            x_m=chosen["x_m"],
            y_m=chosen["y_m"],
            yaw_rad=chosen["yaw_rad"],
            t_offset_s=np.full(len(chosen["x_m"]), np.nan),
            speed_mps=chosen["speed_mps"],
        )
        labels = {"safety_dyn": _label(cols[10]), "safety_stat": _label(cols[11])}
        extras = {"labels": labels, "trajectories": trajs}
        return Frame(
            index=index,
            t_ns=t_ns,
            ego=ego,
            actors=actors,
            plan=plan,
            extras=extras,
            plan_kind=_PLAN_KINDS[self._plan],
        )

    def frames(self, start_ns: int | None = None, end_ns: int | None = None) -> Iterator[Frame]:
        """Yield frames in time order within ``[start_ns, end_ns)``.

        Raises:
            CorruptLogError: After every readable frame, if a row or the archive is damaged.
        """
        index = 0
        with self._open_text() as fh:
            lineno = -1
            try:
                for lineno, line in enumerate(fh):
                    if lineno < self._header.first_row_line or not line.strip():
                        continue
                    t_ns = s_to_ns(float(line.split(";", 1)[0]))
                    if (start_ns is None or t_ns >= start_ns) and (end_ns is None or t_ns < end_ns):
                        yield self._frame(index, line)
                    index += 1
            except InvalidValueError:
                raise
            except (ValueError, IndexError, TypeError, KeyError) as err:
                raise CorruptLogError(self._path, f"bad row: {err}", offset=lineno) from err
            except _ARCHIVE_ERRORS as err:
                raise CorruptLogError(self._path, f"archive damaged: {err}", offset=lineno) from err


def open_scenario_architect(path: str | Path, *, plan: str = "emergency") -> ScenarioArchitectDrive:
    """Open a ScenarioArchitect ``.saa`` archive or ``.scn`` log as a ``Drive``.

    Args:
        path: The file.
        plan: Which trajectory becomes ``Frame.plan``: ``"emergency"`` or ``"performance"``.

    Returns:
        The drive.

    Raises:
        CorruptLogError: The archive or its header is damaged.
        UnsupportedFormatError: Not a ScenarioArchitect log.
        EmptyLogError: No rows.
    """
    p = Path(path)
    if not p.exists():
        raise UnsupportedFormatError(p, "file does not exist")
    return ScenarioArchitectDrive(p, plan)
