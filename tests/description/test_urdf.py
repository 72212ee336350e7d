"""The URDF vocabulary has one owner (description/urdf.py) and matches urdfdom's."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from conftest import CHECK_URDF, check_urdf
from urdftool.description import urdf

PACKAGE = Path(urdf.__file__).resolve().parents[1]


def _check_urdf(tmp_path, kind: str, limit: bool) -> bool:
    """Whether urdfdom accepts a two-link robot whose joint has this type."""
    if not CHECK_URDF:
        pytest.skip("urdfdom's check_urdf is not installed (the pin wheel of the analysis extra "
                    "has it)")
    text = (f'<robot name="r"><link name="a"/><link name="b"/><joint name="j" type="{kind}">'
            '<parent link="a"/><child link="b"/><axis xyz="0 0 1"/>'
            + ('<limit lower="-1" upper="1" effort="1" velocity="1"/>' if limit else "")
            + "</joint></robot>")
    path = tmp_path / f"{kind}{'' if limit else '_without_limit'}.urdf"  # (verdicts cached by path)
    path.write_text(text)
    run = check_urdf(path)  # (bounded in time: urdfdom loops on a cycle)
    return run.returncode == 0 and "Error" not in run.stdout + run.stderr


@pytest.mark.parametrize("kind", urdf.JOINT_TYPES + ("hinge", "ball"))
def test_joint_types_are_urdfdoms(kind, tmp_path):
    assert _check_urdf(tmp_path, kind, limit=True) == (kind in urdf.JOINT_TYPES)
    # urdfdom refuses exactly the LIMITED types without a <limit>
    if kind in urdf.JOINT_TYPES:
        assert _check_urdf(tmp_path, kind, limit=False) == (kind not in urdf.LIMITED)


def test_the_sets_are_consistent():
    assert set(urdf.MOVING) | {"fixed", "floating", "planar"} == set(urdf.JOINT_TYPES)
    assert set(urdf.LIMITED) <= set(urdf.MOVING) <= set(urdf.AXIS) <= set(urdf.VARIABLE)
    assert set(urdf.VARIABLE) == set(urdf.JOINT_TYPES) - {"fixed"}
    assert set(urdf.ANGULAR) | {"prismatic"} == set(urdf.MOVING)
    assert set(urdf.UNITS) == set(urdf.LIMITED)
    assert set(urdf.SHAPE_ATTRIBUTES) == set(urdf.SHAPES) and set(urdf.ROUND) < set(urdf.SHAPES)


_NAMES = "|".join(urdf.JOINT_TYPES + urdf.SHAPES)
_LIST = re.compile(rf"""["']({_NAMES})["'](\s*,\s*["']({_NAMES})["']){{2,}}""")


def test_no_second_copy_of_the_vocabulary():
    """No module but description/urdf.py spells out three or more joint types or shapes."""
    copies = [f"{path.relative_to(PACKAGE.parent)}:{number}"
              for path in sorted(PACKAGE.rglob("*.py")) if path.name != "urdf.py"
              for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1)
              if _LIST.search(line)]
    assert not copies, copies


def test_the_copy_finder_sees_a_copy():
    assert _LIST.search('MOVE = ("revolute", "continuous", "prismatic")')
    assert _LIST.search("if tag in ('box', 'cylinder', 'sphere'):")
    assert not _LIST.search('kind in ("revolute", "prismatic")')


@pytest.mark.parametrize("written, said", [
    ("1\u00b3.0", "is not of the form MAJOR.MINOR"),  # str.isdigit() took it, int() refused it
    ("1.\u0663", "is not of the form MAJOR.MINOR"),  # int() reads it, urdfdom does not
    ("9" * 5000 + ".0", "(5002 characters) is not supported"),  # past int()'s digits
    ("1.2", None), ("01.0", None), ("1.3", "is not supported"),
])
def test_a_version_that_is_no_ascii_number_is_said_not_crashed(written, said):
    """U012 crashed (U900: ValueError) on ``<robot version="1³.0">`` and on a major version
    of 5,000 digits."""
    from urdftool.description.urdf import version_problem

    problem = version_problem(written)
    assert problem is None if said is None else said in problem
