"""A robot file's text read without expanding it (urdftool.description.xacro_text)."""

from __future__ import annotations

from urdftool.description.xacro_text import condition_dropping, unnamed_arguments

SOURCE = b"""<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <ros2_control name="a" type="system">
    <hardware>
      <xacro:if value="$(arg sim)"><plugin>gz_ros2_control/GazeboSimSystem</plugin></xacro:if>
      <xacro:unless value="$(arg sim)"><plugin>mock_components/GenericSystem</plugin></xacro:unless>
    </hardware>
  </ros2_control>
  <ros2_control name="b" type="system">
    <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
  </ros2_control>
</robot>"""


def test_the_condition_a_wanted_element_is_written_under_is_found_at_its_line():
    assert condition_dropping(SOURCE, 3, "hardware", "plugin") == [
        ('xacro:if value="$(arg sim)"', 4), ('xacro:unless value="$(arg sim)"', 5)]
    assert condition_dropping(SOURCE, 9, "hardware", "plugin") == []  # written unconditionally
    assert condition_dropping(SOURCE, 6, "hardware", "plugin") == []  # no <hardware> starts there
    assert condition_dropping(b"<robot><hardware>", 1, "hardware", "plugin") == []  # broken XML


def test_an_element_left_out_by_every_condition_says_which_arguments_dropped_it(tmp_path):
    # poppy-project/poppy_ergo_jr_description: section_4's <geometry> and joint t7f's <parent>
    # are each under xacro:if lamp or xacro:if gripper, both false by default: U401 and U104
    # say so, where the source holds the element a reader looks for
    from urdftool.lint.engine import CheckOptions, load_and_check

    (tmp_path / ".git").mkdir()
    robot = tmp_path / "ergo.urdf.xacro"
    robot.write_text("""<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="lamp" default="false"/>
  <link name="a"><visual>
    <xacro:if value="$(arg lamp)"><geometry><box size="1 1 1"/></geometry></xacro:if>
  </visual></link>
  <link name="tip"/>
  <joint name="t" type="fixed">
    <xacro:if value="$(arg lamp)"><parent link="a"/></xacro:if>
    <child link="tip"/>
  </joint>
</robot>""")
    findings = {f.code: f.message for f in load_and_check(str(robot), CheckOptions()).findings
                if f.code in ("U401", "U104")}
    under = ' is under <xacro:if value="$(arg lamp)"> (line {}) of '
    assert "<visual> has no <geometry>: its <geometry>" + under.format(4) in findings["U401"]
    assert "has no <parent link=\"...\"/>: its <parent>" + under.format(8) in findings["U104"]
    assert findings["U104"].endswith(", false then (--arg NAME=VALUE checks another build)")


def test_a_robot_root_without_a_name_is_told_from_one_with_a_name(tmp_path):
    """A file written for xacro to include (Autoware's vehicle.xacro, bluerov2's
    actuators.xacro) has a nameless <robot>; the xacro namespace's xmlns is no name, and a
    comment or a <robot> of a macro body does not count."""
    from urdftool.description.xacro_text import nameless_robot

    cases = {
        "part.xacro": '<robot xmlns:xacro="http://ros.org/wiki/xacro"><link name="a"/></robot>',
        "named.xacro": '<robot xmlns:xacro="http://ros.org/wiki/xacro"\n name="car"/>',
        "commented.xacro": '<!-- <robot name="x"> --><robot xmlns:xacro="x"/>',
        "plain.urdf": '<robot><link name="a"/></robot>',
    }
    for name, text in cases.items():
        (tmp_path / name).write_text(text)
    assert [nameless_robot(tmp_path / name) for name in cases] == [True, False, True, False]
    # own_links=False: and no <link> or <joint> of its own outside macro definitions
    (tmp_path / "calls.xacro").write_text(
        '<robot xmlns:xacro="x"><xacro:macro name="m"><link name="in_macro"/></xacro:macro>'
        '<xacro:thruster_macro id="0"/></robot>')
    assert [nameless_robot(tmp_path / name, own_links=False)
            for name in ("part.xacro", "calls.xacro")] == [False, True]



def test_a_part_calling_its_own_macros_makes_no_links_whatever_uri_binds_xacro(tmp_path):
    """xacro reads ``xacro:`` by its prefix; a reader given only ``{uri}tag`` (a parser target)
    knows it by the URIs written for it: http://wiki.ros.org/xacro in 672 files of the real sweep
    (mycobot_ros2's), ``.../xacro/#interface`` in 41. A part whose top level only calls its own
    transmission macro (talos' left_arm.transmissions.urdf.xacro) is not a robot under any."""
    from urdftool.description.xacro_text import calls_make_links

    for uri in ("http://www.ros.org/wiki/xacro", "http://ros.org/wiki/xacro",
                "http://wiki.ros.org/xacro", "http://www.ros.org/wiki/xacro/#interface",
                "https://www.ros.org/wiki/xacro"):
        data = f"""<robot xmlns:xacro="{uri}">
  <xacro:macro name="trans" params="joint"><transmission name="t_${{joint}}"/></xacro:macro>
  <xacro:trans joint="a"/>
</robot>""".encode()
        assert not calls_make_links(data, [], False, None, 1 << 20), uri


def test_an_argument_no_file_names_is_unnamed_with_the_declared_names_close_to_it():
    sources = {"robot.urdf.xacro": b'<robot xmlns:xacro="http://www.ros.org/wiki/xacro">'
                                   b'<xacro:arg name="length" default="1"/>'
                                   b'<xacro:include filename="part.xacro"/></robot>',
               "part.xacro": b'<robot><xacro:property name="w" value="$(arg width)"/>'
                             b'<x v="$(eval arg(\'prefix\') + \'a\')"/></robot>'}
    given = {"length": "2", "width": "1", "prefix": "p", "lenght": "2", "sim": "true",
             "len": "3"}
    assert unnamed_arguments(sources, given) == {"lenght": ["length"], "sim": [], "len": []}
    assert unnamed_arguments(sources, {"length": "2"}) == {}
    # a name that is part of another word is not named: 'width' in 'width_2' would be
    assert unnamed_arguments({"a.xacro": b"$(arg width_2) $(arg my-width)"},
                             {"width": "1"}) == {"width": []}
