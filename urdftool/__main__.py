"""``python -m urdftool``: the command line."""

from urdftool.cli import app

app(prog_name="urdftool")
