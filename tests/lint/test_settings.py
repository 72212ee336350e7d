"""Settings discovery: every key documented in docs/settings.md does what it says."""

from __future__ import annotations

import datetime
import json
import os
import random
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

from urdftool.description.robot import CompanionPaths
from urdftool.lint import engine
from urdftool.errors import SettingsError
from urdftool.lint.settings import KEYS, may_hold, settings_file, settings_for

ROBOT = """<robot name="r">
  <link name="base_link"/>
  <link name="arm"/>
  <joint name="elbow" type="revolute">
    <parent link="base_link"/><child link="arm"/>
    <axis xyz="0 0 2"/>
    <limit lower="1" upper="-1" effort="1" velocity="1"/>
  </joint>
</robot>
"""


@pytest.fixture
def project(tmp_path):
    (tmp_path / "robots").mkdir()
    (tmp_path / "robots" / "arm.urdf").write_text(ROBOT)
    return tmp_path


def codes(run_cli, *args) -> tuple[int, list[str]]:
    result = run_cli("check", *args, "--format", "json")
    assert result.exit_code in (0, 1) or result.exit_code == 2 and \
        "not checked: a package" in result.output, result.output
    return result.exit_code, sorted(d["code"] for d in json.loads(result.stdout)["diagnostics"])


def settings(project, text: str, name: str = "pyproject.toml") -> None:
    header = "[tool.urdftool]\n" if name == "pyproject.toml" else ""
    (project / name).write_text(header + text)


def test_a_settings_file_another_user_owns_outside_a_repository_is_not_read_and_said(
        run_cli, project, monkeypatch):
    """Outside a repository settings are looked for up to /: a pyproject.toml another local
    user left in /tmp selected and ignored the rules of a check of an archive unpacked below
    it, in silence. Not read, and said (git reads no repository another user owns); inside a
    repository, or named with --config, it is the user's to read."""
    from conftest import another_users

    settings(project, 'ignore = ["U204"]\n')
    another_users(project / "pyproject.toml", monkeypatch)
    result = run_cli("check", project / "robots", "--format", "json")
    assert sorted(d["code"] for d in json.loads(result.stdout)["diagnostics"]) == ["U204", "U206"]
    assert f"urdftool: settings file '{project / 'pyproject.toml'}' not read: it belongs to " \
           "another user" in result.stderr and "give it with --config" in result.stderr
    assert codes(run_cli, project / "robots", "--config", project / "pyproject.toml") == (0, ["U206"])
    (project / ".git").mkdir()
    assert codes(run_cli, project / "robots") == (0, ["U206"])


def test_no_settings(run_cli, project):
    assert codes(run_cli, project / "robots") == (1, ["U204", "U206"])


def test_select_and_cli_select_replaces_it(run_cli, project):
    settings(project, 'select = ["U206"]\n')
    assert codes(run_cli, project / "robots") == (0, ["U206"])
    assert codes(run_cli, project / "robots", "--select", "U204") == (1, ["U204"])


def test_ignore_by_name_and_cli_ignore_adds(run_cli, project):
    settings(project, 'ignore = ["inverted-limits"]\n')
    assert codes(run_cli, project / "robots") == (0, ["U206"])
    assert codes(run_cli, project / "robots", "--ignore", "U2") == (0, [])


@pytest.mark.parametrize("text, words", [
    ('ignore = ["U"]\n', []),  # a pull request switches every rule off
    ('select = ["U2"]\nignore = ["U2"]\n', []),
    ('select = ["U92"]\n', []),  # MuJoCo's rules, MuJoCo not asked for
    ("", ["--ignore", "U"]),
    ("", ["--select", "U1", "--ignore", "U1"]),
])
def test_a_selection_that_leaves_no_rule_is_an_error_not_a_pass(run_cli, project, text, words):
    """Before: '1 file checked: no problems found', exit 0, on a robot with errors."""
    settings(project, text)
    result = run_cli("check", project / "robots", *words)
    assert result.exit_code == 2 and "leave no rule to check" in result.output, result.output
    assert "no problems found" not in result.output


def test_a_per_file_ignore_of_every_rule_leaves_those_files_out(run_cli, project):
    """How a repository leaves vendored robots out: not a selection of nothing."""
    settings(project, '[tool.urdftool.per-file-ignores]\n"robots/*" = ["U"]\n')
    assert codes(run_cli, project / "robots") == (0, [])


@pytest.mark.parametrize("text", ["[tool]\nurdftool = 5\n", 'tool.urdftool = "select"\n',
                                  "[[tool.urdftool]]\nselect = []\n"])
def test_tool_urdftool_that_is_not_a_table_is_a_settings_error(run_cli, project, text):
    (project / "pyproject.toml").write_text(text)
    result = run_cli("check", project / "robots")
    assert result.exit_code == 2 and "must be a table of settings" in result.output, \
        result.output


def test_per_file_ignores_by_relative_glob_and_by_name(run_cli, project):
    settings(project, '[tool.urdftool.per-file-ignores]\n"robots/*.urdf" = ["U204"]\n'
                      '"arm.urdf" = "axis-not-unit"\n')
    assert codes(run_cli, project / "robots") == (0, [])
    settings(project, '[tool.urdftool.per-file-ignores]\n"other/*.urdf" = ["U2"]\n')
    assert codes(run_cli, project / "robots") == (1, ["U204", "U206"])


def test_strict(run_cli, project):
    settings(project, 'ignore = ["U204"]\nstrict = true\n')
    assert codes(run_cli, project / "robots") == (1, ["U206"])


def test_max_file_size(run_cli, project):
    settings(project, "max-file-size = 10\n")
    assert codes(run_cli, project / "robots") == (1, ["U008"])


@pytest.mark.parametrize("value", ["100000000000000000000", "0", "-5", '"16M"', "true", "1.5"])
def test_max_file_size_out_of_range_is_a_usage_error(run_cli, project, value):
    """10**20 bytes overflowed a read (OverflowError traceback); a string or a bool slipped in."""
    settings(project, f"max-file-size = {value}\n")
    result = run_cli("check", project / "robots")
    assert result.exit_code == 2 and "'max-file-size' must be a whole number" in result.stderr
    assert "Traceback" not in result.output


def test_max_file_size_option_out_of_range_is_a_usage_error(run_cli, project):
    result = run_cli("check", "--max-file-size", str(2 ** 41), project / "robots")
    assert result.exit_code == 2 and "--max-file-size must be a whole number" in result.stderr
    result = run_cli("check", "--max-file-size", str(10 ** 20), project / "robots")  # (no int64)
    assert result.exit_code == 2 and "past what an integer option holds" in result.stderr


def test_urdftool_toml_wins_over_pyproject_in_the_same_folder(run_cli, project):
    settings(project, 'ignore = ["U204"]\n')
    settings(project, 'ignore = ["U206"]\n', "urdftool.toml")
    assert codes(run_cli, project / "robots") == (1, ["U204"])


def test_found_above_the_input_and_pyproject_without_table_is_skipped(run_cli, project):
    settings(project, 'ignore = ["U2"]\n')
    (project / "robots" / "pyproject.toml").write_text("[project]\nname = 'x'\n")
    assert codes(run_cli, project / "robots" / "arm.urdf") == (0, [])


@pytest.mark.parametrize("text", ["[project\nname = 'x'\n", "x = [" + "[" * 5000 + "\n"])
def test_a_pyproject_that_cannot_hold_our_table_is_not_read(run_cli, project, text):
    """Another project's pyproject.toml, broken or hostile, is no settings file of ours: only
    one whose text could spell ``urdftool`` (bare, or quoted with an escape) is parsed."""
    settings(project, 'ignore = ["U2"]\n')
    (project / "robots" / "pyproject.toml").write_text(text)
    assert codes(run_cli, project / "robots" / "arm.urdf") == (0, [])
    (project / "robots" / "pyproject.toml").write_text(text + '[tool."\\u0075rdftool"]\n')
    assert run_cli("check", project / "robots" / "arm.urdf").exit_code == 2


def test_a_pyproject_naming_urdftool_elsewhere_is_not_read(run_cli, project):
    """A Python package's pyproject.toml names its package in other tables (``[project.scripts]
    urdftool = ...``): no settings table of ours can be in it, so a defect in it (a missing
    comma) stops nothing; ``[tool.urdftool]`` added, it is read (and its defect said)."""
    settings(project, 'ignore = ["U2"]\n')
    text = '[project]\nname = "urdftool"\n[project.scripts]\nurdftool = "a:b"\nx = [1 2]\n'
    (project / "robots" / "pyproject.toml").write_text(text)
    assert codes(run_cli, project / "robots" / "arm.urdf") == (0, [])
    (project / "robots" / "pyproject.toml").write_text(text + "[tool.urdftool]\n")
    assert run_cli("check", project / "robots" / "arm.urdf").exit_code == 2


@pytest.mark.parametrize("text, holds", [
    ("[tool.urdftool]\n", True),
    ("[ tool . 'urdftool' ] # settings\n", True),
    ('[[tool."urdftool"]]\n', True),
    ('[tool]\nurdftool = {select = ["U1"]}\n', True),
    ("[tool]\r\nurdftool.select = []\r\n", True),
    ("tool.urdftool.select = []\n", True),
    ("tool = {urdftool = {}}\n", True),
    ('[tool]\nx = [\n  ["a"]\n]\nurdftool = {}\n', True),  # a nested array is no header
    ('[tool]\nx = """\n[project]\n"""\nurdftool = {}\n', True),  # nor a string's line
    ('[tool."\\u0075rdftool"]\n', True),  # an escape: the parser tells
    ("[tool.x]\nurdftool = 1\n", False),
    ('[project.scripts]\nurdftool = "urdftool.__main__:main"\n', False),
    ('[project]\nname = "urdftool"  # [tool.urdftool]\n', False),
    ('"tool.urdftool" = 1\n', False),  # one quoted key
    ('[tool]\nx = {urdftool = 1}\n', False),  # tool.x.urdftool
    ("[project]\nname = 'x'\n", False),
])
def test_may_hold_tells_where_a_key_of_tool_may_be(text, holds):
    assert may_hold(text, "tool", "urdftool") is holds


def _toml_document(chance: random.Random) -> str:
    """A TOML document of headers, keys and values in the spellings the plain lines of
    may_hold read (and some they do not), naming tool and urdftool often."""
    names = ["tool", "urdftool", "project", "x", "a-b", "tool.urdftool", "urdf tool"]

    def key():
        name, style = chance.choice(names), chance.randrange(3)
        if style == 0 and all(c.isalnum() or c in "_-" for c in name):
            return name
        return f'"{name}"' if style == 1 else f"'{name}'"

    def dotted():
        space = chance.choice(["", " ", "\t"])
        return f"{space}.{space}".join(key() for _ in range(chance.randint(1, 3)))

    def value(depth=0):
        kind = chance.randrange(5 if depth < 2 else 3)
        if kind == 0:
            return '"' + chance.choice(["urdftool", "[tool.urdftool]", "# x"]) + '"'
        if kind == 1:
            return chance.choice(["1", "true", "3.5", "1979-05-27", "'urdftool'", '"""a"""'])
        if kind == 2:
            return "'" + chance.choice(["urdftool", "a=b"]) + "'"
        if kind == 3:
            separator = chance.choice([", ", ",\n  ", " ,\n# urdftool\n "])
            return "[" + separator.join(value(depth + 1) for _ in range(chance.randint(0, 3))) \
                + chance.choice(["", ","]) + "]"
        return "{" + ", ".join(f"{dotted()} = {value(depth + 1)}"
                               for _ in range(chance.randint(0, 2))) + "}"

    lines = []
    for _ in range(chance.randint(1, 8)):
        kind = chance.randrange(5)
        if kind == 0:
            lines.append(f"[{dotted()}]" if chance.random() < 0.7 else f"[[{dotted()}]]")
        elif kind == 1:
            lines.append(chance.choice(["# urdftool", "# [tool.urdftool]", ""]))
        else:
            lines.append(f"{chance.choice(['', '  '])}{dotted()} = {value()}")
    return chance.choice(["\n", "\r\n"]).join(lines) + "\n"


def test_may_hold_never_misses_a_table_the_parser_finds():
    """Seeded random documents: whenever tomllib finds ``tool.urdftool`` in one, may_hold says
    it may be there (and it says False for some of the others: the test cannot pass by
    always saying True)."""
    chance, holding, told_not = random.Random(34), 0, 0
    for _ in range(4000):
        text = _toml_document(chance)
        try:
            data = tomllib.loads(text)
        except tomllib.TOMLDecodeError:
            continue
        tool = data.get("tool")
        if isinstance(tool, dict) and "urdftool" in tool:
            holding += 1
            assert may_hold(text, "tool", "urdftool"), text
        elif not may_hold(text, "tool", "urdftool"):
            told_not += 1
    assert holding > 50 and told_not > 500


def test_packages_relative_to_the_settings_file(run_cli, project):
    (project / "src" / "my_description").mkdir(parents=True)
    (project / "src" / "my_description" / "parts.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="arm"/></robot>')
    (project / "robots" / "arm.urdf.xacro").write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:include filename="$(find my_description)/parts.xacro"/>\n'
        '  <link name="base_link"/>\n'
        '  <joint name="j" type="fixed"><parent link="base_link"/><child link="arm"/></joint>\n'
        '</robot>\n')
    (project / "robots" / "arm.urdf").unlink()
    assert codes(run_cli, project / "robots") == (2, ["U006"])  # not checked: exit 2
    settings(project, '[tool.urdftool.packages]\nmy_description = "src/my_description"\n')
    assert codes(run_cli, project / "robots") == (0, [])


def test_companion_files_reach_the_rules(run_cli, project, monkeypatch):
    settings(project, 'spec = "config/limits.yaml"\ncontrollers = "config/c.yaml"\n'
                      'srdf = "config/r.srdf"\n')
    seen = []
    real = engine.load_and_check
    monkeypatch.setattr(engine, "load_and_check", lambda path, options, data=None:
                        seen.append(options.companions) or real(path, options, data))
    codes(run_cli, project / "robots", "--jobs", "1", "--timeout", "0",
          "--max-memory", "0")  # no budget: in this process
    config = project / "config"
    assert seen == [CompanionPaths((config / "c.yaml",), config / "r.srdf", config / "limits.yaml")]


def test_unknown_key_is_a_usage_error(run_cli, project):
    settings(project, 'selct = ["U2"]\n')
    result = run_cli("check", project / "robots")
    assert result.exit_code == 2 and "unknown urdftool setting(s) selct" in result.stderr


def test_the_documented_example_parses(project):
    from conftest import ROOT
    import re

    text = (ROOT / "docs" / "settings.md").read_text(encoding="utf-8")
    example = re.search(r"```toml\n(.*?)```", text, re.S).group(1)
    (project / "pyproject.toml").write_text(example)
    config = settings_for(project)
    assert config.select == ["U"] and config.ignore == ["U206", "axis-not-unit"]
    assert config.per_file_ignores == {"legacy/*.urdf": ["U3"]}
    assert config.packages == {"my_description": project / "src" / "my_description"}
    assert config.max_file_size == 16777216 and config.strict is False


@pytest.fixture
def two_projects(tmp_path):
    """a/ ignores U204 in its urdftool.toml, b/ has no settings; both hold the same robot."""
    for name in ("a", "b"):
        (tmp_path / name).mkdir()
        (tmp_path / name / "arm.urdf").write_text(ROBOT)
    (tmp_path / "a" / "urdftool.toml").write_text('ignore = ["U204"]\nstrict = true\n')
    return tmp_path / "a", tmp_path / "b"


def _found(results):
    return sorted((r.path.split("/")[-2], f.code) for r in results for f in r.findings)


@pytest.mark.parametrize("order", [(0, 1), (1, 0)], ids=["a-b", "b-a"])
def test_settings_apply_per_target_in_either_order(two_projects, order):
    """Bug: settings came from the first path only, so `check a b` and `check b a` differed."""
    from urdftool.lint.runner import check_paths

    run = check_paths([two_projects[i] for i in order], jobs=1, timeout=0)
    assert _found(run.results) == [("a", "U206"), ("b", "U204"), ("b", "U206")]
    assert run.strict == [order[i] == 0 for i in range(2)]  # a's strict = true, b's not
    assert run.exit_code == 1


@pytest.mark.parametrize("order", [(0, 1), (1, 0)], ids=["a-b", "b-a"])
def test_cli_settings_apply_per_target_in_either_order(run_cli, two_projects, order):
    assert codes(run_cli, *[two_projects[i] for i in order]) == (1, ["U204", "U206", "U206"])


def test_strict_settings_fail_only_their_own_files(two_projects):
    """a's strict = true: its warning (U206) fails the run; b's warnings alone do not."""
    from urdftool.lint.runner import check_paths

    a, b = two_projects
    (b / "arm.urdf").write_text(ROBOT.replace('lower="1" upper="-1"', 'lower="-1" upper="1"'))
    assert check_paths([b], jobs=1, timeout=0).exit_code == 0
    assert check_paths([b, a], jobs=1, timeout=0).exit_code == 1
    assert check_paths([b, a], jobs=1, timeout=0, use_settings=False).exit_code == 1
    (a / "urdftool.toml").write_text('ignore = ["U204"]\n')
    assert check_paths([b, a], jobs=1, timeout=0).exit_code == 0


def test_settings_files_are_read_once_per_version(project, monkeypatch):
    from urdftool.lint import settings as module

    settings(project, 'ignore = ["U204"]\n', "urdftool.toml")
    reads = []
    real = module._read
    monkeypatch.setattr(module, "_read", lambda path: reads.append(path) or real(path))
    module._READ_SETTINGS.clear()
    first = settings_for(project / "robots" / "arm.urdf")
    assert settings_for(project / "robots") is first and len(reads) == 1
    settings(project, 'ignore = ["U204", "U206"]\n', "urdftool.toml")
    assert settings_for(project / "robots").ignore == ["U204", "U206"] and len(reads) == 2


def test_core_errors_name_no_flag(project):
    """The core raises SettingsError without a flag; the CLI prints it with exit 2."""
    from urdftool.errors import SettingsError, UrdftoolError
    from urdftool.lint.runner import check_paths

    assert issubclass(SettingsError, UrdftoolError)
    with pytest.raises(SettingsError, match="^max_file_size must be a whole number"):
        check_paths([project], max_file_size=0)
    with pytest.raises(SettingsError, match="companion file '.*nowhere.yaml' does not exist"):
        check_paths([project], companions={"spec": project / "nowhere.yaml"})
    import os

    (project / "dir.yaml").mkdir()
    os.mkfifo(project / "fifo.yaml")
    for name, why in (("dir.yaml", "is a folder"), ("fifo.yaml", "is not a regular file")):
        with pytest.raises(SettingsError, match=f"'.*{name}' {why}"):  # not "does not exist"
            check_paths([project], companions={"spec": project / name})
    settings(project, 'selct = ["U2"]\n')
    with pytest.raises(SettingsError, match="unknown urdftool setting"):
        check_paths([project / "robots"])


def test_max_memory_through_the_api_in_bytes_or_as_the_flag_takes_it(project):
    from urdftool.errors import SettingsError
    from urdftool.lint.settings import CheckRequest, for_file

    robot = project / "robots" / "arm.urdf"
    for given, limit in ((0, None), ("0", None), (1 << 30, 1 << 30), ("512M", 512 << 20)):
        assert for_file(robot, CheckRequest(max_memory=given)).memory == limit
    for wrong in (True, [1], "lots"):
        with pytest.raises(SettingsError, match="^max_memory must be a size"):
            for_file(robot, CheckRequest(max_memory=wrong))


def test_command_line_companions_win_one_by_one(project):
    from urdftool.lint.settings import CheckRequest, Companions, for_file

    (project / "config").mkdir()
    for name in ("c.yaml", "d.yaml", "r.srdf"):
        (project / "config" / name).write_text("")
    settings(project, 'controllers = "config/c.yaml"\nsrdf = "config/r.srdf"\n')
    given = Companions(controllers=[project / "config" / "d.yaml"])
    companions = for_file(str(project / "robots" / "arm.urdf"),
                          CheckRequest(companions=given)).options.companions
    assert companions.controllers == (project / "config" / "d.yaml",)
    assert companions.srdf == project / "config" / "r.srdf"


def test_size_limit_and_per_file_ignores_apply_per_target(two_projects):
    from urdftool.lint.runner import check_paths

    a, b = two_projects
    (a / "urdftool.toml").write_text("max-file-size = 10\n")
    (b / "urdftool.toml").write_text('[per-file-ignores]\n"arm.urdf" = ["U206"]\n')
    for paths in ([a, b], [b, a]):
        run = check_paths(paths, jobs=1, timeout=0)
        assert _found(run.results) == [("a", "U008"), ("b", "U204")]


@pytest.mark.parametrize("words", [["--select", "U999"], ["--ignore", "inverted-limit"],
                                   ["--select", "U2,X1"]])
def test_a_selector_that_picks_no_rule_is_a_usage_error(run_cli, project, words):
    result = run_cli("check", project / "robots", *words)
    assert result.exit_code == 2 and "no rule" in result.stderr, result.output


def test_the_api_refuses_a_selector_that_picks_no_rule():
    from urdftool.errors import UnknownRule
    from urdftool.lint.settings import CheckRequest

    with pytest.raises(UnknownRule, match="did you mean U204 inverted-limits"):
        CheckRequest(ignore=("inverted-limit",))
    assert CheckRequest(select=("U2", "inverted-limits", "u20")).select  # prefixes, names, case


@pytest.mark.parametrize("text, message", [
    ('ignore = ["U99"]\n', "'ignore': no rule 'U99'"),
    ('[tool.urdftool.per-file-ignores]\n"*.urdf" = ["nonsense"]\n',
     "'per-file-ignores.*.urdf': no rule 'nonsense'"),
    ('strict = "false"\n', "'strict' must be true or false"),
    ('packages = "robots"\n', "'packages' must be a table"),
    ('per-file-ignores = ["U2"]\n', "'per-file-ignores' must be a table"),
])
def test_setting_values_are_type_checked(run_cli, project, text, message):
    settings(project, text)
    result = run_cli("check", project / "robots")
    assert result.exit_code == 2 and message in result.stderr, result.output


XACRO = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="upper" default="1"/>
  <link name="base_link"/><link name="arm"/>
  <joint name="elbow" type="revolute"><parent link="base_link"/><child link="arm"/>
    <axis xyz="0 0 1"/><limit lower="0" upper="$(arg upper)" effort="1" velocity="1"/>
  </joint>
</robot>
"""


def test_per_file_args_reach_the_expansion_and_the_command_line_wins(run_cli, project):
    (project / "robots" / "arm.urdf").unlink()
    (project / "robots" / "arm.urdf.xacro").write_text(XACRO)
    settings(project, '[tool.urdftool.per-file-args]\n"robots/*.xacro" = { upper = -1 }\n'
                      '"other.xacro" = { upper = 5 }\n')
    assert codes(run_cli, project / "robots") == (1, ["U204"])
    assert codes(run_cli, project / "robots", "upper:=2") == (0, [])


@pytest.mark.parametrize("text, message", [
    ('per-file-args = ["x"]\n', "'per-file-args' must be a table"),
    ('[tool.urdftool.per-file-args]\n"*" = "upper:=1"\n', "must be a table of xacro arguments"),
    ('[tool.urdftool.per-file-args]\n"*" = { upper = [1] }\n', "must be a string, number or bool"),
])
def test_per_file_args_are_type_checked(run_cli, project, text, message):
    settings(project, text)
    result = run_cli("check", project / "robots")
    assert result.exit_code == 2 and message in result.stderr, result.output


# ---- issue 29, class 2: the repository's settings are the attacker's data -------------------

OUTSIDE_IN = {  # every key, with a value naming a path outside the repository
    "select": 'select = ["/etc/passwd"]\n',
    "ignore": 'ignore = ["../../../etc"]\n',
    "per-file-ignores": '[tool.urdftool.per-file-ignores]\n"/etc/*" = ["U2"]\n',
    "per-file-args": '[tool.urdftool.per-file-args]\n"*" = { cfg = "{outside}/secret.yaml" }\n',
    "packages": '[tool.urdftool.packages]\nsecret = "../outside"\n',
    "spec": 'spec = "~/.ssh/id_rsa"\n',
    "srdf": 'srdf = "file:///etc/passwd"\n',
    "controllers": 'controllers = ["robots/../../outside/c.yaml"]\n',
    "strict": '"/etc/passwd" = true\n',  # a key that is itself a path: unknown, and outside
    "notes": 'notes = "/etc/passwd"\n',
    "max-file-size": 'max-file-size = "C:\\\\Windows"\n',
    "max-memory": 'max-memory = "/dev/zero"\n',
    "timeout": 'timeout = "/dev/zero"\n',
    "max-triangles": 'max-triangles = "~/mesh.stl"\n',
    "targets": 'targets = ["~/mujoco"]\n',
}


@pytest.fixture
def repo_project(project):
    (project / ".git").mkdir()
    outside = project.parent / "outside"
    outside.mkdir(exist_ok=True)
    (outside / "secret.yaml").write_text("password: hunter2\n")
    return project


def test_every_key_has_an_outside_path_case():
    from urdftool.lint.settings import KEYS

    assert set(OUTSIDE_IN) == set(KEYS)  # a new key gets a case here


@pytest.mark.parametrize("key", sorted(OUTSIDE_IN))
def test_no_key_names_a_path_outside_the_repository(run_cli, repo_project, key):
    settings(repo_project, OUTSIDE_IN[key].replace("{outside}", str(repo_project.parent /
                                                                   "outside")))
    result = run_cli("check", repo_project / "robots")
    assert result.exit_code == 2, result.output
    assert "outside the repository" in result.stderr or "unknown urdftool setting" in \
        result.stderr, result.stderr
    assert "hunter2" not in result.output


PEEK = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="cfg" default="none"/>
  <xacro:property name="c" value="${xacro.load_yaml('$(arg cfg)')}"/>
  <link name="${c['password']}"/>
</robot>
"""


@pytest.mark.parametrize("mode", ["--no-env", "--allow-env"])
def test_per_file_args_cannot_make_an_outside_file_readable(run_cli, repo_project, mode):
    """The issue's case: an absolute path given as a xacro argument by the settings was an
    allowed root, so load_yaml read it and its content reached the report."""
    (repo_project / "robots" / "arm.urdf").unlink()
    (repo_project / "robots" / "peek.urdf.xacro").write_text(PEEK)
    settings(repo_project, OUTSIDE_IN["per-file-args"].replace(
        "{outside}", str(repo_project.parent / "outside")))
    result = run_cli("check", mode, repo_project / "robots")
    assert result.exit_code == 2 and "hunter2" not in result.output, result.output


def test_a_settings_argument_is_never_an_allowed_root(run_cli, repo_project, monkeypatch):
    """A relative value (``.``) passes the text check, and was taken from the working folder
    as a root: a robot file reading a file there must still be refused under --no-env (U014),
    never read."""
    (repo_project / "robots" / "arm.urdf").unlink()
    (repo_project / "robots" / "peek.urdf.xacro").write_text(
        PEEK.replace("$(arg cfg)", "../../outside/secret.yaml"))
    settings(repo_project, '[tool.urdftool.per-file-args]\n"*" = { cfg = "." }\n')
    monkeypatch.chdir(repo_project.parent / "outside")
    result = run_cli("check", "--no-env", "--format", "json", repo_project / "robots")
    assert "hunter2" not in result.output
    assert [d["code"] for d in json.loads(result.stdout)["diagnostics"]] == ["U014"]
    given = run_cli("check", "--no-env", repo_project / "robots", "cfg:=.")  # the user's word
    assert given.exit_code == 0 and "U014" not in given.output


@pytest.mark.parametrize("text", [
    "max-file-size = 16777217\n", "max-file-size = 1099511627776\n", 'max-memory = "4G"\n',
    'max-memory = "0"\n', "max-memory = 0\n", 'max-memory = "2049M"\n', "timeout = 61\n",
    "timeout = 60.5\n", "timeout = 0\n", "timeout = -1\n", "timeout = inf\n", "timeout = nan\n",
    'timeout = "30"\n', "timeout = true\n", "max-triangles = 2000001\n", "max-triangles = 0\n",
    "max-triangles = 1.5\n", "max-triangles = true\n"])
def test_settings_may_lower_a_limit_but_never_raise_it(run_cli, repo_project, text):
    settings(repo_project, text)
    result = run_cli("check", repo_project / "robots")
    option = "--" + text.split(" =")[0]
    assert result.exit_code == 2 and f"raise it with {option})" in result.stderr, result.output


def test_the_command_line_may_raise_a_limit(run_cli, repo_project):
    big = repo_project / "robots" / "big.urdf"
    big.write_text(ROBOT + " " * (17 << 20))
    assert run_cli("check", big).exit_code == 1  # U008, over the built-in 16 MiB
    assert run_cli("check", "--max-file-size", str(32 << 20), big, "--format", "json",
                   "--select", "U008").exit_code == 0


@pytest.mark.worker  # a budget applies in the forked worker
@pytest.mark.parametrize("text", ["max-file-size = 1024\n", 'max-memory = "1G"\n',
                                  'max-memory = "2G"\n', "max-file-size = 16777216\n",
                                  "timeout = 30\n", "timeout = 0.5\n", "timeout = 60\n",
                                  "max-triangles = 1000\n", "max-triangles = 2000000\n"])
def test_lowering_a_limit_or_keeping_it_is_fine(run_cli, repo_project, text):
    """Taken, not refused (exit 1: the robots' findings, not 2). A memory cap the forked
    worker reaches (this test process maps over 1 GB before it forks) ends in U018, never in a
    crash of a rule (U900: it once segfaulted while being made)."""
    settings(repo_project, text)
    result = run_cli("check", repo_project / "robots")
    assert result.exit_code == 1, result.output
    assert "U900" not in result.output and "Fatal Python error" not in result.output, \
        result.output


@pytest.mark.parametrize("text, line", [
    ("a = " + "[" * 5000 + "]" * 5000 + "\n", 1),
    ("x = 1\na = " + "{b = " * 3000 + "1" + "}" * 3000 + "\n", 2),
    ("a" + ".a" * 200_000 + " = 1\n", 1),  # tomllib: quadratic, minutes and tens of GB
    ("[" + "a." * 100_000 + "a]\n", 1),
])
def test_deep_settings_are_a_located_usage_error(run_cli, repo_project, text, line,
                                                 monkeypatch):
    """Refused before tomllib reads them (``settings.too_deep``): tomllib recurses, or is
    quadratic in a key's dots (minutes and tens of GB). The guard is asserted, not timed: the
    test once timed the run (under 5 s), which a loaded host can miss."""
    import tomllib

    def never(*args, **kwargs):
        raise AssertionError("tomllib read settings nesting too deep")

    monkeypatch.setattr(tomllib, "loads", never)
    (repo_project / "urdftool.toml").write_text(text)
    result = run_cli("check", repo_project / "robots")
    assert result.exit_code == 2 and "Traceback" not in result.output
    assert f"urdftool.toml:{line}: settings nest deeper than" in result.output, result.output
    assert f"urdftool.toml:{line}: settings nest deeper than 32 levels" in result.stderr


@pytest.mark.parametrize("text", [
    'x = "[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[["\n',
    "# [[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[\n",
    "x = '''\n" + "a." * 100 + "\n'''\n",
    "x = [" + ", ".join(["1.5"] * 100) + "]\n",
])
def test_brackets_and_dots_in_strings_comments_and_numbers_are_not_nesting(text):
    from urdftool.lint.settings import too_deep

    assert too_deep(text) is None


def test_broken_settings_elsewhere_never_stop_another_file(run_cli, tmp_path):
    """Issue 29: a settings file in an unrelated folder made the whole run exit 2 when the
    file named (an empty xacro, replaced by the robots including it) made urdftool walk the
    repository. Now the walk goes on; a file the broken settings apply to is not checked and
    the run says why (exit 2), the others are checked."""
    (tmp_path / ".git").mkdir()
    for folder in ("a", "b"):
        (tmp_path / folder).mkdir()
    (tmp_path / "a" / "arm.urdf").write_text(ROBOT)
    (tmp_path / "a" / "empty.urdf.xacro").write_text("")
    (tmp_path / "b" / "urdftool.toml").write_text("bogus = 1\n")
    (tmp_path / "b" / "arm.urdf").write_text(ROBOT)
    result = run_cli("check", tmp_path / "a" / "empty.urdf.xacro")  # (a blank placeholder:
    assert result.exit_code == 0 and "nothing to check" in result.output, result.output  # U002
    assert "bogus" not in result.output  # only where something loads it: targets.BLANK)
    result = run_cli("check", "--format", "json", tmp_path / "a", tmp_path / "b")
    assert result.exit_code == 2
    assert {d["code"] for d in json.loads(result.stdout)["diagnostics"]} >= {"U204"}
    assert "b/urdftool.toml: unknown urdftool setting(s) bogus" in result.stderr


def test_every_budget_of_the_check_command_line_is_a_setting_that_may_only_lower_it():
    """A budget the command line of ``check`` has (``--timeout``, ``--max-...``) is a settings
    key of the same name in LIMITS, so that a repository can lower it and never raise it."""
    from urdftool.cli import command
    from urdftool.lint.settings import KEYS, LIMITS

    options = {name for parameter in command("check").params
               if parameter.param_type_name == "option" for name in parameter.opts
               if name == "--timeout" or name.startswith("--max-")}
    assert options == {"--timeout", "--max-file-size", "--max-memory", "--max-triangles"}
    assert {f"--{key}" for key in LIMITS} == options and set(LIMITS) <= set(KEYS)


def test_a_lowered_timeout_and_triangle_limit_apply_and_the_command_line_wins(repo_project):
    from urdftool.lint.settings import CheckRequest, for_file

    settings(repo_project, "timeout = 0.5\nmax-triangles = 10\n")
    robot = str(repo_project / "robots" / "arm.urdf")
    found = for_file(robot, CheckRequest())
    assert (found.timeout, found.options.mesh_limits.max_triangles) == (0.5, 10)
    given = for_file(robot, CheckRequest(timeout=120, max_triangles=5_000_000))
    assert (given.timeout, given.options.mesh_limits.max_triangles) == (120, 5_000_000)
    assert for_file(robot, CheckRequest(timeout=0)).timeout is None  # the user's "no budget"
    assert for_file(robot, CheckRequest(use_settings=False)).timeout == 60


def test_a_timeout_in_the_settings_stops_only_its_own_files(tmp_path):
    """Two projects checked together: the one whose settings lower the timeout has its slow
    robot stopped (U015); the other's same robot, under the built-in 60 s, is not.

    The work is ~0.35 s, 7x the lowered budget and 1/170 of the built-in one. It runs in a
    command of its own: forked from a pytest worker, the check's calls sat on a boundary of
    CPython 3.11's 16 KiB frame-stack chunks (each call maps and unmaps one: 12x slower, 1.1
    million page faults, 6 s of CPU in make test; 0.5 s as a command), and on a loaded machine
    1.3 s of work then passed the built-in 60 s."""
    slow = ('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">' + "".join(
        f'<link name="l{i}_${{python.len([0 for i in python.range(3 * 10**4)])}}"/>'
        for i in range(12)) + "</robot>\n")  # legal work, each under MAX_WORK
    for name, text in (("quick", "timeout = 0.05\n"), ("patient", "")):
        (tmp_path / name / "robots").mkdir(parents=True)
        (tmp_path / name / "robots" / "slow.urdf.xacro").write_text(slow)
        (tmp_path / name / "urdftool.toml").write_text(text)
    done = subprocess.run([sys.executable, "-m", "urdftool", "check", "--format", "json",
                           "--select", "U015", "--jobs", "2", "quick", "patient"],
                          cwd=tmp_path, capture_output=True, text=True, timeout=300,
                          env={**os.environ, "CI": "", "GITHUB_ACTIONS": ""})  # the full mode
    found = {(Path(d["file"]).parts[-3], d["code"])
             for d in json.loads(done.stdout)["diagnostics"]}
    assert found == {("quick", "U015")}, done.stdout + done.stderr


def test_a_lowered_triangle_limit_refuses_a_mesh_the_built_in_one_takes(run_cli, repo_project):
    import struct

    stl = b"\0" * 80 + struct.pack("<I", 12) + b"\0" * 50 * 12  # twelve (empty) triangles
    (repo_project / "robots" / "box.stl").write_bytes(stl)
    (repo_project / "robots" / "arm.urdf").write_text(ROBOT.replace(
        '<link name="arm"/>', '<link name="arm"><visual><geometry><mesh filename="box.stl"/>'
        '</geometry></visual></link>'))
    assert codes(run_cli, repo_project / "robots", "--select", "U411")[1] == []
    settings(repo_project, "max-triangles = 10\n")
    assert codes(run_cli, repo_project / "robots", "--select", "U411")[1] == ["U411"]
    assert codes(run_cli, repo_project / "robots", "--select", "U411",
                 "--max-triangles", "12")[1] == []


def test_a_number_past_pythons_digits_is_a_settings_error(tmp_path, run_cli):
    """tomllib converts an integer with int(): past 4,300 digits a ValueError, not a
    TOMLDecodeError (the run ended in a traceback)."""
    (tmp_path / ".git").mkdir()
    (tmp_path / "r.urdf").write_text('<robot name="r"><link name="a"/></robot>')
    (tmp_path / "urdftool.toml").write_text('notes = false\nignore = ["' + "1" * 5000 + '"]\n'
                                            "timeout = " + "9" * 5000 + "\n")
    result = run_cli("check", "--no-cache", tmp_path / "r.urdf")
    assert result.exit_code == 2 and "urdftool.toml:3: an integer of 5,000 characters" in result.output


@pytest.mark.parametrize("key", ["max-file-size", "max-triangles", "timeout", "max-memory", "notes",
                                 "strict"])
def test_an_integer_past_a_double_is_a_settings_error_quoting_it(tmp_path, run_cli, key):
    """The one quoter of a settings value (inputs.shown) asked math.isfinite of an integer
    past a double: OverflowError, a traceback for every key a 4,000-digit integer was given."""
    (tmp_path / ".git").mkdir()
    (tmp_path / "r.urdf").write_text('<robot name="r"><link name="a"/></robot>')
    (tmp_path / "urdftool.toml").write_text(f"{key} = " + "9" * 4000 + "\n")
    result = run_cli("check", "--no-cache", tmp_path / "r.urdf")
    assert result.exit_code == 2 and f"'{key}' must be" in result.output and "999..." in result.output


def test_a_selection_of_100000_codes_is_matched_as_its_few_distinct_ones(tmp_path, monkeypatch):
    """session 9 (session 8's open item): `select` of 100,000 codes cost 3.4 s, each matched
    against every rule in the settings check and, for each rule, in each worker; the codes are
    taken once each (``settings._codes``), a few hundred at most."""
    from urdftool.lint.catalogue import Catalogue
    from urdftool.lint.settings import CheckRequest, for_file

    codes = ["U001", "u101", " U2", "U3", "U201", "inverted-limits", "U4"] * 15000
    (tmp_path / "urdftool.toml").write_text(f"select = {json.dumps(codes)}\n")
    (tmp_path / "robot.urdf").write_text('<robot name="r"><link name="a"/></robot>\n')
    asked = []
    real = Catalogue.matches
    monkeypatch.setattr(Catalogue, "matches", lambda *a: asked.append(1) or real(*a))
    selection = for_file(str(tmp_path / "robot.urdf"), CheckRequest()).options.selection
    assert len(selection.select) == 7
    from urdftool.lint.rules import CATALOGUE

    assert [r.code for r in CATALOGUE if selection.allows(r.code)]
    assert len(asked) < 20000, len(asked)  # (millions before)


@pytest.mark.parametrize("key", sorted(KEYS))
def test_a_settings_error_quotes_a_value_in_toml_words_not_pythons(tmp_path, key):
    """Every key given a TOML datetime: the error says it as written (it said
    ``datetime.datetime(1979, 5, 27, 7, 32, tzinfo=datetime.timezone(...))``)."""
    (tmp_path / ".git").mkdir()
    (tmp_path / "urdftool.toml").write_text(f"{key} = 1979-05-27T07:32:00-08:00\n")
    with pytest.raises(SettingsError) as error:
        settings_file(tmp_path / "urdftool.toml")
    assert "datetime" not in str(error.value) and "(1979" not in str(error.value)


@pytest.mark.parametrize("value, written", [
    (True, "true"), (float("nan"), "nan"), (float("-inf"), "-inf"), (1e300, "1e+300"), (7, "7"),
    ("a\x1b\"b", '"a\\u001b\\"b"'), (datetime.date(1979, 5, 27), "1979-05-27"),
    (datetime.time(7, 32), "07:32:00"), ([1, [True]], "[1, [true]]"), ({}, "{}"),
    ({"a": 1, "b c": "d"}, '{ a = 1, "b c" = "d" }'), ("x" * 100_000, '"' + "x" * 76 + "..."),
    pytest.param(10 ** 5000, "a whole number of 5000 digits or so", id="5000-digits"),
])
def test_shown_writes_a_settings_value_as_toml(value, written):
    from urdftool.lint.settings import shown

    assert shown(value) == written


def test_another_tools_pyproject_larger_or_in_another_encoding_is_not_ours_to_refuse(tmp_path):
    """A 1.3 MB pyproject.toml with no ``[tool.urdftool]`` stopped every check ("over the
    limit of 1048576"), as one in Latin-1 did ("can't decode byte 0xe9"): its size and
    encoding are judged only once it may hold our settings."""
    from urdftool.description.run_memo import one_run

    (tmp_path / ".git").mkdir()
    others = "".join(f'k{i} = "{"v" * 100}"\n' for i in range(12_000))
    (tmp_path / "pyproject.toml").write_text('[project]\nname = "x"\n[tool.other]\n' + others)
    with one_run():
        assert settings_for(tmp_path).path is None
    (tmp_path / "pyproject.toml").write_text('[tool.urdftool]\nstrict = true\n[tool.other]\n' + others)
    with one_run(), pytest.raises(SettingsError, match="over the limit of 1048576"):
        settings_for(tmp_path)
    (tmp_path / "pyproject.toml").write_bytes(b'[project]\ndescription = "caf\xe9"\n')  # Latin-1
    with one_run():
        assert settings_for(tmp_path).path is None
    (tmp_path / "pyproject.toml").write_bytes(b'[tool.urdftool]\nstrict = true # caf\xe9\n')
    with one_run(), pytest.raises(SettingsError, match="can't decode byte 0xe9"):
        settings_for(tmp_path)


def test_per_file_globs_are_compiled_once_for_every_file(tmp_path, monkeypatch):
    """40,000 ``per-file-ignores`` globs (past the 32,768 fnmatch keeps compiled) were
    compiled again for every file, twice (its path and its name): 50,000 over 21 robots took
    90 s of CPU in the parent, outside any file's budget; 3.3 s now."""
    import fnmatch

    from urdftool.lint.settings import Settings

    compiled = []
    real = fnmatch.translate
    monkeypatch.setattr(fnmatch, "translate", lambda pattern: compiled.append(pattern) or real(pattern))
    settings = Settings(path=tmp_path / "urdftool.toml",
                        per_file_ignores={f"d{i}/**": ["U2"] for i in range(40_000)} | {"r*.urdf": ["U3"]})
    for index in range(3):
        assert settings.ignores_for(str(tmp_path / f"sub{index}" / f"r{index}.urdf")) == ["U3"]
    assert len(compiled) == 40_001


@pytest.mark.parametrize("kind", ["pipe", "itself", "loop", "folder", "link to a pipe"])
def test_a_settings_name_holding_no_file_is_said_not_passed_over(run_cli, project, kind):
    """An ``urdftool.toml`` that is a named pipe, a link to itself or to a pipe, or a folder
    was passed over without a word: the check ran with the defaults (or a pyproject above),
    not the settings the repository names. It is a settings error, exit 2."""
    file = project / "urdftool.toml"
    if kind == "pipe":
        os.mkfifo(file)
    elif kind == "itself":
        file.symlink_to("urdftool.toml")
    elif kind == "loop":
        file.symlink_to("other.toml")
        (project / "other.toml").symlink_to("urdftool.toml")
    elif kind == "folder":
        file.mkdir()
    else:
        os.mkfifo(project / "pipe.toml")
        file.symlink_to("pipe.toml")
    result = run_cli("check", project / "robots", "--format", "json")
    assert result.exit_code == 2, result.output
    assert f"settings file '{file}' " in result.output
    assert ("named pipe" if "pipe" in kind else "a folder" if kind == "folder" else
            "too many levels of symbolic links") in result.output
    file.unlink() if kind != "folder" else file.rmdir()
    (project / "urdftool.toml").symlink_to("nowhere.toml")  # a link to nothing: nothing there
    assert codes(run_cli, project / "robots") == (1, ["U204", "U206"])
