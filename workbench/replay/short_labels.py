"""The drive's short object labels (``#1``, ``#2``, ...): one table for the scene and engines.

Object ids of ``derived_object_msgs`` fill 32 columns
(``00000000000000000000000000000001``), so every label the viewer draws, the review table and
its facts name an object by a short label instead; the full id stays in the entity path or
an ``object_id`` component next to the label.

One :class:`ShortLabels` table exists per drive replay: the review numbers the objects of
its incidents first (by first incident, ``workbench.replay.incidents.short_labels``), so the
TUI and the viewer agree; the replay hands the same table to the scene, the highlights and
every engine's sink, which number any other object as it first appears (pure: no Rerun).
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from collections.abc import Iterable

__all__ = ["ShortLabels"]


class ShortLabels(Mapping[str, str]):
    """Short label per object id, numbered in the order objects are first named."""

    def __init__(self, object_ids: Iterable[str] = ()) -> None:
        """Number ``object_ids`` first (``#1`` for the first), in their order."""
        self._labels: dict[str, str] = {}
        for object_id in object_ids:
            self.label(object_id)

    def label(self, object_id: str) -> str:
        """The object's short label, numbering it next when it has none yet."""
        found = self._labels.get(object_id)
        if found is None:
            found = self._labels[object_id] = f"#{len(self._labels) + 1}"
        return found

    def __getitem__(self, object_id: str) -> str:
        """The label of an already numbered object (``KeyError`` else)."""
        return self._labels[object_id]

    def __iter__(self) -> Iterator[str]:
        """The numbered object ids, in numbering order."""
        return iter(self._labels)

    def __len__(self) -> int:
        """How many objects are numbered."""
        return len(self._labels)
