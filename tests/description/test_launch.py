"""Launch files read without running them: the readers (ROS 1 and ROS 2 XML, ROS 2 YAML and
Python), the configurations they make, and what they tell of a robot."""

from __future__ import annotations

import os
import sys
from pathlib import Path

import pytest

from urdftool.description.launch import Arg, Description, Include, ParamFile, Start, substituted
from urdftool.description.launch_configs import launch_index, launch_tests, read_launch, resolve, words


def _repo(root: Path, files: dict[str, str]) -> Path:
    (root / ".git").mkdir(parents=True, exist_ok=True)
    for name, text in files.items():
        (root / name).parent.mkdir(parents=True, exist_ok=True)
        (root / name).write_text(text)
    return root


PACKAGE = "<package format='2'><name>{}</name></package>"


def test_substitutions_of_both_ros_versions_and_nested_ones():
    value = substituted("$(find pkg)/config/$(arg robot)_$(var side).yaml")
    assert value.parts == (("find", "pkg"), "/config/", ("arg", "robot", None), "_",
                           ("arg", "side", None), ".yaml")
    nested = substituted("$(find-pkg-share $(var package))/x")  # an argument names the package
    assert nested.parts == (("find", substituted("$(var package)")), "/x")
    assert nested.names() == {"package"}
    assert substituted("$(find ur_$(arg model)_description)").parts[0][1].names() == {"model"}
    assert substituted("$(find $(arg a) b)/x").parts[0][0] == "unknown"  # two words
    assert substituted("$(eval 1 + 2)").parts == (("unknown", "$(eval 1 + 2)"),)
    command = substituted("$(command 'xacro $(find-pkg-share d)/r.urdf.xacro a:=$(var a)')")
    assert command.parts[0][0] == "command" and command.parts[0][1].names() == {"a"}


def test_words_keep_quoted_parts_and_substitutions_together():
    value = substituted("$(find xacro)/xacro '$(find d)/urdf/r.urdf.xacro'\n  ns:=$(arg ns) prefix:=\"\"")
    assert [w.text for w in words(value)] == ["$(...)/xacro", "$(...)/urdf/r.urdf.xacro",
                                              "ns:=$(...)", "prefix:="]


def test_ros1_xml(tmp_path):
    launch = _repo(tmp_path, {"pkg/launch/a.launch": """<launch>
      <arg name="model" default="arm"/>
      <arg name="fixed" value="1"/>
      <param name="robot_description" command="$(find xacro)/xacro $(find pkg)/urdf/$(arg model).urdf.xacro hw:=$(arg hw)"/>
      <rosparam file="$(find pkg)/config/c.yaml" command="load" subst_value="true"/>
      <group if="$(arg sim)">
        <node name="s" pkg="controller_manager" type="spawner" args="a b --stopped"/>
      </group>
      <include file="$(find pkg)/launch/b.launch" pass_all_args="true"><arg name="x" value="1"/></include>
    </launch>"""}) / "pkg/launch/a.launch"
    read = read_launch(launch)
    assert read.form == "ros1" and read.problem is None
    kinds = [type(a).__name__ for a in read.actions]
    assert kinds == ["Arg", "Arg", "Description", "ParamFile", "Start", "Include"]
    assert read.actions[1] == Arg("fixed", substituted("1"), True, (), 3)
    assert read.actions[3].substitute and read.actions[4].when[0].text == 'if="$(arg sim)"'
    assert read.actions[5].every and read.actions[5].args == (("x", substituted("1")),)


def test_ros2_xml_and_yaml(tmp_path):
    root = _repo(tmp_path, {
        "p/launch/a.launch.xml": """<launch>
          <arg name="gui" default="true"/>
          <let name="cfg" value="$(find-pkg-share p)/config/c.yaml"/>
          <node pkg="controller_manager" exec="spawner" args="jsb arm" if="$(var gui)">
            <param from="$(var cfg)"/>
          </node>
        </launch>""",
        "p/launch/b.launch.yaml": """launch:
- arg: {name: gui, default: "false"}
- node:
    pkg: controller_manager
    exec: spawner
    args: jsb
    param: [{from: $(find-pkg-share p)/config/c.yaml}]
- include: {file: $(find-pkg-share p)/launch/a.launch.xml, arg: [{name: gui, value: "false"}]}
"""})
    xml = read_launch(root / "p/launch/a.launch.xml")
    assert xml.form == "ros2-xml" and [type(a).__name__ for a in xml.actions] == ["Arg", "Arg", "Start"]
    assert xml.actions[1].fixed and xml.actions[2].files[0].substitute
    yaml = read_launch(root / "p/launch/b.launch.yaml")
    assert [type(a).__name__ for a in yaml.actions] == ["Arg", "Start", "Include"]


def test_a_yaml_launch_file_that_does_not_read_says_where(tmp_path):
    """A YAML launch file PyYAML cannot construct (ROS 2's launch reads it with PyYAML) said
    why and not where: U620 named the file alone."""
    root = _repo(tmp_path, {"p/launch/b.launch.yaml": "launch:\n- arg: {name: when, default: 2001-02-30}\n"})
    launch = read_launch(root / "p/launch/b.launch.yaml")
    assert launch.problem_line == 2 and "day is out of range for month" in launch.problem


PYTHON = '''
import os
from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, IncludeLaunchDescription, OpaqueFunction
from launch.conditions import IfCondition
from launch.launch_description_sources import PythonLaunchDescriptionSource
from launch.substitutions import Command, FindExecutable, LaunchConfiguration, PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.substitutions import FindPackageShare

def spawner(name, *extra):
    return Node(package="controller_manager", executable="spawner", arguments=[name, *extra])

def launch_setup(context):
    hw = LaunchConfiguration("hw").perform(context)
    nodes = [spawner(c) for c in ["jsb", "arm_controller"]]
    if hw == "mock":
        nodes.append(spawner("mock_controller", "--inactive"))
    return nodes

def generate_launch_description():
    description = Command([FindExecutable(name="xacro"), " ",
                           PathJoinSubstitution([FindPackageShare("p"), "urdf", "r.urdf.xacro"]),
                           " prefix:=", LaunchConfiguration("prefix")])
    controllers = os.path.join(get_package_share_directory("p"), "config", "c.yaml")
    ld = LaunchDescription()
    ld.add_action(DeclareLaunchArgument("prefix", default_value="left_"))
    ld.add_action(DeclareLaunchArgument("hw", default_value="mock"))
    ld.add_action(Node(package="controller_manager", executable="ros2_control_node",
                       parameters=[{"robot_description": description}, controllers]))
    ld.add_action(Node(package="rviz2", executable="rviz2", condition=IfCondition(LaunchConfiguration("gui"))))
    ld.add_action(IncludeLaunchDescription(PythonLaunchDescriptionSource(
        [FindPackageShare("p"), "/launch/other.launch.py"]), launch_arguments={"x": "1"}.items()))
    ld.add_action(OpaqueFunction(function=launch_setup))
    return ld
'''


def test_ros2_python_by_its_syntax_tree(tmp_path):
    root = _repo(tmp_path, {"p/launch/a.launch.py": PYTHON})
    read = read_launch(root / "p/launch/a.launch.py")
    assert read.form == "ros2-python" and read.problem is None
    args = [a for a in read.actions if isinstance(a, Arg)]
    assert [a.name for a in args] == ["prefix", "hw"]
    described = [a for a in read.actions if isinstance(a, Description)]
    assert len(described) == 1 and described[0].command.names() == {"prefix"}
    starts = [a for a in read.actions if isinstance(a, Start)]
    spawned = [[w.text for w in s.arguments] for s in starts if s.executable.literal == "spawner"]
    assert spawned == [["jsb"], ["arm_controller"], ["mock_controller", "--inactive"]]
    mock = next(s for s in starts if s.arguments and s.arguments[0].literal == "mock_controller")
    assert mock.when[0].kind == "equals"  # the Python if, read as a condition on hw
    node = next(s for s in starts if s.executable.literal == "ros2_control_node")
    assert isinstance(node.files[0], ParamFile) and node.files[0].path.parts[0] == ("find", "p")
    assert [a for a in read.actions if isinstance(a, Include)][0].args[0][0] == "x"


def test_a_package_a_launch_argument_names_is_read_in_each_python_form(tmp_path):
    root = _repo(tmp_path, {"p/launch/a.launch.py": '''
from ament_index_python.packages import get_package_share_directory
from launch_ros.substitutions import FindPackageShare
from moveit_configs_utils import MoveItConfigsBuilder

def launch_setup(context):
    share = get_package_share_directory(context.launch_configurations["moveit_package"])
    family = LaunchConfiguration("family").perform(context)
    MoveItConfigsBuilder(f"kuka_{family}").robot_description(file_path="urdf/r.urdf.xacro")
    return [Node(package="x", executable="y", parameters=[
        PathJoinSubstitution([FindPackageShare(LaunchConfiguration("config_package")), "c.yaml"]),
        share + "/d.yaml", get_package_share_directory(compute()) + "/e.yaml"])]

def generate_launch_description():
    return LaunchDescription([OpaqueFunction(function=launch_setup)])
'''})
    read = read_launch(root / "p/launch/a.launch.py")
    [start] = [a for a in read.actions if isinstance(a, Start)]
    assert [f.path.parts[0][0] for f in start.files] == ["find", "find", "unknown"]  # compute()
    assert [f.path.parts[0][1].names() for f in start.files[:2]] == [{"config_package"},
                                                                   {"moveit_package"}]
    [described] = [a for a in read.actions if isinstance(a, Description)]
    package = described.file.parts[0][1]
    assert package.parts == ("kuka_", ("arg", "family", None), "_moveit_config")


def test_a_description_a_let_holds_is_read_where_a_param_takes_it(tmp_path):
    # ros2_control_demos' example 17, gz_ros2_control's mimic joint demos, Kassow's bringup
    root = _repo(tmp_path, {"p/package.xml": PACKAGE.format("p"), "p/urdf/r.urdf.xacro": "<robot name='r'/>",
                            "p/launch/a.launch.xml": """<launch>
      <let name="robot_description" value="$(command '$(find-exec xacro) $(find-pkg-share p)/urdf/r.urdf.xacro a:=1')"/>
      <node pkg="robot_state_publisher" exec="robot_state_publisher">
        <param name="robot_description" value="$(var robot_description)"/>
      </node>
      <node pkg="x" exec="y"><param name="robot_description" value="$(var other)"/></node>
    </launch>"""})
    [configuration] = launch_index(root).configurations
    [described] = configuration.described
    assert described.path == root / "p/urdf/r.urdf.xacro" and described.xacro
    assert described.args["a"].text == "1"
    assert substituted("$(find-exec xacro) x").parts == ("xacro x",)


def test_configurations_resolve_includes_arguments_and_installed_share_paths(tmp_path):
    root = _repo(tmp_path, {
        "p/package.xml": PACKAGE.format("p"),
        "p/description/urdf/r.urdf.xacro": "<robot name='r'/>",
        "p/bringup/config/c.yaml": "a: {type: x/Y}\n",
        "p/bringup/launch/a.launch.py": PYTHON.replace("OpaqueFunction(function=launch_setup)",
                                                       "OpaqueFunction(function=launch_setup)")})
    index = launch_index(root)
    [configuration] = index.configurations
    [described] = configuration.described
    # share/p/urdf/r.urdf.xacro is installed from p/description/urdf/r.urdf.xacro
    assert described.path == root / "p/description/urdf/r.urdf.xacro"
    assert described.args["prefix"].text == "left_" and described.args["prefix"].free == {"prefix"}
    loaded = [l for l in configuration.loaded if l.path is not None]
    assert loaded[0].path == root / "p/bringup/config/c.yaml"
    assert configuration.incomplete  # other.launch.py is not there


def test_conditions_are_evaluated_with_the_defaults(tmp_path):
    root = _repo(tmp_path, {"p/package.xml": PACKAGE.format("p"), "p/launch/a.launch": """<launch>
      <arg name="sim" default="false"/>
      <arg name="controllers" default="jsb arm"/>
      <node name="real" pkg="controller_manager" type="spawner" args="$(arg controllers)" unless="$(arg sim)"/>
      <node name="fake" pkg="controller_manager" type="spawner" args="fake" if="$(arg sim)"/>
      <node name="never" pkg="controller_manager" type="spawner" args="never" if="false"/>
    </launch>"""})
    [configuration] = launch_index(root).configurations
    started = {tuple(w.text for w in s.arguments): s.when for s in configuration.started}
    assert set(started) == {("jsb", "arm"), ("fake",)}  # if="false" never runs
    assert started["jsb", "arm"].truth is True and started["jsb", "arm"].free == {"sim"}
    assert started["fake",].truth is False and started["fake",].free == {"sim"}


def test_an_eval_comparing_an_argument_with_a_word_is_read_as_that_comparison(tmp_path):
    """roslaunch's ``if="$(eval arg('arm') == 'gen3')"`` (ros_kortex chooses the dof default
    so) is read, never evaluated, as "arm equals gen3"; any other expression stays unknown."""
    root = _repo(tmp_path, {"p/package.xml": PACKAGE.format("p"), "p/launch/a.launch": """<launch>
      <arg name="arm" default="gen3"/>
      <node name="seven" pkg="controller_manager" type="spawner" args="seven" if="$(eval arg('arm') == 'gen3')"/>
      <node name="six" pkg="controller_manager" type="spawner" args="six" if="$(eval arg('arm') == 'gen3_lite')"/>
      <node name="other" pkg="controller_manager" type="spawner" args="other" unless="$(eval arg('arm') != 'gen3')"/>
      <node name="odd" pkg="controller_manager" type="spawner" args="odd" if="$(eval 1 + len(arg('arm')) > 2)"/>
    </launch>"""})
    [configuration] = launch_index(root).configurations
    started = {s.arguments[0].text: s.when for s in configuration.started}
    assert started["seven"].truth is True and started["seven"].free == {"arm"}
    assert "six" not in started or started["six"].truth is False
    assert started["other"].truth is True
    assert started["odd"].truth is None


def _remaps(configuration) -> dict:
    """executable -> its remaps as (from, to, certain, condition in words)."""
    return {s.executable: [(r.source, r.target, r.when.certain, r.when.text()) for r in s.remaps]
            for s in configuration.started}


def test_a_python_set_remap_holds_for_what_follows_it_in_its_group(tmp_path):
    """``SetRemap`` in a ``GroupAction`` holds for the nodes after it there (in nested groups
    and included files too), before a node's own remaps, with its own condition; not for the
    nodes before it, nor after its group."""
    root = _repo(tmp_path, {"q/package.xml": PACKAGE.format("q"), "q/launch/a.launch.py": """
from launch import LaunchDescription
from launch.actions import GroupAction, IncludeLaunchDescription
from launch.conditions import IfCondition
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node, SetRemap

def generate_launch_description():
    return LaunchDescription([
        GroupAction([
            Node(package="q", executable="before"),
            SetRemap(src="/follow_joint_trajectory", dst="/arm/arm_controller/follow_joint_trajectory"),
            SetRemap("g/gripper_cmd", "/arm/gripper/gripper_cmd",
                     condition=IfCondition(LaunchConfiguration("sim"))),
            Node(package="q", executable="move_group", remappings=[("a", "b")]),
            GroupAction(actions=[Node(package="q", executable="nested")]),
            IncludeLaunchDescription(PythonLaunchDescriptionSource(
                [FindPackageShare("q"), "/launch/b.launch.py"])),
        ]),
        Node(package="q", executable="after"),
    ])
""", "q/launch/b.launch.py": """
def generate_launch_description():
    return LaunchDescription([Node(package="q", executable="included")])
"""})
    found = {}
    for configuration in launch_index(root).configurations:
        found.update(_remaps(configuration))
    arm = ("/follow_joint_trajectory", "/arm/arm_controller/follow_joint_trajectory", True, "")
    gripper = ("g/gripper_cmd", "/arm/gripper/gripper_cmd", False,
               "when IfCondition(LaunchConfiguration('sim'))")
    assert found["before"] == [] and found["after"] == []
    assert found["move_group"] == [arm, gripper, ("a", "b", True, "")]
    assert found["nested"] == found["included"] == [arm, gripper]


def test_remaps_of_each_form_reach_the_nodes_of_their_scope(tmp_path):
    """ROS 1's ``<remap>`` beside nodes holds for those after it in its scope, included files'
    too, and a group's ends with it; a node's own comes last (roslaunch applies it last);
    ROS 2's ``remappings=[(from, to)]`` and YAML's ``remap:`` hold for their node."""
    root = _repo(tmp_path, {"p/package.xml": PACKAGE.format("p"), "p/launch/a.launch": """<launch>
      <arg name="sim" default="true"/>
      <node name="early" pkg="p" type="early"/>
      <remap from="/follow_joint_trajectory" to="/arm/arm_controller/follow_joint_trajectory"/>
      <group>
        <remap if="$(arg sim)" from="g/gripper_cmd" to="/arm/gripper/gripper_cmd"/>
        <node name="grouped" pkg="p" type="grouped"/>
      </group>
      <include file="$(find p)/launch/b.launch"/>
      <node name="late" pkg="p" type="late"><remap from="a" to="b"/></node>
    </launch>""", "p/launch/b.launch": '<launch><node name="inner" pkg="p" type="inner"/></launch>',
        "q/package.xml": PACKAGE.format("q"), "q/launch/c.launch.py": """
from launch import LaunchDescription
from launch_ros.actions import Node

def generate_launch_description():
    return LaunchDescription([Node(package="q", executable="python_node",
                                   remappings=[("/follow_joint_trajectory", "/c/follow_joint_trajectory")])])
""", "q/launch/d.launch.yaml": """launch:
- arg: {name: controller, default: arm_controller}
- node:
    pkg: q
    exec: yaml_node
    remap:
    - {from: /follow_joint_trajectory, to: $(var controller)/follow_joint_trajectory}
"""})
    found = {}
    for configuration in launch_index(root).configurations:
        found.update(_remaps(configuration))
    arm = ("/follow_joint_trajectory", "/arm/arm_controller/follow_joint_trajectory", True, "")
    assert found["early"] == []
    assert found["grouped"] == [arm, ("g/gripper_cmd", "/arm/gripper/gripper_cmd", False,
                                      'when if="$(arg sim)"')]
    assert found["inner"] == [arm]  # into the include
    assert found["late"] == [arm, ("a", "b", True, "")]  # the group's remap ended with it
    assert found["python_node"] == [("/follow_joint_trajectory", "/c/follow_joint_trajectory", True, "")]
    assert found["yaml_node"] == [("/follow_joint_trajectory", "arm_controller/follow_joint_trajectory",
                                   False, "as launch argument controller is given")]


# --- hostile launch files -----------------------------------------------------------------------

def test_a_python_launch_file_is_never_run_or_imported(tmp_path):
    marker = tmp_path / "ran"
    root = _repo(tmp_path / "repo", {"p/launch/evil.launch.py": f"""
import os
open({str(marker)!r}, "w").write("x")
os.system("touch {marker}")
def generate_launch_description():
    open({str(marker)!r}, "w").write("x")
    __import__("os").system("touch {marker}")
    return []
"""})
    modules = set(sys.modules)
    launch_index(root)
    assert not marker.exists()
    assert not {m for m in set(sys.modules) - modules if "evil" in m}


def test_hostile_launch_files_are_bounded(tmp_path):
    deep = "(" * 5000 + "1" + ")" * 5000
    root = _repo(tmp_path, {
        "p/launch/deep.launch.py": f"def generate_launch_description():\n    x = {deep}\n",
        "p/launch/loop.launch.py": "def generate_launch_description():\n    while True:\n        pass\n",
        "p/launch/recurse.launch.py": "def f(x):\n    return f(x)\ndef generate_launch_description():\n    return f(1)\n",
        "p/launch/big.launch": "<launch>" + "<arg name='a' default='b'/>" * 60000 + "</launch>",
        "p/launch/entity.launch": '<!DOCTYPE l [<!ENTITY e "x">]><launch><arg name="&e;"/></launch>',
        "p/launch/self.launch": "<launch><include file='$(dirname)/self.launch'/></launch>",
        "p/launch/doubling.launch": "<launch><arg name='a' default='x'/>"
                                    + "".join(f"<arg name='a{i + 1}' default='$(arg a{i})$(arg a{i})'/>"
                                              for i in range(40)).replace("a0", "a") + "</launch>",
        "p/launch/binary.launch": "\0\1\2",
    })
    index = launch_index(root)  # returns; nothing raised
    problems = {Path(f.path).name: f.problem for f in index.files.values()}
    assert "big.launch" not in problems  # over the size limit: not read
    assert all(c.display for c in index.configurations)
    doubling = next(c for c in index.configurations if c.display.endswith("doubling.launch"))
    assert doubling is not None  # the 2**40-character value was not built


@pytest.mark.parametrize("grows", [
    "    x = 'aaaaaaaa'\n" + "    x = x + x\n" * 60,  # a text doubled
    "    x = 'ab'\n" + "    x = f'{x}{x}'\n" * 60,
    "    x = y\n" + "    x = x + z + x\n" * 60,  # substitutions doubled: parts, not characters
    "    x = ['a']\n" + "    x += x\n" * 60,  # a list grown in place
    "    x = ['a']\n" + "    x.extend(x)\n" * 60,
    "    x = [{'a': 'b'}]\n" + "    x = [x, x]\n" * 60,  # 2**60 items to whoever flattens it
    "    x = []\n    y = [x]\n    x.append(y)\n",  # a list inside itself
])
def test_what_a_python_launch_file_builds_is_bounded(tmp_path, grows):
    """The values a Python launch file (here a launch test) makes the reader build are bounded
    in memory and time, whatever builds them: read in part, not 2**60 characters or items
    (under a 2 GiB address space, a build past it fails the read), and what it built is what
    its room was charged, past its bound by one value at most (counted, not timed)."""
    import resource

    from urdftool.description.launch_python import (MAX_REPOSITORY_CHARACTERS,
                                                    MAX_REPOSITORY_ITEMS, Room,
                                                    read_python_launch)

    text = ("def generate_test_description():\n" + grows + "    return LaunchDescription("
            "[Node(package='robot_state_publisher', executable='robot_state_publisher', "
            "parameters=[{'robot_description': x}, *x]), *x])\n")
    limit = resource.getrlimit(resource.RLIMIT_AS)
    resource.setrlimit(resource.RLIMIT_AS, (2 * 1024 ** 3, limit[1]))  # (not the machine's)
    room = Room()
    try:
        launch = read_python_launch(tmp_path / "test_x.py", "test_x.py", text,
                                    "generate_test_description", room)
    finally:
        resource.setrlimit(resource.RLIMIT_AS, limit)
    assert launch.problem == "too large or too deeply nested to read completely; read in part"
    assert room.characters > -MAX_REPOSITORY_CHARACTERS and room.items > -MAX_REPOSITORY_ITEMS


def test_what_all_the_launch_tests_of_a_repository_cost_is_bounded_together(tmp_path,
                                                                            monkeypatch):
    """Hundreds of launch tests, each within the bounds of one file, cost what one
    repository's launch files may cost (launch_python.Room), not their sum: each once built
    its texts up to the bound of a file. The characters built are counted: the test was timed
    (2.9 of its 3 s at load 16), and run outside a check's run, where each file is read at the
    cost of a room of its own, it proved nothing of the rooms shared."""
    from urdftool.description import launch_python

    built, real = [0], launch_python._Reader.built

    def counted(reader, value):
        if isinstance(value, launch_python.Value):
            built[0] += len(value.text)
        return real(reader, value)

    monkeypatch.setattr(launch_python._Reader, "built", counted)
    grows = ("def generate_test_description():\n    x = 'a'\n" + "    x = x + x\n" * 40
             + "    return LaunchDescription([])\n")
    root = _repo(tmp_path, {f"p/test/test_{i}.py": grows for i in range(300)})
    from urdftool.description.run_memo import one_run

    with one_run():  # (a check's: the room is the run's, one per repository)
        launch_tests(root)
    # one repository's room, overshot by one value at most (outside a run each file had its
    # own: 2.5 G characters built in all, 2.9 s)
    assert 0 < built[0] < 3 * launch_python.MAX_REPOSITORY_CHARACTERS, built[0]


def test_paths_outside_the_repository_are_never_followed(tmp_path):
    outside = tmp_path / "outside"
    outside.mkdir()
    (outside / "secret.launch").write_text(
        "<launch><node pkg='controller_manager' type='spawner' args='stolen'/></launch>")
    (outside / "c.yaml").write_text("stolen: {type: a/B}\n")
    root = _repo(tmp_path / "repo", {"p/package.xml": PACKAGE.format("p"), "p/launch/a.launch": f"""<launch>
      <include file="{outside}/secret.launch"/>
      <include file="$(find p)/../../outside/secret.launch"/>
      <rosparam file="{outside}/c.yaml" command="load"/>
    </launch>"""})
    (root / "p/launch/link.launch").symlink_to(outside / "secret.launch")
    index = launch_index(root)
    assert [Path(f.path).name for f in index.files.values()] == ["a.launch"]
    [configuration] = index.configurations
    assert configuration.started == [] and [l.path for l in configuration.loaded] == [None]


def test_resolve_keeps_what_is_not_known_unknown(tmp_path):
    from urdftool.description.launch import LaunchFile
    from urdftool.description.launch_configs import Resolved, Scope

    scope = Scope({"a": Resolved("x", frozenset({"a"}))}, {}, LaunchFile(tmp_path / "l.launch", "l", "ros1"),
                  tmp_path, True)
    assert resolve(substituted("$(arg a)_y"), scope) == Resolved("x_y", frozenset({"a"}))
    assert resolve(substituted("$(arg b)"), scope).text is None
    assert resolve(substituted("$(env HOME)"), scope).text is None  # the environment is not read
    assert resolve(substituted("$(optenv ROBOT arm)"), scope).text == "arm"


def test_only_the_parameters_consumers_read_describe_the_robot(tmp_path):
    # niryo: robot_description_tf2 holds another build beside robot_description; it is not
    # what MoveIt and robot_state_publisher read
    root = _repo(tmp_path, {"p/package.xml": PACKAGE.format("p"),
                            "p/a.urdf.xacro": "<robot name='a'/>", "p/b.urdf.xacro": "<robot name='b'/>",
                            "p/launch/x.launch": """<launch>
      <param name="robot_description" command="xacro $(find p)/a.urdf.xacro"/>
      <param name="robot_description_tf2" command="xacro $(find p)/b.urdf.xacro"/>
      <param name="robot_description_semantic" textfile="$(find p)/a.srdf"/>
    </launch>""", "p/a.srdf": "<robot name='a'/>"})
    [configuration] = launch_index(root).configurations
    assert [d.path.name for d in configuration.described] == ["a.urdf.xacro", "a.srdf"]


def test_a_robot_its_environment_builds_is_not_the_robot_as_checked(tmp_path):
    # kinova-movo: $(optenv MOVO_HAS_KINOVA_ARM false) decides whether the robot has arms
    from urdftool.description.runtime import runtime
    from urdftool.lint.engine import CheckOptions, load_and_check

    root = _repo(tmp_path, {"p/package.xml": PACKAGE.format("p"),
                            "p/r.urdf.xacro": """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <link name="base"/>
  <xacro:if value="$(optenv HAS_ARM false)"><link name="arm"/></xacro:if>
</robot>""", "p/launch/x.launch": """<launch>
      <param name="robot_description" command="xacro $(find p)/r.urdf.xacro"/>
    </launch>"""})
    robot = load_and_check(str(root / "p/r.urdf.xacro"), CheckOptions()).robot
    [(configuration, relation)] = [c for c in runtime(robot).configurations if c[1]]
    assert relation == "as the environment builds it (HAS_ARM)"


def test_a_launch_file_describing_another_robot_keeps_its_controllers(tmp_path):
    """ai_worker's ffw_bg2_ai.launch.py includes the follower's launch file and the leader's,
    each describing its robot and loading its own controllers file: the follower's file is not
    the leader's (its joints are not the leader's), a file loaded by a launch file describing no
    robot stays shared."""
    from urdftool.description.runtime import runtime
    from urdftool.lint.engine import CheckOptions, load_and_check

    def side(name):
        return f"""<launch>
      <param name="robot_description" command="xacro $(find p)/{name}.urdf.xacro"/>
      <node pkg="controller_manager" type="spawner" name="s" args="{name}_controller"/>
      <rosparam file="$(find p)/config/{name}.yaml" command="load"/>
    </launch>"""
    root = _repo(tmp_path, {"p/package.xml": PACKAGE.format("p"),
                            "p/leader.urdf.xacro": "<robot name='leader'><link name='l'/></robot>",
                            "p/follower.urdf.xacro": "<robot name='f'><link name='f'/></robot>",
                            "p/config/leader.yaml": "a: 1\n", "p/config/follower.yaml": "a: 1\n",
                            "p/config/shared.yaml": "a: 1\n",
                            "p/launch/leader.launch": side("leader"),
                            "p/launch/follower.launch": side("follower"),
                            "p/launch/both.launch": """<launch>
      <include file="$(find p)/launch/follower.launch"/>
      <include file="$(find p)/launch/leader.launch"/>
      <rosparam file="$(find p)/config/shared.yaml" command="load"/>
    </launch>"""})
    robot = load_and_check(str(root / "p/leader.urdf.xacro"), CheckOptions()).robot
    facts = runtime(robot)
    assert sorted(p.name for p in facts.loaded_files()) == ["leader.yaml", "shared.yaml"]
    assert {s.arguments[0].text for c, s in facts.starts("controller_manager")} == \
        {"leader_controller"}


def test_an_argument_without_default_but_with_choices_builds_with_the_first(tmp_path):
    # UR's view_ur.launch.py: DeclareLaunchArgument("ur_type", choices=["ur3", ...]) and no
    # default; the robot is built (and checked) with the first choice, not left unbuilt
    text = PYTHON.replace('DeclareLaunchArgument("prefix", default_value="left_")',
                          'DeclareLaunchArgument("prefix", choices=["right_", "left_"])')
    root = _repo(tmp_path, {"p/package.xml": PACKAGE.format("p"),
                            "p/urdf/r.urdf.xacro": "<robot name='r'/>",
                            "p/launch/a.launch.py": text})
    [configuration] = launch_index(root).configurations
    [described] = configuration.described
    assert described.args["prefix"].text == "right_"


LAUNCH_TEST = """import os
import launch
from launch_ros.actions import Node
from ament_index_python.packages import get_package_share_directory
import xacro

def generate_test_description():
    path = os.path.join(get_package_share_directory("p"), "urdf", "r.urdf.xacro")
    doc = xacro.parse(open(path))
    xacro.process_doc(doc, mappings={"prefix": "left_"})
    return launch.LaunchDescription([
        Node(package="robot_state_publisher", executable="robot_state_publisher",
             parameters=[{"robot_description": doc.toxml()}]),
        Node(package="controller_manager", executable="spawner", arguments=["arm_controller"]),
    ])
"""


def test_a_launch_test_shows_how_the_robot_is_built_not_what_a_deployment_starts(tmp_path):
    # gz_ros2_control_tests/tests/position_test.py: launch_testing's generate_test_description,
    # read from its syntax tree as a launch file is; its spawners start nothing for the rules
    from urdftool.description.runtime import builds, runtime
    from urdftool.lint.engine import CheckOptions, load_and_check

    root = _repo(tmp_path, {"p/package.xml": PACKAGE.format("p"),
                            "p/urdf/r.urdf.xacro": "<robot name='r'><link name='a'/></robot>",
                            "p/test/position_test.py": LAUNCH_TEST,
                            "p/test/test_unit.py": "def test_x():\n    open('urdf/r.urdf.xacro')\n"})
    index = launch_index(root)
    assert index.configurations == []
    [test] = launch_tests(root)
    assert test.top.test and [s.executable for s in test.started] == ["robot_state_publisher",
                                                                       "spawner"]
    [build] = builds(str(root / "p/urdf/r.urdf.xacro"))
    assert build.xacro and build.args == {"prefix": "left_"} and build.launch.endswith("position_test.py")
    robot = load_and_check(str(root / "p/urdf/r.urdf.xacro"), CheckOptions()).robot
    assert runtime(robot).configurations == []


def test_a_launch_file_that_includes_a_launch_test_starts_none_of_it(tmp_path):
    """ros2 launch cannot include a file without generate_launch_description (a launch test
    named as a launch file): what the test starts is no deployment's, through an include
    either; the including configuration is incomplete."""
    root = _repo(tmp_path, {
        "p/package.xml": PACKAGE.format("p"),
        "p/urdf/r.urdf.xacro": "<robot name='r'><link name='a'/></robot>",
        "p/launch/robot_test.launch.py": LAUNCH_TEST,
        "p/launch/bringup.launch.py": (
            "import os\nfrom launch import LaunchDescription\n"
            "from launch.actions import IncludeLaunchDescription\n"
            "from launch.launch_description_sources import PythonLaunchDescriptionSource\n"
            "def generate_launch_description():\n"
            "    return LaunchDescription([IncludeLaunchDescription(PythonLaunchDescriptionSource("
            "os.path.join(get_package_share_directory('p'), 'launch', 'robot_test.launch.py')))])"
            "\n")})
    [bringup] = launch_index(root).configurations
    assert bringup.display.endswith("bringup.launch.py")
    assert bringup.started == [] and bringup.incomplete
    [test] = launch_tests(root)
    assert [s.executable for s in test.started] == ["robot_state_publisher", "spawner"]


def test_what_a_launch_test_is_is_decided_by_its_entry_point(tmp_path):
    from urdftool.description.launch import is_launch_test, may_be_launch_test

    assert is_launch_test(LAUNCH_TEST)
    assert is_launch_test("@pytest.mark.launch_test\ndef generate_test_description():\n    pass\n")
    assert not is_launch_test(LAUNCH_TEST + "\ndef generate_launch_description():\n    pass\n")
    assert not is_launch_test("def test_x():\n    generate_test_description()\n")
    root = tmp_path
    assert may_be_launch_test(root / "p/test/position.py", root)
    assert may_be_launch_test(root / "p/tests/integration/x.test.py", root)
    assert may_be_launch_test(root / "p/launch/test_view.py", root)
    assert not may_be_launch_test(root / "p/scripts/teleop.py", root)
    assert not may_be_launch_test(root / "p/test/config.yaml", root)


def test_a_launch_test_not_read_is_unknown_as_a_launch_file_not_read_is(tmp_path):
    """'Could not be read' is one answer for launch files and launch tests (launch.was_read,
    runtime.unread_naming): what one that names the robot does with it is unknown, and each is
    named as what it is. A Python file in a test folder that is no launch test says nothing."""
    from urdftool.description.runtime import unread_naming

    broken = LAUNCH_TEST.replace("def generate_test_description():",
                                 "def generate_test_description(:")
    root = _repo(tmp_path, {"p/package.xml": PACKAGE.format("p"),
                            "p/urdf/r.urdf.xacro": "<robot name='r'><link name='a'/></robot>",
                            "p/test/position_test.py": broken,
                            "p/test/test_unit.py": "def test_x(:\n    open('urdf/r.urdf.xacro')\n",
                            "p/launch/view.launch.py": broken.replace(
                                "generate_test_description", "generate_launch_description"),
                            "p/launch/other.launch.py": broken.replace("r.urdf.xacro", "o.urdf")})
    assert launch_tests(root) == [] and launch_index(root).configurations == []
    assert sorted(unread_naming(str(root / "p/urdf/r.urdf.xacro"))) == [
        f"launch file {root}/p/launch/view.launch.py (not read)",
        f"launch test {root}/p/test/position_test.py (not read)"]


def test_the_launch_walk_asks_where_each_folder_leads_of_its_parent_not_the_system(
        tmp_path, monkeypatch):
    """A repository's folders are listed once each by the launch walk
    (:func:`urdftool.description.files.walk`): where a folder entered leads is its parent's
    real path and its name (it is no link), not an ``lstat`` of it, nor of it again by the
    package walk that follows (both answers kept for the run), and each listing is
    recorded as :func:`~urdftool.description.files.listing` records it (the result cache and
    the language server compare the same entries)."""
    from urdftool.description import files, launch_configs, record, run_memo
    from urdftool.description.packages import packages_below

    folder = tmp_path / "repo"
    for depth in range(1, 6):
        for branch in ("a", "b", "c"):
            (folder / "/".join(["d"] * depth) / branch / "launch").mkdir(parents=True)
    (folder / "d" / "a" / "launch" / "bringup.launch").write_text("<launch/>")
    (folder / "d" / ".hidden" / "launch").mkdir(parents=True)
    (folder / "d" / ".hidden" / "launch" / "x.launch").write_text("<launch/>")
    (tmp_path / "elsewhere").mkdir()
    (folder / "d" / "linked").symlink_to(tmp_path / "elsewhere")
    asked = []
    lstat = os.lstat
    monkeypatch.setattr(os, "lstat", lambda path, *a, **k: asked.append(path) or lstat(
        path, *a, **k))
    with run_memo.one_run(), record.recording() as walked:
        found, _ = launch_configs.launch_files(folder)
        packages_below(folder)  # the package walk that follows: the same folders, known
    monkeypatch.setattr(os, "lstat", lstat)
    assert found == [folder / "d" / "a" / "launch" / "bringup.launch"]
    below = [path for path in map(str, asked) if path.startswith(f"{folder}{os.sep}")]
    on_the_way = {str(found[0]), *map(str, found[0].parents)}  # (inside(): the file found)
    assert set(below) <= on_the_way, sorted(set(below) - on_the_way)
    walk = f"{launch_configs._LAUNCH_NAMES}|[!.]*/"  # (the launch walk's listings)
    listed = [key for key in walked.searched() if key[1] == walk]
    assert len(listed) == 1 + 5 * 7 and not any(".hidden" in f or "linked" in f
                                                for f, _ in listed), sorted(listed)
    with run_memo.one_run(), record.recording() as expected:
        for folder_listed, pattern in listed:
            files.listing(folder_listed, pattern)
    assert {question: answer for question, answer in walked.entries.items()
            if question[0] == record.SEARCH and question[1][1] == walk} == expected.entries
    monkeypatch.chdir(tmp_path)  # a folder named relative: its folders named below it
    with run_memo.one_run():
        assert [current for current, _ in launch_configs._walk(Path("repo"), 3)] == [
            "repo", os.path.join("repo", "d"), *(os.path.join("repo", "d", name)
                                                  for name in ("a", "b", "c", "d"))]


def test_a_quoted_launch_variable_in_a_command_is_the_shells_quote(tmp_path):
    """Yaskawa's view_es165.launch.xml: <let name="xacro_path" value="'$(find-pkg-share p)/
    urdf/r.xacro'"/> then $(command 'xacro $(var xacro_path) f:=$(var c)'): ROS 2 substitutes
    and then splits with shlex, so the quotes are the shell's; the robot is built there, with
    f known only at launch (c has no default)."""
    from urdftool.description.runtime import builds

    root = _repo(tmp_path, {"p/package.xml": PACKAGE.format("p"),
                            "p/urdf/r.xacro": "<robot name='r'><link name='a'/></robot>",
                            "p/launch/view.launch.xml": (
                                "<launch>\n<let name=\"xacro_path\" value=\"'$(find-pkg-share p)/"
                                "urdf/r.xacro'\"/>\n<arg name=\"c\"/>\n<let name=\"cp\" value="
                                "\"'$(find-pkg-share p)/config/v_$(var c).yaml'\"/>\n"
                                "<node pkg=\"robot_state_publisher\" exec=\"robot_state_publisher\">\n"
                                "<param name=\"robot_description\" type=\"str\" value=\"$(command "
                                "'xacro $(var xacro_path) f:=$(var cp)')\"/>\n</node>\n</launch>\n")})
    [build] = builds(str(root / "p/urdf/r.xacro"))
    assert build.xacro and build.args == {"f": None}, build


def test_conditions_on_one_launch_argument_that_cannot_hold_together_exclude_each_other(tmp_path):
    """``mobile == 'husky'`` and ``mobile == 'none'``, ``if gui`` and ``unless gui``, ``gui ==
    'true'`` and ``unless gui`` never hold in one run; a condition urdftool cannot read (an
    expression) excludes nothing."""
    from urdftool.description.launch_configs import launch_index

    root = _repo(tmp_path, {"p/package.xml": PACKAGE.format("p"), "p/launch/a.launch": """<launch>
      <arg name="mobile" default="none"/><arg name="gui" default="true"/>
      <node pkg="a" type="husky" if="$(eval arg('mobile') == 'husky')"/>
      <node pkg="a" type="none" if="$(eval arg('mobile') == 'none')"/>
      <node pkg="a" type="not_husky" unless="$(eval arg('mobile') == 'husky')"/>
      <node pkg="a" type="gui" if="$(arg gui)"/>
      <node pkg="a" type="no_gui" unless="$(arg gui)"/>
      <node pkg="a" type="gui_word" if="$(eval arg('gui') == 'true')"/>
      <node pkg="a" type="gui_other" if="$(eval arg('gui') == 'maybe')"/>
      <node pkg="a" type="either" if="$(eval arg('mobile') == 'husky' or arg('gui'))"/>
    </launch>"""})
    [configuration] = launch_index(root).configurations
    when = {s.executable: s.when for s in configuration.started}
    excluded = {(a, b) for a in when for b in when if when[a].excludes(when[b])}
    assert excluded == {("husky", "none"), ("none", "husky"), ("husky", "not_husky"),
                        ("not_husky", "husky"), ("gui", "no_gui"), ("no_gui", "gui"),
                        ("gui_word", "no_gui"), ("no_gui", "gui_word"),
                        ("gui_word", "gui_other"), ("gui_other", "gui_word"),
                        ("gui", "gui_other"), ("gui_other", "gui")}


def test_a_controller_started_under_a_condition_no_build_of_the_robot_meets_is_not_its(tmp_path):
    """Doosan's shape: a base launch file builds the arm when ``mobile == 'none'`` and the arm on
    wheels when ``mobile == 'husky'``, and spawns the wheels' controller when ``mobile ==
    'husky'``; MoveIt's launch file beside it builds the arm for planning whatever ``mobile``
    is. The wheels' controller is never started with the arm alone: nothing is said of it
    against the arm, and it stays the wheeled robot's."""
    from urdftool.description.runtime import runtime
    from urdftool.lint.engine import CheckOptions, load_and_check

    arm = "<robot name='arm'><link name='base'/><link name='l1'/>" \
          "<joint name='j1' type='revolute'><parent link='base'/><child link='l1'/>" \
          "<limit effort='1' velocity='1' lower='-1' upper='1'/></joint></robot>"
    wheeled = "<robot name='arm'><link name='base_link'/><link name='w'/>" \
              "<joint name='wheel' type='continuous'><parent link='base_link'/><child link='w'/></joint></robot>"
    root = _repo(tmp_path, {
        "p/package.xml": PACKAGE.format("p"),
        "p/arm.urdf.xacro": arm, "p/armmobile.urdf.xacro": wheeled,
        "p/config/control.yaml": """wheels_controller:
  type: diff_drive_controller/DiffDriveController
  left_wheel: wheel_left
  right_wheel: wheel_right
  base_frame_id: base_link
arm_controller:
  type: position_controllers/JointTrajectoryController
  joints: [j1]
""",
        "p/launch/description.launch": """<launch>
      <arg name="mobile" default="none"/>
      <group if="$(eval arg('mobile') == 'none')">
        <param name="robot_description" command="xacro $(find p)/arm.urdf.xacro"/></group>
      <group if="$(eval arg('mobile') == 'husky')">
        <param name="robot_description" command="xacro $(find p)/armmobile.urdf.xacro"/></group>
    </launch>""",
        "p/launch/control.launch": """<launch>
      <arg name="mobile" default="none"/>
      <rosparam file="$(find p)/config/control.yaml" command="load"/>
      <node pkg="controller_manager" type="spawner" name="s" args="wheels_controller"
            if="$(eval arg('mobile') == 'husky')"/>
      <node pkg="controller_manager" type="spawner" name="t" args="arm_controller"
            if="$(eval arg('mobile') == 'none')"/>
    </launch>""",
        "p/launch/base.launch": """<launch>
      <arg name="mobile" default="none"/>
      <include file="$(find p)/launch/control.launch"><arg name="mobile" value="$(arg mobile)"/></include>
      <include file="$(find p)/launch/description.launch"><arg name="mobile" value="$(arg mobile)"/></include>
    </launch>""",
        "p/launch/moveit.launch": """<launch>
      <param name="robot_description" command="xacro $(find p)/arm.urdf.xacro"/>
    </launch>""",
        "p/launch/bringup.launch": """<launch>
      <arg name="mobile" default="none"/>
      <include file="$(find p)/launch/base.launch"><arg name="mobile" value="$(arg mobile)"/></include>
      <include file="$(find p)/launch/moveit.launch"/>
    </launch>"""})
    result = load_and_check(str(root / "p/arm.urdf.xacro"), CheckOptions())
    assert {s.name for s in runtime(result.robot).spawns} == {"arm_controller"}
    assert not [f for f in result.findings if f.code in ("U602", "U616")], result.findings
    wheels = load_and_check(str(root / "p/armmobile.urdf.xacro"), CheckOptions()).robot
    assert {s.name for s in runtime(wheels).spawns} == {"wheels_controller"}


@pytest.mark.parametrize("rewrite, replaced", [
    ("text = text.replace('$(config)', share)", ("$(config)",)),
    ("text = text.replace('$(a)', share).replace(name, share)", ("$(a)", None)),
    ("text = text.format(share=share)", (None,)),
    ("text = text.format_map({'share': share})", (None,)),
    ("text = re.sub('[$][(]config[)]', share, text)", (None,)),
    ("text = string.Template(text).substitute(share=share)", (None, None)),
    ("", ()),
])
def test_the_text_a_python_launch_file_rewrites_before_loading_it_is_recorded(tmp_path, rewrite,
                                                                              replaced):
    """my-zzy/am_description: ``open(urdf).read().replace('$(controllers_yaml_path)', path)``,
    a template the launch file fills; U007 asks what it replaces (None: not known)."""
    root = _repo(tmp_path, {"p/launch/a.launch.py": f'''
import os, re, string
from launch import LaunchDescription
from launch_ros.actions import Node
from ament_index_python.packages import get_package_share_directory

def generate_launch_description():
    share = get_package_share_directory('p')
    name = os.environ.get('PLACEHOLDER', 'x')
    with open(os.path.join(share, 'r.urdf')) as file:
        text = file.read()
    {rewrite}
    return LaunchDescription([Node(package='robot_state_publisher',
                                   executable='robot_state_publisher',
                                   parameters=[{{'robot_description': text}}])])
'''})
    read = read_launch(root / "p/launch/a.launch.py")
    [described] = [a for a in read.actions if isinstance(a, Description)]
    assert not described.xacro and described.replaced == replaced


@pytest.mark.parametrize("end", ["\n", "\r\n", "\r"])
def test_a_launch_file_is_told_from_a_launch_test_whatever_ends_its_lines(end):
    """``def generate_launch_description`` at the start of a line as Python ends lines: a file
    ended by CR alone was a launch test (the multi-line ``^`` starts a line after LF only)."""
    from urdftool.description.launch import is_launch_test

    text = ("import x\ndef generate_test_description():\n    pass\n"
            "def generate_launch_description():\n    pass\n").replace("\n", end)
    assert not is_launch_test(text)
    assert is_launch_test(text.replace("generate_launch", "other"))


def test_nested_conditional_groups_of_each_form_need_both_conditions(tmp_path):
    """A node in a group with a condition inside another group with one runs only when both
    hold: Python's nested ``GroupAction(condition=...)``, XML's and YAML's nested
    ``<group if>`` say the same, the outer condition first."""
    root = _repo(tmp_path, {"p/package.xml": PACKAGE.format("p"), "p/launch/a.launch.py": """
from launch import LaunchDescription
from launch.actions import GroupAction
from launch.conditions import IfCondition
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node

def generate_launch_description():
    return LaunchDescription([
        GroupAction([
            GroupAction([Node(package="controller_manager", executable="spawner", arguments=["arm"])],
                        condition=IfCondition(LaunchConfiguration("real"))),
        ], condition=IfCondition(LaunchConfiguration("sim"))),
    ])
""", "p/launch/b.launch.xml": """<launch>
      <group if="$(var sim)"><group if="$(var real)">
        <node pkg="controller_manager" exec="spawner" args="arm"/>
      </group></group>
    </launch>""", "p/launch/c.launch.yaml": """launch:
- group:
    if: $(var sim)
    children:
    - group:
        if: $(var real)
        children:
        - node: {pkg: controller_manager, exec: spawner, args: arm}
"""})
    found = {}
    for configuration in launch_index(root).configurations:
        for started in configuration.started:
            found[configuration.top.path.name] = (started.when.certain, started.when.truth,
                                                     tuple(sorted(started.when.free)),
                                                     len(started.when.words))
    assert len(found) == 3 and len(set(found.values())) == 1, found
    certain, truth, free, words = found["a.launch.py"]
    assert not certain and truth is None and free == ("real", "sim") and words == 2


@pytest.mark.parametrize("item", ["None", "{'a': [1]}", "IfCondition(None)", "{**extra}"])
@pytest.mark.parametrize("where", ["Command(['xacro ', {item}, path])",
                                   "PythonExpression(['1 + ', {item}])",
                                   "Command(['xacro ', path], condition=IfCondition([{item}]))",
                                   "DeclareLaunchArgument('x', default_value=[{item}])"])
def test_what_is_no_text_where_launch_takes_a_substitution_is_unknown(tmp_path, item, where):
    """attack30: ``Command(['xacro ', None, path])`` (or a dict, a condition, a number) was
    joined as text by ``launch.concat``: AttributeError, U900 for every rule of the robot the
    launch file names, and a traceback of ``check robot.urdf``, which reads the launch files
    before any robot. concat takes anything: what is no text is unknown."""
    root = _repo(tmp_path, {"p/package.xml": PACKAGE.format("p"), "p/launch/a.launch.py": f'''
from launch.actions import DeclareLaunchArgument
from launch.conditions import IfCondition
from launch.substitutions import Command, PythonExpression
from launch_ros.actions import Node

def generate_launch_description():
    extra = dict(a=1)
    path = "urdf/arm.urdf.xacro"
    return LaunchDescription([Node(package="robot_state_publisher",
                                   executable="robot_state_publisher",
                                   parameters=[{{"robot_description": {where.format(item=item)}}}])])
'''})
    read = read_launch(root / "p/launch/a.launch.py", root)
    assert read.problem is None and read.actions
