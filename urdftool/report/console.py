"""Terminal output shared by the command renderers: rich consoles and fixed-point numbers
(:mod:`urdftool.numbers` formats them)."""

from __future__ import annotations

import sys


def wide_console():
    """A rich console on standard output that never squeezes a table: off a terminal (a pipe, a
    file) it is as wide as the widest table; on one, :func:`print_table` decides the layout."""
    from rich.console import Console

    console = Console(highlight=False)
    if not console.is_terminal:
        console.width = 10_000
    return console


def print_table(console, title: str, headers: list[str], rows: list[list[str]],
                left: int = 1) -> None:
    """A table that fits the terminal: columns when they fit its width, else one block per row
    (``header: value`` lines) that any width can show. Off a terminal, always columns.

    left: how many leading columns are text (left-aligned); the others are numbers
    """
    from rich.markup import escape
    from rich.table import Table

    widths = [max([len(h), *(len(row[i]) for row in rows)]) for i, h in enumerate(headers)]
    needed = sum(widths) + 3 * len(widths) + 1  # rich's borders and one space of padding
    if not console.is_terminal or needed <= console.width:
        table = Table(title=escape(title), title_justify="left")
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
    title, the headers and the text cells are made printable (a name cannot start a line of
    its own); the numbers are this program's."""
    from urdftool.report.summary import printable

    cells = [[printable(cell) for cell in headers]]
    cells += [[*map(printable, row[:left]), *row[left:]] for row in rows]
    widths = [max(len(line[i]) for line in cells) for i in range(len(headers))]
    out = [printable(title)]
    for line in cells:
        out.append("  ".join(cell.ljust(width) if i < left else cell.rjust(width)
                             for i, (cell, width) in enumerate(zip(line, widths))).rstrip())
    stream.write("\n".join(out) + "\n")


def plain_console(stream=None):
    """A rich console on ``stream`` (default: standard output) that never wraps lines."""
    from rich.console import Console

    return Console(file=stream or sys.stdout, highlight=False, soft_wrap=True)


def fixed(value: float, places: int = 6) -> str:
    """``value`` with ``places`` decimals, without the '-0.000000' that round-off leaves."""
    from urdftool.numbers import number

    return number(value, places=places)
