"""Terminal output shared by the command renderers: rich consoles and fixed-point numbers
(:mod:`urdftool.numbers` formats them)."""

from __future__ import annotations

import functools
import sys


def wide_console():
    """A rich console on standard output that never squeezes a table: off a terminal (a pipe, a
    file) it is as wide as the widest table; on one, :func:`print_table` decides the layout."""
    from rich.console import Console

    return _guarded(Console(highlight=False, emoji=False))


def print_table(console, title: str, headers: list[str], rows: list[list[str]],
                left: int = 1) -> None:
    """A table that fits the terminal: columns when they fit its width, else one block per row
    (``header: value`` lines) that any width can show. Off a terminal, always columns.

    left: how many leading columns are text (left-aligned); the others are numbers
    """
    from rich.table import Table
    from rich.text import Text

    from urdftool.report.escape import markup as escape, text

    widths = [max([len(h), *(len(text(row[i])) for row in rows)])
              for i, h in enumerate(headers)]
    needed = sum(widths) + 3 * len(widths) + 1  # rich's borders and one space of padding
    if not console.is_terminal or needed <= console.width:
        # the title on one line, however long (rich wraps it at the table's width: a name's
        # blank would start a line of its own there)
        table = Table(title=Text(text(title), no_wrap=True, overflow="ignore"),
                      title_justify="left")
        for i, header in enumerate(headers):
            table.add_column(escape(header), justify="left" if i < left else "right",
                             no_wrap=True)
        for row in rows:
            table.add_row(*map(escape, row))
        console.print(table)
        return
    console.print(escape(title))
    label = max(len(h) for h in headers[left:]) if headers[left:] else 0
    for row in rows:
        console.print(escape("  ".join(row[:left])))
        for header, value in zip(headers[left:], row[left:]):
            console.print(escape(f"  {header:<{label}}  {value:>12}"))


LONG_TABLE = 50  # [rows]: past this a table is plain text on a terminal too (rich: ~2 ms a row)


def plain_tables(rows: int, stream=None) -> bool:
    """Whether a table of ``rows`` rows goes out as plain aligned text (:func:`write_table`)
    rather than through rich: off a terminal (a pipe, a file: rich's borders earn nothing
    there) and for long tables, where rich's layout costs seconds."""
    stream = stream or sys.stdout
    try:
        terminal = stream.isatty()
    except (AttributeError, ValueError):
        terminal = False
    return rows > LONG_TABLE or not terminal


def write_table(stream, title: str, headers: list[str], rows: list[list[str]],
                left: int = 1) -> None:
    """A table as plain text: its title, then the headers and the rows in columns two spaces
    apart, the ``left`` leading (text) columns left-aligned, the numbers right-aligned. The
    title, the headers and the text cells are terminal text (urdftool.report.escape.text: a
    name cannot start a line of its own); the numbers are this program's. Linear in the cells,
    a few string operations each: ``fk --q-file`` writes 10,000 tables of the same frames."""
    from urdftool.report.escape import text

    cells = [[_cell_text(cell) for cell in headers]]
    cells += [[*map(_cell_text, row[:left]), *row[left:]] for row in rows]
    widths = [max(map(len, column)) for column in zip(*cells)]
    line = "  ".join(f"{{:{'<' if i < left else '>'}{width}}}"
                     for i, width in enumerate(widths)).format
    out = [text(title)]
    out += [line(*cells_of_line).rstrip() for cells_of_line in cells]
    stream.write("\n".join(out) + "\n")


@functools.lru_cache(maxsize=4096)
def _cell_text(cell: str) -> str:
    """:func:`urdftool.report.escape.text` of a header or text cell, remembered: long outputs
    repeat the same names in every table."""
    from urdftool.report.escape import text

    return text(cell)


def plain_console(stream=None):
    """A rich console on ``stream`` (default: standard output) that never wraps lines."""
    from rich.console import Console

    return _guarded(Console(file=stream or sys.stdout, highlight=False, soft_wrap=True,
                            emoji=False))


def _guarded(console):
    """``console`` off a terminal (a CI log, a pipe, a file): as wide as its widest table (a
    table squeezed to 80 columns wraps a name at its blanks: a piece of it would start a line),
    and every line it writes through urdftool.report.escape.text (whatever a renderer let
    through, no line is a workflow command or holds an escape sequence). On a terminal, rich's
    own colours stand, and the renderers' markup() alone guards; rich never breaks a line
    there either (``soft_wrap``: a name or a ``file:line`` longer than the terminal is folded by
    the terminal, one line still, whole when copied or searched, not cut at a blank into a
    line a piece of the name starts). A terminal of no columns is 80 wide, rich's own width
    where it cannot tell: rich took ``COLUMNS=0`` as said, and printed nothing at all (a
    check's findings and its summary, with exit 1)."""
    from urdftool.report.escape import Lines

    console.soft_wrap = True
    if not console.is_terminal:
        console.width = 10_000
        console.file = Lines(console.file)
    elif console.width < 1:  # COLUMNS=0 (a script's `export COLUMNS=$(tput cols)` where tput
        console.width = 80  # knows no width): rich drew everything in no columns, nothing
    return console


def fixed(value: float, places: int = 6) -> str:
    """``value`` with ``places`` decimals, without the '-0.000000' that round-off leaves."""
    from urdftool.numbers import number

    return number(value, places=places)
