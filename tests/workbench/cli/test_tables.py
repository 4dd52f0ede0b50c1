"""Tables printed whole, piped or in a narrow terminal."""

from __future__ import annotations

import io

from rich.console import Console
from rich.table import Table

from workbench.cli.tables import print_table

CELLS = ("rss-000100-d4d4f5cc56", "reachsets", "RSS lon BrakeMin, lat-left BrakeMin", "100-185")
HEADERS = ("id", "engine", "cause", "frames")


def _table() -> Table:
    table = Table(title="incidents")
    for header in HEADERS:
        table.add_column(header)
    table.add_row(*CELLS)
    table.add_row(*reversed(CELLS))
    return table


def _printed(width: int, *, terminal: bool) -> str:
    out = io.StringIO()
    console = Console(file=out, width=width, force_terminal=terminal, color_system=None)
    print_table(_table(), console)
    return out.getvalue()


def test_piped_tables_keep_every_cell_on_one_line() -> None:
    text = _printed(20, terminal=False)
    rows = [line for line in text.splitlines() if CELLS[0] in line]
    assert len(rows) == 2
    assert all(cell in rows[0] for cell in CELLS)
    assert "…" not in text


def test_a_narrow_terminal_wraps_cells_and_keeps_headers_and_words_whole() -> None:
    text = _printed(72, terminal=True)
    assert "…" not in text
    assert max(len(line) for line in text.splitlines()) <= 72
    for word in {w for cell in (*CELLS, *HEADERS) for w in cell.split()}:
        assert word in text


def test_a_very_narrow_terminal_prints_one_block_per_row() -> None:
    text = _printed(30, terminal=True)
    assert "…" not in text
    assert max(len(line) for line in text.splitlines()) <= 30
    squeezed = "".join(text.split())
    for header, cell in zip(HEADERS, CELLS, strict=True):
        assert any(line.split()[:1] == [header] for line in text.splitlines())
        assert header + "".join(cell.split()) in squeezed
