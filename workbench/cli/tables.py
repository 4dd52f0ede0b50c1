"""Tables printed whole: piped, redirected or in a narrow terminal, no cell is cut.

Rich fits a table to the console's width by cutting cells (``en…``, ``ob…``), and a console
that is not a terminal is 80 columns wide. :func:`print_table` prints instead:

- piped or redirected: at the table's natural width (one line per row, for ``grep``/``cut``);
- in a terminal wide enough: as Rich draws it;
- in a narrower terminal: cells wrap inside their column, each column at least as wide as its
  header and its longest word;
- in a terminal too narrow even for that: one block per row, ``column: value`` per line.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from rich.console import Console
from rich.measure import Measurement
from rich.text import Text

if TYPE_CHECKING:
    from rich.console import RenderableType
    from rich.table import Table

__all__ = ["print_table"]

#: Width of a column's borders and padding in Rich's default box (characters).
_COLUMN_FRAME = 3


def _plain(cell: RenderableType) -> str:
    if isinstance(cell, Text):
        return cell.plain
    return Text.from_markup(cell).plain if isinstance(cell, str) else str(cell)


def _least_width(table: Table) -> int:
    """The narrowest the table gets with every header and every word whole."""
    total = 1
    for column in table.columns:
        words = [w for cell in column.cells for w in _plain(cell).split()]
        longest = max((len(w) for w in words), default=0)
        total += max(len(_plain(column.header)), longest) + _COLUMN_FRAME
    return total


def _as_blocks(table: Table, console: Console) -> None:
    headers = [_plain(c.header) for c in table.columns]
    pad = max((len(h) for h in headers), default=0)
    if table.title:
        console.print(Text(_plain(table.title), style="bold"))
    rows = zip(*(list(c.cells) for c in table.columns), strict=True)
    for n, row in enumerate(rows):
        if n:
            console.print()
        for header, cell in zip(headers, row, strict=True):
            console.print(Text(f"{header:<{pad}}  {_plain(cell)}"), overflow="fold")


def print_table(table: Table, console: Console | None = None) -> None:
    """Print ``table`` so that no cell is cut (see the module docstring).

    Args:
        table: The table (its columns' wrapping may be changed to fit).
        console: Where to print (default: standard output).
    """
    console = console or Console()
    natural = Measurement.get(console, console.options.update(width=10**6), table).maximum
    if not console.is_terminal:
        Console(
            file=console.file, width=max(natural, console.width), no_color=True, soft_wrap=True
        ).print(table)
        return
    if natural <= console.width:
        console.print(table)
        return
    if _least_width(table) > console.width:
        _as_blocks(table, console)
        return
    for column in table.columns:
        words = [w for cell in column.cells for w in _plain(cell).split()]
        column.min_width = max([len(_plain(column.header)), *(len(w) for w in words)])
        column.no_wrap = False
        column.overflow = "fold"
    console.print(table)
