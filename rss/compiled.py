"""Compiled twins of the per-object Python of scene creation (mypyc), used when asked and fresh.

Scene creation (``rss.scene``) is plain Python over dicts, tuples and small records: about
0.1 ms per object and frame. mypyc (the compiler that ships with mypy, which type-checks
this code strictly anyway) turns the listed modules into C extensions that compute the
same floats in the same order, about 1.7x faster. They are optional:

* ``make`` builds them with ``tools/build_compiled.py`` into ``build/compiled/`` (outside
  the source tree, git-ignored), with a manifest of each source's sha256, the interpreter's
  extension suffix and the module list.
* Nothing happens on import. An application switches them on with one explicit call of
  :func:`activate` at its start, before anything imports the listed modules (the
  ``workbench`` package does it in ``workbench/__init__.py``; benchmarks in
  ``bench/__init__.py``; the test suite in ``tests/conftest.py``). Only if every listed
  source still has the hash it was compiled from (and the interpreter matches) does it
  install an import hook that loads the extensions in place of their sources. Otherwise,
  or with ``RSS_WORKBENCH_PURE_PYTHON=1``, or without the call, everything runs from the
  sources; a stale build is logged once (``make`` rebuilds it). All modules or none:
  compiled modules call each other natively, so a mix could run stale code; a call made
  after one of them was imported from its source switches nothing on.

``tests/rss/scene/test_compiled.py`` checks that both ways give bit-identical scenes.
"""

from __future__ import annotations

import hashlib
import importlib.abc
import importlib.machinery
import importlib.util
import json
import logging
import os
import sys
import sysconfig
from pathlib import Path
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from collections.abc import Sequence
    from types import ModuleType

__all__ = [
    "BUILD_DIR",
    "GROUP",
    "MODULES",
    "PURE_ENV",
    "activate",
    "source_digests",
    "stale_reason",
    "status",
]

_LOG = logging.getLogger(__name__)

#: The compiled modules (the per-object Python of scene creation, the row-by-row
#: structured engine of small frames, ``rss.structured.small``, the point-by-point
#: trajectory sets of small unstructured frames, ``rss.unstructured.*_small``, and the reach
#: sets' scalar ``bound`` curves, one-frame occupancy and polygon clipper,
#: ``reachsets.bound_scalar``, ``small_scalar``, ``clip_rings``, ``clip_scalar``,
#: ``clip_cells`` and ``track_scalar``).
MODULES = (
    "rss.structured.batch",
    "rss.structured.stacking",
    "rss.structured.codes",
    "rss.structured.scalar_physics",
    "rss.structured.scalar_extract",
    "rss.structured.scalar_checks",
    "rss.structured.small_input",
    "rss.structured.small_merge",
    "rss.structured.small",
    "rss.structured.small_output",
    "rss.structured.small_arrays",
    "rss.unstructured.convex",
    "rss.unstructured.scalar_motion",
    "rss.unstructured.pedestrian_small",
    "rss.unstructured.vehicle_small",
    "rss.scene.align",
    "rss.scene.border_stations",
    "rss.scene.connecting",
    "rss.scene.corridor",
    "rss.scene.create",
    "rss.scene.frame",
    "rss.scene.graph_scalars",
    "rss.scene.junction_arms",
    "rss.scene.junction_pairs",
    "rss.scene.junction_relations",
    "rss.scene.lane_segments",
    "rss.scene.memo",
    "rss.scene.pairs",
    "rss.scene.roadarea",
    "rss.scene.routes",
    "rss.scene.segment_plans",
    "reachsets.bound_scalar",
    "reachsets.small_scalar",
    "reachsets.clip_rings",
    "reachsets.clip_scalar",
    "reachsets.clip_cells",
    "reachsets.track_scalar",
)
#: Name of mypyc's shared library of the group (``<GROUP>__mypyc``).
GROUP = "rss_workbench_compiled"
#: Set (non-empty) to run everything from the sources.
PURE_ENV = "RSS_WORKBENCH_PURE_PYTHON"
_ROOT = Path(__file__).resolve().parents[1]
BUILD_DIR = _ROOT / "build" / "compiled"

_STATE: dict[str, str | bool] = {"active": False, "reason": "not requested"}


def source_digests(root: Path = _ROOT) -> dict[str, str]:
    """sha256 of each source of :data:`MODULES` under ``root`` (empty string if missing)."""
    out = {}
    for module in MODULES:
        path = root / (module.replace(".", "/") + ".py")
        out[module] = hashlib.sha256(path.read_bytes()).hexdigest() if path.is_file() else ""
    return out


def _read_manifest(build_dir: Path) -> tuple[dict[str, Any], str | None]:
    try:
        return json.loads((build_dir / "manifest.json").read_text()), None
    except FileNotFoundError:
        return {}, "not built (make builds it with tools/build_compiled.py)"
    except (OSError, ValueError) as exc:
        return {}, f"unreadable manifest: {exc}"


def stale_reason(build_dir: Path = BUILD_DIR, root: Path = _ROOT) -> str | None:
    """Why the build in ``build_dir`` cannot be used (``None``: it can)."""
    if os.environ.get(PURE_ENV):
        return f"{PURE_ENV} is set"
    manifest, reason = _read_manifest(build_dir)
    if reason is None and manifest.get("ext_suffix") != sysconfig.get_config_var("EXT_SUFFIX"):
        reason = f"built for another interpreter ({manifest.get('ext_suffix')})"
    if reason is None and tuple(manifest.get("modules", ())) != MODULES:
        reason = "built for another module list"
    if reason is None:
        built = manifest.get("sha256", {})
        changed = sorted(m for m, d in source_digests(root).items() if built.get(m) != d)
        if changed:
            reason = f"sources changed since the build: {', '.join(changed)}"
    return reason


class _CompiledFinder(importlib.abc.MetaPathFinder):
    """Finds the extensions of :data:`MODULES` in the build directory."""

    def __init__(self, build_dir: Path) -> None:
        self._build_dir = build_dir
        self._suffix = str(sysconfig.get_config_var("EXT_SUFFIX"))

    def find_spec(
        self,
        fullname: str,
        path: Sequence[str] | None,  # noqa: ARG002 - the finder protocol
        target: ModuleType | None = None,  # noqa: ARG002
    ) -> importlib.machinery.ModuleSpec | None:
        """The extension's spec for a listed module, else ``None`` (the next finder's)."""
        if fullname not in MODULES:
            return None
        where = str(self._build_dir / (fullname.replace(".", "/") + self._suffix))
        loader = importlib.machinery.ExtensionFileLoader(fullname, where)
        return importlib.util.spec_from_file_location(fullname, where, loader=loader)


def activate(build_dir: Path = BUILD_DIR) -> bool:
    """Switch the compiled modules on if the build is fresh (once per process).

    Call it at the start of an application, before anything imports a module of
    :data:`MODULES`; later calls return the first decision.

    Returns:
        Whether the compiled modules are used (:func:`status` says why not).
    """
    if _STATE["active"] or _STATE["reason"] != "not requested":
        return bool(_STATE["active"])
    reason = stale_reason(build_dir)
    imported = sorted(m for m in MODULES if m in sys.modules)
    if reason is None and imported:
        reason = f"{', '.join(imported)} already imported from the sources"
    if reason is not None:
        if (build_dir / "manifest.json").exists() and not os.environ.get(PURE_ENV):
            _LOG.warning("compiled scene modules not used (%s); running from the sources", reason)
        _STATE["reason"] = reason
        return False
    suffix = sysconfig.get_config_var("EXT_SUFFIX")
    name = f"{GROUP}__mypyc"
    if name not in sys.modules:
        lib = str(build_dir / f"{name}{suffix}")
        loader = importlib.machinery.ExtensionFileLoader(name, lib)
        spec = importlib.util.spec_from_file_location(name, lib, loader=loader)
        if spec is None:  # pragma: no cover - a file path always gives a spec
            _STATE["reason"] = f"cannot load {lib}"
            return False
        sys.modules[name] = importlib.util.module_from_spec(spec)
    sys.meta_path.insert(0, _CompiledFinder(build_dir))
    _STATE.update(active=True, reason="")
    return True


def status() -> tuple[bool, str]:
    """``(whether the compiled modules are in use, why not)``."""
    return bool(_STATE["active"]), str(_STATE["reason"])
