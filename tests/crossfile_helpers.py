"""Helpers for the cross-file rule tests: tiny robots with companions, broken example copies."""

from __future__ import annotations

import shutil
import textwrap
from pathlib import Path

from conftest import CASES, ROBOTS
from urdftool.description.robot import CompanionPaths
from urdftool.lint.engine import CheckOptions, Selection, load_and_check

HEAD_ROBOT = """<robot name="r">
  <link name="base_link"/><link name="head"/><link name="cam"/>
  <joint name="head_joint" type="revolute">
    <parent link="base_link"/><child link="head"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="5" velocity="1"/>
  </joint>
  <joint name="cam_joint" type="fixed"><parent link="head"/><child link="cam"/></joint>
  {body}
</robot>
"""


def served_copy(tmp_path: Path, text: str, name: str = "robot.urdf") -> Path:
    """A robot file ``text`` that a web application of the repository at ``tmp_path`` serves
    as it is (``frontend/public/NAME``) and its source fetches (three.js urdf-loader): a web
    page reads it (urdftool.description.readers). Returns its path."""
    (tmp_path / ".git").mkdir()  # (the application is the repository's own)
    frontend = tmp_path / "frontend"
    (frontend / "src").mkdir(parents=True)
    (frontend / "public").mkdir()
    (frontend / "package.json").write_text("{}")
    (frontend / "src" / "model.ts").write_text(f"loader.load('/{name}');\n")
    path = frontend / "public" / name
    path.write_text(text)
    return path


def check_folder(folder: Path, files: dict, select=("U5", "U6", "U7", "U8"), controllers=(),
                 srdf=None, spec=None):
    """Write ``files`` (name -> text) into ``folder`` and check ``robot.urdf`` there.

    Returns [(file name, line, code)] of the selected findings, and the findings.
    """
    for name, text in files.items():
        path = folder / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(textwrap.dedent(text))
    options = CheckOptions(selection=Selection(tuple(select)),
                           companions=CompanionPaths(tuple(controllers), srdf, spec))
    result = load_and_check(str(folder / "robot.urdf"), options)
    return [(Path(f.file).name, f.line, f.code) for f in result.findings], result.findings


def broken_copy(tmp_path: Path, robot: str, file: str, old: str, new: str, count: int = 1):
    """Copy robots/ROBOT to tmp_path, replace ``old`` by ``new`` in FILE, check the robot."""
    folder = tmp_path / robot
    shutil.copytree(ROBOTS / robot, folder)
    path = folder / file
    text = path.read_text()
    assert text.count(old) == count, f"{old!r} occurs {text.count(old)} times in {file}"
    path.write_text(text.replace(old, new))
    result = load_and_check(str(folder / f"{robot}.urdf.xacro"), CheckOptions())
    return result.findings


def line_of(path: Path, text: str) -> int:
    """1-based line of the first line containing ``text``."""
    return next(n for n, line in enumerate(path.read_text().splitlines(), 1) if text in line)


def case_messages(case: str, code: str) -> list[str]:
    """The messages of ``code`` that checking the case file or folder ``case`` gives."""
    path = CASES / case
    if path.is_dir():
        path = next(p for p in path.iterdir() if p.name.endswith((".urdf", ".urdf.xacro")))
    return [f.message for f in load_and_check(str(path), CheckOptions()).findings if f.code == code]
