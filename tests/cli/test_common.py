"""``urdftool.cli._common``: what every robot command shares; here, options given without what
they act on, which the commands read and then did nothing with (exit 0, as if they counted)."""

from __future__ import annotations

import json
import sys

import pytest

# a slider carrying a cylinder: every command has work, none much
ARM = ('<robot name="arm"><link name="base"/><link name="upper"><inertial><mass value="1"/>'
       '<inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>'
       '<collision><geometry><cylinder radius="0.05" length="0.3"/></geometry></collision>'
       '</link><joint name="shoulder" type="prismatic"><parent link="base"/>'
       '<child link="upper"/><axis xyz="1 0 0"/>'
       '<limit lower="-1" upper="1" effort="10" velocity="1"/></joint></robot>')


@pytest.fixture
def arm(tmp_path):
    path = tmp_path / "arm.urdf"
    path.write_text(ARM)
    return path


@pytest.mark.parametrize("words, message", [
    (["fk", "--q", "shoulder=1", "--seed", "5"], "--seed needs --random or --verify"),
    (["fk", "--deg"], "--deg needs --q or --q-file"),
    (["fk", "--dh", "arm.urdf", "--floating"], "--floating does not go with --dh"),
    (["dynamics", "--seed", "3"], "--seed needs --samples"),
    (["dynamics", "--deg"], "--deg needs --q, --v or --a"),
    (["workspace", "--tip", "upper", "--deg"], "--deg needs --q"),
    (["render", "-o", "arm.png", "--deg"], "--deg needs --q"),
    (["inertia", "--all"], "--all needs --write"),
    (["inertia", "--write", "out.urdf", "--all", "-f", "json"],
     "--format json does not go with --write"),
    (["collisions", "--samples", "100", "--margin", "0.01"],
     "--samples and --margin need --matrix (without it, they do nothing)"),
    (["collisions", "--all"], "--all needs --matrix"),
    (["collisions", "--deg"], "--deg needs --q"),
    (["collisions", "--max-scene-triangles", "5"], "--max-scene-triangles needs --render"),
    (["collisions", "--matrix", "--srdf", "arm.urdf"], "--matrix reads no SRDF"),
])
def test_an_option_without_what_it_acts_on_is_a_usage_error(arm, run_cli, words, message,
                                                               monkeypatch):
    monkeypatch.chdir(arm.parent)
    result = run_cli(words[0], arm, *words[1:])
    assert result.exit_code == 2, result.output
    assert message in result.output


@pytest.mark.parametrize("words", [
    ["fk", "--random", "2", "--seed", "5"],
    ["fk", "--q", "shoulder=10", "--deg"],
    ["dynamics", "--samples", "3", "--seed", "2"],
    ["collisions", "--q", "shoulder=10", "--deg"],
    ["collisions", "--matrix", "--samples", "500", "--seed", "1", "--workers", "1"],
])
def test_the_same_options_with_what_they_act_on_run(arm, run_cli, words):
    result = run_cli(words[0], arm, *words[1:])
    assert result.exit_code == 0, result.output


@pytest.mark.parametrize("command, option, key", [
    ("fk", "--q", None), ("dynamics", "--q", "q"), ("dynamics", "--v", None),
    ("dynamics", "--a", None), ("collisions", "--q", None),
    ("ik", "--target-q", None), ("ik", "--q", None)])
def test_a_joint_name_may_hold_an_equals_sign(tmp_path, run_cli, command, option, key):
    # every command's joint values split at the last '=': 'gain=2=0.5' is joint 'gain=2' at 0.5
    path = tmp_path / "gain.urdf"
    path.write_text(ARM.replace('name="shoulder"', 'name="gain=2"'))
    words = []
    if command == "ik":
        words = ["--tip", "upper"] + (["--xyz", "0.5", "0", "0"] if option == "--q" else
                                      ["--target-frame", "upper"])
    result = run_cli(command, path, *words, option, "gain=2=0.5", "-f", "json")
    assert result.exit_code in (0, 1), result.output  # (collisions: 1 when a pair collides)
    assert "does not exist" not in result.output and "gain" not in result.stderr
    if key is not None:
        assert json.loads(result.stdout)[key] == {"gain=2": 0.5}


# every command with a JSON format, and the words it needs besides the file
JSON_COMMANDS = [("fk", []), ("dynamics", []), ("inertia", []), ("collisions", []),
                 ("dh", ["--tip", "a"]), ("ik", ["--tip", "a", "--xyz", "0", "0", "0"]),
                 ("workspace", ["--tip", "a"]), ("crosscheck", ["-l", "pinocchio"]),
                 ("diff", ["SAME"])]


@pytest.mark.parametrize("command, words", JSON_COMMANDS, ids=[c for c, _ in JSON_COMMANDS])
def test_a_json_command_that_cannot_compute_writes_an_error_document(run_cli, tmp_path,
                                                                     command, words):
    """With --format json an error about the robot is also a document on standard output
    (check's schema and 'error'), as ruff and mypy report an unreadable file among their JSON
    diagnostics; a script reading stdout got nothing (stderr only)."""
    path = tmp_path / "robot.urdf"
    path.write_text('<robot name="x"><link name="a">\n')
    words = [str(path) if word == "SAME" else word for word in words]
    result = run_cli(command, path, *words, "-f", "json")
    assert result.exit_code == 1, result.output
    document = json.loads(result.stdout)
    assert document["error"].startswith("malformed XML")
    assert [d["code"] for d in document["diagnostics"]] == ["U001"]
    assert document["version"] == 1 and document["summary"]["errors"] == 1


def test_an_error_that_is_no_finding_is_a_diagnostic_without_code(run_cli, tmp_path):
    path = tmp_path / "robot.urdf"
    # (a robot urdfdom refuses is refused with the linter's findings: an axis of no direction,
    # which urdfdom takes, is fk's own error)
    path.write_text('<robot name="x"><link name="a"/><link name="b"/><joint name="j" '
                    'type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 0"/>'
                    '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>')
    result = run_cli("fk", path, "-f", "json")
    assert result.exit_code == 1
    document = json.loads(result.stdout)
    [diagnostic] = document["diagnostics"]
    assert (diagnostic["code"], diagnostic["line"], diagnostic["severity"]) == \
        (None, 1, "error")
    assert document["error"] == diagnostic["message"]
    assert diagnostic["message"].startswith("joint 'j'") and "no direction" in \
        diagnostic["message"]
    text = run_cli("fk", path)  # text: stderr only, as before
    assert text.exit_code == 1 and text.stdout == ""
    path.write_text('<robot name="x"><link name="a"/></robot>')
    usage = run_cli("fk", path, "-f", "json", "--q", "nope=1")  # usage: stderr only
    assert usage.exit_code == 2 and usage.stdout == ""


@pytest.mark.parametrize("command, words", [("check", []), *JSON_COMMANDS],
                         ids=["check", *(c for c, _ in JSON_COMMANDS)])
def test_an_error_document_is_the_same_through_the_door_and_through_typer(
        run_cli, tmp_path, monkeypatch, capsys, command, words):
    """The error format is read from the command line where the error is reported
    (``error_format``), not set by each command beforehand: ``python -m urdftool`` (the door,
    ``urdftool.__main__``: check answered without Typer, the others handed to it) and the
    Typer app give the same standard output, the JSON document, for every command with a JSON
    format."""
    import urdftool.__main__ as door
    from conftest import one_piece_here

    path = tmp_path / "robot.urdf"
    path.write_text('<robot name="x"><link name="a">\n')
    words = [str(path) if word == "SAME" else word for word in words]
    words = [*words, "-f", "json", *(["--no-cache"] if command == "check" else [])]
    typer = run_cli(command, path, *words)
    assert typer.exit_code == 1, typer.output
    monkeypatch.setattr(door, "PROGRAM", {"entry": None})  # a caller's: nothing forked, ended
    # (the collector's rhythm and the kept code are the program's, not this test process's)
    monkeypatch.setattr(door, "kept_code", lambda path=None: None)
    monkeypatch.setattr(door, "_collect_less", lambda: None)
    monkeypatch.setattr(sys, "argv", ["urdftool", command, str(path), *words])
    one_piece_here(monkeypatch)
    capsys.readouterr()
    with pytest.raises(SystemExit) as ended:
        door.main()
    assert ended.value.code == 1
    assert json.loads(capsys.readouterr().out) == json.loads(typer.stdout)


def test_a_command_that_sets_nothing_reports_its_errors_in_its_format(tmp_path, capsys):
    """A command is not asked to say its format before it fails: ``fail_at`` reads it from the
    command line (before, a command that did not call ``errors_as`` wrote text only)."""
    import typer
    from typer.testing import CliRunner

    from urdftool.cli import _common

    path = tmp_path / "robot.urdf"
    path.write_text('<robot name="x"><link name="a"/></robot>\n')
    app = typer.Typer()

    @app.command()
    def new(word: str, output_format: str = typer.Option("text", "--format")) -> None:
        from urdftool.description.load import load

        _common.fail_at(load(word), ValueError("cannot compute"))

    for given, stdout in (("json", True), ("text", False)):
        result = CliRunner().invoke(app, [str(path), "--format", given])
        assert result.exit_code == 1
        assert ('"error": "cannot compute"' in result.stdout) is stdout, result.stdout


def test_a_xacro_argument_no_file_names_is_said_to_change_nothing(tmp_path, run_cli):
    """``--arg lenght=2`` for ``length``: xacro takes it without a word and the robot is
    built from the defaults; the commands said nothing of it either."""
    path = tmp_path / "arm.urdf.xacro"
    path.write_text(ARM.replace('<robot name="arm">', '<robot name="arm" xmlns:xacro='
                                '"http://www.ros.org/wiki/xacro"><xacro:arg name="length" '
                                'default="0.3"/>').replace('length="0.3"',
                                                           'length="$(arg length)"'))
    result = run_cli("fk", str(path), "--arg", "lenght=2", "length:=0.5")
    assert result.exit_code == 0, result.output
    assert "warning: xacro argument 'lenght' (lenght:=2) is named by no file of the robot " \
        "(no <xacro:arg name=\"lenght\">, no $(arg lenght)): it changes nothing; did you " \
        "mean 'length'?" in result.stderr
    assert "'length'" not in result.stderr.replace("did you mean 'length'", "")
    result = run_cli("fk", str(path), "--arg", "length=0.5")
    assert result.exit_code == 0 and "warning" not in result.stderr, result.output


def test_a_xacro_argument_for_a_urdf_is_said_to_change_nothing(arm, run_cli):
    result = run_cli("fk", str(arm), "--arg", "x=1")
    assert result.exit_code == 0, result.output
    assert "warning: xacro argument 'x' given, but " in result.stderr
    assert "is read as URDF, not expanded by xacro: it changes nothing" in result.stderr


# a slider on a planar base: limbs and chains to ask for wrongly, and a mimic loop to refuse
PLANAR_ARM = ('<robot name="p"><link name="world"/><link name="base"/><link name="upper"/>'
              '<link name="lower"/><joint name="slide" type="planar"><parent link="world"/>'
              '<child link="base"/><axis xyz="0 0 1"/></joint>'
              '<joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/>'
              '<origin xyz="0 0 0.1"/><axis xyz="0 1 0"/>'
              '<limit lower="-1" upper="1" effort="10" velocity="1"/></joint>'
              '<joint name="wrist" type="fixed"><parent link="upper"/><child link="lower"/>'
              '<origin xyz="0.3 0 0"/></joint></robot>')
IK = ["--xyz", "0.3", "0", "0"]


@pytest.mark.parametrize("words, message", [
    (["dh", "--base", "upper", "--tip", "base"], "swap --base and --tip"),
    (["dh", "--base", "upper", "--tip", "lower"], "no revolute or prismatic joint"),
    (["dh", "--tip", "upper"], "joint 'slide' is planar"),
    (["dh", "--base", "base", "--tip", "nolink"], "link 'nolink' does not exist"),
    (["ik", "--base", "upper", "--tip", "lower", *IK], "no joint moves 'lower'"),
    (["ik", "--tip", "upper", *IK], "joint 'slide' between 'world' and 'upper' is planar"),
    (["ik", "--base", "base", "--tip", "nolink", *IK], "link 'nolink' does not exist"),
    (["workspace", "--base", "lower", "--tip", "lower"], "no joint moves 'lower'"),
    (["workspace", "--tip", "lower"], "is planar"),
    (["fk", "--frame", "nolink"], "link 'nolink' does not exist"),
    (["dynamics", "--support", "nolink"], "link 'nolink' does not exist"),
    (["inertia", "--link", "nolink"], "link 'nolink' does not exist"),
    (["diff", "SAME", "--chain", "base:nolink"], "--chain: link 'nolink' does not exist"),
    (["diff", "SAME", "--chain", "lower:lower"], "names link 'lower' at both ends"),
])
@pytest.mark.parametrize("output_format", ["text", "json"])
def test_a_question_the_robot_cannot_answer_as_asked_is_a_usage_error_in_every_command(
        run_cli, tmp_path, words, message, output_format):
    """The user's mistake (a link that does not exist, a base below its tip, a limb no joint
    moves, a limb or chain through a joint the computation does not take) ends every command
    the same way: one line on standard error, nothing on standard output, exit 2
    (``UrdftoolError.asked``, read by ``fail_at`` alone). dh, ik and workspace exited 1 for
    "swap --base and --tip" and "no joint moves", 2 for a link that does not exist."""
    path = tmp_path / "robot.urdf"
    path.write_text(PLANAR_ARM)
    words = [str(path) if word == "SAME" else word for word in words]
    result = run_cli(words[0], path, *words[1:], "-f", output_format)
    assert result.exit_code == 2, result.output
    assert result.stdout == ""
    [line] = result.stderr.splitlines()
    assert line.startswith("urdftool: error: ") and message in line, line


def test_a_robot_the_command_cannot_take_is_still_the_robots_error(run_cli, tmp_path):
    """The other side of the line: what no command line can change (a mimic loop, a support
    link with no geometry to stand on) stays exit 1, at its line."""
    path = tmp_path / "robot.urdf"
    path.write_text(PLANAR_ARM.replace(
        '<limit lower="-1"', '<mimic joint="shoulder"/><limit lower="-1"'))
    result = run_cli("ik", path, "--base", "base", "--tip", "upper", *IK)
    assert result.exit_code == 1, result.output
    assert f"{path.name}:" in result.stderr and "urdftool: error" not in result.stderr
    path.write_text(PLANAR_ARM.replace('type="planar"', 'type="fixed"'))
    standing = run_cli("dynamics", path, "--support", "lower")
    assert standing.exit_code == 1, standing.output
    assert "has no collision or visual geometry" in standing.stderr


# a chain of three joints reaching 2e7 m out and back: its --textbook form is its table with the
# sign of two link lengths moved into theta, equal to it up to the rounding at 2e7 m
FAR_CHAIN = ('<robot name="far"><link name="b"/><link name="l1"/><link name="l2"/>'
             '<link name="l3"/>' + "".join(
                 f'<joint name="j{i}" type="revolute"><parent link="{parent}"/>'
                 f'<child link="l{i}"/><origin xyz="{x} 0 0"/><axis xyz="0 0 1"/>'
                 '<limit lower="-3" upper="3" effort="1" velocity="1"/></joint>'
                 for i, parent, x in ((1, "b", 0), (2, "l1", -1e7), (3, "l2", -1e7)))
             + '</robot>')


def _refused_by_design(case: str, tmp_path, monkeypatch) -> str:
    """The robot of a refusal by design, and what makes the command refuse it."""
    if case == "too big":  # Pinocchio's data of 300 joints (~1.7 GB) in 1 GiB
        import resource

        from conftest import synthetic_robot

        limit = resource.getrlimit
        monkeypatch.setattr(resource, "getrlimit", lambda kind: (
            1024 ** 3, resource.RLIM_INFINITY) if kind == resource.RLIMIT_AS else limit(kind))
        return str(synthetic_robot(tmp_path, 301))
    path = tmp_path / "far.urdf"
    path.write_text(FAR_CHAIN)
    if case == "no textbook form":  # (the textbook form always reproduces the table: made
        # not to, so that the refusal is seen)
        from urdftool.kinematics import dh

        monkeypatch.setattr(dh, "_reach_tolerance", lambda table: -1.0)
    else:  # "no Graphviz"
        monkeypatch.setenv("PATH", str(tmp_path / "empty"))
    return str(path)


@pytest.mark.parametrize("case, words, message", [
    ("too big", ["ik", "--tip", "l300", *IK], "300 joint variables from 'l0' to 'l300'"),
    ("too big", ["workspace", "--tip", "l300"], "300 joint variables from 'l0' to 'l300'"),
    ("too big", ["dynamics"], "300 joint variables"),
    ("too big", ["dynamics", "--support", "l300"], "300 joint variables"),
    ("no textbook form", ["dh", "--tip", "l3", "--textbook"],
     "the textbook form of the table does not reproduce it ("),
    ("no Graphviz", ["graph", "-o", "OUT.svg"], "'dot' program is not installed"),
])
def test_a_request_the_command_refuses_by_design_exits_2_in_every_command(
        run_cli, tmp_path, monkeypatch, case, words, message):
    """What a command refuses to compute by its own design, before or instead of an answer
    (a limb or robot whose Pinocchio data cannot fit the memory allowed, as the size limits
    --max-matrix-rows and --max-scene-triangles refuse; a --textbook form it cannot vouch for,
    as an axis with no D-H form; Graphviz missing, as an analysis extra missing) is no answer
    about the robot: exit 2, said on standard error only, as every usage error. ik, workspace
    and dynamics exited 1 for the data, dh for the textbook form, graph without Graphviz; a
    computed negative answer (ik not solving, dynamics' margins, fk --verify) stays 1."""
    path = _refused_by_design(case, tmp_path, monkeypatch)
    words = [str(tmp_path / "tree.svg") if word == "OUT.svg" else word for word in words]
    result = run_cli(words[0], path, *words[1:])
    assert result.exit_code == 2, result.output
    assert result.stdout == ""
    assert message in result.stderr, result.stderr


def test_a_textbook_form_far_out_is_vouched_for_at_its_reach(run_cli, tmp_path):
    """The textbook form's check held the table to the rounding at its base and tool only: a
    chain reaching 2e7 m out and back (within numbers.MAX_COORDINATE), whose own table dh gives,
    was refused by --textbook for a difference of 3.7e-9 m, the rounding at 2e7 m."""
    path = tmp_path / "far.urdf"
    path.write_text(FAR_CHAIN)
    result = run_cli("dh", path, "--tip", "l3", "--textbook", "-f", "json")
    assert result.exit_code == 0, result.output
    assert [row["a"] for row in json.loads(result.stdout)["joints"]] == [1e7, 1e7, 0.0]


def test_a_d_h_table_that_does_not_fit_is_a_usage_error_named_by_its_file(run_cli, tmp_path):
    """A D-H table given to ``fk --dh`` is the user's input, as a --q-file: unreadable, or
    naming a joint the robot lacks, exit 2 with the file named (it was exit 1, as if the
    robot were wrong)."""
    path = tmp_path / "robot.urdf"
    path.write_text(PLANAR_ARM)
    table = tmp_path / "table.yaml"
    for text, message in (
            ("joints: [{joint: nope, theta: 0, d: 0, a: 0, alpha: 0}]",
             f"{table}: D-H table joint 'nope' is not a joint of the robot"),
            ("joints: [{joint: shoulder, theta: 0 d: 0}", f"{table}:1: invalid JSON/YAML")):
        table.write_text(text)
        result = run_cli("fk", path, "--dh", table, "--base", "base", "--frame", "upper")
        assert result.exit_code == 2, result.output
        assert result.stderr.splitlines() == [f"urdftool: error: {message}"] or \
            result.stderr.startswith(f"urdftool: error: {message}"), result.stderr


@pytest.mark.parametrize("command", ["tree", "fk", "inertia", "dynamics", "collisions"])
def test_an_only_link_without_a_name_is_the_link_urdfdom_takes(tmp_path, run_cli, command):
    """check_urdf takes ``<link/>`` alone as a link named '' (U103 Taken: no refusal of
    urdfdom), and so does Pinocchio; every command poses it as ``name=""`` is posed. They
    refused it before ("urdftool's model names every link"). urdfdom's parseLink stops at the
    missing name: what the link holds is in no model of urdfdom or Pinocchio (mass 0 where
    ``name=""`` keeps 1 kg), and the commands say so."""
    path = tmp_path / "r.urdf"
    for link in ("<link/>", '<link name=""/>', f"<link>{_INERTIAL}</link>"):
        path.write_text(f'<robot name="r">\n{link}</robot>')
        result = run_cli(command, "--timeout", "0", "--max-memory", "0", path)
        assert result.exit_code == 0, result.output
        said = f"{path}:2: <link> has no name attribute: urdfdom reads it as the link ''"
        assert (said in result.stderr) == (_INERTIAL in link), result.stderr


_INERTIAL = ('<inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" '
             'iyz="0"/></inertial>')


def test_an_only_link_without_a_name_has_pinocchios_mass(tmp_path, run_cli):
    """dynamics' total mass of a lone link is Pinocchio's: 0 without a name (urdfdom read
    nothing in it), 1 kg with one."""
    import pinocchio

    path = tmp_path / "r.urdf"
    for attribute in ("", ' name="a"'):
        path.write_text(f'<robot name="r"><link{attribute}>{_INERTIAL}</link></robot>')
        model = pinocchio.buildModelFromUrdf(str(path))
        mass = sum(inertia.mass for inertia in model.inertias)
        result = run_cli("dynamics", "--timeout", "0", "--max-memory", "0", path, "-f", "json")
        assert json.loads(result.stdout)["total_mass"] == pytest.approx(mass)
        assert mass == (1.0 if attribute else 0.0)




def _beside_the_tree() -> str:
    """``r -> x`` and a loop ``a <-> b`` no joint from the root reaches, every link with a
    mass and a box."""
    def link(name, mass):
        return (f'<link name="{name}"><inertial><mass value="{mass}"/><inertia ixx="1" iyy="1" '
                'izz="1" ixy="0" ixz="0" iyz="0"/></inertial><collision><geometry><box '
                'size="0.1 0.1 0.1"/></geometry></collision><visual><geometry><box '
                'size="0.1 0.1 0.1"/></geometry></visual></link>')

    def joint(name, parent, child, kind="fixed"):
        return (f'<joint name="{name}" type="{kind}"><parent link="{parent}"/><child '
                f'link="{child}"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" '
                'velocity="1"/></joint>')

    return ('<robot name="r">' + link("r", 1) + link("x", 2) + link("a", 3) + link("b", 4)
            + joint("j0", "r", "x", "revolute") + joint("j1", "a", "b") + joint("j2", "b", "a")
            + "</robot>")


@pytest.mark.parametrize("command", ["tree", "fk", "inertia", "dynamics", "collisions",
                                     "render"])
def test_the_links_beside_the_tree_are_left_out_by_every_command(tmp_path, run_cli, command):
    """A loop beside the tree (U109 Taken: check_urdf drops its links): every command works
    on the links urdfdom's tree holds and names the ones left out. inertia listed the loop's
    links, render died in trimesh's scene graph ("Iteration limit exceeded!"), collisions in a
    KeyError, where fk, tree and dynamics (Pinocchio) left them out."""
    path = tmp_path / "r.urdf"
    path.write_text(_beside_the_tree())
    extra = {"render": ("-o", str(tmp_path / "r.png")), "inertia": ("-f", "json"),
             "fk": ("-f", "json")}.get(command, ())
    result = run_cli(command, "--timeout", "0", "--max-memory", "0", path, *extra)
    assert result.exit_code in ((0, 1) if command == "inertia" else (0,)), result.output
    assert "2 links beside the tree" in result.stderr and "'a', 'b'" in result.stderr
    if command == "inertia":
        assert [row["link"] for row in json.loads(result.stdout)["links"]] == ["r", "x"]
        assert run_cli(command, "--timeout", "0", "--max-memory", "0", path,
                       "--link", "a").exit_code == 2  # as fk --frame a
    if command == "fk":
        assert [row["frame"] for row in json.loads(result.stdout)["frames"]] == ["r", "x"]


def test_dynamics_beside_the_tree_has_pinocchios_mass(tmp_path, run_cli):
    import pinocchio

    path = tmp_path / "r.urdf"
    path.write_text(_beside_the_tree())
    model = pinocchio.buildModelFromUrdf(str(path))
    result = run_cli("dynamics", "--timeout", "0", "--max-memory", "0", path, "-f", "json")
    assert json.loads(result.stdout)["total_mass"] == pytest.approx(
        sum(inertia.mass for inertia in model.inertias)) == pytest.approx(3.0)


@pytest.mark.parametrize("words", [
    ["fk", "--frame", "a"], ["dh", "--base", "a", "--tip", "b"], ["dh", "--tip", "a"],
    ["ik", "--tip", "a", "--xyz", "0", "0", "0"], ["workspace", "--tip", "a"],
    ["dynamics", "--support", "a"], ["inertia", "--link", "a"],
    ["diff", "SAME", "--chain", "r:a"]])
def test_a_link_beside_the_tree_named_by_an_option_is_said_so(tmp_path, run_cli, words):
    """An option naming a link beside the tree: every command refuses it as the link no model
    has (exit 2), saying why. dynamics --support died in an IndexError, dh made a chain of
    links no model poses, inertia compared it, fk, ik and workspace said it did not exist."""
    path = tmp_path / "r.urdf"
    path.write_text(_beside_the_tree())
    command, *rest = words
    result = run_cli(command, "--timeout", "0", "--max-memory", "0", path,
                     *[str(path) if word == "SAME" else word for word in rest])
    assert result.exit_code == 2, result.output
    assert "link 'a' is beside the tree (no joint from the root reaches it" in result.stderr
