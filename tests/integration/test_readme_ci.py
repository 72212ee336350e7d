"""Every urdftool command line of the CI guide (docs/ci.md) runs, and its output is valid.

The command lines are taken from the guide's code blocks, so the examples cannot rot. Each is
run through the CLI on a copy of robots/ (clean) and on the same copy plus one broken robot.
"""

from __future__ import annotations

import json
import re
import shlex
import shutil
from pathlib import Path

import pytest

import sarif_schema
from rule_links import assert_rule_page
from lxml import etree

from conftest import ROBOTS, ROOT

BROKEN = """<robot name="broken">
  <link name="base_link"/>
  <link name="arm"/>
  <joint name="elbow" type="revolute">
    <parent link="base_link"/><child link="arm"/>
    <limit lower="1" upper="-1" effort="1" velocity="1"/>
  </joint>
</robot>
"""


def ci_section() -> str:
    return (ROOT / "docs" / "ci.md").read_text(encoding="utf-8")


def readme_commands() -> dict:
    """{format: argv after 'urdftool'} for each ``urdftool check`` in the section's code blocks,
    and {"pytest": source} for its Python test file."""
    commands = {}
    for block in re.findall(r"```(\w+)\n(.*?)```", ci_section(), re.S):
        language, body = block
        if language == "python":
            commands.setdefault("pytest", body)  # the first: the make-and-pytest recipe
            continue
        for line in body.splitlines():
            line = line.strip().removeprefix("- ").removeprefix("run: ")
            if line.startswith("urdftool check"):
                argv = shlex.split(line.split("||")[0].split("#")[0])[1:]
                name = argv[argv.index("--format") + 1] if "--format" in argv else "make"
                commands[name] = argv
    return commands


def test_every_integration_has_a_command_line():
    assert set(readme_commands()) == {"github", "sarif", "gitlab", "junit", "make", "pytest"}


@pytest.fixture(scope="module")
def workspaces(tmp_path_factory):
    """(clean copy of robots/, copy with a broken robot added)."""
    base = tmp_path_factory.mktemp("ci")
    clean, broken = base / "clean" / "robots", base / "broken" / "robots"
    for target in (clean, broken):
        shutil.copytree(ROBOTS, target)
    (broken / "broken.urdf").write_text(BROKEN)
    return clean.parent, broken.parent


def readme_test():
    """The test function of the guide's Python test file (it calls urdftool in process)."""
    source = readme_commands()["pytest"]
    assert "subprocess" not in source
    namespace = {}
    exec(compile(source, "docs/ci.md:tests/test_urdf.py", "exec"), namespace)
    (test,) = [value for name, value in namespace.items() if name.startswith("test_")]
    return test


def run(run_cli, monkeypatch, workspace: Path, argv: list[str]):
    """Run a command line of the guide in ``workspace`` (its robots/ and output files are there)."""
    monkeypatch.chdir(workspace)
    return run_cli(*argv)


@pytest.mark.parametrize("broken", [False, True], ids=["clean", "broken"])
def test_github_annotations(run_cli, monkeypatch, workspaces, broken):
    result = run(run_cli, monkeypatch, workspaces[broken], readme_commands()["github"])
    assert result.exit_code == int(broken)
    lines = result.stdout.splitlines()
    errors = "1 error" if broken else "0 errors"
    assert lines[-1] == f"urdftool: {3 + broken} files, {errors}, 0 warnings, 0 notes"
    annotations = lines[:-1]
    assert len(annotations) == int(broken)
    for line in annotations:
        assert re.fullmatch(r"::error file=robots/broken\.urdf,line=6,col=5,"
                            r"title=U204 inverted-limits::joint 'elbow'.*", line)


@pytest.mark.parametrize("broken", [False, True], ids=["clean", "broken"])
def test_sarif(run_cli, monkeypatch, workspaces, broken):
    argv = readme_commands()["sarif"]
    result = run(run_cli, monkeypatch, workspaces[broken], argv)
    assert result.exit_code == int(broken)  # the guide tolerates 1, not 2
    log = json.loads((workspaces[broken] / argv[argv.index("--output") + 1]).read_text())
    sarif_schema.validate(log)
    rules = log["runs"][0]["tool"]["driver"]["rules"]
    results = log["runs"][0]["results"]
    assert [r["ruleId"] for r in results] == (["U204"] if broken else [])
    for entry in results:
        rule = rules[entry["ruleIndex"]]
        assert rule["id"] == entry["ruleId"] and "Bad:" in rule["help"]["text"]
        assert_rule_page(rule["helpUri"], rule["id"])
        assert entry["locations"][0]["physicalLocation"]["artifactLocation"]["uri"] == \
            "robots/broken.urdf"


@pytest.mark.parametrize("broken", [False, True], ids=["clean", "broken"])
def test_gitlab_code_quality(run_cli, monkeypatch, workspaces, broken):
    argv = readme_commands()["gitlab"]
    result = run(run_cli, monkeypatch, workspaces[broken], argv)
    assert result.exit_code == int(broken)  # the guide tolerates 1, not 2
    issues = json.loads((workspaces[broken] / argv[argv.index("--output") + 1]).read_text())
    assert [(i["check_name"], i["location"]["path"]) for i in issues] == \
        ([("U204 inverted-limits", "robots/broken.urdf")] if broken else [])


@pytest.mark.parametrize("broken", [False, True], ids=["clean", "broken"])
def test_junit(run_cli, monkeypatch, workspaces, broken):
    argv = readme_commands()["junit"]
    result = run(run_cli, monkeypatch, workspaces[broken], argv)
    assert result.exit_code == int(broken)
    root = etree.parse(str(workspaces[broken] / argv[argv.index("--output") + 1])).getroot()
    assert root.tag == "testsuites"
    assert (root.get("tests"), root.get("failures")) == (str(3 + broken), str(int(broken)))
    assert len(root.findall("testsuite")) == 3 + broken
    failures = root.findall(".//failure")
    assert [f.getparent().get("name") for f in failures] == \
        (["U204 inverted-limits"] if broken else [])
    assert ["robots/broken.urdf:6" in f.get("message", "") + (f.text or "") for f in failures] == \
        [True] * int(broken)


@pytest.mark.parametrize("broken", [False, True], ids=["clean", "broken"])
@pytest.mark.parametrize("integration", ["make", "pytest"])
def test_make_and_pytest(run_cli, monkeypatch, workspaces, broken, integration):
    if integration == "pytest":  # the guide's test file, run as pytest would, in process
        monkeypatch.chdir(workspaces[broken])
        if not broken:
            readme_test()()
            return
        with pytest.raises(AssertionError) as failure:
            readme_test()()
        assert "robots/broken.urdf:6: U204 " in str(failure.value)
        return
    result = run(run_cli, monkeypatch, workspaces[broken], readme_commands()[integration])
    assert result.exit_code == int(broken)


# A robot that prints an environment variable into the report when $(env) is expanded: the
# unconnected link's name is in U108's message.
LEAK = """<robot name="leak" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <link name="base_link"/>
  <link name="$(env URDFTOOL_SECRET)"/>
</robot>
"""
SECRET = "hunter2-token"


def invoke(argv: list[str], **env: str):
    """The CLI with ``env`` set (CI unset unless given), as a CI job would run it."""
    from typer.testing import CliRunner

    from urdftool.cli import app

    return CliRunner().invoke(app, [str(a) for a in argv], env={
        "COLUMNS": "120", "NO_COLOR": "1", "TERM": "dumb", "GITHUB_ACTIONS": "", "CI": "",
        "URDFTOOL_SECRET": SECRET, **env})


@pytest.fixture
def leaky(tmp_path, monkeypatch):
    """A workspace whose robots/ holds the examples and the robot that reads $(env)."""
    shutil.copytree(ROBOTS, tmp_path / "robots")
    (tmp_path / "robots" / "leak.urdf.xacro").write_text(LEAK)
    monkeypatch.chdir(tmp_path)
    return tmp_path


def _report(workspace: Path, argv: list[str], result) -> str:
    written = argv[argv.index("--output") + 1] if "--output" in argv else None
    return result.output + ((workspace / written).read_text() if written else "")


def hook_entry() -> list[str]:
    import yaml

    (hook,) = yaml.safe_load((ROOT / ".pre-commit-hooks.yaml").read_text())
    return shlex.split(hook["entry"])


def test_ci_recipes_write_out_the_safe_mode():
    commands = readme_commands()
    for integration in ("github", "sarif", "gitlab", "junit"):
        assert "--no-env" in commands[integration] and "--allow-env" not in commands[integration]
    assert hook_entry() == ["urdftool", "check", "--no-env"]


@pytest.mark.parametrize("integration", ["github", "sarif", "junit", "pre-commit"])
def test_ci_recipes_do_not_leak_the_environment_even_without_ci(leaky, integration):
    """The GitHub, GitLab and pre-commit recipes are safe on their own, CI set or not."""
    argv = hook_entry()[1:] + ["robots/leak.urdf.xacro"] if integration == "pre-commit" \
        else readme_commands()[integration]
    result = invoke(argv)
    report = _report(leaky, argv, result)
    assert result.exit_code == 1 and "U005" in report and SECRET not in report


def test_recipes_without_the_flag_are_safe_under_ci(leaky):
    result = invoke(readme_commands()["make"], CI="true")
    assert result.exit_code == 1 and "U005" in result.output and SECRET not in result.output


def test_the_readme_pytest_is_safe_under_ci(leaky, monkeypatch):
    monkeypatch.setenv("CI", "true")
    monkeypatch.setenv("URDFTOOL_SECRET", SECRET)
    with pytest.raises(AssertionError) as failure:
        readme_test()()
    assert "U005" in str(failure.value) and SECRET not in str(failure.value)


@pytest.mark.parametrize(("ci", "flag", "leaks"), [
    ("", None, True),            # a developer's machine: the full mode
    ("false", None, True),
    ("true", None, False),       # GitHub Actions, GitLab CI, ...: the safe mode
    ("1", None, False),
    ("true", "--allow-env", True),  # opted out
    ("", "--no-env", False),
])
def test_ci_makes_the_safe_mode_the_default(leaky, ci, flag, leaks):
    argv = ["check", "robots/leak.urdf.xacro", *([flag] if flag else [])]
    output = invoke(argv, CI=ci).output
    assert (SECRET in output) is leaks
    assert ("U005" in output) is not leaks


@pytest.mark.parametrize("command", ["tree", "xacro", "fk", "graph"])
def test_every_command_is_in_the_safe_mode_under_ci(leaky, command):
    """Not only check: a CI job that runs tree, xacro or fk on a pull request's robot leaks no
    secret either; off CI (or with --allow-env on check) the robot's $(env) expands."""
    result = invoke([command, "--timeout", "0", "robots/leak.urdf.xacro"], CI="true")
    assert result.exit_code == 1 and "U005" in result.output, result.output
    assert SECRET not in result.output
    assert SECRET in invoke(["xacro", "--timeout", "0", "robots/leak.urdf.xacro"]).output
