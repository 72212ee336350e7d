"""description.xacro: what the in-process expansion relies on in the xacro library."""

from __future__ import annotations

import pytest

from urdftool.description.load import load
from urdftool.errors import LoadError


@pytest.mark.parametrize("text", ["0 0 0.1", "base_link", "", " spaced  out ", "a{b}(c)",
                                  "package://pkg/mesh.stl", "1e-3", "true"])
def test_xacro_returns_text_without_a_dollar_as_it_is(text):
    # The expansion hands such text back without running xacro's lexer (description.xacro's
    # eval_text): right only while xacro itself returns it unchanged, as checked here.
    import xacro

    assert xacro.eval_text(text, xacro.Table()) == text


def test_attributes_keep_their_order_values_and_namespaces_after_expansion(tmp_path):
    (tmp_path / "r.urdf.xacro").write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro" '
        'xmlns:gz="http://gazebosim.org/schema">\n'
        '  <xacro:property name="w" value="0.5"/>\n'
        '  <link name="a"><visual><geometry><box size="${w} 1 $${x}" gz:kind="plain"/>'
        '</geometry></visual></link>\n</robot>\n')
    robot = load(tmp_path / "r.urdf.xacro")
    box = robot.root.find("link/visual/geometry/box")
    assert list(box.attrib.items()) == [("size", "0.5 1 ${x}"),
                                        ("{http://gazebosim.org/schema}kind", "plain")]
    assert robot.locate(box).line == 3


def _package(folder, build_tool):
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "package.xml").write_text(
        f'<package format="2"><name>{folder.name}</name><version>1.0.0</version>'
        f'<buildtool_depend>{build_tool}</buildtool_depend></package>')
    return folder


_ROS1_ROBOT = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <property name="w" value="0.5"/>
  <include filename="$(find arm)/urdf/parts.xacro"/>
  <macro name="box_link" params="name">
    <link name="${name}"><visual><geometry><box size="${w} 1 1"/></geometry></visual></link>
  </macro>
  <if value="true"><box_link name="base"/></if>
  <unless value="true"><link name="never"/></unless>
  <part parent="base"/>
  <gazebo><include><uri>model://sun</uri></include></gazebo>
</robot>
"""
_ROS1_PARTS = """<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <macro name="part" params="parent">
    <link name="tool"/>
    <joint name="j" type="fixed"><parent link="${parent}"/><child link="tool"/></joint>
  </macro>
</robot>
"""


def test_a_catkin_package_is_expanded_as_ros1_xacro_read_unprefixed_tags(tmp_path):
    # ROS 1's xacro up to Melodic (1.13) read include, property, macro, arg, if, unless and
    # insert_block, and macro calls, without the xacro: prefix; Noetic's and ROS 2's do not.
    arm = _package(tmp_path / "arm", "catkin")
    (arm / "urdf").mkdir()
    (arm / "urdf" / "parts.xacro").write_text(_ROS1_PARTS)
    (arm / "urdf" / "r.urdf.xacro").write_text(_ROS1_ROBOT)
    robot = load(arm / "urdf" / "r.urdf.xacro")
    assert [link.get("name") for link in robot.root.iter("link")] == ["base", "tool"]
    assert robot.root.find("link/visual/geometry/box").get("size") == "0.5 1 1"
    # Gazebo's <include> holds an element: never xacro's (ROS 1's is_include)
    assert robot.root.find("gazebo/include/uri").text == "model://sun"
    warned = [(note.location.file, note.location.line, note.message) for note in robot.notes
              if note.kind == "xacro-warning"]
    assert [(file.rsplit("/", 1)[-1], line) for file, line, _ in warned] == [
        ("r.urdf.xacro", 2), ("parts.xacro", 2)]
    assert "<property> without the xacro: prefix (and 6 more in this file)" in warned[0][2]
    assert "Noetic (1.14)" in warned[0][2]


def test_a_catkin_file_only_melodics_xacro_fails_on_is_expanded_as_noetics(tmp_path):
    # curiosity_mars_rover (Noetic): its macro 'camera' writes Gazebo's <camera name="camera">,
    # which Melodic's xacro reads as a call of that macro ('Invalid parameter "name"'); Noetic's
    # expands the file. The robot is checked so, and Melodic's failure is a warning there.
    arm = _package(tmp_path / "arm", "catkin")
    (arm / "urdf").mkdir()
    (arm / "urdf" / "r.urdf.xacro").write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:macro name="camera" params="camera_name">\n'
        '    <link name="${camera_name}"/>\n'
        '    <gazebo reference="${camera_name}"><sensor type="camera" name="s">\n'
        '      <camera name="camera"/></sensor></gazebo>\n'
        '  </xacro:macro>\n'
        '  <xacro:camera camera_name="mast"/>\n</robot>\n')
    robot = load(arm / "urdf" / "r.urdf.xacro")
    assert robot.root.find("gazebo/sensor/camera").get("name") == "camera"
    [warned] = [note for note in robot.notes if note.kind == "xacro-warning"]
    assert warned.location.line == 5 and "Melodic (1.13) fails here: Invalid parameter" \
        in warned.message and "Noetic (1.14)" in warned.message
    # a file that fails as Noetic reads it too keeps its failure, as Melodic says it
    text = (arm / "urdf" / "r.urdf.xacro").read_text().replace(
        "</robot>", '<link name="${nowhere}"/></robot>')
    (arm / "urdf" / "r.urdf.xacro").write_text(text)
    with pytest.raises(LoadError, match='Invalid parameter "name"'):
        load(arm / "urdf" / "r.urdf.xacro")
    # xacro's own tags unprefixed are Melodic's file (robotis_op's constants.xacro, a property
    # 'lb-in-in_kg-m-m'): Noetic's xacro would leave them unread, which is no expansion of it
    (arm / "urdf" / "c.xacro").write_text(
        '<robot name="c" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <property name="lb-in-in" value="0.04"/>\n  <link name="base"/>\n</robot>\n')
    with pytest.raises(LoadError, match="valid python identifiers"):
        load(arm / "urdf" / "c.xacro")


@pytest.mark.parametrize("build_tool", ["ament_cmake", None])
def test_other_packages_are_expanded_as_ros2_xacro_reads_them(tmp_path, build_tool):
    arm = _package(tmp_path / "arm", build_tool) if build_tool else tmp_path / "arm"
    (arm / "urdf").mkdir(parents=True)
    (arm / "urdf" / "r.urdf.xacro").write_text(
        '<robot name="r"><property name="w" value="1"/><include filename="parts.xacro"/>'
        '<link name="base"/></robot>')
    robot = load(arm / "urdf" / "r.urdf.xacro")
    assert robot.root.find("include") is not None  # ROS 2's xacro leaves such tags as they are
    assert robot.root.find("property") is not None
    assert not [note for note in robot.notes if note.kind == "xacro-warning"]


def test_a_macro_used_before_its_definition_is_told_where_it_is_defined(tmp_path):
    # xacro up to Lunar read every definition first (legacy order); since Melodic it expands
    # in document order, and the use fails as an unknown macro
    from urdftool.errors import LoadError

    (tmp_path / "r.urdf.xacro").write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:part/>\n'
        '  <xacro:macro name="part">\n'
        '    <link name="base"/>\n'
        '  </xacro:macro>\n'
        '</robot>\n')
    with pytest.raises(LoadError) as raised:
        load(tmp_path / "r.urdf.xacro")
    assert raised.value.location.line == 2
    assert "it is defined further on (its body begins at " in str(raised.value)
    assert "r.urdf.xacro:4)" in str(raised.value) and "--legacy" in str(raised.value)
    assert raised.value.certain is True  # no ROS 1 package: every xacro since 2018 fails
    # in a catkin package, ROS 1's xacro up to Lunar (Kinetic's default order) expands it:
    # not certain (U005 a warning). allegro_hand_ros_v4 (its README: ROS Kinetic) and
    # cassie_description were errors on their 4 robots
    (tmp_path / "package.xml").write_text(
        '<package format="2"><name>r</name><buildtool_depend>catkin</buildtool_depend></package>')
    with pytest.raises(LoadError) as raised:
        load(tmp_path / "r.urdf.xacro")
    assert raised.value.certain is False and "up to Lunar (Kinetic's)" in str(raised.value)


@pytest.mark.parametrize("declared", [True, False])
def test_a_missing_package_the_package_xml_declares_is_said_to_be_not_installed(tmp_path,
                                                                                declared):
    # husky_description's package.xml declares fath_pivot_mount_description (another
    # repository): missing here, it is a dependency not installed, not a misspelt name
    from urdftool.errors import LoadError

    (tmp_path / ".git").mkdir()
    depend = "<exec_depend>mount_description</exec_depend>" if declared else ""
    (tmp_path / "package.xml").write_text(
        f'<package format="2"><name>bot_description</name>{depend}</package>')
    (tmp_path / "bot.urdf.xacro").write_text(
        '<robot name="b" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:include filename="$(find mount_description)/urdf/mount.xacro"/>\n</robot>\n')
    with pytest.raises(LoadError) as raised:
        load(tmp_path / "bot.urdf.xacro")
    assert raised.value.location.line == 2
    said = "the package.xml of 'bot_description' declares it as a dependency"
    assert (said in str(raised.value)) is declared
    undeclared = "the package.xml of 'bot_description' does not declare it, so rosdep would"
    assert (undeclared in str(raised.value)) is not declared
    assert "Pass --package mount_description=PATH" in str(raised.value)


def test_an_include_of_a_package_uri_says_xacro_does_not_resolve_it(tmp_path):
    """example-robot-data's hector quadrotor_base.xacro: the hint was lost (the URI is a path by
    then, its // one /) and the OSError printed twice ("... [Errno 2] No such file ...")."""
    from urdftool.errors import LoadError

    (tmp_path / "robot.xacro").write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<xacro:include filename="package://pkg/urdf/base.xacro"/></robot>')
    with pytest.raises(LoadError) as caught:
        load(str(tmp_path / "robot.xacro"))
    message = caught.value.message
    assert "does not resolve package:// URIs" in message and "Errno" not in message, message
    assert message.endswith("write '$(find pkg)/urdf/base.xacro'"), message


def test_an_include_not_found_says_which_include_and_where_it_looked(tmp_path):
    """Stretch's batch/guthrie/urdf/stretch_description_dex.xacro includes
    stretch_dex_wrist.xacro, which its folder lacks: "No such file or directory: PATH" named
    neither the include as written nor that the path was where xacro looked for it. Said once
    ("not found", not also "No such file or directory"), the place left out when the include
    writes it."""
    (tmp_path / "urdf").mkdir()
    (tmp_path / "urdf" / "robot.xacro").write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<xacro:include filename="wrist.xacro"/></robot>')
    with pytest.raises(LoadError) as caught:
        load(str(tmp_path / "urdf" / "robot.xacro"))
    assert caught.value.message == (f"xacro:include 'wrist.xacro' not found (looked at "
                                    f"{tmp_path / 'urdf' / 'wrist.xacro'})")
    gone = tmp_path / "gone.xacro"
    (tmp_path / "urdf" / "robot.xacro").write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        f'<xacro:include filename="{gone}"/></robot>')
    with pytest.raises(LoadError) as caught:
        load(str(tmp_path / "urdf" / "robot.xacro"))
    assert caught.value.message.startswith(f"xacro:include '{gone}' not found; "), \
        caught.value.message


@pytest.mark.parametrize("given, said", [({}, True), ({"arm": "wx200"}, False)])
def test_an_include_naming_an_empty_argument_says_which(tmp_path, given, said):
    """Interbotix's locobot built without arm_model includes 'arms/.urdf.xacro', which xacro
    reports only as not found: the argument the path names, empty, is said."""
    (tmp_path / "robot.xacro").write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<xacro:arg name="arm" default=""/>'
        '<xacro:include filename="arms/$(arg arm).urdf.xacro"/></robot>')
    with pytest.raises(LoadError) as caught:
        load(str(tmp_path / "robot.xacro"), xacro_args=given)
    message = caught.value.message
    assert "xacro:include 'arms/$(arg arm).urdf.xacro' not found (looked at " in message, message
    assert ("names argument 'arm', which is empty here: pass arm:=VALUE" in message) == said, \
        message


def test_an_include_of_an_absolute_path_found_nowhere_says_it_is_absolute(tmp_path):
    """uned_crazyflie_ros_pkg's crazyflie2.xacro includes /home/kiko-hp-omen/RoboticPark/...:
    xacro says only 'No such file or directory'; the path is absolute, there only on its
    author's machine. A relative path that is missing is not said to be absolute."""
    for written, said in (("/nowhere-at-all/multirotor_base.xacro", True), ("parts/gone.xacro", False)):
        (tmp_path / "robot.xacro").write_text(
            '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
            f'<xacro:include filename="{written}"/></robot>')
        with pytest.raises(LoadError) as caught:
            load(str(tmp_path / "robot.xacro"))
        message = caught.value.message
        assert f"xacro:include '{written}' not found" in message, message
        assert ("the include names an absolute path, there only on the machine it was written "
                "on" in message) == said, message


def test_an_include_written_relative_to_the_repository_root_says_where_it_is(tmp_path):
    """Upkie's xacro/upkie.xacro includes "xacro/utils/box_inertia.xacro", written from the
    repository root (its build, xacrodoc, runs there); xacro reads it beside the including
    file: "No such file or directory: xacro/xacro/utils/box_inertia.xacro" left the reader to
    work out why."""
    from urdftool.errors import LoadError

    (tmp_path / ".git").mkdir()
    (tmp_path / "xacro" / "utils").mkdir(parents=True)
    (tmp_path / "xacro" / "utils" / "box.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"/>')
    (tmp_path / "xacro" / "top.xacro").write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<xacro:include filename="xacro/utils/box.xacro"/><link name="a"/></robot>')
    with pytest.raises(LoadError) as caught:
        load(str(tmp_path / "xacro" / "top.xacro"))
    message = caught.value.message
    assert ("xacro reads an include beside the file including it; 'xacro/utils/box.xacro' is "
            "there from the repository's root") in message, message
    # not certain (U005 a warning): the tool run from there reads it (upkie's Makefile runs
    # xacrodoc from the root); it was an error on both of upkie's robots
    assert caught.value.certain is False
    # an include missing everywhere gets no such advice, and is certain
    (tmp_path / "xacro" / "top.xacro").write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<xacro:include filename="xacro/utils/gone.xacro"/><link name="a"/></robot>')
    with pytest.raises(LoadError) as caught:
        load(str(tmp_path / "xacro" / "top.xacro"))
    assert "beside the file including it" not in caught.value.message
    assert caught.value.certain is True


def test_an_include_written_with_cwd_is_not_certain_where_it_is_there_from_a_folder_above(
        tmp_path, monkeypatch):
    """ridgeback-baxter's left_end_effector.urdf.xacro includes
    "$(cwd)/src/baxter/.../rethink_electric_gripper.xacro", for xacro run from its catkin
    workspace: run from the repository root it is missing, which said nothing certain."""
    from urdftool.errors import LoadError

    (tmp_path / ".git").mkdir()
    workspace = tmp_path / "ws"
    (workspace / "src" / "grip").mkdir(parents=True)
    (workspace / "src" / "grip" / "grip.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"/>')
    (workspace / "src" / "arm").mkdir(parents=True)
    top = workspace / "src" / "arm" / "arm.xacro"
    top.write_text('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
                   '<xacro:include filename="$(cwd)/src/grip/grip.xacro"/><link name="a"/></robot>')
    monkeypatch.chdir(tmp_path)
    with pytest.raises(LoadError) as caught:
        load(str(top))
    assert not caught.value.certain
    assert caught.value.message.endswith(
        "(looked at src/grip/grip.xacro): written with $(cwd), the folder xacro runs from; it is "
        "there when xacro runs from 'ws'")
    # from the workspace it is read; a file there from no folder stays certain
    monkeypatch.chdir(workspace)
    assert load(str(top)).links
    top.write_text(top.read_text().replace("grip/grip.xacro", "grip/gone.xacro"))
    monkeypatch.chdir(tmp_path)
    with pytest.raises(LoadError) as caught:
        load(str(top))
    assert caught.value.certain


def test_xacro_warnings_are_not_prefixed_warning_twice(tmp_path):
    # RealMan's MoveIt configs: 'warning U010 warning: Using load_yaml() directly is
    # deprecated. Use xacro.load_yaml() instead.'
    from urdftool.description.load import load

    (tmp_path / "j.yaml").write_text("a: 1\n")
    path = tmp_path / "r.urdf.xacro"
    path.write_text('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
                    '<xacro:property name="j" value="${load_yaml(\'j.yaml\')[\'a\']}"/>'
                    '<link name="base${j}"/></robot>')
    messages = [note.message for note in load(path).notes if note.kind == "xacro-warning"]
    assert messages == ["Using load_yaml() directly is deprecated. Use xacro.load_yaml() "
                        "instead."]


def test_xacros_own_warnings_are_located_where_the_expansion_was(tmp_path):
    """xacro prints its warnings without a line ('Using load_yaml() directly is deprecated',
    'redefining global symbol: pi'): each is located at the element being expanded when xacro
    wrote it, and a deprecated name at its use written at or above that element (a property's
    value is evaluated where it is first used, a line below)."""
    from urdftool.description.load import load

    (tmp_path / "j.yaml").write_text("a: 1\n")
    path = tmp_path / "r.urdf.xacro"
    path.write_text('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                    '  <xacro:property name="pi" value="3.14"/>\n'
                    '  <xacro:macro name="m" params="p">\n'
                    '    <xacro:property name="j" value="${load_yaml(p)[\'a\']}"/>\n'
                    '    <link name="base${j}"/>\n'
                    '  </xacro:macro>\n'
                    '  <xacro:m p="j.yaml"/>\n'
                    '</robot>\n')
    found = {note.message.split()[0]: note.location.line for note in load(path).notes
             if note.kind == "xacro-warning"}
    assert found == {"redefining": 2, "Using": 4}, found


def _run(program: str, *paths) -> list[str]:
    import os
    import subprocess
    import sys

    environment = {**os.environ, "PYTHONPATH": os.pathsep.join(
        [*map(str, paths), os.environ.get("PYTHONPATH", "")])}
    done = subprocess.run([sys.executable, "-c", program], capture_output=True, text=True,
                          timeout=120, env=environment)
    assert done.returncode == 0, done.stderr
    return done.stdout.split()


def test_an_unknown_substitution_is_said_once_by_its_exception_name(tmp_path):
    """xacro writes ``f"{type(e)}: {e}"`` and ``e`` again: "<class 'xacro.substitution_args.
    SubstitutionException'>: Unknown substitution command [x]. ... Unknown substitution command
    [x]. ..." (my-zzy/am_description's ``$(controllers_yaml_path)``, a placeholder its launch file
    fills); said once, the class by its name."""
    said = _load_error(tmp_path, '<robot name="r"><link name="a"/>\n'
                       '  <gazebo><plugin name="p" filename="x"><parameters>$(controllers_yaml_path)'
                       '</parameters></plugin></gazebo>\n</robot>\n').message
    assert said.startswith("SubstitutionException: Unknown substitution command "
                           "[controllers_yaml_path]. Valid commands are"), said
    assert said.count("Unknown substitution command") == 1 and "<class" not in said, said


def test_a_macro_call_giving_a_parameter_it_lacks_names_those_it_takes(tmp_path):
    """xacro says 'Invalid parameter "use_mock_hardware"' at the call (adv4ncr/motoman_ROS2's
    hc10.xacro calls motoman_ros2_control, whose parameter is mock_hardware): the macro's
    parameters are said, the close one first."""
    error = _load_error(tmp_path, '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                        '  <xacro:macro name="arm" params="prefix mock_hardware:=^|false">'
                        '<link name="${prefix}a"/></xacro:macro>\n'
                        '  <xacro:arm prefix="r1_" use_mock_hardware="true"/>\n</robot>\n')
    said, _, taken = error.message.partition("; the macro called here ('arm') takes no "
                                             "parameter of that name: ")
    assert (said, taken, error.location.line) == (
        'Invalid parameter "use_mock_hardware"',
        "did you mean 'mock_hardware'? available parameters: mock_hardware, prefix", 3)


def test_a_macro_call_lacking_a_parameter_says_what_it_lacks(tmp_path):
    """xacro says "Undefined parameters [velocity]" at the call (ABB's irb_120_dual.urdf.xacro
    calls irb_120_arm, which gained a velocity parameter, without it): said as what it means."""
    error = _load_error(tmp_path, '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                        '  <xacro:macro name="arm" params="prefix velocity"><link name="${prefix}a"/>'
                        '</xacro:macro>\n  <xacro:arm prefix="r1_"/>\n</robot>\n')
    assert error.message == ("Undefined parameters [velocity]: the macro called here ('arm') has "
                             'velocity '
                             'without a default, and the call gives it no value; pass '
                             'velocity="..."'), error.message
    assert error.location.line == 3


def _load_error(folder, text: str):
    """The LoadError of loading ``text`` as ``folder``/r.urdf.xacro."""
    from urdftool.errors import LoadError

    (folder / "r.urdf.xacro").write_text(text)
    with pytest.raises(LoadError) as raised:
        load(folder / "r.urdf.xacro")
    return raised.value



@pytest.mark.parametrize("source", [b'<robot name="r"><link name="a"><visual/></link></robot>',
                                    b'<robot name="r" xmlns:urdftool-loc="urn:loc:9:9:9">'
                                    b'<link name="a"/></robot>'])
def test_a_location_stamp_is_the_attribute_setattribute_makes_with_its_local_name(source):
    # The stamps are made as minidom's setAttribute makes them, their local name given (one
    # without it is found by an AttributeError at each asking): the same nodes, names, values
    # and clones, whatever the source writes.
    import xml.dom.minidom

    from urdftool.description.xacro import STAMP, _StampingBuilder

    stamped = _StampingBuilder(0).parseString(source)
    plain = xml.dom.minidom.parseString(source)
    for element, other in zip(stamped.getElementsByTagName("*"),
                              plain.getElementsByTagName("*"), strict=True):
        other.setAttribute(STAMP, element.getAttribute(STAMP))
        for node, made in ((element, other), (element.cloneNode(True), other.cloneNode(True))):
            assert [(a.name, a.namespaceURI, a.localName, a.prefix, a.value)
                    for a in node.attributes.values()] == [
                (a.name, a.namespaceURI, a.localName, a.prefix, a.value)
                for a in made.attributes.values()]
        assert element.getAttributeNode(STAMP)._localName == "urdftool-loc"
    assert stamped.documentElement.getAttribute(STAMP).startswith("urn:loc:0:1:")


@pytest.mark.parametrize("body, undefined", [
    ('<link name="${nope}"/>', True),  # a property (Python's NameError)
    ('<xacro:wheel side="l"/>', True),  # a macro
    ('<xacro:macro name="m" params="x:=^"><link name="a"/></xacro:macro><xacro:m/>', True),
    ('<xacro:include filename="x is not defined.xacro"/>', False),  # the words, in a file name
    ('<xacro:include filename="unknown macro name.xacro"/>', False),
])
def test_a_failure_on_a_name_the_file_does_not_define_is_said_by_a_flag(tmp_path, body,
                                                                         undefined):
    """``LoadError.undefined``: xacro failed on a name the file uses and does not define (a
    robot including it may define it), read from the exceptions xacro raised; the loading
    rules read the message's words before, which a file name holding them fooled."""
    path = tmp_path / "part.urdf.xacro"
    path.write_text('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
                    f'{body}</robot>')
    with pytest.raises(LoadError) as raised:
        load(path)
    assert raised.value.kind == "xacro" and raised.value.undefined is undefined, \
        raised.value.message


def test_macro_calls_one_after_another_expand_in_time_linear_in_their_number(tmp_path):
    """attack26: xacro replaces each macro call by minidom's ``insertBefore``, which looks the
    call's place up from the first sibling, and moves its one blank text node after each call
    the same way: 19,000 flat calls took 20 s, a macro calling itself twice 11 deep (a 300-byte
    file, 4,096 links) 20 s, both under the macro-call bound. Spliced where the last ended:
    the same document, and a tenth of the comparisons the square would make."""
    import xml.dom.minidom

    def expand(calls: int, comment: str = "") -> tuple[list, int]:
        body = "".join(f'{comment}<xacro:m n="{i}"/>\n' for i in range(calls))
        (tmp_path / "r.urdf.xacro").write_text(
            '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
            '<xacro:macro name="m" params="n"><link name="l${n}"/></xacro:macro>\n'
            f'<link name="base"/>\n{body}</robot>')
        looked, index = [0], xml.dom.minicompat.NodeList.index

        def counted(self, *args):  # the places looked up, and how far each look went
            found = index(self, *args)
            looked[0] += found - (args[1] if len(args) > 1 else 0) + 1
            return found

        xml.dom.minicompat.NodeList.index = counted
        try:
            robot = load(str(tmp_path / "r.urdf.xacro"))
        finally:
            xml.dom.minicompat.NodeList.index = index
        return [link.get("name") for link in robot.root.iter("link")], looked[0]

    for comment in ("", "<!-- c -->"):
        names, looked = expand(2000, comment)
        assert names == ["base"] + [f"l{i}" for i in range(2000)]
        assert looked < 100 * 2000, looked  # the square: over 2 * 10^6


def test_a_yaml_file_load_yaml_cannot_read_is_said_without_pythons_errno(tmp_path):
    """motoman's es165_macro.xacro calls load_yaml(joint_velocities_file), its argument empty
    by default: xacro reads the macro's folder, and the message was Python's "[Errno 21] not a
    regular file: 'motoman_es_support/urdf'"; a file missing said "[Errno 2] No such file or
    directory: 'x.yaml'". Each is said as an include's is: what was asked, what is wrong."""
    def failure(expression: str) -> str:
        (tmp_path / "robot.xacro").write_text(
            '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
            '<xacro:arg name="f" default=""/>'
            f'<xacro:property name="v" value="${{xacro.load_yaml({expression})}}"/>'
            '<link name="a"><visual><geometry><box size="${v[\'x\']} 1 1"/></geometry></visual>'
            '</link></robot>')
        with pytest.raises(LoadError) as caught:
            load(str(tmp_path / "robot.xacro"))
        assert "Errno" not in caught.value.message, caught.value.message
        return caught.value.message

    (tmp_path / "config").mkdir()
    assert failure("'config/'").startswith(
        f"load_yaml was given no file name ('{tmp_path / 'config'}', a folder: a file name or "
        "argument left empty?) when evaluating expression"), failure("'config/'")
    assert failure("'config'").startswith(
        f"YAML file '{tmp_path / 'config'}': a folder, not a regular file when evaluating")
    assert failure("'missing.yaml'").startswith(
        f"YAML file '{tmp_path / 'missing.yaml'}' not found when evaluating")
    assert failure("'$(arg f)'").startswith("load_yaml was given no file name")
