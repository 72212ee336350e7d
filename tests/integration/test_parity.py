"""Parity with urdfdom's check_urdf (shipped in the pin wheel), both ways: check_urdf refuses a
file exactly when urdftool reports one of the errors urdfdom refuses for (URDFDOM), located;
`urdftool tree` prints what check_urdf prints."""

from __future__ import annotations

import pytest

from conftest import CASES, CHECK_URDF, CORPUS, check_urdf, corpus_entry_points
from conftest import CASE_PATHS, CHECK_URDF_TIMEOUT, case_result, case_robot
from urdftool.lint.engine import URDFDOM_REFUSES

pytestmark = pytest.mark.skipif(CHECK_URDF is None, reason="urdfdom's check_urdf is not installed (the pin wheel of the analysis extra has it)")

# The errors for what urdfdom refuses too (the linter owns the set; `urdftool tree` fails on
# them): the file does not parse, is not a <robot> of a version it reads, or its tree, joint
# types, limits or joint numbers are broken. urdftool's other errors (inertia, geometry,
# materials, spec, ...) are on files check_urdf accepts: urdftool is stricter there, so they
# must not be in this set.
URDFDOM = URDFDOM_REFUSES
# U007 (a .urdf holding xacro) is on files check_urdf accepts (robotis_op: leftover
# <xacro:grey/> elements) and on files it refuses (sam_bot: ${...} in numbers), so it
# counts for a refusal but is not a refusal code itself.
XACRO_IN_URDF = "U007"
# A part of a robot defined elsewhere, checked alone (U105 as a note: no root link of its own,
# its joints hang on the includer's links; U106 as a note: no link of its own, only <gazebo>
# blocks and the like) is refused by check_urdf alone, as the note says; its consumers read it
# inside the robot that includes it (docs/certainty.md, urdftool/lint/parts.py). A clash of
# names that only xacro arguments left at their empty defaults make (U101-U107 as a warning
# naming them) is refused by check_urdf given xacro's default build, as the warning says.


def assert_parity(name: str, reference, result) -> None:
    errors = [f for f in result.findings if f.severity.value == "error"]
    codes = {f.code for f in errors}
    # (a finding its rule says urdfdom takes is none of its refusals: engine.urdfdom_refusals)
    refused = {f.code for f in errors if not f.urdfdom_takes} & URDFDOM
    said = reference.stdout + reference.stderr
    parts = [f for f in result.findings if f.code in URDFDOM and f.severity.value != "error"]
    if reference.returncode != 0:
        assert refused or XACRO_IN_URDF in codes or parts, \
            f"check_urdf refuses {name} but urdftool reports none of {sorted(URDFDOM)} " \
            f"(it reports {sorted(codes)}):\n{said}"
        assert any(f.line is not None for f in errors + parts), "urdftool's errors are not located"
    else:
        assert not refused, f"check_urdf accepts {name} but urdftool refuses it " \
            f"({[f'{f.location} {f.code} {f.message}' for f in errors if f.code in refused]})"


def test_the_urdfdom_codes_are_the_case_files_check_urdf_refuses():
    """URDFDOM is exactly the codes whose case files check_urdf refuses: it holds no code urdfdom
    lets through, and a new rule whose case check_urdf refuses must join it."""
    refused = {case.name[:4] for case in CASE_PATHS if not case_robot(case).name.endswith(".xacro")
               and check_urdf(case_robot(case)).returncode != 0}
    assert refused == URDFDOM, f"refused but not listed: {sorted(refused - URDFDOM)}; listed " \
        f"but accepted: {sorted(URDFDOM - refused)}"


def test_parity_fails_either_way():
    """assert_parity fails when urdftool misses a refusal and when it invents one."""
    from subprocess import CompletedProcess
    from types import SimpleNamespace

    from urdftool.diagnostics import Finding, Location, Severity

    def result(code):
        return SimpleNamespace(findings=[Finding(code, "name", Severity.ERROR, "message",
                                                 Location("r.urdf", 3))])

    refuses, accepts = CompletedProcess([], 255, "", "Error: ..."), CompletedProcess([], 0, "", "")
    with pytest.raises(AssertionError, match="reports none of"):
        assert_parity("r.urdf", refuses, result("U301"))  # stricter code, not a refusal
    with pytest.raises(AssertionError, match="refuses it"):
        assert_parity("r.urdf", accepts, result("U101"))
    assert_parity("r.urdf", refuses, result("U101"))
    assert_parity("r.urdf", accepts, result("U301"))


def _link(*names: str) -> str:
    return "".join(f'<link name="{name}"/>' for name in names)


def _joint(name: str, parent: str, child: str, mimic: str | None = None) -> str:
    """A fixed joint; a revolute one when ``mimic`` is given (mimicking that joint, or nothing
    when it is empty)."""
    ends = f'<parent link="{parent}"/><child link="{child}"/>'
    if mimic is None:
        return f'<joint name="{name}" type="fixed">{ends}</joint>'
    return (f'<joint name="{name}" type="revolute">{ends}'
            '<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/>'
            + (f'<mimic joint="{mimic}"/>' if mimic else "") + "</joint>")


def _loop_below(size: int) -> str:
    """``r -> l0 -> ... -> l{size-1} -> l0``: a loop of ``size`` links under the root."""
    links = [f"l{i}" for i in range(size)]
    return _link("r", *links) + _joint("j0", "r", "l0") + "".join(
        _joint(f"j{i + 1}", links[i], links[(i + 1) % size]) for i in range(size))


def _material(name: str | None) -> str:
    """A top-level red material named ``name`` (None: without the attribute)."""
    named = "" if name is None else f' name="{name}"'
    return f'<material{named}><color rgba="1 0 0 1"/></material>'


# Shapes of tree that urdfdom handles badly or differently, each with what check_urdf does on it
# (run under a timeout: "hangs" is its outcome, not a failure of the test) and urdftool's errors,
# judged. AGREES: urdftool refuses (with a code of URDFDOM) exactly where check_urdf refuses or
# hangs. STRICTER: check_urdf accepts and urdftool refuses; the reason, measured, is written.
# The last item is what `tree` and `fk` do with it (POSES: exit 0, tree printing what
# check_urdf prints; REFUSES: exit 1 at the errors' lines): they refuse a shape urdfdom takes
# only where no model poses it as written (fk: a link with two parents, U107, which Pinocchio
# hangs under one parent or refuses, by the joints' names; mimic loops, which no value
# satisfies and Pinocchio's mimic model refuses: measured by the two tests after the table),
# never as urdfdom's refusal.
AGREES = "agrees"
POSES, REFUSES = "poses", "refuses"
SHAPES = {
    # a loop below the root: urdfdom's initRoot finds the root, its tree walk then loops
    "self-joint below the root": (_loop_below(1), "hangs", {"U107", "U109", "U110"}, AGREES,
                                  (REFUSES, REFUSES)),
    "loop of 2 below the root": (_loop_below(2), "hangs", {"U107", "U109"}, AGREES,
                                 (REFUSES, REFUSES)),
    "loop of 3 below the root": (_loop_below(3), "hangs", {"U107", "U109"}, AGREES,
                                 (REFUSES, REFUSES)),
    "loop of 8 below the root": (_loop_below(8), "hangs", {"U107", "U109"}, AGREES,
                                 (REFUSES, REFUSES)),
    "loop below a branch": (_link("r", "a", "b", "c", "d") + _joint("j0", "r", "a")
                            + _joint("j1", "a", "b") + _joint("jd", "a", "d")
                            + _joint("j2", "b", "c") + _joint("j3", "c", "b"),
                            "hangs", {"U107", "U109"}, AGREES, (REFUSES, REFUSES)),
    # a loop through every link, or through the root: no link without a parent
    "self-joint on the only link": (_link("r") + _joint("j", "r", "r"), "refuses",
                                    {"U109", "U110"}, AGREES, (REFUSES, REFUSES)),
    "a joint whose parent is its own child": (_link("r", "a") + _joint("j0", "r", "a")
                                              + _joint("j1", "a", "r"), "refuses", {"U109"},
                                              AGREES, (REFUSES, REFUSES)),
    "loop of 3 through the root": (_link("r", "a", "b") + _joint("j0", "r", "a")
                                   + _joint("j1", "a", "b") + _joint("j2", "b", "r"),
                                   "refuses", {"U109"}, AGREES, (REFUSES, REFUSES)),
    "duplicate joint name on a loop": (_link("r", "a", "b") + _joint("j", "r", "a")
                                       + _joint("j", "a", "b") + _joint("j2", "b", "a"),
                                       "refuses", {"U102", "U107", "U109"}, AGREES,
                                       (REFUSES, REFUSES)),
    "duplicate joint name": (_link("r", "a", "b") + _joint("j", "r", "a") + _joint("j", "r", "b"),
                             "refuses", {"U102"}, AGREES, (REFUSES, REFUSES)),
    # names: urdfdom refuses a joint without a name attribute, takes a joint's name=""; it reads
    # a link without one as a link named '', which no joint can attach to (link="" is "missing
    # a parent and/or child link specification"), so a second root beside any other link
    "empty child link name": (_link("r", "") + _joint("j", "r", ""), "refuses",
                              {"U103", "U104"}, AGREES, (REFUSES, REFUSES)),
    "link without a name as a joint's child": (
        _link("r") + "<link/>" + _joint("j", "r", ""), "refuses", {"U103", "U104"}, AGREES,
        (REFUSES, REFUSES)),
    "empty link name as the root": (_link("", "a") + _joint("j", "", "a"), "refuses",
                                    {"U103", "U104"}, AGREES, (REFUSES, REFUSES)),
    "empty link name beside a link": (_link("r", ""), "refuses", {"U103", "U108"}, AGREES,
                                      (REFUSES, REFUSES)),
    "link without a name beside a link": (_link("r") + "<link/>", "refuses", {"U103"}, AGREES,
                                          (REFUSES, REFUSES)),
    "two links named empty": (_link("", ""), "refuses", {"U101", "U103"}, AGREES,
                              (REFUSES, REFUSES)),
    "joint without a name": (_link("r", "a") + '<joint type="fixed"><parent link="r"/>'
                             '<child link="a"/></joint>', "refuses", {"U103"}, AGREES,
                             (REFUSES, REFUSES)),
    "two joints named empty": (_link("r", "a", "b") + _joint("", "r", "a") + _joint("", "r", "b"),
                               "refuses", {"U102", "U103"}, AGREES, (REFUSES, REFUSES)),
    "a joint named empty and one without a name": (
        _link("r", "a", "b") + _joint("", "r", "a") + '<joint type="fixed"><parent link="r"/>'
        '<child link="b"/></joint>', "refuses", {"U103"}, AGREES, (REFUSES, REFUSES)),
    # check_urdf accepts
    "loop beside the tree": (_link("r", "x", "a", "b") + _joint("j0", "r", "x")
                             + _joint("j1", "a", "b") + _joint("j2", "b", "a"), "accepts",
                             {"U109"}, "stricter: urdfdom builds the tree from the root and drops "
                             "links a and b silently (its listing shows r -> x only); any "
                             "consumer of the tree loses them", (POSES, POSES)),
    "a link with two parents, no loop": (_link("r", "a", "b") + _joint("j0", "r", "a")
                                         + _joint("j1", "r", "b") + _joint("j2", "a", "b"),
                                         "accepts", {"U107"}, "stricter, and not a URDFDOM "
                                         "code: urdfdom lists b twice (under r and under a), "
                                         "its parent joint the one whose name sorts last; "
                                         "fk refuses it: b has two poses, and Pinocchio poses "
                                         "it under that joint or refuses the robot, by the "
                                         "joints' names (test_fk_refuses_what_pinocchio_"
                                         "poses_by_name_or_not_at_all)", (POSES, REFUSES)),
    "empty joint name": (_link("r", "a") + _joint("", "r", "a"), "accepts", {"U103"},
                         "stricter: urdfdom refuses a joint without a name attribute but "
                         "takes name=\"\"; a joint no /joint_states, controller or "
                         "transmission can name", (POSES, POSES)),
    "empty robot name": ('<robot name=""><link name="r"/></robot>', "accepts", {"U011"},
                         "stricter: urdfdom refuses a robot without a name attribute but takes "
                         "name=\"\" (check_urdf prints 'robot name is: '); the name is what "
                         "an SRDF and a simulator's model are matched by", (POSES, POSES)),
    "empty link name, the only link": ('<link name=""/>', "accepts", {"U103"},
                                       "stricter: urdfdom takes name=\"\" (its root is "
                                       "''); no joint can attach to it", (POSES, POSES)),
    "link without a name, the only link": ("<link/>", "accepts", {"U103"},
                                           "stricter: urdfdom logs 'No name given for the "
                                           "link.' and takes it as a link named '' (read no "
                                           "further: what it holds is dropped); no joint can "
                                           "attach to it", (POSES, POSES)),
    "link without a name holding an inertial, the only link": (
        '<link><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" '
        'iyz="0"/></inertial></link>', "accepts", {"U103"}, "stricter (as above)",
        (POSES, POSES)),
    "mimic joints that mimic each other": (_link("r", "a", "b") + _joint("ja", "r", "a", "jb")
                                           + _joint("jb", "r", "b", "ja"), "accepts",
                                           {"U211"}, "stricter, and not a URDFDOM code: "
                                           "urdfdom does not read <mimic> against the joints; "
                                           "fk refuses it: no value satisfies a loop of mimics, "
                                           "and Pinocchio's model with its mimic joints "
                                           "refuses it ('The parent joint of the mimic joint "
                                           "is not in the kinematic tree')",
                                           (POSES, REFUSES)),
    "mimic loop of 3": (_link("r", "a", "b", "c") + _joint("ja", "r", "a", "jc")
                        + _joint("jb", "r", "b", "ja") + _joint("jc", "r", "c", "jb"),
                        "accepts", {"U211"}, "stricter, and not a URDFDOM code (as above)",
                        (POSES, REFUSES)),
    "a joint mimicking itself": (_link("r", "a") + _joint("ja", "r", "a", "ja"), "accepts",
                                 {"U210"}, "stricter, and not a URDFDOM code (as above)",
                                 (POSES, REFUSES)),
    "a mimic chain without a loop": (_link("r", "a", "b", "c") + _joint("ja", "r", "a", "")
                                     + _joint("jb", "r", "b", "ja") + _joint("jc", "r", "c", "jb"),
                                     "accepts", set(), AGREES, (POSES, POSES)),
    # materials (U405): urdfdom refuses a top-level name given twice ("material 'm' is not
    # unique"), a missing name counting as '', and logs the rest
    "two top-level materials named alike": (_material("m") * 2 + _link("r"), "refuses",
                                            {"U405"}, AGREES, (REFUSES, REFUSES)),
    "two top-level materials without a name": (_material(None) * 2 + _link("r"), "refuses",
                                               {"U405"}, AGREES, (REFUSES, REFUSES)),
    "a top-level material without a name": (_material(None) + _link("r"), "accepts", {"U405"},
                                            "stricter: urdfdom logs 'Material must contain a "
                                            "name attribute' and keeps it as ''; no visual can "
                                            "name it", (POSES, POSES)),
    "a top-level material without a colour": ('<material name="m"/>' + _link("r"), "accepts",
                                              {"U405"}, "stricter: urdfdom logs 'Material [m] "
                                              "color has no rgba'; a visual naming it has no "
                                              "colour", (POSES, POSES)),
    "a visual's material without a name": (
        '<link name="r"><visual><geometry><box size="1 1 1"/></geometry><material><color '
        'rgba="1 0 0 1"/></material></visual><collision><geometry><box size="1 1 1"/>'
        "</geometry></collision></link>", "accepts", {"U405"}, "stricter: urdfdom stops "
        "reading the link there ('Could not parse visual element', parseLink's failure "
        "unread): the link has no visual and no collision (Pinocchio's geometry models of it "
        "are empty)", (POSES, POSES)),
}


_MIMIC_LOOPS = ("mimic joints that mimic each other", "mimic loop of 3", "a joint mimicking itself")


@pytest.mark.parametrize("shape", _MIMIC_LOOPS)
def test_pinocchio_refuses_the_mimic_loops_fk_refuses(shape, tmp_path):
    """The mimic shapes urdfdom takes and fk refuses (U210, U211): Pinocchio's model read
    with its mimic joints refuses each too (read without them, its frames ignore what the
    URDF says of those joints: no pose of the robot as written)."""
    pinocchio = pytest.importorskip("pinocchio")
    path = tmp_path / "shape.urdf"
    path.write_text(f'<robot name="r">{SHAPES[shape][0]}</robot>')
    with pytest.raises(ValueError, match="mimic joint is not in the kinematic tree"):
        pinocchio.buildModelFromUrdf(str(path), mimic=True)


def test_fk_refuses_what_pinocchio_poses_by_name_or_not_at_all(tmp_path):
    """A link with two parent joints (U107; urdfdom takes it): Pinocchio hangs it under the
    joint whose name sorts last (b 1 m out under r, or under a 5 m up) or refuses the robot
    ("Model does not have any body named a"), by the joints' names alone: no pose of it to
    give, so fk refuses it."""
    pinocchio = pytest.importorskip("pinocchio")

    def joint(name, parent, child, xyz):
        return (f'<joint name="{name}" type="fixed"><origin xyz="{xyz}"/><parent '
                f'link="{parent}"/><child link="{child}"/></joint>')

    placed = {}
    for names in (("j1", "j2"), ("z1", "a2"), ("a1", "z2")):
        text = (f'<robot name="r">{_link("r", "a", "b")}{joint("j0", "r", "a", "0 0 5")}'
                f'{joint(names[0], "r", "b", "1 0 0")}{joint(names[1], "a", "b", "0 0 0")}'
                "</robot>")
        try:
            model = pinocchio.buildModelFromXML(text)
        except ValueError as error:
            placed[names] = str(error)
            continue
        data = model.createData()
        pinocchio.framesForwardKinematics(model, data, pinocchio.neutral(model))
        placed[names] = data.oMf[model.getFrameId("b")].translation.tolist()
    assert placed[("j1", "j2")] == [0, 0, 5] and placed[("z1", "a2")] == [1, 0, 0]
    assert "does not have any body named a" in placed[("a1", "z2")]


def outcome(verdict) -> str:
    """What check_urdf did: "hangs" (stopped after its timeout), "crashes" (killed by a
    signal), "accepts" or "refuses"."""
    if verdict.returncode == -9 and "did not finish in" in verdict.stderr:
        return "hangs"
    if verdict.returncode < 0:
        return "crashes"
    return "accepts" if verdict.returncode == 0 and "Successfully Parsed XML" in verdict.stdout \
        else "refuses"


@pytest.mark.parametrize("shape", sorted(SHAPES))
def test_parity_on_shapes_check_urdf_handles_badly(shape, tmp_path, run_cli):
    """Each shape's check_urdf outcome as recorded, urdftool's errors as recorded, and parity
    wherever the row says they agree; where urdftool is stricter, check_urdf accepts (a hang or
    a refusal would be agreement) and the row says why. A hang costs its timeout, a core spun
    for all of it: 0.5 s for a shape recorded as hanging (it never returns: 2 s proved no more,
    and the five cost 10 s of CPU), the usual 20 s for the others, so that a slow start on a
    busy machine is never taken for a hang (a healthy run of these files takes 10 ms). Then
    what `tree` and `fk` do with it, as the row says; `tree` prints what check_urdf prints
    where it poses it."""
    from urdftool.lint.engine import CheckOptions, load_and_check

    body, expected, codes, judged, (tree, fk) = SHAPES[shape]
    path = tmp_path / "shape.urdf"
    path.write_text(body if body.startswith("<robot") else f'<robot name="r">{body}</robot>')
    verdict = check_urdf(path, timeout=0.5 if expected == "hangs" else CHECK_URDF_TIMEOUT)
    assert outcome(verdict) == expected, verdict.stdout + verdict.stderr
    result = load_and_check(str(path), CheckOptions())
    assert {f.code for f in result.findings if f.severity.value == "error"} == codes
    if judged == AGREES:
        assert_parity(shape, verdict, result)
    else:
        assert expected == "accepts" and judged.startswith("stricter") and codes
    for command, does in (("tree", tree), ("fk", fk)):
        ran = run_cli(command, *IN_PROCESS, path)
        assert ran.exit_code == (0 if does == POSES else 1), (command, ran.output)
        if does == REFUSES and expected != "accepts":  # urdfdom's refusal, at its lines
            assert f"{path.name}:1: error U" in ran.stderr, (command, ran.output)
    if tree == POSES:
        assert run_cli("tree", *IN_PROCESS, path).stdout == verdict.stdout


def test_outcome_tells_a_hang_from_a_crash_from_a_refusal():
    from subprocess import CompletedProcess

    assert outcome(CompletedProcess([], -9, "", "check_urdf did not finish in 2 s")) == "hangs"
    assert outcome(CompletedProcess([], -11, "", "")) == "crashes"
    assert outcome(CompletedProcess([], 255, "", "Error: ...")) == "refuses"
    assert outcome(CompletedProcess([], 0, "---------- Successfully Parsed XML", "")) == \
        "accepts"


@pytest.mark.parametrize("case", CASE_PATHS, ids=[p.name for p in CASE_PATHS])
def test_parity_on_case_files(case, tmp_path):
    """check_urdf reads the file itself, or urdftool's expansion of a xacro."""
    robot_file = case_robot(case)
    result = case_result(case)
    urdf = robot_file
    if robot_file.name.endswith(".xacro"):
        if result.robot is None:
            pytest.skip("xacro does not expand; urdftool reports that itself")
        urdf = tmp_path / "expanded.urdf"
        urdf.write_text(result.robot.urdf)
    assert_parity(case.name, check_urdf(urdf), result)


CORPUS_URDFS = [path for path, args in corpus_entry_points()
                if not path.endswith(".xacro") and not args]


@pytest.mark.parametrize("relative", CORPUS_URDFS)
def test_parity_on_corpus_urdfs(relative, corpus_run):
    _, result = corpus_run[relative]
    assert_parity(relative, check_urdf(CORPUS / relative), result)


# no budget: `tree` in this process, not in a worker forked for each file (a fork of the test
# process costs more than the tree; tests/cli runs tree under its budget)
IN_PROCESS = ("--timeout", "0", "--max-memory", "0")


@pytest.mark.parametrize("relative", CORPUS_URDFS)
def test_tree_matches_check_urdf_on_corpus_urdfs(relative, run_cli, corpus_run):
    assert_tree_matches(CORPUS / relative, run_cli, lambda: corpus_run[relative][1].robot)


@pytest.mark.parametrize("path", sorted(CASES.glob("U*.urdf")), ids=lambda p: p.name)
def test_tree_matches_check_urdf_on_case_files(path, run_cli):
    assert_tree_matches(path, run_cli, lambda: case_result(path).robot)


def assert_tree_matches(path, run_cli, robot) -> None:
    """`urdftool tree` prints what check_urdf prints, and fails, located, where it fails;
    ``robot()``: urdftool's loaded robot of ``path`` (None where it refuses to load it)."""
    reference = check_urdf(path)
    if reference.returncode != 0:
        result = run_cli("tree", *IN_PROCESS, path)
        assert result.exit_code == 1 and "Successfully Parsed XML" not in result.stdout
        assert f"{path.name}:" in result.stderr and " error U" in result.stderr, result.output
        assert "--fix" not in result.stderr.replace("urdftool check --fix", ""), result.output
        return
    if robot() is None:
        pytest.skip("urdftool refuses to load it (e.g. entity declarations, U009)")
    result = run_cli("tree", *IN_PROCESS, path)
    assert result.exit_code == 0, result.output
    assert result.stdout == reference.stdout
