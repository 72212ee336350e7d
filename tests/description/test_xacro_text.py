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
