"""Helpers shared by the command renderers: fixed-point numbers."""

from __future__ import annotations

import io

from urdftool.report.console import fixed


def test_fixed_drops_the_minus_of_a_rounded_zero():
    assert fixed(-1e-9) == "0.000000"
    assert fixed(-0.5) == "-0.500000"
    assert fixed(1.23456789, 3) == "1.235"


def _plain(text: str) -> str:
    import re

    return re.sub(r"\x1b\[[0-9;]*m", "", text)


def _terminal(width: int):
    import io

    from rich.console import Console

    return Console(file=io.StringIO(), width=width, force_terminal=True, no_color=True,
                   highlight=False)


HEADERS = ["frame", "x [m]", "y [m]", "z [m]", "roll [rad]"]
ROWS = [["base_link", "0.000000", "0.100000", "0.200000", "1.570796"],
        ["a_much_longer_link_name", "1.000000", "-2.000000", "3.000000", "0.000000"]]


def test_a_table_that_fits_the_terminal_is_printed_as_columns():
    from urdftool.report.console import print_table

    console = _terminal(120)
    print_table(console, "poses", HEADERS, ROWS)
    lines = _plain(console.file.getvalue()).splitlines()
    assert any("roll [rad]" in line and "x [m]" in line for line in lines)
    assert max(map(len, lines)) <= 120


def test_a_table_wider_than_the_terminal_turns_vertical_with_units():
    from urdftool.report.console import print_table

    console = _terminal(40)
    print_table(console, "poses", HEADERS, ROWS)
    lines = _plain(console.file.getvalue()).splitlines()
    assert max(map(len, lines)) <= 40
    assert lines[:3] == ["poses", "base_link", "  x [m]           0.000000"]
    assert "  roll [rad]      1.570796" in lines


class _Stream(io.StringIO):
    def __init__(self, terminal: bool):
        super().__init__()
        self.terminal = terminal

    def isatty(self) -> bool:
        return self.terminal


def test_tables_are_plain_text_off_a_terminal_or_when_long():
    from urdftool.report.console import LONG_TABLE, plain_tables

    assert plain_tables(3, _Stream(False)) and plain_tables(LONG_TABLE + 1, _Stream(True))
    assert not plain_tables(3, _Stream(True))


def test_a_plain_table_aligns_names_left_and_numbers_right_and_prints_names_safely():
    from urdftool.report.console import write_table

    stream = io.StringIO()
    write_table(stream, "poses", HEADERS, [*ROWS, ["evil\nname", "1.0", "2", "3", "4"]])
    lines = stream.getvalue().splitlines()
    assert lines[0] == "poses" and len(lines) == 5  # a line break in a name stays in its row
    assert lines[1].split() == HEADERS[:1] + ["x", "[m]", "y", "[m]", "z", "[m]", "roll", "[rad]"]
    assert lines[2].startswith("base_link ") and lines[2].endswith(" 1.570796")
    assert len({len(line) for line in lines[1:4]}) == 1  # columns line up


def test_no_console_breaks_a_name_or_a_location_on_a_narrow_terminal(monkeypatch):
    """On a real terminal narrower than a name, rich cut ``fk --matrix``'s title and the
    name of a row at a blank: ``::error::forged`` started a line of its own, and a
    ``file:line`` holding a blank came out as two lines no click or grep finds (attacks.md
    A171). The terminal folds a long line itself; rich never breaks one."""
    from urdftool.report.console import plain_console, print_table, wide_console

    name = "base link with blanks ::error::forged and more words"
    where = "my robots/urdf/robot.urdf:12"
    for make in (wide_console, lambda: plain_console(_Stream(True))):
        stream = _Stream(True)
        monkeypatch.setattr("sys.stdout", stream)
        monkeypatch.setenv("COLUMNS", "30")
        console = make()
        assert console.is_terminal and console.width == 30
        print_table(console, f"poses relative to {name}", HEADERS, [[name, *ROWS[0][1:]]])
        console.print(f"{where}: joint '{name}': a finding")
        lines = _plain(console.file.getvalue()).splitlines()
        assert lines[:2] == [f"poses relative to {name}", name], lines
        assert f"{where}: joint '{name}': a finding" in lines


def test_a_terminal_of_no_columns_is_drawn_80_wide_not_left_empty(monkeypatch):
    """``COLUMNS=0`` on a terminal (a script's ``export COLUMNS=$(tput cols)`` where tput knows
    no width): rich drew in no columns and printed nothing, a check's findings and summary
    gone with exit 1, fk's poses gone with exit 0."""
    from urdftool.report.console import plain_console, print_table, wide_console

    for make in (wide_console, lambda: plain_console(_Stream(True))):
        monkeypatch.setattr("sys.stdout", _Stream(True))
        monkeypatch.setenv("COLUMNS", "0")
        console = make()
        assert console.is_terminal and console.width == 80
        print_table(console, "poses", HEADERS, ROWS)
        console.print("robot.urdf:3: error U204 a finding")
        text = _plain(console.file.getvalue())
        assert "a_much_longer_link_name" in text and "robot.urdf:3: error U204" in text, text
