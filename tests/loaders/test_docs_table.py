"""docs/loaders.md lists every message type the registry decodes, with its role."""

from __future__ import annotations

import re
from pathlib import Path

from loaders.message_logs.registry import FAMILIES

DOC = Path(__file__).resolve().parents[2] / "docs" / "loaders.md"


def _table_rows() -> list[tuple[str, str]]:
    text = DOC.read_text(encoding="utf-8")
    section = text[text.index("## Message types") : text.index("## Topic roles")]
    rows = []
    for line in section.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) >= 3 and cells[0] in {"ego", "objects", "plan", "ego + objects"}:
            rows.append((cells[0], cells[1]))
    return rows


def test_every_decoded_type_has_a_row_of_its_role() -> None:
    rows = _table_rows()
    for msgtype, family in FAMILIES.items():
        roles = [role for role, types in rows if f"`{msgtype}`" in types]
        assert roles, f"{msgtype} has no row in the docs/loaders.md type table"
        want = "ego + objects" if family.carries_objects else family.role
        assert want in roles, (msgtype, roles)


def test_every_row_names_a_decoded_type() -> None:
    names = set(FAMILIES)
    for role, types in _table_rows():
        found = re.findall(r"`([\w.]+/?\w+)`", types)
        assert any(t in names for t in found), (role, types)
