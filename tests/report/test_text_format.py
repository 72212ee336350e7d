"""The text report says each thing once: findings that say the same thing are one line with a
count and the places; a long "available ..." list is written once; notes show when asked for.
The machine formats keep every finding."""

from __future__ import annotations

import io
import json

from urdftool.diagnostics import Finding, Location, Severity
from urdftool.errors import available
from urdftool.lint.engine import FileResult
from urdftool.report import render

JOINTS = [f"j{i}" for i in range(24)]


def _prefix(i: int) -> Finding:
    return Finding("U508", "hardware-interface-prefix", Severity.WARNING,
                   f"transmission 't_{JOINTS[i]}': joint '{JOINTS[i]}' names "
                   "'EffortJointInterface' without hardware_interface/; write "
                   "hardware_interface/EffortJointInterface", Location("robot.urdf", 100 + 12 * i))


def _text(results, **options) -> str:
    stream = io.StringIO()
    render("text", results, stream, **options)
    return stream.getvalue()


def test_findings_that_say_the_same_thing_are_one_line_with_count_and_places():
    results = [FileResult("robot.urdf", [_prefix(i) for i in range(24)])]
    lines = _text(results).splitlines()
    assert len([line for line in lines if "U508" in line]) == 1
    [line] = [line for line in lines if "U508" in line]
    assert line.startswith("  robot.urdf:100: warning U508 transmission 't_j0'")
    assert "[24 times: lines 100, 112, 124," in line and "... (24 in all); also 't_j1', " in line
    assert line.endswith("... (23 in all)]")  # (the other transmissions)
    assert "1 file checked: 0 errors, 24 warnings" in lines[-1]
    # the machine formats keep every finding
    stream = io.StringIO()
    render("json", results, stream)
    assert len(json.loads(stream.getvalue())["diagnostics"]) == 24


def test_different_things_stay_apart():
    other = Finding("U508", "hardware-interface-prefix", Severity.WARNING,
                    "transmission 't': joint 'j' names 'VelocityJointInterface' without "
                    "hardware_interface/; write hardware_interface/VelocityJointInterface",
                    Location("robot.urdf", 5))
    error = Finding("U204", "inverted-limits", Severity.ERROR, "joint 'j0': lower 1 is above "
                    "upper -1; swap them", Location("robot.urdf", 7))
    text = _text([FileResult("robot.urdf", [other, error, _prefix(0), _prefix(1)])])
    assert text.count("U508") == 2 and "[2 times: lines 100, 112; also 't_j1']" in text
    assert "U204" in text


def test_names_in_quotes_and_absolute_paths_are_set_aside_but_not_a_slash_in_a_word():
    from urdftool.report.text_format import groups

    def said(line: int, message: str) -> Finding:
        return Finding("U311", "implausible-density", Severity.WARNING, message,
                       Location("robot.urdf", line))

    same = [said(1, "link 'a': 2 kg/m^3 in /x/a.stl (/x/a.dae)"),
            said(2, "link 'b': 2 kg/m^3 in /y/b.stl (/y/b.dae)")]
    apart = [said(3, "link 'a': 2 kg/m^2 in /x/a.stl (/x/a.dae)"),  # "kg/m" is no path
             said(4, "link 'a':/x 2 kg/m^3 in /x/a.stl (/x/a.dae)")]  # nor a slash after ':'
    assert [len(group) for group in groups(same + apart)] == [2, 1, 1]


def test_a_grouped_line_says_the_other_names_it_is_about():
    """session 11, read as a stranger (CommonplaceRobotics/iRC_ROS): one macro line expanded for
    three joints, each its own limit, read "joint 'rebel_1_joint2' position min is -2.0944 to
    -1.65806 [3 times: line 7 (3x)]", as if of one joint; the other names are said. Findings of
    one name, or naming another count of things, say none."""
    def said(line: int, message: str) -> Finding:
        return Finding("U515", "ros2-control-limits", Severity.WARNING, message,
                       Location("ros2_control.xacro", line))

    joints = [said(7, f"ros2_control joint '{name}' position min is {low}, beyond the URDF "
                      f"<limit> ({limit})")
              for name, low, limit in (("j2", -2.0944, -1.91986), ("j3", -2.0944, -1.91986),
                                       ("j5", -1.65806, -1.52716))]
    lines = [line for line in _text([FileResult("r.xacro", joints)]).splitlines() if "U515" in line]
    # (j5's two figures differ from the others': its own line, test below)
    assert lines[0].endswith("[2 times on this line; also 'j3']") and "'j5'" in lines[1], lines
    one = [said(7, "ros2_control joint 'j2' has no limit"), said(9, "ros2_control joint 'j2' has no limit")]
    assert "[2 times: lines 7, 9]\n" in _text([FileResult("r.xacro", one)])
    counts = [said(7, "joints 'a' and 'b' have no limit"), said(9, "joints 'a' and 'b' have no limit"),
              said(11, "joints 'c', 'd' and 'e' have no limit")]
    text = _text([FileResult("r.xacro", counts)])
    assert "also" not in text
    many = [said(7 + i, f"ros2_control joint 'j{i}' has no limit") for i in range(1001)]
    [line] = [line for line in _text([FileResult("r.xacro", many)]).splitlines() if "U515" in line]
    assert line.endswith("(1001 in all); also 'j1', 'j2', 'j3', 'j4', 'j5', 'j6', 'j7', 'j8', "
                         "'j9', 'j10', 'j11', 'j12', ...]"), line  # (names of the first 1,000 read)


def test_a_macro_line_expanded_by_several_calls_is_one_place():
    findings = [Finding("U022", "no-effect", Severity.WARNING, "<dynamics> attribute 'K' has no "
                        "effect", Location("arm.xacro", line, (Location("robot.xacro", call),)))
                for line in (36, 51) for call in (29, 33)]
    text = _text([FileResult("robot.xacro", findings)])
    assert "arm.xacro:36: warning U022" in text
    assert "[4 times: lines 36 (2x), 51 (2x)]" in text
    assert "expanded from 2 macro calls at robot.xacro:29, 33" in text


def test_the_summary_says_on_how_many_lines_the_findings_are_in_every_format():
    """Two robots expanding one macro line twice each are four findings of one line to change:
    the summary said "4 warnings" (and Shadow's hands "299 warnings" over 64 lines), a count
    no report line showed. Each severity says its lines when some are fewer than its
    findings, the same in text, github and json."""
    def macro(robot: str, line: int, call: int) -> Finding:
        return Finding("U022", "no-effect", Severity.WARNING, "<dynamics> attribute 'K' has "
                       "no effect", Location("arm.xacro", line, (Location(robot, call),)))

    error = Finding("U204", "inverted-limits", Severity.ERROR, "joint 'j': lower 1 is above "
                    "upper -1; swap them", Location("a.urdf.xacro", 7))
    results = [FileResult("a.urdf.xacro", [error, macro("a.urdf.xacro", 36, 3),
                                           macro("a.urdf.xacro", 36, 4)]),
               FileResult("b.urdf.xacro", [macro("b.urdf.xacro", 36, 3),
                                           macro("b.urdf.xacro", 51, 3)])]
    assert _text(results).splitlines()[-1] == \
        "2 files checked: 1 error on 1 line, 4 warnings on 2 lines, 0 notes"
    stream = io.StringIO()
    render("github", results, stream)
    assert stream.getvalue().splitlines()[-1] == \
        "urdftool: 2 files, 1 error on 1 line, 4 warnings on 2 lines, 0 notes"
    stream = io.StringIO()
    render("json", results, stream)
    assert json.loads(stream.getvalue())["summary"] == {
        "files": 2, "errors": 1, "warnings": 4, "notes": 0,
        "lines": {"errors": 1, "warnings": 2, "notes": 0}}
    # one finding a line: the counts alone, as before
    assert _text([FileResult("a.urdf.xacro", [error])]).splitlines()[-1] == \
        "1 file checked: 1 error, 0 warnings, 0 notes"


def test_call_sites_are_listed_in_reading_order():
    # KapiBara's five lasers, sorted by name, were "lasers_joints.xacro:94, 92, 93, 95, 96"
    findings = [Finding("U615", "sensor-unknown-link", Severity.ERROR, f"'{name}' is not a link",
                        Location("lasers_def.xacro", 47, (Location("lasers_joints.xacro", call),)))
                for name, call in (("floor", 94), ("front_left", 92), ("front_right", 93),
                                   ("side_left", 95), ("side_right", 96))]
    text = _text([FileResult("robot.xacro", findings)])
    assert "expanded from 5 macro calls at lasers_joints.xacro:92, 93, 94, 95, 96" in text


def test_call_sites_write_each_file_once_for_its_run_of_lines():
    """ROBOTIS-OP3 named by an absolute path wrote 21 call sites with their 80-character
    folder each; a file is written once for its run, a site of another file names its own."""
    from urdftool.report.text_format import _same_file_once

    assert _same_file_once(["/r/a.xacro:28", "/r/a.xacro:52", "/r/b.xacro:28", "/r/a.xacro:9",
                            "c:d", "c:d:4", "c:d:5"]) == [
        "/r/a.xacro:28", "52", "/r/b.xacro:28", "/r/a.xacro:9", "c:d", "c:d:4", "5"]


def _listing(code: str, name: str, message: str, line: int) -> Finding:
    """A finding as a rule makes it of ``message``, which may hold a list ``available`` wrote."""
    return Finding(code, name, Severity.ERROR, str(message), Location("robot.urdf", line),
                   repeated=getattr(message, "repeated", ()))


def test_a_long_list_of_names_is_written_once():
    links = [f"link_{i:02d}" for i in range(31)]
    findings = [_listing("U611", "gazebo-unknown-reference", f"<gazebo reference='{name}'> names "
                         "no link or joint; " + available('links', name, links), line)
                for name, line in (("head", 10), ("arm", 20))]
    findings.append(_listing("U501", "transmission-unknown-joint",
                             "transmission 't' names link 'x'; " + available('links', 'x', links),
                             30))
    text = _text([FileResult("robot.urdf", findings)])
    assert text.count("link_00, link_01") == 1
    assert "available links: the 31 listed at line 10" in text
    assert "U501 transmission 't' names link 'x'; available links: the 31 listed at line 10" \
        in text
    # a short list is cheaper to repeat than to refer to
    short = [_listing("U406", "undefined-material", f"material '{m}' is not defined; "
                      + available('materials', m, ['Red']), line)
             for m, line in (("a", 1), ("b", 2))]
    assert _text([FileResult("robot.urdf", short)]).count("available materials: Red") == 1


NOTE = Finding("U308", "root-link-inertia", Severity.INFO, "root link 'base' has mass 1 kg, "
               "which KDL ignores", Location("robot.urdf", 2))


def test_notes_are_counted_when_not_shown():
    results = [FileResult("robot.urdf", [NOTE, _prefix(0)])]
    hidden = _text(results, notes=False)
    assert "U308" not in hidden
    assert hidden.splitlines()[-1] == \
        "1 file checked: 0 errors, 1 warning (1 note not shown: --notes shows them)"
    assert "U308" in _text(results, notes=True)
    alone = _text([FileResult("robot.urdf", [NOTE])], notes=False)
    assert alone == "1 file checked: no problems found (1 note not shown: --notes shows them)\n"


ROBOT = """<robot name="r">
  <link name="base"><inertial><mass value="1"/>
    <inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial></link>
</robot>
"""


def test_check_hides_notes_unless_asked_by_option_or_setting(run_cli, tmp_path):
    (tmp_path / ".git").mkdir()
    robot = tmp_path / "robot.urdf"
    robot.write_text(ROBOT)
    plain = run_cli("check", robot, "--no-cache")
    assert "U308" not in plain.stdout and "1 note not shown" in plain.stdout
    assert "U308" in run_cli("check", robot, "--no-cache", "--notes").stdout
    assert "U308" in json.loads(run_cli("check", robot, "--no-cache", "-f", "json").stdout
                                )["diagnostics"][0]["code"]
    (tmp_path / "urdftool.toml").write_text("notes = true\n")
    assert "U308" in run_cli("check", robot, "--no-cache").stdout
    assert "U308" not in run_cli("check", robot, "--no-cache", "--no-notes").stdout
    (tmp_path / "urdftool.toml").write_text("notes = \"yes\"\n")
    refused = run_cli("check", robot, "--no-cache")
    assert refused.exit_code == 2 and "'notes' must be true or false" in refused.output


def test_the_same_thing_said_of_named_things_with_their_own_figures_is_one_true_line():
    """RealMan's six links "has mass 0.59 kg but zero inertia", each its own mass: one line,
    whose differing figure is the range of the group's, so that it is true of each. A value to
    write (in double quotes) is never a figure to fold, and a message naming nothing keeps its
    figures apart: they are what it says."""
    from urdftool.report.text_format import groups

    def said(line: int, message: str, code: str = "U304") -> Finding:
        return Finding(code, "inertia-not-positive-definite", Severity.ERROR, message,
                       Location("robot.urdf", line))

    masses = [said(68 + 66 * i, f"link 'Link{i + 1}' has mass {mass} kg but zero inertia and is "
                                "moved by a joint") for i, mass in enumerate((0.593563, 0.0649018, 0.2188))]
    [line] = [line for line in _text([FileResult("robot.urdf", masses)]).splitlines() if "U304" in line]
    assert "has mass 0.0649018 to 0.593563 kg but zero" in line and "[3 times: lines 68, 134, 200; also 'Link2', 'Link3']" in line
    fixes = [said(1, "joint 'j' axis has length 2, not 1; write xyz=\"0 0 1\"", "U206"),
             said(2, "joint 'k' axis has length 3, not 1; write xyz=\"1 0 0\"", "U206")]
    unnamed = [said(5, "the robot weighs 2 kg", "U399"), said(6, "the robot weighs 3 kg", "U399")]
    assert [len(group) for group in groups(fixes + unnamed)] == [1, 1, 1, 1]


def _random_texts(seed: int, count: int, alphabet: str, longest: int) -> list[str]:
    import random

    chance = random.Random(seed)
    return ["".join(chance.choice(alphabet) for _ in range(chance.randint(0, longest)))
            for _ in range(count)]


def test_figures_are_what_the_plain_pattern_finds():
    """_FIGURE is written to start with its first character (a search that skips to the next
    sign or digit); it finds what the pattern written plainly finds, in any text."""
    import re

    from urdftool.report.text_format import _FIGURE

    plain = re.compile(r"(?<![\w.+\-^/])[-+]?\d+(?:\.\d+)?(?:e[-+]?\d+)?(?![\w.]\w|\w)")
    texts = _random_texts(3, 20000, "0123456789.+-e^/ab_ '\"()x,;E\u0661\t", 24)
    texts += ["link 'l0': 1 kg in at most 4e-05 m^3 is at least 25,000 kg/m^3 (22,590)",
              "-5 +3 x-1 1.2.3 m^3 2e-3e4 /a/5 (7) 5. .5 ^2 1e 1e+ \u0661\u0662"]
    for text in texts:
        assert [(m.span(), m.group()) for m in _FIGURE.finditer(text)] == \
            [(m.span(), m.group()) for m in plain.finditer(text)], text


def test_where_a_missing_package_was_looked_for_is_written_once_per_file():
    from urdftool.errors import PackageNotFound

    def missing(name: str, line: int, part: str, file: str = "robot.urdf",
                severity: Severity = Severity.WARNING) -> Finding:
        error = PackageNotFound(name, ["package.xml above /ws/src/bot/urdf up to /ws",
                                       "package.xml below /ws"]).declared("bot", False)
        return Finding("U407", "mesh-package-not-found", severity,
                       f"link 'base' <{part}>: mesh 'package://{name}/m.stl': {error}",
                       Location(file, line), repeated=error.repeated)

    # (an error and a warning: two lines; of one severity, <visual> and <collision> are one)
    findings = [missing("meshes_a", 22, "visual"),
                missing("meshes_a", 29, "collision", severity=Severity.ERROR),
                missing("meshes_b", 40, "visual")]
    text = _text([FileResult("robot.urdf", findings),
                  FileResult("other.urdf", [missing("meshes_a", 5, "visual", "other.urdf")])])
    assert text.count("package.xml below /ws") == 3  # each package, in each file, once
    assert ("<collision>: mesh 'package://meshes_a/m.stl': package 'meshes_a' not found, and the "
            "package.xml of 'bot' does not declare it") in text
    assert "; looked in the places listed at line 22; pass --package meshes_a=PATH as said " \
        "there (mesh-package-not-found)" in text
    alike = _text([FileResult("robot.urdf", [missing("meshes_a", 22, "visual"),
                                             missing("meshes_a", 29, "collision")])])
    assert "(mesh-package-not-found) [2 times: lines 22, 29; also <collision>]" in alike
    assert text.count("looked in the places listed") == 1
    # the machine formats keep every message whole
    stream = io.StringIO()
    render("json", [FileResult("robot.urdf", findings)], stream)
    assert stream.getvalue().count("package.xml below /ws") == 3


def test_a_note_saying_why_a_file_was_not_checked_is_shown_with_notes_left_out():
    from urdftool.errors import PackageNotFound

    declared = str(PackageNotFound("sensors", ["package.xml below /ws"]).declared("bot"))
    why = Finding("U006", "package-not-found", Severity.INFO, declared, Location("bot.urdf.xacro", 9),
                  not_checked=True)
    other = Finding("U212", "zero-effort-or-velocity", Severity.INFO, "a note", Location("a.urdf", 3))
    results = [FileResult("bot.urdf.xacro", [why]), FileResult("a.urdf", [other])]
    assert results[0].unexpanded  # (the run exits 2 for it)
    text = _text(results, notes=False)
    assert "bot.urdf.xacro:9: info U006 package 'sensors' not found" in text
    assert "a note" not in text
    assert text.splitlines()[-1] == ("1 file checked, 1 not (a package it needs is not "
                                     "installed): 0 errors, 0 warnings, 1 note (1 note not shown: "
                                     "--notes shows them)")


def test_messages_alike_once_their_names_are_set_aside_give_the_same_figures():
    """A group whose messages are one text without their names (and give no value in double
    quotes) is written as its first message without looking for figures (_grouped's alike):
    they are the same figures, in the same order, wherever a name sits beside one."""
    import random

    from urdftool.report.text_format import _figures, _grouped

    chance = random.Random(5)
    pieces = _random_texts(11, 3000, "0123456789.+-e^/ab_ ()x,;E<>\u0661", 8)
    inside = "0123456789.+-e^/ab_()x,E\u0661"

    def name() -> str:
        letters = "".join(chance.choice(inside) for _ in range(chance.randint(0, 6)))
        kind = chance.random()
        if kind < 0.3:  # a tag: <a1>, </b.c-d>
            tag = chance.choice("ab_") + "".join(c for c in letters if c.isascii() and
                                                 (c.isalnum() or c in "_.-"))
            return f"<{chance.choice(['', '/'])}{tag}>"
        return f"'{letters}'" if kind < 0.65 else "/" + letters.replace(")", "")

    compared = 0  # alike pairs whose messages differ (in their names)
    for _ in range(12000):
        parts = chance.sample(pieces, chance.randint(1, 4))

        def message() -> str:
            return parts[0] + "".join(chance.choice(" (") + name() + part for part in parts[1:])

        group = [Finding("U399", "x", Severity.WARNING, message(), Location("r.urdf", line))
                 for line in (1, 2)]
        grouped = _grouped(group)
        if len(grouped) == 1 and grouped[0][1]:  # one group, alike
            compared += group[0].message != group[1].message
            first, second = (_figures(f.message) for f in group)
            assert [t for _, _, t in first] == [t for _, _, t in second], group
    assert compared > 500


def test_tags_in_angle_brackets_are_names_that_a_line_sets_aside():
    """session 18, read as a stranger (sam_bot_description, of the corpus): a camera plugin's
    nine ROS 1 parameters were nine U640 lines differing only in the tag (``<updateRate>``,
    ``<distortionK1>``...), each repeating the same evidence; U022's "<kinematic> in <link>"
    and "<gravity> in <link>" likewise. A tag is a name: one line naming the others. A tag
    with attributes, another file or another rule stays apart; the machine formats keep every
    finding."""
    def said(line: int, message: str, code: str = "U640", file: str = "r.urdf") -> Finding:
        return Finding(code, "x", Severity.WARNING, message, Location(file, line))

    ros1 = [said(380 + i, f"plugin 'cam' (gazebo_ros_camera): <{tag}> is the ROS 1 plugin's "
                          "name; 0 asks for what the ROS 2 one does without it (not what "
                          f"<{new}>0</{new}> asks): remove it")
            for i, (tag, new) in enumerate((("Cx", "cx"), ("Cy", "cy"), ("focalLength",
                                                                      "focal_length")))]
    effect = [said(5, "<kinematic> in <link> has no effect", "U022"),
              said(9, "<gravity> in <link> has no effect", "U022")]
    apart = [said(7, "<gravity> in <link> has no effect", "U022", "arm.xacro"),
             said(8, "<gazebo reference=x> in <link> has no effect", "U022"),
             said(9, "<gravity> in <link> has no effect", "U021")]
    results = [FileResult("r.urdf", ros1 + effect + apart)]
    lines = [line.strip() for line in _text(results).splitlines() if " U0" in line or " U6" in line]
    assert lines[0].endswith("[3 times: lines 380, 381, 382; also <Cy> (<cy>), <focalLength> "
                             "(<focal_length>)]"), lines
    assert "(not what <cx>0</cx> asks)" in lines[0]
    assert [line for line in lines if "U022" in line and "r.urdf" in line] == [
        "r.urdf:5: warning U022 <kinematic> in <link> has no effect (x) [2 times: lines 5, 9; "
        "also <gravity>]",
        "r.urdf:8: warning U022 <gazebo reference=x> in <link> has no effect (x)"], lines
    assert len(lines) == 5 and "arm.xacro:7: warning U022" in lines[2] and "U021" in lines[4], lines
    for kind, count in (("json", lambda out: len(json.loads(out)["diagnostics"])),
                        ("sarif", lambda out: len(json.loads(out)["runs"][0]["results"]))):
        stream = io.StringIO()
        render(kind, results, stream)
        assert count(stream.getvalue()) == 8, kind


def test_findings_naming_things_of_different_kinds_are_lines_of_their_own():
    """session 18, with tags as names (agilexrobotics/ugv_gazebo_sim's limo_xacro.xacro): "<pose>
    in <link>" and "<ambient>, <diffuse>... in <material>" were one line saying "<pose> in
    <link> [15 times; also <ambient>, ...]", as if each were in a <link>. Where findings name
    different things at two places, one a kind they fall into (a tag not one to one with the
    names differing most: the element they are in; the plugin of tags differing most), each
    kind is its own line; places going one to one (a transmission and its joint, a tag and
    the one suggested) stay one line, the other place's tag said beside each name."""
    def said(line: int, message: str) -> Finding:
        return Finding("U022", "x", Severity.WARNING, message, Location("r.xacro", line))

    def shown(findings) -> list[str]:
        return [line.strip().split(" U022 ", 1)[1] for line in
                _text([FileResult("r.xacro", findings)]).splitlines() if " U022 " in line]

    kinds = [said(35, "<pose> in <link> has no effect"), said(76, "<pose> in <link> has no effect")]
    kinds += [said(51 + i, f"<{tag}> in <material> has no effect")
              for i, tag in enumerate(("ambient", "diffuse", "specular"))]
    assert shown(kinds) == ["<pose> in <link> has no effect (x) [2 times: lines 35, 76]",
                            "<ambient> in <material> has no effect (x) [3 times: lines 51, 52, 53; "
                            "also <diffuse>, <specular>]"]
    plugins = [said(i, f"plugin '{plugin}': <{tag}> is ignored") for i, (plugin, tag) in
               enumerate((("a", "x"), ("a", "y"), ("a", "z"), ("b", "x")), start=1)]
    assert shown(plugins) == [
        "plugin 'a': <x> is ignored (x) [3 times: lines 1, 2, 3; also <y>, <z>]",
        "plugin 'b': <x> is ignored (x)"]
    meshes = [said(i, f"link '{link}' <{holder}>: mesh '{link}.{kind}' not found")
              for i, (link, holder, kind) in enumerate((
                  ("a", "visual", "dae"), ("a", "collision", "stl"), ("b", "visual", "dae"),
                  ("b", "collision", "stl"), ("c", "visual", "dae")), start=1)]
    assert shown(meshes) == [  # (a link and its mesh: "also" names both, session 21)
        "link 'a' <visual>: mesh 'a.dae' not found (x) [3 times: lines 1, 3, 5; also 'b' "
        "('b.dae'), 'c' ('c.dae')]",
        "link 'a' <collision>: mesh 'a.stl' not found (x) [2 times: lines 2, 4; also 'b' "
        "('b.stl')]"]
    pairs = [said(i, f"<{old}> is ignored; did you mean <{new}>?") for i, (old, new) in
             enumerate((("xyzOffsets", "xyz_offsets"), ("rpyOffsets", "rpy_offsets")), start=1)]
    assert shown(pairs) == ["<xyzOffsets> is ignored; did you mean <xyz_offsets>? (x) [2 times: "
                            "lines 1, 2; also <rpyOffsets> (<rpy_offsets>)]"]
    # (OpenQuadruped/spot_mini_mini: each tag in its own element, one to one, said with it)
    parents = [said(1, "<joint_properties> in <joint> has no effect"),
               said(2, "<contact_coefficients> in <collision> has no effect")]
    assert shown(parents) == ["<joint_properties> in <joint> has no effect (x) [2 times: lines 1, "
                              "2; also <contact_coefficients> (<collision>)]"]


def test_figures_folded_only_where_the_line_stays_true_and_readable():
    """Read as a stranger on robots new to the sweep: two figures differing folded into "min
    -1.2 to 2.8857 is above max -1.475 to 2.486" (five joints, each its own pair), a vector's
    coordinate into "(0.06525 -0.133 to 0.133 -0.056)", and 33,333 and 35,368 kg/m^3 into
    "33 to 35,333 to 368". Such a group is one line per message, each as it is; one figure
    standing alone still folds into its range."""
    def said(line: int, message: str, code: str = "U515") -> Finding:
        return Finding(code, "x", Severity.WARNING, message, Location("r.urdf", line))

    def shown(findings) -> list[str]:
        return [line.strip() for line in _text([FileResult("r.urdf", findings)]).splitlines()
                if " U" in line]

    pairs = shown([said(1, "joint 'a': min 2.044 is above max 0.54"),
                   said(2, "joint 'b': min -1.2 is above max -1.45")])
    assert [line.split(": ", 1)[1] for line in pairs] == [
        "warning U515 joint 'a': min 2.044 is above max 0.54 (x)",
        "warning U515 joint 'b': min -1.2 is above max -1.45 (x)"], pairs
    vectors = shown([said(1, "link 'l': centre of mass (0.06525 -0.133 -0.056) is 0.133 m out"),
                     said(2, "link 'r': centre of mass (0.06525 0.133 -0.056) is 0.133 m out")])
    assert len(vectors) == 2 and " to " not in " ".join(vectors), vectors
    thousands = shown([said(1, "link 'a': at least 35,368 kg/m^3", "U311"),
                       said(2, "link 'b': at least 33,333 kg/m^3", "U311")])
    assert len(thousands) == 2 and "35,368 kg" in thousands[0] and "33,333 kg" in thousands[1]
    places = shown([said(1, "link 'a' is defined 2 times (first at m.xacro:49)", "U101"),
                    said(2, "link 'b' is defined 2 times (first at m.xacro:137)", "U101")])
    assert len(places) == 2 and " to " not in " ".join(places), places  # (ABB's dual arms)
    alone = shown([said(1, "link 'a' has mass 0.5 kg", "U304"), said(2, "link 'b' has mass 2 kg",
                                                                     "U304")])
    assert len(alone) == 1 and "has mass 0.5 to 2 kg" in alone[0], alone
    same = shown([said(1, "joint 'a': min 1 is above max 0"), said(2, "joint 'b': min 3 is above "
                  "max 2"), said(3, "joint 'c': min 1 is above max 0")])
    assert len(same) == 2 and same[0].endswith("[2 times: lines 1, 3; also 'c']"), same


def test_names_holding_the_grouped_name_in_different_patterns_are_lines_of_their_own():
    """session 18 (fresh18's OpenLoong): a link's mesh missing, 'meshes/base_link.STL', and nine
    whose package is written twice, 'loong_control/loong_control/meshes/Link_arm_r_01.STL',
    were one line saying only the first: "also" names the links, and the meshes' other pattern
    was nowhere. Where each finding's name at another place holds the name the line groups by
    (a mesh named after its link), a pattern of its own is a line of its own; names that do
    not hold it (a transmission and its joint) stay one line."""
    def said(line: int, link: str, mesh: str) -> Finding:
        return Finding("U408", "x", Severity.ERROR,
                       f"link '{link}' <visual>: mesh '{mesh}' not found", Location("r.urdf", line))

    def shown(findings) -> list[str]:
        return [line.strip().split(" U408 ", 1)[1] for line in
                _text([FileResult("r.urdf", findings)]).splitlines() if " U408 " in line]

    links = ["base_link", "arm_01", "arm_02", "arm_03"]
    found = [said(1, links[0], "package://p/meshes/base_link.STL")]
    found += [said(2 + i, link, f"package://p/p/meshes/{link}.STL")
              for i, link in enumerate(links[1:])]
    assert shown(found) == [
        "link 'base_link' <visual>: mesh 'package://p/meshes/base_link.STL' not found (x)",
        "link 'arm_01' <visual>: mesh 'package://p/p/meshes/arm_01.STL' not found (x) [3 times: "
        "lines 2, 3, 4; also 'package://p/p/meshes/arm_02.STL', 'package://p/p/meshes/arm_03.STL']"]
    one_pattern = [said(1 + i, link, f"package://p/meshes/{link}.STL")
                   for i, link in enumerate(links)]
    assert len(shown(one_pattern)) == 1
    shared = [said(1 + i, link, "package://p/meshes/part.STL") for i, link in enumerate(links)]
    assert len(shown(shared)) == 1  # (a mesh not named after its link: one line, as before)


def test_a_grouped_line_names_what_the_reader_needs_the_other_findings_for():
    """session 20, read as a stranger: AuboRobot's aubo_e3.urdf, three meshes missing, read
    "[3 times: lines 67, 129, 160; also 'wrist1_Link', 'wrist2_Link']": the links, where the
    reader needs the files to find. A name another place's name holds in one pattern (a link
    in its mesh's path, a joint in its transmission's name) is said by that one; names that
    hold none of each other are said together ('b' ('b_part.stl')); a name the same in all
    (one mesh used by three links) is not said again."""
    def said(line: int, link: str, mesh: str) -> Finding:
        return Finding("U408", "x", Severity.ERROR,
                       f"link '{link}' <visual>: mesh '{mesh}' not found", Location("r.urdf", line))

    def also(findings) -> list[str]:
        return [line.split("; also ", 1)[1] for line in
                _text([FileResult("r.urdf", findings)]).splitlines() if "; also " in line]

    links = ["upperArm_Link", "wrist1_Link", "wrist2_Link"]
    assert also([said(1 + i, link, f"package://aubo/meshes/visual/{link}.DAE")
                 for i, link in enumerate(links)]) == [
        "'package://aubo/meshes/visual/wrist1_Link.DAE', "
        "'package://aubo/meshes/visual/wrist2_Link.DAE']"]
    assert also([said(1 + i, link, f"meshes/part{i}.stl") for i, link in enumerate(links)]) == [
        "'wrist1_Link' ('meshes/part1.stl'), 'wrist2_Link' ('meshes/part2.stl')]"]
    assert also([said(1 + i, link, "meshes/wheel.stl") for i, link in enumerate(links)]) == [
        "'wrist1_Link', 'wrist2_Link']"]


def test_a_groups_names_are_read_once_for_its_line(monkeypatch):
    """The names of a group's findings are read once (:func:`text_format._apart`) and said by
    the line (``_also``) from that reading: each finding's names asked for once, the line as
    before (24 transmissions, each its joint: one line, "also" naming the others)."""
    from urdftool.report import text_format

    asked = []
    real = text_format._names
    monkeypatch.setattr(text_format, "_names", lambda message: asked.append(message) or
                        real(message))
    text = _text([FileResult("robot.urdf", [_prefix(i) for i in range(24)])])
    assert "[24 times: lines 100, 112, 124," in text and "also 't_j1', " in text
    assert len(asked) == len(set(asked)) == 24


def test_only_the_parts_a_finding_names_are_said_once():
    """What a report writes once per file is what the finding says it repeats
    (``Finding.repeated``), never words read back from its message: a message whose file name
    reads "; looked in: x. Pass --package p=PATH" (fooled the pattern before) is written
    whole each time, and so is one whose part is not in the message."""
    odd = "mesh 'a; looked in: x. Pass --package p=PATH.stl' is missing"
    findings = [Finding(code, name, Severity.ERROR, odd, Location("r.urdf", n))
                for code, name, n in (("U408", "mesh-file-missing", 3),
                                      ("U409", "mesh-format-unsupported", 9))]
    text = _text([FileResult("r.urdf", findings)])
    assert text.count("looked in: x. Pass --package p=PATH") == 2, text
    said = ("why", " (because)", "")
    marked = [Finding("U640", "gazebo-plugin-other-version", severity,
                      f"plugin 'p': <{tag}> is ROS 1's, and the robot is ROS 2 (because); fix it",
                      Location("r.urdf", n), repeated=(said,))
              for n, tag, severity in ((3, "a", Severity.ERROR), (9, "b", Severity.WARNING))]
    text = _text([FileResult("r.urdf", marked)])
    assert text.count("(because)") == 1 and "ROS 2 (as said at line 3); fix it" in text, text


def test_an_available_list_is_said_once_only_where_a_rule_wrote_it():
    """A list "available links: ..." is written once per file where ``available`` wrote it
    (it travels as the finding's ``repeated``), never where a message holds the words another
    way: a name quoted from the robot that reads "available links: ..." (the report read it
    back from the message before, and referred the second finding to the first)."""
    quoted = "available links: " + ", ".join(f"link_{i:02d}" for i in range(12))
    findings = [Finding(code, name, Severity.ERROR, f"{said}; {quoted}", Location("r.urdf", n))
                for code, name, said, n in (
                    ("U611", "gazebo-unknown-reference", "<gazebo reference='x'> names nothing", 3),
                    ("U501", "transmission-unknown-joint", "transmission 't' names 'y'", 9))]
    text = _text([FileResult("r.urdf", findings)])
    assert text.count("link_00, link_01") == 2 and "listed at" not in text, text
    written = available("links", "x", [f"link_{i:02d}" for i in range(12)])
    assert written == quoted and written.repeated == (("available", quoted, "12 links"),)
    assert ("names x; " + written).repeated == written.repeated  # kept through +


def test_fixes_only_unsafe_and_only_of_hidden_notes_are_said_so():
    # "[~] 1 more with --unsafe-fixes" after "no problems found" named more than nothing, of
    # a note the report did not show (mastering_ros' cool_arm)
    from urdftool.diagnostics import Fix, Finding, Location, Severity
    from urdftool.lint.engine import FileResult
    from urdftool.report.text_format import lines

    note = Finding("U999", "x", Severity.INFO, "a note", Location("r.urdf", 1),
                   Fix("do", (), safe=False))
    text = ["".join(span for span, _ in line) for line in lines([FileResult("r.urdf", [note])],
                                                                notes=False)]
    assert text[-1] == "[~] 1 fixable with --unsafe-fixes; 1 of them in notes not shown"
    shown = ["".join(span for span, _ in line) for line in lines([FileResult("r.urdf", [note])])]
    assert shown[-1] == "[~] 1 fixable with --unsafe-fixes"


def test_an_also_list_of_long_names_shows_the_first_few_and_how_many():
    """AgiBot's G1 (43 links of one macro whose meshes' package is not found: U407) and Nao
    (39) said twelve links each with its package:// path after "also": 1,900 characters on
    one line. Long names are cut to the width of a line (three at least), short ones to
    twelve, each list then saying how many in all."""
    def said(line: int, message: str) -> Finding:
        return Finding("U407", "mesh-package-not-found", Severity.WARNING, message,
                       Location("nao.urdf", line))

    long = [said(25 + 26 * i, f"link 'Link{i}' <visual>: mesh 'V40_{i}/a_mesh_of_a_long_name_"
                              "in_a_folder_of_its_own.dae' not found") for i in range(39)]
    [line] = [line for line in _text([FileResult("nao.urdf", long)]).splitlines() if "U407" in line]
    also = line.split("; also ")[1]
    assert also == ("'Link1' ('V40_1/a_mesh_of_a_long_name_in_a_folder_of_its_own.dae'), "
                    "'Link2' ('V40_2/a_mesh_of_a_long_name_in_a_folder_of_its_own.dae'), "
                    "'Link3' ('V40_3/a_mesh_of_a_long_name_in_a_folder_of_its_own.dae'), "
                    "... (38 in all)]"), also
    # a folder they share, the first's written in full, is "..." in the list
    shared = [said(25 + 26 * i, f"link 'Link{i}' <visual>: mesh 'package://nao_meshes/meshes/V40/"
                                f"Link{i}_long_mesh_name.dae': package 'nao_meshes' not found")
              for i in range(39)]
    [line] = [line for line in _text([FileResult("nao.urdf", shared)]).splitlines()
              if "U407" in line]
    assert "mesh 'package://nao_meshes/meshes/V40/Link0_long_mesh_name.dae'" in line
    assert line.split("; also ")[1] == (
        "'.../Link1_long_mesh_name.dae', '.../Link2_long_mesh_name.dae', "
        "'.../Link3_long_mesh_name.dae', '.../Link4_long_mesh_name.dae', "
        "'.../Link5_long_mesh_name.dae', '.../Link6_long_mesh_name.dae', ... (38 in all)]"), line
    # with the link each mesh goes with (Shadow's UR10: six links, one package folder)
    arm = [said(11 + 30 * i, f"link 'ra_{part}_link' <visual>: mesh 'package://ur_description/"
                             f"meshes/ur10/visual/{mesh}.dae': package 'ur_description' not found")
           for i, (part, mesh) in enumerate((("base", "base"), ("shoulder", "shoulder"),
                                              ("upper_arm", "upperarm"), ("forearm", "forearm"),
                                              ("wrist_1", "wrist1"), ("wrist_2", "wrist2"),
                                              ("wrist_3", "wrist3")))]
    [line] = [line for line in _text([FileResult("ur10.urdf", arm)]).splitlines() if "U407" in line]
    assert line.endswith("also 'ra_shoulder_link' ('.../shoulder.dae'), 'ra_upper_arm_link' "
                         "('.../upperarm.dae'), 'ra_forearm_link' ('.../forearm.dae'), "
                         "'ra_wrist_1_link' ('.../wrist1.dae'), 'ra_wrist_2_link' "
                         "('.../wrist2.dae'), ... (6 in all)]"), line
    # a list within its width is written as it is
    [line] = [line for line in _text([FileResult("ur10.urdf", arm[:3])]).splitlines()
              if "U407" in line]
    assert line.endswith("also 'ra_shoulder_link' ('package://ur_description/meshes/ur10/visual/"
                         "shoulder.dae'), 'ra_upper_arm_link' ('package://ur_description/meshes/"
                         "ur10/visual/upperarm.dae')]"), line
    short = [said(7, f"link 'Link{i}' has no limit") for i in range(39)]
    [line] = [line for line in _text([FileResult("nao.urdf", short)]).splitlines() if "U407" in line]
    assert line.endswith("also 'Link1', 'Link2', 'Link3', 'Link4', 'Link5', 'Link6', 'Link7', "
                         "'Link8', 'Link9', 'Link10', 'Link11', 'Link12', ... (38 in all)]"), line


def test_lines_a_group_is_written_in_are_in_the_file_s_order():
    """PAROL6's ros2_control macro: each joint's command interface min and max beyond its
    <limit> (U515), each its own figures, so each its own line; the lines were written group
    by group (every min, then every max: 49, 71, 105, 50, 89, 106). They are in the order of
    the file, the first line of a group where it stands."""
    def bound(line: int, joint: str, name: str, value: float, edge: float) -> Finding:
        return Finding("U515", "ros2-control-limits", Severity.WARNING,
                       f"ros2_control joint '{joint}' position {name} is {value:g}, beyond the "
                       f"URDF <limit> ({edge:g})", Location("parol6.ros2_control.xacro", line))

    findings = [bound(49, "joint_L1", "min", -3.14159, -1.7),
                bound(50, "joint_L1", "max", 3.14159, 1.7),
                bound(71, "joint_L2", "min", -0.98, -0.802444),
                bound(89, "joint_L3", "max", 1.3, 1.29),
                bound(105, "joint_L4", "min", -3.14159, -2.52944),
                bound(106, "joint_L4", "max", 3.14159, 1.84911)]
    text = _text([FileResult("parol6.urdf.xacro", findings)])
    lines = [int(line.split(":")[1]) for line in text.splitlines() if "U515" in line]
    assert lines == [49, 50, 71, 89, 105, 106], text
