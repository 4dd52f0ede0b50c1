"""What a batch result depends on besides the drive: engine versions and a settings hash.

The engine versions are the package version and a fingerprint of the source of every package
a drive's incidents depend on (loaders, engines, incident detection), so a code change
invalidates the results a resumed batch would otherwise keep.
"""

from __future__ import annotations

import functools
import hashlib
from pathlib import Path
from typing import TYPE_CHECKING

from workbench.outputs import json_text

if TYPE_CHECKING:
    from workbench.incidents import IncidentRequest

__all__ = ["FINGERPRINTED", "engine_versions", "settings_hash"]

_ROOT = Path(__file__).resolve().parents[2]

#: Source folders (relative to the repository root) whose code decides incidents, besides
#: the packages each engine's spec names (``EngineSpec.packages``).
FINGERPRINTED = (
    "loaders",
    "workbench/driver",
    "workbench/engines",
    "workbench/incidents",
)


def _folders() -> tuple[str, ...]:
    """:data:`FINGERPRINTED` and every registered engine's packages, once each."""
    from workbench.engines.registry import engine, names  # noqa: PLC0415

    packages = (p for name in names() for p in engine(name).packages)
    return tuple(dict.fromkeys((*FINGERPRINTED, *packages)))


@functools.cache
def engine_versions() -> dict[str, str]:
    """``{"rss-workbench": version, "engine_code": sha256 of the fingerprinted sources}``."""
    from workbench import __version__  # noqa: PLC0415 - avoids a cycle at import

    digest = hashlib.sha256()
    for folder in _folders():
        for path in sorted((_ROOT / folder).rglob("*.py")):
            digest.update(path.relative_to(_ROOT).as_posix().encode() + b"\0")
            digest.update(path.read_bytes())
    return {"rss-workbench": __version__, "engine_code": digest.hexdigest()[:16]}


def settings_hash(request: IncidentRequest) -> str:
    """Hex SHA-256 (16 digits) of :meth:`IncidentRequest.record` (no drive) as canonical JSON."""
    text = json_text(request.record(), sort_keys=True, default=str)
    return hashlib.sha256(text.encode()).hexdigest()[:16]
