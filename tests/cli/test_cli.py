"""`urdftool check` as a user meets it: exit codes, formats, selection, settings, stdin."""

from __future__ import annotations

import json

import pytest

from conftest import CASES, ROBOTS

INVERTED = CASES / "U204_inverted_limits.urdf"
AXIS = CASES / "U206_axis_not_unit.urdf"


def test_bundled_robots_check_clean(run_cli):
    result = run_cli("check", ROBOTS, "--format", "json")
    data = json.loads(result.stdout)
    assert result.exit_code == 0, data
    assert data["summary"] == {"files": 3, "errors": 0, "warnings": 0, "notes": 0,
                               "lines": {"errors": 0, "warnings": 0, "notes": 0}}
    assert data["diagnostics"] == []


def test_errors_exit_1_warnings_exit_0_unless_strict(run_cli):
    assert run_cli("check", INVERTED).exit_code == 1
    assert run_cli("check", AXIS).exit_code == 0
    assert run_cli("check", AXIS, "--strict").exit_code == 1


def test_usage_errors_exit_2(run_cli):
    assert run_cli("check", "no/such/file.urdf").exit_code == 2
    assert run_cli("check", INVERTED, "--format", "xml").exit_code == 2
    assert run_cli("check", INVERTED, "--package", "no-equals-sign").exit_code == 2
    assert run_cli("check", "--bogus-option", INVERTED).exit_code == 2


def test_unparsable_file_is_a_finding_not_a_usage_error(run_cli):
    result = run_cli("check", CASES / "U001_malformed_xml.urdf", "--format", "json")
    assert result.exit_code == 1
    assert json.loads(result.stdout)["diagnostics"][0]["code"] == "U001"


def test_select_and_ignore_by_code_prefix_and_name(run_cli):
    for selector in ("U204", "U2", "inverted-limits"):
        assert run_cli("check", INVERTED, "--ignore", selector).exit_code == 0
    assert run_cli("check", INVERTED, "--select", "U1").exit_code == 0
    assert run_cli("check", INVERTED, "--select", "U1,U204").exit_code == 1


def test_pyproject_settings_apply_and_cli_adds_to_them(tmp_path, run_cli):
    robot = tmp_path / "r.urdf"
    robot.write_text(INVERTED.read_text())
    (tmp_path / "pyproject.toml").write_text('[tool.urdftool]\nignore = ["inverted-limits"]\n')
    assert run_cli("check", robot).exit_code == 0
    (tmp_path / "pyproject.toml").write_text('[tool.urdftool]\nper-file-ignores = {"r.urdf" = ["U2"]}\n')
    assert run_cli("check", robot).exit_code == 0
    (tmp_path / "pyproject.toml").write_text('[tool.urdftool]\nselekt = ["U1"]\n')
    result = run_cli("check", robot)
    assert result.exit_code == 2 and "selekt" in result.output


def test_output_file_and_formats(tmp_path, run_cli):
    for name in ("json", "sarif", "junit", "github", "text"):
        out = tmp_path / f"report.{name}"
        result = run_cli("check", INVERTED, "--format", name, "--output", out)
        assert result.exit_code == 1
        assert "U204" in out.read_text()


def test_auto_format_is_github_under_actions(run_cli, monkeypatch):
    from typer.testing import CliRunner

    from urdftool.cli import app

    result = CliRunner().invoke(app, ["check", str(INVERTED)], env={"GITHUB_ACTIONS": "true"})
    assert result.stdout.startswith("::error file=")


def test_stdin(run_cli):
    result = run_cli("check", "-", "--format", "json", input=INVERTED.read_text())
    data = json.loads(result.stdout)
    assert result.exit_code == 1
    assert (data["diagnostics"][0]["file"], data["diagnostics"][0]["code"]) == ("<stdin>", "U204")


def test_verbose_says_which_files_were_skipped(run_cli):
    result = run_cli("check", ROBOTS / "r2d2", "-v")
    assert "skipped" in result.output and "included by" in result.output


def test_xacro_command_expands_with_args(tmp_path, run_cli):
    source = tmp_path / "r.urdf.xacro"
    source.write_text('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
                      '<xacro:arg name="n" default="a"/><link name="$(arg n)"/></robot>')
    out = tmp_path / "r.urdf"
    assert run_cli("xacro", source, "n:=wheel", "-o", out).exit_code == 0
    assert '<link name="wheel"/>' in out.read_text()
    bad = run_cli("xacro", CASES / "U005_xacro_error" / "robot.urdf.xacro")
    assert bad.exit_code == 1 and "wheel.xacro:6" in bad.output and "Traceback" not in bad.output


def test_tree_on_a_bundled_robot(run_cli):
    result = run_cli("tree", ROBOTS / "r2d2" / "r2d2.urdf.xacro")
    assert result.exit_code == 0
    assert result.stdout.splitlines()[2].startswith("root Link: base_footprint")


@pytest.mark.parametrize("words", [
    ["fk", "--frame", "nosuch"], ["fk", "--base", "nosuch"], ["fk", "--q", "nosuch=1"],
    ["dh", "--base", "nosuch", "--tip", "head"], ["inertia", "--link", "nosuch"],
    ["dynamics", "--q", "nosuch=1"], ["collisions", "--q", "nosuch=1"],
])
def test_an_unknown_name_on_the_command_line_is_exit_2_in_every_command(run_cli, words):
    from conftest import ROBOTS

    command, *options = words
    result = run_cli(command, ROBOTS / "r2d2" / "r2d2.urdf.xacro", *options, "--timeout", "0")
    assert result.exit_code == 2, result.output
    assert "nosuch" in result.stderr and "available" in result.stderr


@pytest.mark.parametrize("command", ["fk", "dynamics", "collisions"])
def test_a_robot_pinocchio_refuses_is_reported_at_its_line_without_urdfdom_noise(
        command, tmp_path, capfd):
    import subprocess
    import sys

    path = tmp_path / "r.urdf"
    path.write_text('<robot name="r"><link name="a"/><link name="b"/>\n<joint name="j" '
                    'type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>'
                    '</joint>\n</robot>')
    result = subprocess.run([sys.executable, "-m", "urdftool", command, str(path)],
                            capture_output=True, text=True)
    assert result.returncode == 1
    assert "r.urdf:2: error U202 revolute joint 'j' has no <limit>" in result.stderr
    assert "urdf_parser" not in result.stderr and "Error:" not in result.stderr


@pytest.mark.parametrize("command", ["fk", "dynamics", "collisions"])
def test_a_joint_axis_without_direction_fails_instead_of_nan_poses(command, tmp_path, run_cli):
    path = tmp_path / "r.urdf"
    path.write_text('<robot name="r"><link name="a"/><link name="b"><inertial><mass value="1"/>'
                    '<inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>\n'
                    '<joint name="j" type="revolute"><parent link="a"/><child link="b"/>'
                    '<axis xyz="0 0 0"/><limit lower="0" upper="1" effort="1" velocity="1"/>'
                    '</joint>\n</robot>')
    result = run_cli(command, path, "--timeout", "0")
    assert result.exit_code == 1 and "r.urdf:2: error: joint 'j'" in result.stderr, result.output
    assert "has no direction" in result.stderr


@pytest.mark.worker  # each command's result through the forked worker, as outside the tests
@pytest.mark.parametrize("words", [["tree"], ["graph"], ["fk"], ["dh", "--tip", "x"],
                                   ["ik", "--tip", "x", "--xyz", "0", "0", "0"],
                                   ["workspace", "--tip", "x"], ["inertia"], ["dynamics"],
                                   ["collisions"], ["collisions", "--matrix"],
                                   ["render", "-o", "{tmp}/x.png"]])
def test_a_robot_without_a_link_is_refused_alike_by_every_command(words, tmp_path, run_cli):
    """Materials only (TurtleBot3's common_properties.urdf, which check finds as a robot):
    fk and collisions said 'no root link (a cycle?)', graph drew an empty graph, inertia
    printed ' (0 links)', render wrote a picture of 0 triangles, all but the first two exit 0."""
    path = tmp_path / "colours.urdf"
    path.write_text('<robot name="colours">\n<material name="black"><color rgba="0 0 0 1"/>'
                    '</material>\n</robot>\n')
    command, *rest = words
    result = run_cli(command, path, *(word.format(tmp=tmp_path) for word in rest))
    assert result.exit_code == 1, result.output
    assert "colours.urdf:1: error U106 robot has no <link> elements" in result.stderr
    assert "cycle" not in result.output + result.stderr and not (tmp_path / "x.png").exists()
    assert run_cli("xacro", path).exit_code == 0  # a macro library's expansion has no link


POSING = [["fk"], ["dh", "--tip", "{tip}"], ["ik", "--tip", "{tip}", "--xyz", "0", "0", "0"],
          ["workspace", "--tip", "{tip}", "--samples", "10"], ["dynamics"], ["collisions"],
          ["render", "-o", "{tmp}/x.png"]]


@pytest.mark.parametrize("words", POSING)
@pytest.mark.parametrize("case, tip, line", [
    pytest.param("U105_unknown_link.urdf", "arm", "U105_unknown_link.urdf:5: error U105 joint "
                 "'j' names parent link 'bse_link'",
                 # each command's refusal through the forked worker, as outside the tests, once;
                 # the other robots' in this process (a fork of the pytest worker: 0.15 s each)
                 marks=pytest.mark.worker),
    ("U109_kinematic_cycle.urdf", "b", "U109_kinematic_cycle.urdf:5: error U109 joints form a "
                                       "cycle"),
    ("U207_malformed_number.urdf", "arm", "U207_malformed_number.urdf:5: error U207 joint "
                                          "'elbow': <origin xyz>"),
    ("U201_unknown_joint_type.urdf", "arm", "U201_unknown_joint_type.urdf:4: error U201"),
    ("U107_multiple_parents.urdf", "c", "U107_multiple_parents.urdf:9: error U107 link 'c' has "
                                        "2 parent joints"),
])
def test_a_robot_in_error_is_refused_alike_by_every_command_that_poses_it(
        words, case, tip, line, tmp_path, run_cli):
    """One owner of "this robot cannot be posed, because": the linter's errors at their lines.
    render said 'yourdfpy cannot build the scene (ValueError: ...)' (U207, U107) or printed a
    traceback (U105, U109: trimesh's 'No path from base_link->arm'); fk, ik, collisions and
    workspace 'no root link (a cycle?)' (U109) or 'reached twice (a cycle?)' (U107); dh 'no
    revolute or prismatic joint' (U107); dynamics computed U107's robot with the link under one
    of its parents, exit 0."""
    command, *rest = words
    result = run_cli(command, CASES / case, *(w.format(tmp=tmp_path, tip=tip) for w in rest))
    assert result.exit_code == 1, result.output
    assert line in result.stderr, result.stderr
    assert "Traceback" not in result.stderr and "yourdfpy" not in result.stderr
    assert "cycle?" not in result.stderr and not (tmp_path / "x.png").exists()


@pytest.mark.worker  # each command's result through the forked worker, as outside the tests
@pytest.mark.parametrize("words", [["tree"], *POSING])
def test_a_part_of_a_robot_defined_elsewhere_is_refused_as_that_part(words, tmp_path, run_cli):
    """A part (lint.parts: its joints hang on a link it does not write, no root of its own),
    whose U105 and U011 are notes: ridgeback_iiwa's arm, hung on the base's mid_mount. fk, dh,
    tree, ik, workspace and collisions said 'no root link (a cycle?)', render 'an element lacks
    its 'name' attribute', dynamics listed the part's other errors (its meshes not found) as
    why Pinocchio refused it."""
    path = tmp_path / "arm.urdf"
    path.write_text('<robot name="arm">\n<link name="a"/>\n<link name="b"/>\n'
                    '<joint name="mount" type="fixed"><parent link="mid_mount"/><child link="a"/>'
                    '</joint>\n<joint name="j" type="revolute"><parent link="a"/><child link="b"/>'
                    '<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/>'
                    '</joint>\n</robot>\n')
    command, *rest = words
    result = run_cli(command, path, *(w.format(tmp=tmp_path, tip="b") for w in rest))
    assert result.exit_code == 1, result.output
    assert ("arm.urdf:1: error: a part of a robot defined elsewhere (its joints hang on links it "
            "does not write, and it has no root link of its own): it cannot be loaded alone"
            ) in result.stderr, result.stderr
    assert "cycle?" not in result.stderr and not (tmp_path / "x.png").exists()


@pytest.mark.parametrize("command", ["tree", "fk", "inertia", "dynamics", "collisions", "graph",
                                     "crosscheck"])
def test_a_robot_needing_a_package_not_installed_exits_2_as_check_does(command, tmp_path,
                                                                        run_cli):
    """A package this machine lacks (U006: the environment's, not the robot's; TurtleBot's
    create_description in the sweep) is check's exit 2, 'not checked'; the commands exited 1,
    as for a robot in error. A xacro error in the robot stays 1."""
    path = tmp_path / "r.urdf.xacro"
    path.write_text('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                    '<xacro:include filename="$(find absent_description)/urdf/base.xacro"/>\n'
                    '<link name="a"/>\n</robot>\n')
    assert run_cli("check", path).exit_code == 2
    result = run_cli(command, path)
    assert result.exit_code == 2, result.output
    assert "r.urdf.xacro:2: warning U006 package 'absent_description' not found" in result.stderr
    path.write_text('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                    '<link name="${nowhere}"/>\n</robot>\n')
    result = run_cli(command, path)
    assert result.exit_code == 1 and "r.urdf.xacro:2: error U005" in result.stderr


TWO_LINKS = '<robot name="r">\n<link name="a"/><link name="b"/>\n{joint}\n</robot>'


@pytest.mark.parametrize("joint, code", [
    ('<joint name="j" type="fixed"><parent link="a"/><child link="c"/></joint>', "U105"),
    ('<joint name="j" type="revolute"><parent link="a"/><child link="b"/></joint>', "U202"),
    ('<joint name="j" type="hinge"><parent link="a"/><child link="b"/></joint>', "U201"),
    ('<joint name="j" type="fixed"><origin xyz="1x 0 0"/><parent link="a"/><child link="b"/>'
     '</joint>', "U207"),
    # a .urdf holding xacro is read as check_urdf reads it, unexpanded: ${} is not a number
    ('<joint name="j" type="fixed" xmlns:xacro="http://www.ros.org/wiki/xacro">'
     '<origin xyz="${1 + 1} 0 0"/><parent link="a"/><child link="b"/></joint>', "U207"),
])
def test_tree_fails_located_where_check_urdf_fails(run_cli, tmp_path, joint, code):
    path = tmp_path / "r.urdf"
    path.write_text(TWO_LINKS.format(joint=joint))
    result = run_cli("tree", path)
    assert result.exit_code == 1 and "Successfully Parsed XML" not in result.stdout
    assert f"r.urdf:3: error {code}" in result.stderr


def test_a_reader_that_leaves_early_gets_no_traceback():
    """``urdftool collisions --matrix --all ... | head -1``: the rest of the output meets a closed
    pipe in the worker; the command stops quietly with exit code 1. The pipe holds one page and
    the reader takes only the first line, so the rest (some 15 kB) cannot all be written before
    the reader leaves, however the two processes are scheduled."""
    import fcntl
    import os
    import subprocess
    import sys

    read, write = os.pipe()
    if hasattr(fcntl, "F_SETPIPE_SZ"):  # Linux; elsewhere pipes hold 16 kB at most
        fcntl.fcntl(write, fcntl.F_SETPIPE_SZ, 4096)
    process = subprocess.Popen(
        [sys.executable, "-m", "urdftool", "collisions", str(ROBOTS / "humanoid" /
                                                             "humanoid.urdf.xacro"),
         "--matrix", "--all", "--samples", "500"], stdout=write, stderr=subprocess.PIPE)
    os.close(write)
    first = b""
    while not first.endswith(b"\n") and (byte := os.read(read, 1)):  # unbuffered: one line
        first += byte
    os.close(read)  # as head does after its line
    _, errors = process.communicate(timeout=300)
    assert first.startswith(b"humanoid_robot:")
    assert b"Traceback" not in errors and process.returncode == 1, errors.decode()


def _float_parameters():
    """(command, option, parameter) of every float the command line reads, tuples' members
    included (``ik --xyz X Y Z``)."""
    from typer._click import types

    from urdftool.cli import COMMANDS, command

    for name in COMMANDS:
        for param in command(name).params:
            kinds = param.type.types if isinstance(param.type, types.Tuple) else [param.type]
            if any(isinstance(kind, types.FloatParamType) for kind in kinds):
                yield name, max(param.opts, key=len), param


def test_every_float_option_refuses_nan_and_infinity():
    """click reads 'nan', 'inf' and '1e999' as floats and a NaN passes every min=/max=: a NaN
    --density gave NaN masses, --min-fraction nan an 'Always' for no pair, --tolerance 1e999
    every change equal, --timeout 1e999 a traceback. One guard (cli._finite_numbers) for every
    float option of every command."""
    from typer._click.exceptions import BadParameter

    found = list(_float_parameters())
    assert len(found) >= 15 and {"--density", "--timeout", "--xyz", "--min-fraction"} <= \
        {option for _, option, _ in found}
    for name, option, param in found:
        kinds = getattr(param.type, "types", [param.type])
        for kind in kinds:
            with pytest.raises(BadParameter, match="finite"):  # NaN passes any range
                kind.convert("nan", param, None)
            for word in ("inf", "-inf", "1e999"):  # (or out of its range)
                with pytest.raises(BadParameter, match="finite|range"):
                    kind.convert(word, param, None)
            assert kind.convert("0.5", param, None) == 0.5, (name, option)


def test_every_integer_option_is_converted_once_and_held_within_int64():
    """click's int() of 5,000 digits said "is not a valid integer" quoting every digit, and
    an integer past int64 reached numpy (fk --random 10**30: "Maximum allowed dimension
    exceeded", a traceback) or a pool (collisions --workers 10**30 forked until stopped). One
    guard (cli._bounded_integers, numbers.integer) for every integer option of every
    command."""
    from typer._click.exceptions import BadParameter
    from typer._click import types

    from urdftool.cli import COMMANDS, command

    found = [(name, param) for name in COMMANDS for param in command(name).params
             for kind in (param.type.types if isinstance(param.type, types.Tuple) else [param.type])
             if isinstance(kind, types.IntParamType)]
    assert len(found) >= 15 and {"--seed", "--samples", "--workers", "--jobs", "--random"} <= \
        {max(param.opts, key=len) for _, param in found}
    for name, param in found:
        with pytest.raises(BadParameter, match=r"too long: an integer of 5,000 characters") as raised:
            param.type.convert("9" * 5000, param, None)
        assert len(str(raised.value)) < 400
        with pytest.raises(BadParameter, match="int64|range"):
            param.type.convert(str(2 ** 63), param, None)
        assert param.type.convert(str(2 ** 63 - 1), param, None) == 2 ** 63 - 1 or \
            getattr(param.type, "max", None) is not None, (name, param.opts)


@pytest.mark.parametrize("words", [["fk", "--random", str(10 ** 30)], ["check", "--jobs", str(10 ** 30)]])
def test_an_integer_past_int64_is_a_usage_error(tmp_path, words):
    """Through the real door too: check's plain words are read without Typer (__main__)."""
    import subprocess
    import sys

    robot = tmp_path / "r.urdf"
    robot.write_text('<robot name="r"><link name="a"/><link name="b"/><joint name="j" '
                     'type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>'
                     '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>')
    result = subprocess.run([sys.executable, "-m", "urdftool", words[0], str(robot), *words[1:]],
                            capture_output=True, text=True, timeout=60)
    assert result.returncode == 2 and "int64" in result.stderr, result.stderr


@pytest.mark.parametrize("words", [["check", "--timeout", "nan"], ["check", "--timeout", "1e999"],
                                   ["inertia", "--density", "nan"],
                                   ["ik", "--tip", "b", "--xyz", "0", "nan", "0"]])
def test_a_non_finite_number_is_a_usage_error(tmp_path, words):
    """Through the real door too: check's plain words are read without Typer (__main__)."""
    import subprocess
    import sys

    robot = tmp_path / "r.urdf"
    robot.write_text('<robot name="r"><link name="a"/><link name="b"/><joint name="j" '
                     'type="fixed"><parent link="a"/><child link="b"/></joint></robot>')
    result = subprocess.run([sys.executable, "-m", "urdftool", words[0], str(robot), *words[1:]],
                            capture_output=True, text=True, timeout=60)
    assert result.returncode == 2 and "not a finite number" in result.stderr, result.stderr


def test_a_file_named_like_an_option_is_never_read_as_one(tmp_path, monkeypatch, run_cli):
    """pre-commit appends the staged file names without '--': a committed file named
    '--controllers=x.yaml' (a link to a file outside the repository) was read as the option,
    and a companion named on the command line is read wherever it leads (/etc/passwd parsed,
    U601); '--select=U0.urdf' would choose the rules. Every command, both doors: a usage error
    that names the word."""
    import subprocess
    import sys

    (tmp_path / ".git").mkdir()
    (tmp_path / "r.urdf").write_text('<robot name="r"><link name="a"/></robot>')
    outside = tmp_path.parent / f"{tmp_path.name}-secret.yaml"
    outside.write_text("SECRET: 1\n")
    (tmp_path / "x.yaml").symlink_to(outside)
    (tmp_path / "--controllers=x.yaml").write_text("")
    (tmp_path / "-oREADME.urdf").write_text("")
    monkeypatch.chdir(tmp_path)
    for words in (["check", "--controllers=x.yaml", "r.urdf"], ["tree", "-oREADME.urdf", "r.urdf"]):
        result = run_cli(*words)
        assert result.exit_code == 2 and f"'{words[1]}' reads as an option" in result.output
        assert "SECRET" not in result.output
        door = subprocess.run([sys.executable, "-m", "urdftool", *words], capture_output=True,
                              text=True, timeout=60)
        assert door.returncode == 2 and "reads as an option" in door.stderr, door.stderr
    assert run_cli("check", "--no-cache", "--", "--controllers=x.yaml", "r.urdf").exit_code == 0
    assert run_cli("check", "--no-cache", "--select=U2", "r.urdf").exit_code == 0


@pytest.mark.parametrize("written, direction", [("1e308 1e308 1e308", "0.57735 0.57735 0.57735"),
                                                ("1e-170 0 0", "1 0 0")])
def test_an_axis_whose_squares_overflow_or_underflow_still_has_its_direction(
        written, direction, tmp_path, run_cli):
    """Scaled before it is normalised, an axis of 1e308 (its squares overflow) or 1e-170 (they
    underflow) has a direction: fk computes poses, and dynamics says that Pinocchio's own
    normalisation (Eigen's, unscaled) loses it. check proposes the unit axis for 1e308 (U206,
    not 0 0 0); 1e-170, whose squares underflow in every loader that normalises it, is U205's
    error (attack10), which says to give a unit vector."""
    path = tmp_path / "r.urdf"
    path.write_text('<robot name="r"><link name="a"/><link name="b"><inertial><mass value="1"/>'
                    '<inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>\n'
                    '<joint name="j" type="revolute"><parent link="a"/><child link="b"/>'
                    f'<axis xyz="{written}"/><limit lower="0" upper="1" effort="1" velocity="1"/>'
                    '</joint>\n</robot>')
    result = run_cli("fk", path, "--q", "j=1")
    assert result.exit_code == 0 and "no direction" not in result.output, result.output
    assert "RuntimeWarning" not in result.stderr, result.stderr
    result = run_cli("check", path, "--no-cache", "--select", "U205,U206")
    if written.startswith("1e-170"):
        assert "U205" in result.output and "underflows to 0" in result.output, result.output
    else:
        assert f'write xyz="{direction}"' in result.output, result.output
    result = run_cli("dynamics", path, "--timeout", "0")
    assert "has no direction" not in result.stderr and "Eigen normalises it" in result.stderr, \
        result.output


@pytest.mark.parametrize("words", [["fk"], ["dynamics", "--samples", "5", "-f", "json"],
                                   ["collisions"],
                                   ["workspace", "--tip", "b", "--samples", "10"],
                                   ["ik", "--tip", "b", "--xyz", "0", "0.1", "0"]])
def test_a_negative_effort_or_velocity_limit_is_no_reason_to_refuse_a_robot(words, tmp_path,
                                                                             run_cli):
    """urdfdom (so ROS) loads a joint of ``effort="-1.0" velocity="-1.0"`` (U212 warns of it),
    Pinocchio refuses the model: fk, ik, workspace, collisions and dynamics refused Halodi's EVE
    (every joint so written) at its <robot> line with 'Pinocchio (urdfdom) cannot build a
    model: Some components of min_effort are greater than max_effort'. Given to Pinocchio as
    0, which dynamics judges as it judges -1: no limit to hold a torque against."""
    path = tmp_path / "r.urdf"
    path.write_text('<robot name="r"><link name="a"/><link name="b"><inertial><mass value="2"/>'
                    '<origin xyz="0.1 0 0"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" '
                    'iyz="0"/></inertial></link>\n<joint name="j" type="revolute"><parent '
                    'link="a"/><child link="b"/><origin xyz="0 0.1 0"/><axis xyz="0 1 0"/>'
                    '<limit lower="-1" upper="1" effort="-1.0" velocity="-1.0"/></joint>\n'
                    '</robot>\n')
    command, *rest = words
    result = run_cli(command, path, *rest, "--timeout", "0")
    assert result.exit_code == 0, result.output
    assert "cannot build" not in result.stderr
    if command == "dynamics":
        document = json.loads(result.stdout)
        assert document["G"] == [pytest.approx(-2 * 9.81 * 0.1)]  # m g x, about the y axis
        assert [(load["judged"], load["holds"]) for load in document["gravity_loads"]] == [
            (False, None)]


@pytest.mark.parametrize("words", [["fk"], ["dh", "--tip", "x_link"]])
def test_urdfdoms_refusal_in_a_file_drake_reads_is_still_refused(words, tmp_path, run_cli):
    """RobotLocomotion/models' PR2 (xmlns:drake, nothing says ROS runs it): a prismatic joint
    without <limit> is a warning naming the condition, "if urdfdom loads it", and still
    urdfdom's refusal (lint.catalogue.Refused): fk and dh stop at it as at the error."""
    path = tmp_path / "pr2.urdf"
    path.write_text('<robot name="pr2" xmlns:drake="http://drake.mit.edu">\n<link name="base"/>\n'
                    '<link name="x_link"/>\n'
                    '<joint name="x" type="prismatic"><parent link="base"/><child link="x_link"/>'
                    '<axis xyz="1 0 0"/></joint>\n</robot>\n')
    command, *rest = words
    result = run_cli(command, path, *rest)
    assert result.exit_code == 1, result.output
    assert "pr2.urdf:4: warning U202 if urdfdom loads it (Drake reads it" in result.stderr, \
        result.stderr
    path.write_text(path.read_text().replace('<axis xyz="1 0 0"/>', '<axis xyz="1 0 0"/><limit '
                                             'lower="0" upper="1" effort="1" velocity="1"/>'))
    assert run_cli(command, path, *rest).exit_code == 0


SECRET = "URDFTOOL_SECRET_29"
SECRET_ROBOT = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <link name="base"><visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual>
    <inertial><mass value="1"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/>
    </inertial></link>
  <link name="{tip}"><visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual>
    <inertial><mass value="1"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/>
    </inertial></link>
  <joint name="j" type="revolute"><parent link="base"/><child link="{tip}"/><axis xyz="0 0 1"/>
    <origin xyz="0 0 0.5"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>
"""


def _every_command_on(robot, old, out):
    """(command, argv) for every command of the app that reads a robot, its required options
    filled (the tip is 'tip', the name the safe mode gives it)."""
    from tests.fuzz import forge

    required = {"--base": "base", "--tip": "tip", "--output": str(out / "x.svg")}
    runs = []
    for name in forge.commands():
        if name in forge.NO_ROBOT:
            continue
        fill = [word for option, param in forge.command_options(name).items()
                if getattr(param, "required", False) and option.startswith("-")
                for word in (option, required[option])]
        also = {"ik": ["--xyz", "0", "0", "0.5"], "crosscheck": ["--loader", "pinocchio"],
                "workspace": ["--samples", "5"], "dynamics": ["--samples", "2"],
                }.get(name, [])
        runs.append((name, [name, *([old, robot] if name == "diff" else [robot]), *fill, *also]))
    return runs


@pytest.mark.parametrize("written", ["$(optenv URDFTOOL_SECRET_29 tip)",
                                     "$(env URDFTOOL_SECRET_29)"])
def test_every_command_under_ci_reads_no_environment_variable_a_robot_names(
        written, tmp_path, monkeypatch, analysis_imported):
    """Under ``CI`` every command takes check's safe mode (``description.files.env_allowed``):
    ``crosscheck`` loaded with the full mode, and its report named the link
    ``$(optenv URDFTOOL_SECRET_29 tip)`` made from the job's secret. Each command of the app's
    table runs on a robot naming the variable, under ``CI=1`` and (the control: the test can
    fail) without it: the variable is read, and its value printed, only without."""
    from typer.testing import CliRunner

    from conftest import one_piece_here
    from urdftool.cli import app
    from urdftool.description import files

    (tmp_path / ".git").mkdir()
    robot = tmp_path / "r.urdf.xacro"
    robot.write_text(SECRET_ROBOT.format(tip=written))
    old = tmp_path / "old.urdf.xacro"
    old.write_text(SECRET_ROBOT.format(tip="tip").replace('xyz="0 0 0.5"', 'xyz="0 0 0.4"'))
    read: list[str] = []
    reader = files.environ
    monkeypatch.setattr(files, "environ", lambda name, variables=None: (
        read.append(name) if variables is None else None, reader(name, variables))[1])
    one_piece_here(monkeypatch)
    found = []
    for ci in ("1", ""):
        for name, argv in _every_command_on(str(robot), str(old), tmp_path):
            read.clear()
            result = CliRunner().invoke(app, argv, env={
                "COLUMNS": "120", "NO_COLOR": "1", "TERM": "dumb", "GITHUB_ACTIONS": "",
                "CI": ci, SECRET: "s3cr3t-value"})
            shown = result.stdout + result.stderr
            if ci and (SECRET in read or "s3cr3t-value" in shown):
                found.append(f"{name} under CI read {SECRET}: {shown[-300:]}")
            if not ci and SECRET not in read:  # the control
                found.append(f"{name} without CI never read {SECRET}: {shown[-300:]}")
    assert found == [], "\n".join(found)
