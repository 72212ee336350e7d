"""A lint-only install (no Pinocchio, FCL, yourdfpy or Pillow) checks robots, and the analysis
commands say which extra to install. The analysis libraries are hidden from a fresh interpreter
(``sys.modules[name] = None`` makes importing them fail as if they were not installed)."""

from __future__ import annotations

import subprocess
import sys

import pytest

from conftest import CASES, ROBOTS
from urdftool.origin import install_command

HIDE = ("import sys; sys.modules.update(pinocchio=None, fcl=None, yourdfpy=None, PIL=None); "
        "sys.argv = ['urdftool', *sys.argv[1:]]; from urdftool.cli import main; main()")


def lint_only(*words):
    return subprocess.run([sys.executable, "-c", HIDE, *map(str, words)], capture_output=True,
                          text=True, timeout=300)


def test_check_needs_no_analysis_library():
    result = lint_only("check", ROBOTS, CASES / "U204_inverted_limits.urdf", "-f", "concise")
    assert result.returncode == 1, result.stderr
    assert "U204" in result.stdout and "U900" not in result.stdout
    notes = [line for line in result.stdout.splitlines() if " U902 " in line]
    # only the SRDF pose checks (FCL) are left out, each said once per robot with an SRDF
    assert notes and all("did not run" in line and any(code in line for code in ("U810", "U811", "U823"))
                         for line in notes), result.stdout
    # a robot without an SRDF loses nothing: no note says a check of its SRDF did not run
    assert all("humanoid" in line for line in notes), result.stdout


@pytest.mark.parametrize("command", [["fk"], ["dynamics"], ["collisions"]])
def test_analysis_commands_say_which_extra_to_install(command):
    result = lint_only(*command, ROBOTS / "r2d2" / "r2d2.urdf.xacro")
    assert result.returncode == 2, result.stderr
    assert install_command("analysis") in result.stderr
    assert "Traceback" not in result.stderr


def test_a_rule_that_needs_an_analysis_library_is_a_note_not_a_crash(monkeypatch):
    from urdftool.description.load import load
    from urdftool.lint import engine
    from urdftool.lint.rules import CATALOGUE

    def needs_fcl(robot):
        import fcl  # noqa: F401

        yield None, "never"

    rule = CATALOGUE.get("U204")
    monkeypatch.setitem(sys.modules, "fcl", None)
    robot = load(str(CASES / "U204_inverted_limits.urdf"))
    rules = [r for r in CATALOGUE if r.code != "U204"]
    fake = type(rule)(rule.code, rule.name, rule.severity, needs_fcl, rule.doc)
    monkeypatch.setattr(CATALOGUE, "running", lambda targets: (*rules, fake))
    findings = engine.check_robot(robot)
    [note] = [f for f in findings if f.code == "U902" and "U204" in f.message]
    assert "rule U204 (inverted-limits) did not run" in note.message
    assert install_command("analysis") in note.message
    assert not [f for f in findings if f.code == "U900"]
