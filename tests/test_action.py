"""``action.yml``, the GitHub Action: well formed, injection-safe, and its scripts work as
written (run here with bash, urdftool on PATH, the action's environment variables set)."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

from conftest import ROBOTS, ROOT
from rule_links import assert_rule_page

ACTION = yaml.safe_load((ROOT / "action.yml").read_text())
STEPS = ACTION["runs"]["steps"]


def step(name: str) -> dict:
    return next(s for s in STEPS if s.get("name") == name)


def test_composite_action_with_documented_inputs():
    assert ACTION["runs"]["using"] == "composite"
    assert set(ACTION["inputs"]) == {"paths", "args", "extras", "sarif", "python-version"}
    assert all(value.get("description") for value in ACTION["inputs"].values())
    for entry in STEPS:
        if "run" in entry:
            assert entry["shell"] == "bash"


def test_inputs_reach_scripts_only_through_the_environment():
    for entry in STEPS:
        assert "${{" not in entry.get("run", ""), entry  # no expression pasted into a script


def test_it_installs_this_checkout_and_uploads_sarif():
    assert '"${GITHUB_ACTION_PATH}${EXTRAS:+[$EXTRAS]}"' in step("Install urdftool")["run"]
    upload = next(s for s in STEPS if s.get("uses", "").startswith("github/codeql-action/upload"))
    assert upload["with"]["sarif_file"].endswith("urdftool.sarif")


@pytest.mark.skipif(shutil.which("bash") is None, reason="needs bash")
@pytest.mark.parametrize("planted", ["pip/__init__.py", "pip.py", "typing.py"])
def test_the_install_step_imports_nothing_from_the_checked_repository(tmp_path, planted):
    """The install step starts in the checked repository: ``python -m pip`` put that folder
    first on sys.path, so a pull request's ``pip/__init__.py`` (or a module pip imports) ran
    instead of pip, with the workflow's token. ``python -I`` leaves the folder out; pip itself
    fails here on an action path that does not exist, offline, without installing anything."""
    work = tmp_path / "work"
    (work / planted).parent.mkdir(parents=True, exist_ok=True)
    marker = tmp_path / "ran"
    (work / planted).write_text(f"open({str(marker)!r}, 'w').write('ran')\n")
    _run(step("Install urdftool")["run"] + " || true", tmp_path, cwd=work,
         GITHUB_ACTION_PATH=str(tmp_path / "absent"), EXTRAS="", PIP_NO_INDEX="1")
    assert not marker.exists()


def _run(script: str, tmp_path: Path, cwd: Path = ROOT, **env) -> subprocess.CompletedProcess:
    bin_dir = str(Path(sys.executable).parent)
    environment = {**os.environ, "PATH": f"{bin_dir}{os.pathsep}{os.environ['PATH']}",
                   "RUNNER_TEMP": str(tmp_path), "CI": "true", "GITHUB_ACTION_PATH": str(ROOT),
                   **env}
    return subprocess.run(["bash", "-e", "-c", script], cwd=cwd, env=environment,
                          capture_output=True, text=True, timeout=300)


@pytest.mark.skipif(shutil.which("bash") is None, reason="needs bash")
def test_the_check_and_sarif_scripts_run_as_written(tmp_path):
    broken = tmp_path / "robots"
    shutil.copytree(ROBOTS / "r2d2", broken)
    urdf = broken / "bad.urdf"
    urdf.write_text('<robot name="r"><link name="a"/><link name="b"/><joint name="j" '
                    'type="revolute"><parent link="a"/><child link="b"/><limit lower="1" '
                    'upper="-1" effort="1" velocity="1"/></joint></robot>')
    env = {"PATHS": f"{ROBOTS} {urdf}", "ARGS": "--ignore U901"}
    checked = _run(step("Check (annotations on the diff)")["run"], tmp_path, **env)
    assert checked.returncode == 1
    assert "::error file=" in checked.stdout and "U204" in checked.stdout
    sarif = _run(step("SARIF")["run"], tmp_path, **env)
    assert sarif.returncode == 0, sarif.stderr  # findings (exit 1) still upload
    log = json.loads((tmp_path / "urdftool.sarif").read_text())
    assert any(r["ruleId"] == "U204" for r in log["runs"][0]["results"])
    assert_rule_page(log["runs"][0]["tool"]["driver"]["rules"][0]["helpUri"], "U001")
    # run as the action of a repository at a tag: the links go to its pages at that tag
    tagged = _run(step("SARIF")["run"], tmp_path, **env, ACTION_REPOSITORY="you/urdftool",
                  ACTION_REF="v0.1.0", GITHUB_SERVER_URL="https://github.com")
    assert tagged.returncode == 0, tagged.stderr
    rule = json.loads((tmp_path / "urdftool.sarif").read_text())["runs"][0]["tool"]["driver"][
        "rules"][0]
    assert rule["helpUri"] == "https://github.com/you/urdftool/blob/v0.1.0/docs/rules/U001.md"
    assert_rule_page(rule["helpUri"], "U001")
    usage = _run(step("SARIF")["run"], tmp_path, PATHS=str(urdf), ARGS="--select U999")
    assert usage.returncode != 0  # a usage error is not hidden


GOOD = '<robot name="r"><link name="a"/></robot>\n'
BAD = ('<robot name="r"><link name="a"/><link name="b"/><joint name="j" type="revolute">'
       '<parent link="a"/><child link="b"/><limit lower="1" upper="-1" effort="1" '
       'velocity="1"/></joint></robot>\n')


@pytest.mark.skipif(shutil.which("bash") is None, reason="needs bash")
@pytest.mark.parametrize("name", ["--output=report.urdf", "-o report.urdf", "--select=U9.urdf",
                                  "--format=json.urdf", "-"])
def test_a_file_name_is_never_an_option(tmp_path, name):
    """Issue 29, class 8: with ``paths: '*.urdf'``, a file of the pull request named
    ``--output=report.urdf`` became an option (the report went to report.urdf, the file was
    not checked). Every path now comes after ``--``: the file is checked, nothing written."""
    work = tmp_path / "work"
    work.mkdir()
    (work / f"{name}.urdf" if name == "-" else work / name).write_text(BAD)
    (work / "ok.urdf").write_text(GOOD)
    checked = _run(step("Check (annotations on the diff)")["run"], tmp_path, cwd=work,
                   PATHS="*.urdf", ARGS="")
    assert checked.returncode == 1, checked.stderr
    assert checked.stdout.count("::error file=") == 1 and "U204" in checked.stdout
    assert sorted(p.name for p in work.iterdir()) == sorted(
        [f"{name}.urdf" if name == "-" else name, "ok.urdf"])


@pytest.mark.skipif(shutil.which("bash") is None, reason="needs bash")
def test_paths_split_at_white_space_and_lines_and_matches_stay_one_word(tmp_path):
    work = tmp_path / "work"
    (work / "with space").mkdir(parents=True)
    (work / "with space" / "a b.urdf").write_text(BAD)
    (work / "ok.urdf").write_text(GOOD)
    (work / "$(id>pwned).urdf").write_text(GOOD)
    checked = _run(step("SARIF")["run"], tmp_path, cwd=work,
                   PATHS="ok.urdf\n  with*/*.urdf  $(id>pwned).urdf", ARGS="--strict")
    assert checked.returncode == 0, checked.stderr
    log = json.loads((tmp_path / "urdftool.sarif").read_text())
    assert {r["ruleId"] for r in log["runs"][0]["results"]} == {"U204"}
    assert not (work / "pwned").exists()


@pytest.mark.skipif(shutil.which("bash") is None, reason="needs bash")
def test_args_are_words_without_expansion(tmp_path):
    work = tmp_path / "work"
    work.mkdir()
    (work / "ok.urdf").write_text(GOOD)
    (work / "a.xyz").write_text(GOOD)  # an unquoted $ARGS would have matched it
    for words, literal in (("--strict *.xyz", "*.xyz"), ("--strict $HOME", "$HOME")):
        checked = _run(step("Check (annotations on the diff)")["run"], tmp_path, cwd=work,
                       PATHS="ok.urdf", ARGS=words)
        assert checked.returncode == 2, checked.stderr
        assert f"path '{literal}' does not exist" in checked.stderr
