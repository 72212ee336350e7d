"""``check --target``: portability rules run only for the targets asked for (command line,
settings), each finding carries its target into every machine format, unknown names are
refused with the valid ones, and the portability fixes (a <mujoco> compiler block, a world link,
a COLLADA mesh converted to OBJ) make the loader accept the file."""

from __future__ import annotations

import io
import json
import shutil
import subprocess
import sys

import pytest

from conftest import CASES
from urdftool.errors import SettingsError, UsageError
from urdftool.lint import fixes
from urdftool.lint.engine import CheckOptions, load_and_check
from urdftool.lint.options import Selection
from urdftool.lint.runner import check_paths
from urdftool.report import render

WELDED = CASES / "U928_mujoco_welded_root.urdf"


def test_target_rules_run_only_for_their_target():
    plain = load_and_check(str(WELDED), CheckOptions())
    assert not [f for f in plain.findings if f.code.startswith("U92")]
    mujoco = load_and_check(str(WELDED), CheckOptions(selection=Selection(targets=("mujoco",))))
    [finding] = [f for f in mujoco.findings if f.code == "U928"]
    assert finding.target == "mujoco" and "MuJoCo" in finding.message
    assert not [f for f in mujoco.findings if f.code.startswith("U94")]  # drake not asked


def test_select_and_ignore_narrow_target_rules():
    both = Selection(ignore=("U928",), targets=("mujoco", "drake"))
    found = {f.code for f in load_and_check(str(WELDED), CheckOptions(selection=both)).findings}
    assert "U944" in found and "U928" not in found


def test_a_version_changes_the_facts():
    """MuJoCo before 3.7 drops a mesh path's folders: package:// is no error of its own."""
    case = CASES / "U920_mujoco_package_uri" / "robot.urdf"
    new = load_and_check(str(case), CheckOptions(selection=Selection(targets=("mujoco",))))
    old = load_and_check(str(case), CheckOptions(selection=Selection(targets=("mujoco@3.6",))))
    assert "U920" in {f.code for f in new.findings}
    assert "U920" not in {f.code for f in old.findings}
    assert "MuJoCo 3.6" in " ".join(f.message for f in old.findings)  # U922: not beside it


def test_settings_targets_apply_and_are_checked(tmp_path):
    shutil.copy(WELDED, tmp_path / "robot.urdf")
    (tmp_path / ".git").mkdir()
    (tmp_path / "urdftool.toml").write_text('targets = ["drake"]\n')
    run = check_paths([str(tmp_path / "robot.urdf")], jobs=1, timeout=0)
    assert {f.code for f in run.results[0].findings} >= {"U944"}
    run = check_paths([str(tmp_path / "robot.urdf")], jobs=1, timeout=0, targets=("mujoco",))
    codes = {f.code for f in run.results[0].findings}
    assert "U928" in codes and "U944" not in codes  # the command line replaces the settings'
    (tmp_path / "urdftool.toml").write_text('targets = ["mujuco"]\n')
    with pytest.raises(SettingsError, match="did you mean 'mujoco'"):
        check_paths([str(tmp_path / "robot.urdf")], jobs=1, timeout=0)
    with pytest.raises(UsageError, match="available targets: drake, gazebo, gz"):
        check_paths([str(WELDED)], targets=("bullet",))


@pytest.mark.parametrize("where", ["command line", "settings"])
def test_a_target_spelt_otherwise_runs_the_rules_of_the_target_it_was_taken_for(tmp_path, where):
    """``MUJOCO`` (`` Drake ``, ``MuJoCo@3.7``) was refused by no check, since parse_target
    reads a name in any case, and matched no rule's target (Selection.allows compared the
    word as given): the check ran none of the target's rules, without a word. Now the word is
    what parse_target made of it (settings.checked_targets) wherever it is given."""
    shutil.copy(WELDED, tmp_path / "robot.urdf")
    (tmp_path / ".git").mkdir()
    words = ("MUJOCO", " Drake ")
    if where == "settings":
        (tmp_path / "urdftool.toml").write_text('targets = ["MUJOCO", " Drake "]\n')
    run = check_paths([str(tmp_path / "robot.urdf")], jobs=1, timeout=0,
                      **({"targets": words} if where == "command line" else {}))
    assert {"U928", "U944"} <= {f.code for f in run.results[0].findings}


def test_every_machine_format_carries_the_target():
    result = load_and_check(str(WELDED), CheckOptions(selection=Selection(targets=("mujoco",))))
    result.findings = [f for f in result.findings if f.code == "U928"]

    def out(name):
        stream = io.StringIO()
        render(name, [result], stream)
        return stream.getvalue()

    assert json.loads(out("json"))["diagnostics"][0]["target"] == "mujoco"
    assert json.loads(out("json-lines"))["target"] == "mujoco"
    assert json.loads(out("sarif"))["runs"][0]["results"][0]["properties"] == {
        "target": "mujoco"}
    assert json.loads(out("gitlab"))[0]["target"] == "mujoco"
    assert json.loads(out("rdjson"))["diagnostics"][0]["source"]["name"] == \
        "urdftool --target mujoco"
    assert "U928 mujoco-welded-root (mujoco)" in out("junit")
    assert "title=U928 mujoco-welded-root (mujoco)" in out("github")
    assert "(mujoco-welded-root, mujoco)" in out("text")


def test_cli_target_option_and_its_refusal():
    done = subprocess.run([sys.executable, "-m", "urdftool", "check", "--no-cache", "-f",
                           "concise", "--target", "drake", str(WELDED)],
                          capture_output=True, text=True, timeout=300)
    assert " U944 " in done.stdout and " U928 " not in done.stdout
    bad = subprocess.run([sys.executable, "-m", "urdftool", "check", "--target", "mujuco",
                          str(WELDED)], capture_output=True, text=True, timeout=300)
    assert bad.returncode == 2 and "did you mean 'mujoco'" in bad.stderr


def _fixed(tmp_path, case, code, target):
    """The case copied, checked for ``target``, and ``code``'s unsafe fix applied; returns the
    robot path."""
    folder = tmp_path / "robot"
    if case.is_dir():
        shutil.copytree(case, folder)
    else:
        folder.mkdir()
        shutil.copy(case, folder / "robot.urdf")
    (folder / ".git").mkdir()
    robot = folder / "robot.urdf"
    options = CheckOptions(selection=Selection(select=(code,), targets=(target,)))
    result = load_and_check(str(robot), options)
    assert [f for f in result.findings if f.code == code and f.fix is not None]
    changes = fixes.plan([result], unsafe=True)
    assert changes.applied and not changes.skipped, changes.skipped
    fixes.write(changes)
    assert not [f for f in load_and_check(str(robot), options).findings if f.code == code]
    return robot


@pytest.mark.parametrize("case, code, target", [
    (CASES / "U921_mujoco_mesh_format", "U921", "mujoco"),
    (CASES / "U920_mujoco_package_uri", "U920", "mujoco"),
    (CASES / "U924_mujoco_inertia_refused.urdf", "U924", "mujoco"),
    (CASES / "U940_drake_collision_mesh_format", "U940", "drake"),
])
def test_a_portability_fix_makes_the_loader_accept_the_file(tmp_path, case, code, target):
    from urdftool.crosscheck import crosscheck
    from urdftool.crosscheck.loaders import LOADERS, available

    robot = _fixed(tmp_path, case, code, target)
    if not available(target):
        pytest.skip(f"{target} is not installed: {LOADERS[target].install}")
    [result] = crosscheck(str(robot), [target]).loaders
    assert result.loaded, result.error


def test_the_world_link_fix_welds_the_robot_in_drake(tmp_path):
    robot = _fixed(tmp_path, CASES / "U944_drake_floating_root.urdf", "U944", "drake")
    assert '<link name="world"/>' in robot.read_text()
