"""The engine: selection, stamping, and a crashing rule or loader as U900, never a traceback."""

from __future__ import annotations

import re

import pytest

from conftest import CASES
from urdftool.description.load import load
from urdftool.errors import LoadError
from urdftool.lint import engine
from urdftool.lint.engine import (LOAD_CODES, NOTE_CODES, CheckOptions, Selection, load_and_check,
                                  load_error_findings)
from urdftool.lint.catalogue import Catalogue, Rule, Severity
from urdftool.lint.rules import CATALOGUE

ROBOT = CASES / "U204_inverted_limits.urdf"


def test_a_crashing_rule_is_u900_and_the_other_rules_still_run(monkeypatch):
    def broken(robot):
        yield robot.root, "about to fail"
        raise ZeroDivisionError("boom")

    original = CATALOGUE.get("U204")
    crashing = Rule("U204", original.name, original.severity, broken, original.doc)
    monkeypatch.setattr(engine, "CATALOGUE", Catalogue(
        [crashing if r.code == "U204" else r for r in CATALOGUE.rules]))
    findings = load_and_check(str(ROBOT), CheckOptions()).findings
    crash = [f for f in findings if f.code == "U900"]
    assert len(crash) == 1
    assert "rule U204 (inverted-limits) crashed: ZeroDivisionError: boom" in crash[0].message
    assert crash[0].file.endswith("U204_inverted_limits.urdf")
    assert any(f.code == "U204" and f.message == "about to fail" for f in findings)


def test_a_rules_findings_stamped_together_are_those_stamped_one_by_one(tmp_path):
    from urdftool.diagnostics import Edit, Fix, Location
    from urdftool.lint.catalogue import Conditional

    (tmp_path / "r.urdf").write_text('<robot name="r">\n<link name="a">\n  <visual/></link>\n'
                                     '<!-- c --><link name="b"/>\n</robot>\n')
    robot = load(tmp_path / "r.urdf")
    a, b = robot.root.findall("link")
    elsewhere = Location("other.urdf", 7, column=2)
    fix = Fix("f", (Edit("r.urdf", 0, 1, "x", "<", 1, 0),))
    yielded = [(a, "plain", []), (a[0], "a visual", []), (None, "the file", []),
               (elsewhere, "in another file", []), (b, "with a fix", [fix]),
               (b, "lowered", [None, Severity.WARNING]), (a, Conditional("conditional"), []),
               (robot.root, "plain", [])]
    rule = CATALOGUE.get("U204")
    each = [engine.stamp(rule, where, message, robot, *rest) for where, message, rest in yielded]
    assert engine.stamp_all(rule, yielded, robot) == each
    assert [(f.line, f.column) for f in each[:2]] == [(2, 1), (3, 3)]
    assert each[4].line == 4 and each[4].fix == fix and each[5].severity is Severity.WARNING


def test_a_finding_a_rule_cannot_stamp_is_its_crash_after_the_findings_before_it(monkeypatch):
    def broken(robot):
        yield robot.root, "first"
        yield robot.root, "too severe", None, Severity.ERROR  # (a rule below errors)
        yield robot.root, "never stamped"
        raise ZeroDivisionError("later")

    original = CATALOGUE.get("U218")
    assert original.severity is not Severity.ERROR
    crashing = Rule("U218", original.name, original.severity, broken, original.doc)
    monkeypatch.setattr(engine, "CATALOGUE", Catalogue(
        [crashing if r.code == "U218" else r for r in CATALOGUE.rules]))
    findings = load_and_check(str(ROBOT), CheckOptions(selection=Selection(select=("U218", "U900")))).findings
    assert [f.message for f in findings if f.code == "U218"] == ["first"]
    crash = [f for f in findings if f.code == "U900"]
    assert len(crash) == 1 and "crashed: ValueError: U218's severity is info" in crash[0].message and \
        "a finding of it cannot be more severe (error)" in crash[0].message


def test_a_crashing_loader_is_u900_naming_the_file(monkeypatch):
    import urdftool.description.load

    def explode(*args, **kwargs):
        raise RecursionError("deep")

    monkeypatch.setattr(urdftool.description.load, "load", explode)
    [finding] = load_and_check(str(ROBOT), CheckOptions()).findings
    assert finding.code == "U900" and finding.severity is Severity.ERROR
    assert finding.message.startswith("loading crashed: RecursionError: deep")


def test_load_failures_are_reported_whatever_the_selection():
    result = load_and_check(str(CASES / "U001_malformed_xml.urdf"),
                        CheckOptions(selection=Selection(ignore=("U0",))))
    assert [f.code for f in result.findings] == ["U001"]


def test_selection_by_code_prefix_and_name():
    assert Selection(select=("U2",)).allows("U204")
    assert not Selection(select=("U2",)).allows("U101")
    assert not Selection(ignore=("inverted-limits",)).allows("U204")
    assert Selection(ignore=("inverted-limits",)).allows("U205")


def test_allowing_answers_as_allows_does_once_per_selection():
    """The engine asks ``allowing()`` of every rule for every robot: the same answers as
    ``allows``, and one table for equal selections (each file's settings make their own)."""
    selections = (Selection(), Selection(select=("U2",)), Selection(ignore=("U103", "U2")),
                  Selection(select=("U", "inverted-limits"), ignore=("U2",)),
                  Selection(targets=("mujoco",)), Selection(select=("U92",), targets=("mujoco",)))
    codes = [rule.code for rule in CATALOGUE.rules] + ["U999"]
    for selection in selections:
        allows = selection.allowing()
        assert [allows(code) for code in codes] == [selection.allows(code) for code in codes]
    assert Selection(ignore=("U103",)).allowing() == Selection(ignore=("U103",)).allowing()
    assert not Selection(ignore=("U103",)).allowing()("U103")


def _load_error(tmp_path, name: str, text: str, **options):
    path = tmp_path / name
    path.write_text(text)
    with pytest.raises(LoadError) as caught:
        load(path, **options)
    return caught.value


XACRO = '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'


def test_load_errors_become_their_rule_with_the_hint_on_what_to_pass(tmp_path):
    big = _load_error(tmp_path, "big.urdf", "<robot name='r'>" + " " * 2000 + "</robot>",
                      max_file_size=1000)
    [finding] = load_error_findings(big)
    assert (finding.code, finding.line) == ("U008", None)
    assert finding.message == ("file is 2024 bytes, over the limit of 1000 "
                               "(raise it with --max-file-size)")
    argument = _load_error(tmp_path, "r.urdf.xacro", XACRO + '<link name="$(arg part)"/>\n</robot>')
    [finding] = load_error_findings(argument)
    assert (finding.code, finding.line) == ("U005", 2)
    assert finding.message == ("Undefined substitution argument part; "
                               "pass it as part:=VALUE (or --arg part=VALUE)")


def test_every_kind_the_loader_raises_or_notes_has_a_code():
    """The kinds listed in LoadError's and LoadNote's docstrings are the tables' keys."""
    from urdftool.description.robot import LoadNote
    from urdftool.errors import LoadError as Error

    def listed(doc):
        return set(re.findall(r"'([a-z-]+)'", doc.split("kind:")[1].split("message:")[0]))

    assert listed(Error.__doc__) == set(LOAD_CODES)
    assert listed(LoadNote.__doc__ + "message:") == set(NOTE_CODES)
    assert all(code in CATALOGUE for code in [*LOAD_CODES.values(), *NOTE_CODES.values()])


def test_a_disguised_xacro_that_does_not_expand_keeps_the_hint(tmp_path):
    path = tmp_path / "r.urdf"
    path.write_text(XACRO + '<link name="$(arg part)"/>\n</robot>')
    [finding] = [f for f in load_and_check(str(path), CheckOptions()).findings if f.code == "U007"]
    assert finding.line == 2
    assert "which xacro cannot expand (Undefined substitution argument part; pass it as " \
           "part:=VALUE (or --arg part=VALUE)) and URDF parsers ignore" in finding.message


def test_notes_become_findings_that_the_selection_and_suppressions_filter(tmp_path):
    path = tmp_path / "r.urdf.xacro"
    path.write_text(XACRO + '<xacro:property name="p" value="1" bogus="2"/>\n<link name="a"/>\n'
                    '</robot>')
    codes = [f.code for f in load_and_check(str(path), CheckOptions()).findings]
    assert codes.count("U010") == 1
    ignoring = CheckOptions(selection=Selection(ignore=("xacro-warning",)))
    assert "U010" not in [f.code for f in load_and_check(str(path), ignoring).findings]


def _repository(tmp_path, files: dict[str, str]) -> None:
    """A repository (its .git, as a clone has) of ``files``: path -> text."""
    (tmp_path / ".git").mkdir()
    for name, text in files.items():
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / name).write_text(text)


def test_a_robot_needing_an_argument_is_built_as_a_launch_file_builds_it(tmp_path):
    # ur.xacro needs robot_model, which has no default: load_ur5.launch gives it. The robot is
    # checked as that launch file builds it, and U005 is a note naming it (issue 30: the
    # launch files say against which xacro arguments)
    from urdftool.diagnostics import Severity

    files = {
        "arm/package.xml": "<package format='2'><name>arm</name></package>",
        "arm/urdf/arm.urdf.xacro": """<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <link name="$(arg model)_base"/>
</robot>""",
        "arm/launch/load_arm.launch": """<launch>
  <arg name="model"/>
  <param name="robot_description" command="xacro $(find arm)/urdf/arm.urdf.xacro model:=$(arg model)"/>
</launch>""",
        "arm/launch/load_m5.launch": """<launch>
  <include file="$(find arm)/launch/load_arm.launch"><arg name="model" value="m5"/></include>
</launch>"""}
    _repository(tmp_path, files)
    robot = str(tmp_path / "arm/urdf/arm.urdf.xacro")
    result = load_and_check(robot, CheckOptions())
    assert result.robot is not None and "m5_base" in result.robot.links
    [note] = [f for f in result.findings if f.code == "U005"]
    assert note.severity == Severity.INFO and "load_m5.launch builds it (model:=m5)" in note.message
    given = load_and_check(robot, CheckOptions(xacro_args={"model": "m10"}))
    assert "m10_base" in given.robot.links and not [f for f in given.findings if f.code == "U005"]
    (tmp_path / "arm/launch/load_m5.launch").unlink()  # load_arm.launch gives it only at launch
    failed = load_and_check(robot, CheckOptions())
    assert failed.robot is None and [f.severity for f in failed.findings] == [Severity.INFO]
    assert "load_arm.launch gives it a value known only at launch" in failed.findings[0].message
    # a launch file building the robot, unconditionally, without the argument: xacro fails there
    (tmp_path / "arm/launch/load_arm.launch").write_text("""<launch>
  <param name="robot_description" command="xacro $(find arm)/urdf/arm.urdf.xacro"/>
</launch>""")
    failed = load_and_check(robot, CheckOptions())
    assert failed.robot is None and [f.severity for f in failed.findings] == [Severity.ERROR]
    assert "load_arm.launch:2 builds this robot without it" in failed.findings[0].message


def test_a_launch_files_build_failing_on_a_package_not_installed_here_is_u006s(tmp_path):
    # mmuav_gazebo's mmcuav.gazebo.xacro needs $(arg name), which mmcuav.launch gives, and
    # includes RotorS' $(find rotors_description): built so, xacro fails only because that
    # package is not installed here, the environment's (U006, a warning), not an error
    from urdftool.diagnostics import Severity

    files = {
        "uav/package.xml": "<package format='2'><name>uav</name></package>",
        "uav/urdf/uav.urdf.xacro": """<robot name="uav" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <link name="$(arg name)_base"/>
  <xacro:include filename="$(find rotors_description)/urdf/component_snippets.xacro"/>
</robot>""",
        "uav/launch/uav.launch": """<launch>
  <param name="robot_description" command="xacro $(find uav)/urdf/uav.urdf.xacro name:=uav"/>
</launch>"""}
    _repository(tmp_path, files)
    result = load_and_check(str(tmp_path / "uav/urdf/uav.urdf.xacro"), CheckOptions())
    [finding] = result.findings
    assert (finding.code, finding.severity) == ("U006", Severity.WARNING)
    assert "uav.launch builds it (name:=uav), and xacro fails so here" in finding.message


def test_findings_name_a_launch_test_as_a_launch_test(tmp_path):
    """A build told by a launch test is named as one (launch.named), in U005's and U007's
    messages alike: a launch test builds the robot for the test alone. One that cannot be read
    is unknown: U005's 'declared nowhere' is then a note naming it."""
    from urdftool.diagnostics import Severity

    test = ("import xacro\n\ndef generate_test_description():\n"
            "    doc = xacro.process_file(os.path.join(get_package_share_directory('arm'), "
            "'urdf', '{name}'), mappings={{'model': 'm5'}})\n"
            "    return LaunchDescription([Node(package='robot_state_publisher', "
            "executable='robot_state_publisher', parameters=[{{'robot_description': "
            "doc.toxml()}}])])\n")
    files = {"arm/package.xml": "<package format='2'><name>arm</name></package>",
             "arm/urdf/arm.urdf.xacro": '<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/'
                                        'xacro">\n  <link name="$(arg model)_base"/>\n</robot>',
             "arm/urdf/plain.urdf": '<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/'
                                    'xacro">\n<xacro:property name="m" value="m5"/>\n'
                                    '<link name="${m}_base"/>\n</robot>',
             "arm/test/arm.py": test.format(name="arm.urdf.xacro"),
             "arm/test/plain.py": test.format(name="plain.urdf")}
    _repository(tmp_path, files)
    [u005] = [f for f in load_and_check(str(tmp_path / "arm/urdf/arm.urdf.xacro"),
                                        CheckOptions()).findings if f.code == "U005"]
    assert f"launch test {tmp_path}/arm/test/arm.py builds it (model:=m5)" in u005.message
    [u007] = [f for f in load_and_check(str(tmp_path / "arm/urdf/plain.urdf"),
                                        CheckOptions()).findings if f.code == "U007"]
    assert u007.severity == Severity.INFO and f"(launch test {tmp_path}/arm/test/plain.py)" in \
        u007.message, u007.message
    # declared nowhere, a near name declared: a warning, unless a launch test not read names it
    (tmp_path / "arm/urdf/arm.urdf.xacro").write_text(
        '<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:arg name="modle" default="m1"/>\n  <link name="$(arg model)_base"/>\n</robot>')
    (tmp_path / "arm/test/arm.py").write_text(test.format(name="other.urdf.xacro"))
    [u005] = [f for f in load_and_check(str(tmp_path / "arm/urdf/arm.urdf.xacro"),
                                        CheckOptions()).findings if f.code == "U005"]
    assert u005.severity == Severity.WARNING, u005.message
    (tmp_path / "arm/test/arm.py").write_text(test.format(name="arm.urdf.xacro").replace(
        "():", "(:"))
    [u005] = [f for f in load_and_check(str(tmp_path / "arm/urdf/arm.urdf.xacro"),
                                        CheckOptions()).findings if f.code == "U005"]
    assert u005.severity == Severity.INFO and \
        f"(but launch test {tmp_path}/arm/test/arm.py (not read) may)" in u005.message, \
        u005.message


def test_the_latest_robot_is_kept_only_where_a_program_installs_the_slot(tmp_path, monkeypatch):
    """``engine.LATEST``: a program ending with os._exit (the command line) keeps the last
    robot checked, each check freeing the one before; a library user's robot is freed with
    its result."""
    import gc
    import weakref

    for name in "ab":
        (tmp_path / f"{name}.urdf").write_text(f'<robot name="{name}"><link name="l"/></robot>\n')

    def robot_of(name):
        result = load_and_check(str(tmp_path / f"{name}.urdf"), CheckOptions())
        return weakref.ref(result.robot)

    assert engine.LATEST is None  # unless installed
    freed = robot_of("a")
    gc.collect()  # (a robot's memos may hold cycles)
    assert freed() is None
    monkeypatch.setattr(engine, "LATEST", [])
    first = robot_of("a")
    assert first() is not None and engine.LATEST == [first()]
    alive = []  # the robots alive when the next one is loaded: the kept one is freed first
    monkeypatch.setattr(engine, "_recorded", lambda *args, recorded=engine._recorded: (
        gc.collect(), alive.append(first()), recorded(*args))[-1])
    second = robot_of("b")
    gc.collect()
    assert alive == [None] and first() is None
    assert second() is not None and engine.LATEST == [second()]


def test_a_part_failing_on_its_includers_name_is_a_note_a_robot_failing_so_an_error(tmp_path):
    """talos_description's left_arm.transmissions.urdf.xacro: transmissions through macro
    calls using ${name}, which the robot including it defines; nothing here includes it. A
    part (its top level writes no link): U005 a note. Writing a link of its own, or built by
    a launch file, the same failure is an error (tests/cases/U005_part_uses_a_name_...)."""
    from urdftool.diagnostics import Severity

    (tmp_path / ".git").mkdir()
    (tmp_path / "arm.transmission.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><xacro:macro name="t" params="n">'
        '<transmission name="${n}_trans"><joint name="${n}_joint"/></transmission>'
        '</xacro:macro></robot>')
    call = '<xacro:include filename="arm.transmission.xacro"/><xacro:t n="${name}"/>'
    for own, severity in (("", Severity.INFO), ('<link name="base"/>', Severity.ERROR)):
        robot = tmp_path / "part.urdf.xacro"
        robot.write_text(f'<robot xmlns:xacro="http://www.ros.org/wiki/xacro">{own}{call}'
                         '</robot>')
        [finding] = load_and_check(str(robot), CheckOptions()).findings
        assert (finding.code, finding.severity) == ("U005", severity), finding.message


def test_a_library_of_macros_needing_a_missing_package_is_a_note_a_robot_not_checked(tmp_path):
    """talos_description's sensors/xtion_pro_live.urdf.xacro includes ``$(find reemc)`` (not
    installed) and only defines macros; nothing here builds it. Expanded with reemc it would
    make no robot, so its U006 is a note and the run has nothing it could not check (it made
    the whole repository exit 2). A file calling a macro, or writing a link, is a robot not
    checked: a warning, and unexpanded."""
    from urdftool.diagnostics import Severity

    (tmp_path / ".git").mkdir()
    include = '<xacro:include filename="$(find no_such_sensors)/urdf/calibration.xacro"/>'
    macro = '<xacro:macro name="cam" params="name"><link name="${name}"/></xacro:macro>'
    for top, severity in (("", Severity.INFO), ('<xacro:cam name="c"/>', Severity.WARNING),
                          ('<link name="base"/>', Severity.WARNING)):
        robot = tmp_path / "sensor.urdf.xacro"
        robot.write_text(f'<robot xmlns:xacro="http://www.ros.org/wiki/xacro">{include}{macro}'
                         f'{top}</robot>')
        result = load_and_check(str(robot), CheckOptions())
        [finding] = result.findings
        assert (finding.code, finding.severity) == ("U006", severity), finding.message
        assert result.unexpanded is (severity == Severity.WARNING)
    # a name nearly a package's found here (doosan-robot2's libraries naming the ROS 1
    # dsr_description beside dsr_description2): wrong for any robot including it
    (tmp_path / "package.xml").write_text(
        '<package format="2"><name>no_such_sensors2</name></package>')
    robot.write_text(f'<robot xmlns:xacro="http://www.ros.org/wiki/xacro">{include}{macro}'
                     '</robot>')
    [finding] = load_and_check(str(robot), CheckOptions()).findings
    assert finding.severity == Severity.WARNING and "did you mean" in finding.message


def test_a_robot_needing_a_package_its_package_xml_declares_is_a_note_not_checked(tmp_path):
    """Robotnik's rb1_base.urdf.xacro includes ``$(find robotnik_sensors)``, which the
    package.xml of rb1_base_description declares: not installed here, it is a question of the
    workspace, not a defect of the file (a warning the sweep judged DEBATABLE 100 times): a
    note, and still a robot not checked (the run exits 2). A library of macros needing it is
    a note that loses nothing, as when undeclared."""
    from urdftool.diagnostics import Severity

    (tmp_path / ".git").mkdir()
    (tmp_path / "package.xml").write_text(
        '<package format="2"><name>rb1_base_description</name>'
        '<exec_depend>robotnik_sensors</exec_depend></package>')
    include = '<xacro:include filename="$(find robotnik_sensors)/urdf/all_sensors.urdf.xacro"/>'
    macro = '<xacro:macro name="cam" params="name"><link name="${name}"/></xacro:macro>'
    robot = tmp_path / "rb1_base.urdf.xacro"
    for top, unexpanded in (('<link name="base"/>', True), ("", False)):
        robot.write_text(f'<robot xmlns:xacro="http://www.ros.org/wiki/xacro">{include}{macro}'
                         f'{top}</robot>')
        result = load_and_check(str(robot), CheckOptions())
        [finding] = result.findings
        assert (finding.code, finding.severity) == ("U006", Severity.INFO), finding.message
        assert "declares it as a dependency" in finding.message
        assert result.unexpanded is unexpanded


def test_a_package_is_declared_by_the_package_xml_not_by_the_words_of_a_path(tmp_path):
    """Whether a missing package is one the package.xml declares travels with the error
    (``LoadError.declared``), set where the package.xml was read; it was read back from the
    message's words, and the folder a repository was cloned into is in that message (where
    the package was looked for): a folder named "x declares it as a dependency" made an
    undeclared package a note."""
    from urdftool.diagnostics import Severity

    folder = tmp_path / "x declares it as a dependency"
    (folder / ".git").mkdir(parents=True)
    (folder / "package.xml").write_text('<package format="2"><name>bot</name></package>')
    robot = folder / "r.urdf.xacro"
    robot.write_text('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro"><xacro:include '
                     'filename="$(find no_such_pkg)/a.xacro"/><link name="a"/></robot>')
    result = load_and_check(str(robot), CheckOptions())
    [finding] = result.findings
    assert "does not declare it" in finding.message and "declares it as a" in finding.message
    assert (finding.code, finding.severity) == ("U006", Severity.WARNING), finding.message
    assert finding.not_checked and result.unexpanded


def test_a_file_is_not_checked_when_a_finding_says_so_not_when_its_words_do():
    """``FileResult.not_checked_by`` reads each finding's ``not_checked``, set where the load
    error became the finding; a note whose words are those of a declared dependency (a path, a
    package's name) is not one, and a finding saying so in any words is."""
    from urdftool.diagnostics import Finding, Location
    from urdftool.lint.engine import FileResult

    words = ("package 'a' not found: the package.xml of 'b' declares it as a dependency, which "
             "is not installed here")
    said = Finding("U006", "unresolved-package", Severity.INFO, words, Location("r.xacro", 1))
    told = Finding("U006", "unresolved-package", Severity.INFO, "any words", Location("r.xacro", 1),
                   not_checked=True)
    assert not FileResult("r.xacro", [said]).unexpanded
    assert FileResult("r.xacro", [said, told]).not_checked_by == [told]


@pytest.mark.parametrize("conditional, severity", [(False, Severity.ERROR), (True, Severity.WARNING)])
def test_a_parameter_the_macro_lacks_fails_whatever_the_launch_gives_unless_under_a_condition(
        tmp_path, conditional, severity):
    # adv4ncr/motoman_ROS2's hc10dt_b10.xacro (tests/cases/U005_invalid_parameter_whatever_the_
    # launch_gives): xacro checks a call's parameter names before any value, so only a condition
    # around the call can make another argument value succeed
    call = '<xacro:c ip="$(arg ip)" use_mock="1"/>'
    if conditional:
        call = f'<xacro:if value="$(arg mock)">{call}</xacro:if><link name="base"/>'
    files = {
        "arm/package.xml": "<package format='2'><name>arm</name></package>",
        "arm/urdf/arm.urdf.xacro": f"""<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="ip" default=""/><xacro:arg name="mock" default="true"/>
  <xacro:macro name="c" params="ip mock"><link name="base"/></xacro:macro>
  {call}
</robot>""",
        "arm/launch/load_arm.launch": """<launch>
  <arg name="ip"/>
  <param name="robot_description" command="xacro $(find arm)/urdf/arm.urdf.xacro ip:=$(arg ip)"/>
</launch>"""}
    _repository(tmp_path, files)
    result = load_and_check(str(tmp_path / "arm/urdf/arm.urdf.xacro"), CheckOptions())
    [failed] = [f for f in result.findings if f.code == "U005"]
    assert failed.severity == severity, failed.message


FRAME_NOT_PUSHED = "error return without exception set"  # Python 3.11's, at the memory cap


@pytest.mark.parametrize("where", ["rule", "loading"])
def test_a_call_refused_at_the_memory_cap_stops_the_piece_as_over_its_memory(monkeypatch, where):
    """In a worker at its address-space cap, Python 3.11 could not map the next chunk of its
    frame stack for a call (rule U222 reading its companions: SystemError "error return
    without exception set"); the U900 then built for it was the next call refused, and the
    worker died of a segmentation fault ("Fatal Python error" in every ``make test`` log, from
    tests/lint/test_settings.py under ``max-memory = "1G"``). Such an error is the budget's:
    U018, no U900, no death."""
    from urdftool.lint.runner import check_files

    def refused(*args, **kwargs):
        raise SystemError(FRAME_NOT_PUSHED)

    def refused_rule(robot):
        yield from refused()

    if where == "rule":
        original = CATALOGUE.get("U204")
        monkeypatch.setattr(engine, "CATALOGUE", Catalogue(
            [Rule("U204", original.name, original.severity, refused_rule, original.doc)
             if r.code == "U204" else r for r in CATALOGUE.rules]))
    else:
        import urdftool.description.load

        monkeypatch.setattr(urdftool.description.load, "load", refused)
    [result] = check_files([str(ROBOT)], lambda path: CheckOptions(), jobs=1, timeout=60,
                           memory=4 << 30)  # (in a forked worker, the memory capped)
    assert [f.code for f in result.findings] == ["U018"], [str(f) for f in result.findings]


def test_an_empty_robot_name_is_no_refusal_of_urdfdom_and_a_missing_one_is(tmp_path):
    """urdfdom refuses ``<robot>`` without a name and takes ``name=""`` (check_urdf: "robot
    name is: "); U011 finds both, but only the first is a refusal, which every command that
    poses a robot stops at (tree and fk refused the empty name, exit 1, as if urdfdom had)."""
    path = tmp_path / "r.urdf"
    path.write_text('<robot name=""><link name="a"/></robot>')
    assert engine.urdfdom_refusals(load(str(path))) == []
    assert [f.code for f in load_and_check(str(path), CheckOptions()).findings] == ["U011"]
    path.write_text('<robot><link name="a"/></robot>')
    assert [f.code for f in engine.urdfdom_refusals(load(str(path)))] == ["U011"]


def test_urdfdom_refusals_are_decided_per_finding(tmp_path):
    """One robot with a joint's name="" (check_urdf takes it) and a joint without the attribute
    (check_urdf: "unnamed joint found"): U103 twice, one refusal; U109 on a loop beside the tree
    (check_urdf drops its links) is none."""
    path = tmp_path / "r.urdf"
    path.write_text('<robot name="r"><link name="r"/><link name="a"/><link name="b"/>'
                    '<joint name="" type="fixed"><parent link="r"/><child link="a"/></joint>'
                    '<joint type="fixed"><parent link="r"/><child link="b"/></joint></robot>')
    [refusal] = engine.urdfdom_refusals(load(str(path)))
    assert (refusal.code, refusal.message) == ("U103", "<joint> has no name attribute")
    assert [f.code for f in load_and_check(str(path), CheckOptions()).findings] == \
        ["U103", "U103"]
    path.write_text('<robot name="r"><link name="r"/><link name="a"/><link name="b"/>'
                    '<joint name="j1" type="fixed"><parent link="a"/><child link="b"/></joint>'
                    '<joint name="j2" type="fixed"><parent link="b"/><child link="a"/></joint>'
                    '</robot>')
    assert engine.urdfdom_refusals(load(str(path))) == []
    assert "U109" in {f.code for f in load_and_check(str(path), CheckOptions()).findings}


_DRAKE_PR2 = ('<robot name="pr2" xmlns:drake="http://drake.mit.edu">\n<link name="base"/>\n'
              '<link name="x_link"/>\n'
              '<joint name="world_joint" type="fixed"><parent link="world"/>'
              '<child link="base"/></joint>\n'
              '<joint name="x" type="prismatic"><parent link="base"/><child link="x_link"/>'
              '<axis xyz="1 0 0"/></joint>\n</robot>\n')
_CATKIN = ('<package format="2"><name>bot</name><version>0.0.0</version><description>d'
           '</description><maintainer email="a@b.c">a</maintainer><license>MIT</license>'
           '<buildtool_depend>catkin</buildtool_depend></package>')


def test_urdfdoms_refusals_in_a_file_drake_reads_are_warnings_and_still_refusals(tmp_path):
    """RobotLocomotion/models' PR2: parent 'world' (Drake's world frame) and a prismatic joint
    without <limit> (Drake: unbounded) are warnings naming the condition, "if urdfdom loads it";
    urdfdom refuses them all the same, and urdfdom_refusals counts them (Refused)."""
    path = tmp_path / "pr2.urdf"
    path.write_text(_DRAKE_PR2)
    findings = [f for f in load_and_check(str(path), CheckOptions()).findings
                if f.code in ("U105", "U202")]
    assert [(f.code, f.severity, f.urdfdom_refuses) for f in findings] == [
        ("U105", Severity.WARNING, True), ("U202", Severity.WARNING, True)]
    assert all(f.message.startswith("if urdfdom loads it (Drake reads it: its <robot> declares "
                                    'xmlns:drake="http://drake.mit.edu"; nothing says ROS runs')
               for f in findings), [f.message for f in findings]
    assert [f.code for f in engine.urdfdom_refusals(load(str(path)))] == ["U105", "U202"]


def test_urdfdoms_refusals_in_a_drake_namespaced_file_of_a_ros_package_stay_errors(tmp_path):
    """The same file in a catkin package: ROS runs it, the errors hold for its consumers."""
    (tmp_path / "package.xml").write_text(_CATKIN)
    path = tmp_path / "pr2.urdf"
    path.write_text(_DRAKE_PR2)
    findings = [f for f in load_and_check(str(path), CheckOptions()).findings
                if f.code in ("U105", "U202")]
    assert [(f.code, f.severity, f.urdfdom_refuses) for f in findings] == [
        ("U105", Severity.ERROR, False), ("U202", Severity.ERROR, False)]
    assert not any(f.message.startswith("if urdfdom") for f in findings)
    assert [f.code for f in engine.urdfdom_refusals(load(str(path)))] == ["U105", "U202"]


def test_a_shape_drake_refuses_too_stays_an_error_in_a_file_drake_reads(tmp_path):
    """Only what the rule says the reader takes is lowered: a child link not written is no
    world frame, Drake refuses it as urdfdom does."""
    path = tmp_path / "pr2.urdf"
    path.write_text(_DRAKE_PR2.replace("</robot>", '<joint name="j" type="fixed"><parent '
                                                   'link="x_link"/><child link="ghost"/></joint>'
                                                   "\n</robot>"))
    found = [(f.severity, f.urdfdom_refuses, f.message.split(",")[0])
             for f in load_and_check(str(path), CheckOptions()).findings if f.code == "U105"]
    assert (Severity.ERROR, False, "joint 'j' names child link 'ghost'") in found, found


def test_a_browsers_copy_takes_what_drake_alone_takes_as_an_error(tmp_path):
    """A web page's copy (three.js urdf-loader) with parent 'world': the loader finds no such
    link either, so U105 stays an error there, while U202 is a warning."""
    from crossfile_helpers import served_copy

    path = served_copy(tmp_path, _DRAKE_PR2.replace(' xmlns:drake="http://drake.mit.edu"', ""),
                       "pr2.urdf")
    findings = {f.code: f for f in load_and_check(str(path), CheckOptions()).findings}
    assert findings["U105"].severity == Severity.ERROR
    assert findings["U202"].severity == Severity.WARNING
    assert findings["U202"].message.startswith("if urdfdom loads it (a web page reads it: ")


@pytest.mark.parametrize("code, body", [
    ("U203", '<link name="b"/><joint name="j" type="revolute"><parent link="a"/><child link="b"/>'
             '<axis xyz="0 0 1"/><limit lower="0" upper="1"/></joint>'),
    ("U405", ""),
])
def test_each_marked_shape_is_a_warning_in_a_file_drake_reads_and_an_error_in_ros(code, body,
                                                                                 tmp_path):
    """U203's <limit> without effort or velocity, U405's unnamed visual material
    (RobotLocomotion/models' table_top): warnings naming Drake in Drake's file; errors in the
    same file of a catkin package."""
    text = ('<robot name="r" xmlns:drake="http://drake.mit.edu">\n<link name="a"><visual>'
            '<geometry><box size="1 1 1"/></geometry>\n<material><color rgba="1 0 0 1"/>'
            f'</material></visual></link>\n{body}\n</robot>\n')
    if code == "U203":
        text = text.replace("<material><color rgba=\"1 0 0 1\"/></material>", "")
    path = tmp_path / "drake" / "r.urdf"
    path.parent.mkdir()
    path.write_text(text)
    (tmp_path / "ros").mkdir()
    (tmp_path / "ros" / "package.xml").write_text(_CATKIN)
    (tmp_path / "ros" / "r.urdf").write_text(text)
    for folder, severity in (("drake", Severity.WARNING), ("ros", Severity.ERROR)):
        [finding] = [f for f in load_and_check(str(tmp_path / folder / "r.urdf"),
                                               CheckOptions()).findings if f.code == code]
        assert finding.severity == severity, finding
        assert finding.message.startswith("if urdfdom loads it (Drake") == (folder == "drake")


def test_an_error_of_the_defaults_build_no_launch_file_runs_is_a_warning(tmp_path):
    """autonomous_excavator's launch files build its xacro with use_nominal_extrinsics:=true,
    which makes the camera frame a joint hangs from; the robot's own default (false) leaves
    the joint naming a link that does not exist: a U105 error for a plain xacro of the file
    alone, so a warning naming the launch file's build. An error that build has too stays one,
    and so does this one when no launch file builds the robot otherwise."""
    from urdftool.diagnostics import Severity

    launch = ("import xacro\nfrom launch_ros.actions import Node\n\n"
              "def generate_launch_description():\n"
              "    doc = xacro.process_file(os.path.join(get_package_share_directory('arm'), "
              "'urdf', 'arm.urdf.xacro'), mappings={'frames': 'true'})\n"
              "    return LaunchDescription([Node(package='robot_state_publisher', "
              "executable='robot_state_publisher', parameters=[{'robot_description': "
              "doc.toxml()}])])\n")
    files = {"arm/package.xml": "<package format='2'><name>arm</name></package>",
             "arm/urdf/arm.urdf.xacro": """<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="frames" default="false"/>
  <link name="base"/>
  <xacro:if value="$(arg frames)">
    <link name="optical"/>
    <joint name="optical_joint" type="fixed"><parent link="base"/><child link="optical"/></joint>
  </xacro:if>
  <link name="tool"/>
  <joint name="tool_joint" type="fixed"><parent link="optical"/><child link="tool"/></joint>
  <link name="loose"/>
  <joint name="loose_joint" type="fixed"><parent link="nowhere"/><child link="loose"/></joint>
</robot>""",
             "arm/launch/arm.launch.py": launch}
    _repository(tmp_path, files)
    robot = str(tmp_path / "arm/urdf/arm.urdf.xacro")
    found = {f.line: f for f in load_and_check(robot, CheckOptions()).findings if f.code == "U105"}
    assert found[9].severity == Severity.WARNING and found[9].urdfdom_refuses
    assert "arm.launch.py builds it with frames:=true, which does not have it" in found[9].message
    assert found[11].severity == Severity.ERROR  # (the launch file's build has it too)
    chosen = load_and_check(robot, CheckOptions(xacro_args={"frames": "false"})).findings
    assert [f.severity for f in chosen if f.code == "U105"] == [Severity.ERROR] * 2
    (tmp_path / "arm/launch/arm.launch.py").unlink()
    alone = load_and_check(robot, CheckOptions()).findings
    assert [f.severity for f in alone if f.code == "U105"] == [Severity.ERROR] * 2
