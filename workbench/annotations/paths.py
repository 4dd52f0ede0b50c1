"""Where the label store lives unless ``--store`` says otherwise."""

from __future__ import annotations

import os
from pathlib import Path

__all__ = ["default_store_path"]


def default_store_path() -> Path:
    """``$XDG_DATA_HOME/rss-workbench/labels.sqlite`` (``~/.local/share/...`` when unset)."""
    base = os.environ.get("XDG_DATA_HOME") or str(Path.home() / ".local" / "share")
    return Path(base) / "rss-workbench" / "labels.sqlite"
