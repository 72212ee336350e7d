"""Parity with urdfdom's check_urdf (shipped in the pin wheel), both ways: check_urdf refuses a
file exactly when urdftool reports one of the errors urdfdom refuses for (URDFDOM), located;
`urdftool tree` prints what check_urdf prints."""

from __future__ import annotations

import pytest

from conftest import CASES, CHECK_URDF, CORPUS, check_urdf, corpus_entry_points
from conftest import CASE_PATHS, case_result, case_robot
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
    refused = codes & URDFDOM
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


def test_a_check_urdf_that_never_returns_is_a_refusal(tmp_path):
    """urdfdom loops on a cycle below the root (``b -> c -> b`` under ``r -> b``): check_urdf
    never returns. Stopped after its timeout it refuses; a test that ran it on such a file
    waited for ever."""
    path = tmp_path / "cycle.urdf"
    path.write_text('<robot name="r"><link name="r"/><link name="b"/><link name="c"/>'
                    '<joint name="j0" type="fixed"><parent link="r"/><child link="b"/></joint>'
                    '<joint name="j1" type="fixed"><parent link="b"/><child link="c"/></joint>'
                    '<joint name="j2" type="fixed"><parent link="c"/><child link="b"/></joint>'
                    '</robot>')
    verdict = check_urdf(path, timeout=2.0)
    assert verdict.returncode != 0 and "did not finish in 2 s" in verdict.stderr


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
