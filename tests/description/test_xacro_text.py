"""A robot file's text read without expanding it (urdftool.description.xacro_text)."""

from __future__ import annotations

from urdftool.description.xacro_text import condition_dropping

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
