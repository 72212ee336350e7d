"""A lint-only install (no Pinocchio, FCL, yourdfpy or Pillow) checks robots, and the analysis
commands say which extra to install. The analysis libraries are hidden from a fresh interpreter
(``sys.modules[name] = None`` makes importing them fail as if they were not installed)."""

from __future__ import annotations

import json
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


# what a check reads through its libraries' optional paths: an OBJ in UTF-16 with materials
# (trimesh's util.decode_text, which urdftool calls, imports charset_normalizer)
UTF16_ROBOT = ('<robot name="r"><link name="a"><visual><geometry><mesh filename="m.obj"/>'
               '</geometry></visual></link></robot>\n')
# a check in a fresh interpreter, the modules of sys.argv[2] (JSON) not installed; its findings
ONLY = ("import json, sys\n"
        "from importlib.machinery import PathFinder\n"
        "class Absent(PathFinder):\n"  # (found nowhere, as an uninstalled module is)
        "    @classmethod\n"
        "    def find_spec(cls, name, path=None, target=None):\n"
        "        if name.split('.')[0] not in json.loads(sys.argv[2]):\n"
        "            return PathFinder.find_spec(name, path, target)\n"
        "sys.meta_path[sys.meta_path.index(PathFinder)] = Absent\n"
        "import urdftool\n"
        "result = urdftool.check_file(sys.argv[1], use_settings=False)\n"
        "print(json.dumps([(f.code, f.location.line, f.message) for f in result.findings]))\n")


def _installed_with_urdftool() -> set[str]:
    """The distributions a lint-only install holds: what ``[project] dependencies`` name and
    what those require, without their extras (canonical names)."""
    import tomllib
    from importlib import metadata

    from packaging.requirements import Requirement
    from packaging.utils import canonicalize_name

    from conftest import ROOT

    installed, todo = {"urdftool"}, [Requirement(text) for text in tomllib.loads(
        (ROOT / "pyproject.toml").read_text())["project"]["dependencies"]]
    while todo:
        requirement = todo.pop()
        name = canonicalize_name(requirement.name)
        if name in installed or (requirement.marker and not requirement.marker.evaluate({"extra": ""})):
            continue
        installed.add(name)
        todo.extend(Requirement(text) for text in metadata.requires(requirement.name) or ())
    return installed


def test_a_check_finds_the_same_with_only_what_installing_urdftool_installs(tmp_path):
    """A lint-only install holds what ``[project] dependencies`` name and what those require
    (no extra of theirs). trimesh decodes a mesh's text that is not UTF-8 with
    charset_normalizer, which only trimesh's ``easy`` extra installs: this environment had it,
    an install of urdftool (and the lowest-versions environment, make test-lowest) did not, and
    a check of a UTF-16 OBJ with materials there failed on the import. Every other module of
    this environment absent, the check finds what it finds here."""
    from importlib import metadata

    from packaging.utils import canonicalize_name

    (tmp_path / "m.obj").write_bytes("v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl m\nf 1 2 3\n".encode("utf-16"))
    (tmp_path / "r.urdf").write_text(UTF16_ROBOT)
    installed = _installed_with_urdftool()
    absent = sorted(module for module, names in metadata.packages_distributions().items()
                    if not {canonicalize_name(name) for name in names} & installed
                    and module not in sys.stdlib_module_names)
    found = [subprocess.run([sys.executable, "-c", ONLY, tmp_path / "r.urdf", json.dumps(hidden)],
                            capture_output=True, text=True, timeout=300) for hidden in ([], absent)]
    assert all(done.returncode == 0 for done in found), found[1].stderr
    assert json.loads(found[1].stdout) == json.loads(found[0].stdout)
