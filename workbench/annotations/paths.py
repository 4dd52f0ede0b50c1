"""Where the label store lives unless ``--store`` says otherwise."""

from __future__ import annotations

import getpass
import os
from pathlib import Path

__all__ = ["default_reviewer", "default_store_path"]


def default_reviewer() -> str:
    """The login name (``--reviewer`` not given); ``unknown`` when there is none."""
    try:
        return getpass.getuser()
    except (KeyError, OSError):
        return "unknown"


def default_store_path() -> Path:
    """``$XDG_DATA_HOME/rss-workbench/labels.sqlite`` (``~/.local/share/...`` when unset)."""
    base = os.environ.get("XDG_DATA_HOME") or str(Path.home() / ".local" / "share")
    return Path(base) / "rss-workbench" / "labels.sqlite"
