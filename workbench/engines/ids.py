"""Integer engine ids for string actor ids, shared by the RSS engines."""

from __future__ import annotations

__all__ = ["EGO_OBJECT_ID", "IdMap"]

#: Id of the ego in constellations (never a published actor id).
EGO_OBJECT_ID = 2**62
_MAX_DECIMAL_DIGITS = 12


class IdMap:
    """Stable integer ids for string actor ids (decimal ids keep their value)."""

    def __init__(self) -> None:
        """Start empty; non-decimal ids get 2**40, 2**40 + 1, ... in order of appearance."""
        self._ids: dict[str, int] = {}
        self._back: dict[int, str] = {}

    def to_int(self, actor_id: str) -> int:
        """The integer id of ``actor_id``."""
        value = self._ids.get(actor_id)
        if value is None:
            value = (
                int(actor_id)
                if actor_id.isdigit() and len(actor_id) < _MAX_DECIMAL_DIGITS
                else 2**40 + len(self._ids)
            )
            self._ids[actor_id] = value
            self._back[value] = actor_id
        return value

    def to_str(self, value: int) -> str:
        """The actor id of an integer id."""
        return self._back.get(value, str(value))
