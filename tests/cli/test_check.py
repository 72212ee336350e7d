"""``urdftool check``'s options for CI and editors: exit codes, quiet, statistics, stdin
filename, --config and --isolated."""

from __future__ import annotations

import json

import pytest

BROKEN = """<robot name="r">
  <link name="a"/><link name="b"/>
  <joint name="j" type="revolute"><parent link="a"/><child link="b"/>
    <axis xyz="0 0 2"/><limit lower="1" upper="-1" effort="1" velocity="1"/></joint>
</robot>
"""


@pytest.fixture
def broken(tmp_path):
    (tmp_path / "robots").mkdir()
    path = tmp_path / "robots" / "arm.urdf"
    path.write_text(BROKEN)
    return path


def test_exit_zero_reports_but_exits_0(run_cli, broken):
    result = run_cli("check", broken, "--exit-zero")
    assert result.exit_code == 0 and "U204" in result.stdout
    assert run_cli("check", broken, "--exit-zero", "--select", "U999").exit_code == 2


def test_quiet_prints_findings_without_the_summary(run_cli, broken):
    result = run_cli("check", broken, "-q")
    assert result.exit_code == 1
    assert "U204" in result.stdout and "checked" not in result.stdout
    assert run_cli("check", broken, "-q", "--select", "U1").stdout == ""


def test_statistics_counts_each_rule_most_first(run_cli, broken, tmp_path):
    second = tmp_path / "robots" / "leg.urdf"
    second.write_text(BROKEN.replace('xyz="0 0 2"', 'xyz="0 0 1"'))
    result = run_cli("check", tmp_path / "robots", "--statistics")
    assert result.exit_code == 1
    assert result.stdout.splitlines() == ["2  U204  error    inverted-limits",
                                          "1  U206  warning  axis-not-unit"]


def test_stdin_filename_names_the_input_and_finds_its_includes(run_cli, tmp_path):
    (tmp_path / "parts.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><xacro:macro name="arm">'
        '<link name="b"/><joint name="j" type="revolute"><parent link="a"/><child link="b"/>'
        '<limit lower="1" upper="-1" effort="1" velocity="1"/></joint></xacro:macro></robot>')
    text = ('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
            '<xacro:include filename="parts.xacro"/>\n<link name="a"/>\n<xacro:arm/>\n</robot>\n')
    name = str(tmp_path / "robot.urdf.xacro")
    result = run_cli("check", "-", "--stdin-filename", name, "-f", "json", input=text)
    data = json.loads(result.stdout)
    assert result.exit_code == 1, result.output
    [finding] = data["diagnostics"]
    assert finding["code"] == "U204" and finding["file"].endswith("parts.xacro")
    assert finding["via"][0]["file"] == finding["file"].replace("parts.xacro", "robot.urdf.xacro")
    assert finding["via"][0]["line"] == 4


def test_stdin_filename_without_stdin_is_a_usage_error(run_cli, broken):
    result = run_cli("check", broken, "--stdin-filename", "x.urdf")
    assert result.exit_code == 2 and "give '-'" in result.stderr


def test_stdin_filename_applies_the_settings_there(run_cli, broken, tmp_path):
    (tmp_path / "urdftool.toml").write_text('ignore = ["U204"]\n')
    result = run_cli("check", "-", "--stdin-filename", str(tmp_path / "robots" / "x.urdf"),
                     "-f", "json", input=BROKEN)
    assert [d["code"] for d in json.loads(result.stdout)["diagnostics"]] == ["U206"]


def test_config_replaces_and_isolated_ignores_the_settings(run_cli, broken, tmp_path):
    (tmp_path / "urdftool.toml").write_text('ignore = ["U204"]\n')
    other = tmp_path / "ci.toml"
    other.write_text('[tool.urdftool]\nignore = ["U206"]\n')

    def codes(*words):
        result = run_cli("check", broken, "-f", "json", *words)
        return [d["code"] for d in json.loads(result.stdout)["diagnostics"]]

    assert codes() == ["U206"]
    assert codes("--config", other) == ["U204"]
    assert codes("--isolated") == ["U204", "U206"]
    assert run_cli("check", broken, "--config", other, "--isolated").exit_code == 2
    missing = run_cli("check", broken, "--config", tmp_path / "nope.toml")
    assert missing.exit_code == 2 and "does not exist" in missing.stderr


def test_version_short_flag(run_cli):
    from urdftool import __version__

    result = run_cli("-V")
    assert result.exit_code == 0 and result.stdout.strip() == f"urdftool {__version__}"


def test_shell_completion_is_offered(run_cli):
    assert "--show-completion" in run_cli("--help").stdout


def test_a_symlinked_folder_and_its_includes_are_shown_the_same_way(run_cli, tmp_path,
                                                                     monkeypatch):
    real = tmp_path / "real"
    real.mkdir()
    (tmp_path / ".git").mkdir()
    (real / "robot.urdf.xacro").write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '<xacro:include filename="arm.xacro"/>\n<link name="a"/>\n<xacro:arm/>\n</robot>\n')
    (real / "arm.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><xacro:macro name="arm">\n'
        '<link name="b"/><joint name="j" type="revolute"><parent link="a"/><child link="b"/>\n'
        '<limit lower="1" upper="-1" effort="1" velocity="1"/></joint>\n'
        '</xacro:macro></robot>\n')
    (tmp_path / "alias").symlink_to(real)
    monkeypatch.chdir(tmp_path)
    result = run_cli("check", "alias/robot.urdf.xacro", "-f", "json", "--no-cache")
    [finding] = json.loads(result.stdout)["diagnostics"]
    assert finding["file"] == "alias/arm.xacro"
    assert finding["via"][0]["file"] == "alias/robot.urdf.xacro"


def test_a_run_checking_nothing_says_why_of_the_launch_files_named_alone(run_cli, tmp_path):
    """A launch file named (pre-commit names it) that builds no robot: said without -v when the
    run checks nothing, each once; a YAML no robot uses stays quiet (said with -v)."""
    (tmp_path / ".git").mkdir()
    (tmp_path / "empty.launch").write_text("<launch/>")
    (tmp_path / "robot.yaml").write_text("a: 1\n")
    named = [tmp_path / "empty.launch", tmp_path / "robot.yaml", tmp_path / "empty.launch"]
    result = run_cli("check", *named)
    said = [line for line in result.stderr.splitlines() if line.startswith("skipped ")]
    assert len(said) == 1 and said[0].startswith(f"skipped {named[0]}: a launch file that "), said
    verbose = run_cli("check", "-v", *named).stderr
    assert f"skipped {named[1]}: no robot below" in verbose


ARGUED = """<robot name="{name}" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="{arg}" default="1"/>
  <link name="a"><visual><geometry><box size="$(arg {arg}) 1 1"/></geometry></visual></link>
</robot>
"""


@pytest.mark.parametrize("output_format", ["text", "json"])
def test_a_xacro_argument_no_robot_checked_names_is_said_once_on_standard_error(
        run_cli, tmp_path, output_format):
    """``check --arg lenght=2`` for ``length`` was silent (the robot commands warn): a
    warning on standard error, once for the run, for an argument no file of any robot checked
    names; none for one that a robot of the folder reads (``width``), though another does
    not; the report and the exit code as without it."""
    for name, arg in (("long", "length"), ("wide", "width")):
        (tmp_path / f"{name}.urdf.xacro").write_text(ARGUED.format(name=name, arg=arg))
    result = run_cli("check", tmp_path, "--arg", "lenght=2", "width:=3", "-f", output_format,
                     "--no-cache")
    plain = run_cli("check", tmp_path, "-f", output_format, "--no-cache")
    assert result.exit_code == plain.exit_code == 0, result.output
    assert result.stdout == plain.stdout
    assert result.stderr.splitlines() == [
        "urdftool: warning: xacro argument 'lenght' (lenght:=2) is named by no file of the 2 "
        "robots checked (no <xacro:arg name=\"lenght\">, no $(arg lenght)): it changes "
        "nothing; did you mean 'length'?"]
    named = run_cli("check", tmp_path, "--arg", "length=2", "--no-cache")
    assert named.exit_code == 0 and named.stderr == "", named.output


def test_the_argument_warning_reads_what_each_check_kept_not_the_disk_again():
    """check's warning of an argument no file names read every file each robot read again
    from disk (99 for the humanoid: its meshes skipped, its SRDF, YAML and package.xml not);
    it reads what each check kept of its robot's text (FileResult.arguments, made where the
    robot was built): files gone since change nothing (read again, they silenced it)."""
    from urdftool import checking
    from urdftool.lint.options import FileResult
    from urdftool.lint.runner import Run

    run = Run([FileResult("long.urdf.xacro", [], read=("/gone/long.urdf.xacro",),
                          arguments=[["length"], ["length"]]),
               FileResult("wide.urdf.xacro", [], read=("/gone/wide.urdf.xacro",),
                          arguments=[["width"], ["width"]])])
    assert checking._unnamed_arguments(run, {"lenght": "2", "width": "3"}) == [
        "xacro argument 'lenght' (lenght:=2) is named by no file of the 2 robots checked (no "
        "<xacro:arg name=\"lenght\">, no $(arg lenght)): it changes nothing; did you mean "
        "'length'?"]
    unknown = Run([FileResult("long.urdf.xacro", [], read=("/gone/long.urdf.xacro",))])
    assert checking._unnamed_arguments(unknown, {"lenght": "2"}) == []  # not known: not said


def test_the_argument_warning_is_said_when_the_result_cache_serves_the_check(run_cli,
                                                                            tmp_path):
    """The result cache keeps what the check read of the arguments (schema 8), so a second
    run, served by the cache, warns as the first."""
    folder = tmp_path / "robots"
    folder.mkdir()
    (folder / "long.urdf.xacro").write_text(ARGUED.format(name="long", arg="length"))
    words = ["check", folder / "long.urdf.xacro", "--arg", "lenght=2", "--cache-dir",
             tmp_path / "cache"]
    first, second = run_cli(*words), run_cli(*words)
    assert first.exit_code == second.exit_code == 0, second.output
    assert "xacro argument 'lenght' (lenght:=2) is named by no file" in first.stderr
    assert second.stderr == first.stderr
    assert list((tmp_path / "cache").rglob("*")), "nothing was cached"


def test_a_check_without_an_argument_imports_no_mesh_module(tmp_path):
    """The warning of an argument no file names reads what each robot read, skipping meshes by
    their extension: asked before anything is given, it imported the mesh package for every
    check (7 M instructions of r2d2's 555 M, for a robot without a mesh). A fresh process, as
    a user's run: ``-X importtime`` prints a line per import."""
    import re
    import subprocess
    import sys

    (tmp_path / "r.urdf").write_text('<robot name="r"><link name="a"/></robot>\n')
    done = subprocess.run([sys.executable, "-X", "importtime", "-m", "urdftool", "check",
                           "--no-cache", "--jobs", "1", "r.urdf"], capture_output=True,
                          text=True, cwd=tmp_path, timeout=120)
    assert done.returncode == 0 and "no problems found" in done.stdout, done.stderr
    assert not re.search(r"\|\s+urdftool\.description\.(meshes|mesh_arrays|collada)\b",
                         done.stderr), done.stderr
