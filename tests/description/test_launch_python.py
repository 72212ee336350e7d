"""Python launch files read by their syntax tree: helpers returning from inside ``try``,
method chains on FindPackageShare, functions and classes of other modules of the repository
(urdftool/description/launch_python.py; the forms of test_launch.py's tests are not repeated)."""

from __future__ import annotations

import sys
from pathlib import Path

from urdftool.description.launch import Arg, Description, Start
from urdftool.description.launch_configs import launch_index, read_launch, repository_modules

from tests.description.test_launch import PACKAGE, _repo


def _read(root: Path, name: str):
    return read_launch(root / name, root)


def _described(read) -> list[Description]:
    return [a for a in read.actions if isinstance(a, Description)]


def _text(value) -> str:
    return "".join(p if isinstance(p, str) else f"<{p[0]}:{p[1]}>" for p in value.parts)


def test_a_helper_returning_from_inside_try_and_with_returns_it(tmp_path):
    root = _repo(tmp_path, {"p/package.xml": PACKAGE.format("p"), "p/launch/a.launch.py": '''
import os
from ament_index_python.packages import get_package_share_directory
from launch_ros.actions import Node

def load_file(package_name, file_path):
    absolute_file_path = os.path.join(get_package_share_directory(package_name), file_path)
    try:
        with open(absolute_file_path, "r") as file:
            return file.read()
    except EnvironmentError:
        return None

def generate_launch_description():
    description = load_file("p", "urdf/arm.urdf")
    return LaunchDescription([Node(package="robot_state_publisher",
                                   executable="robot_state_publisher",
                                   parameters=[{"robot_description": description}])])
'''})
    [described] = _described(_read(root, "p/launch/a.launch.py"))
    assert _text(described.file) == "<find:p>/urdf/arm.urdf" and not described.xacro


def test_a_list_indexed_by_a_digit_int_does_not_read_is_unknown_not_a_crash(tmp_path):
    """``files["²"]``: str.isdigit() takes '²' and int() refuses it, so reading the launch file
    raised ValueError (58 rules crashed, U900, on the robot it builds; a traceback of ``check
    a.launch.py``). An index is ASCII digits, as Python's own literals are."""
    root = _repo(tmp_path, {"p/package.xml": PACKAGE.format("p"), "p/launch/a.launch.py": '''
from launch_ros.actions import Node

def generate_launch_description():
    files = ["urdf/arm.urdf", "urdf/b.urdf"]
    second = files[1]
    return LaunchDescription([Node(package="robot_state_publisher",
                                   executable="robot_state_publisher",
                                   parameters=[{"robot_description": files["²"] + second}])])
'''})
    read = _read(root, "p/launch/a.launch.py")
    assert read.problem is None and read.actions  # (read, its node started)


def test_find_package_share_find_is_the_packages_share_folder(tmp_path):
    root = _repo(tmp_path, {"p/launch/a.launch.py": '''
import os
from launch.substitutions import Command
from launch_ros.substitutions import FindPackageShare

def generate_launch_description():
    share = FindPackageShare("p").find("p")
    return LaunchDescription([Node(package="robot_state_publisher", executable="x",
        parameters=[{"robot_description": Command(["xacro ", os.path.join(share, "urdf", "a.xacro")])}])])
'''})
    [described] = _described(_read(root, "p/launch/a.launch.py"))
    assert _text(described.command) == "xacro <find:p>/urdf/a.xacro"


MIXIN = '''
from launch.actions import DeclareLaunchArgument
from launch.substitutions import Command, FindExecutable, LaunchConfiguration, PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.substitutions import FindPackageShare

STARTED = Node(package="top_level", executable="of_the_module")  # importing it starts nothing


class DescriptionMixin:
    @staticmethod
    def param_robot_description(model=LaunchConfiguration("model", default="arm7"),
                                mode=LaunchConfiguration("mode", default="mock")):
        return {"robot_description": Command([FindExecutable(name="xacro"), " ",
            PathJoinSubstitution([FindPackageShare("arm_description"), "urdf", model]), ".xacro",
            " mode:=", mode])}

    @staticmethod
    def arg_model(default_value: str = "arm7"):
        return DeclareLaunchArgument(name="model", default_value=default_value)

    @classmethod
    def node_spawner(cls, controller):
        return cls.spawner(controller)

    @staticmethod
    def spawner(controller):
        return Node(package="controller_manager", executable="spawner", arguments=[controller])
'''


def test_a_mixin_class_of_another_package_builds_as_its_static_methods_say(tmp_path):
    root = _repo(tmp_path, {
        "arm_bringup/package.xml": PACKAGE.format("arm_bringup"),
        "arm_bringup/arm_bringup/__init__.py": "",
        "arm_bringup/arm_bringup/description.py": MIXIN,
        "arm_description/package.xml": PACKAGE.format("arm_description"),
        "arm_bringup/launch/hardware.launch.py": '''
from launch import LaunchDescription
from arm_bringup.description import DescriptionMixin as Mixin

def generate_launch_description():
    ld = LaunchDescription()
    ld.add_action(Mixin.arg_model())
    description = Mixin.param_robot_description(mode="hardware")
    ld.add_action(Node(package="robot_state_publisher", executable="robot_state_publisher",
                       parameters=[description]))
    ld.add_action(Mixin.node_spawner("arm_controller"))
    return ld
'''})
    read = _read(root, "arm_bringup/launch/hardware.launch.py")
    assert [(a.name, a.default.literal) for a in read.actions if isinstance(a, Arg)] == \
        [("model", "arm7")]  # the parameter's default, evaluated
    [described] = _described(read)
    assert _text(described.command) == "xacro <find:arm_description>/urdf/<arg:model>.xacro mode:=hardware"
    assert described.line == 8  # the launch file's call, not the module's line
    starts = [a for a in read.actions if isinstance(a, Start)]
    assert [s.executable.literal for s in starts] == ["robot_state_publisher", "spawner"]
    assert [w.literal for w in starts[1].arguments] == ["arm_controller"]  # through cls
    assert starts[1].line == 11


def test_a_helper_loaded_as_a_module_by_its_share_path_is_read(tmp_path):
    root = _repo(tmp_path, {
        "arm_description/package.xml": PACKAGE.format("arm_description"),
        "arm_description/launch/lib/description_lib.py": '''
from launch.substitutions import Command, FindExecutable, PathJoinSubstitution

def get_xacro_file_content(xacro_file, arguments={}):
    command = [PathJoinSubstitution([FindExecutable(name="xacro")]), " ", xacro_file, " "]
    if arguments and isinstance(arguments, dict):
        for key, val in arguments.items():
            command.extend(["{}:=".format(key), val, " "])
    return Command(command)
''',
        "arm_description/launch/a.launch.py": '''
import os
from ament_index_python import get_package_share_directory
from launch.launch_description_sources import load_python_launch_file_as_module

def launch_setup(context, *args, **kwargs):
    mod = load_python_launch_file_as_module(os.path.join(
        get_package_share_directory("arm_description"), "launch", "lib", "description_lib.py"))
    content = getattr(mod, "get_xacro_file_content")
    description = {"robot_description": content(xacro_file="/tmp/x.xacro",
                                                arguments={"dof": LaunchConfiguration("dof", default=7)})}
    return [Node(package="robot_state_publisher", executable="robot_state_publisher",
                 parameters=[description])]

def generate_launch_description():
    return LaunchDescription([OpaqueFunction(function=launch_setup)])
'''})
    [described] = _described(_read(root, "arm_description/launch/a.launch.py"))
    assert _text(described.command) == "xacro /tmp/x.xacro dof:=<arg:dof> "


def test_a_module_beside_the_launch_file_and_a_relative_import_are_read(tmp_path):
    root = _repo(tmp_path, {
        "p/package.xml": PACKAGE.format("p"),
        "p/launch/common.py": "def path():\n    return 'urdf/' + NAME\nNAME = 'a.urdf.xacro'\n",
        "p/launch/a.launch.py": '''
import common
from launch.substitutions import Command

def generate_launch_description():
    return [Node(package="robot_state_publisher", executable="x",
                 parameters=[{"robot_description": Command(["xacro ", common.path()])}])]
''',
        "q/package.xml": PACKAGE.format("q"),
        "q/q/__init__.py": "",
        "q/q/paths.py": "from .names import NAME as N\ndef path():\n    return 'urdf/' + N\n",
        "q/q/names.py": "NAME = 'b.urdf.xacro'\n",
        "q/launch/b.launch.py": '''
from q import paths
def generate_launch_description():
    return [Node(package="robot_state_publisher", executable="x",
                 parameters=[{"robot_description": Command(["xacro ", paths.path()])}])]
'''})
    [described] = _described(_read(root, "p/launch/a.launch.py"))
    assert _text(described.command) == "xacro urdf/a.urdf.xacro"
    [described] = _described(_read(root, "q/launch/b.launch.py"))
    assert _text(described.command) == "xacro urdf/b.urdf.xacro"


def test_modules_outside_the_repository_or_not_python_are_not_read(tmp_path):
    (tmp_path / "outside.py").write_text("def path():\n    return 'urdf/out.urdf.xacro'\n")
    root = _repo(tmp_path / "repo", {
        "p/package.xml": PACKAGE.format("p"),
        "p/launch/cycle_a.py": "from cycle_b import f\ndef g():\n    return f()\n",
        "p/launch/cycle_b.py": "from cycle_a import g\ndef f():\n    return g()\n",
        "p/launch/a.launch.py": '''
from ... import outside
import os, yaml, launch_ros
from cycle_a import g
def generate_launch_description():
    return [Node(package="robot_state_publisher", executable="x",
                 parameters=[{"robot_description": Command(["xacro ", outside.path(), g()])}])]
'''})
    modules = repository_modules(root)
    assert modules.named("", 3, root / "p/launch/a.launch.py") is None  # (the file above the root)
    assert modules.named("os", 0, root / "p/launch/a.launch.py") is None
    [described] = _described(_read(root, "p/launch/a.launch.py"))
    assert [p[0] for p in described.command.parts if isinstance(p, tuple)] == ["unknown", "unknown"]


def test_an_imported_module_is_never_run_and_its_top_level_starts_nothing(tmp_path):
    marker = tmp_path / "ran"
    root = _repo(tmp_path / "repo", {
        "p/package.xml": PACKAGE.format("p"),
        "p/p/__init__.py": "",
        "p/p/evil.py": f"""
import os
open({str(marker)!r}, "w").write("x")
node = Node(package="started", executable="on_import")
def helper():
    os.system("touch {marker}")
    return Node(package="helper", executable="h")
""",
        "p/launch/a.launch.py": "from p.evil import helper\n"
                                "def generate_launch_description():\n    return [helper()]\n"})
    modules = set(sys.modules)
    index = launch_index(root)
    assert not marker.exists()
    assert not {m for m in set(sys.modules) - modules if "evil" in m}
    [read] = index.files.values()
    assert [s.package.literal for s in read.actions if isinstance(s, Start)] == ["helper"]


def test_an_instance_of_a_class_of_another_package_keeps_the_attributes_set_on_it(tmp_path):
    # crane_plus: RobotDescriptionLoader() sets the path in __init__, the launch file an argument
    root = _repo(tmp_path, {
        "arm_description/package.xml": PACKAGE.format("arm_description"),
        "arm_description/arm_description/loader.py": '''
import os
from ament_index_python.packages import get_package_share_directory
from launch.substitutions import Command

class Loader():
    def __init__(self, port="/dev/ttyUSB0"):
        self.path = os.path.join(get_package_share_directory("arm_description"), "urdf", "arm.xacro")
        self.port = port
        self.use_camera = "false"

    def load(self):
        return Command(["xacro ", self.path, " port:=", self.port, " use_camera:=", self.use_camera])
''',
        "arm_description/launch/display.launch.py": '''
from arm_description.loader import Loader
from launch.substitutions import LaunchConfiguration

def generate_launch_description():
    loader = Loader(port="/dev/ttyACM0")
    loader.use_camera = LaunchConfiguration("use_camera")
    return [Node(package="robot_state_publisher", executable="robot_state_publisher",
                 parameters=[{"robot_description": loader.load()}]), Loader().missing()]
'''})
    [described] = _described(_read(root, "arm_description/launch/display.launch.py"))
    assert _text(described.command) == \
        "xacro <find:arm_description>/urdf/arm.xacro port:=/dev/ttyACM0 use_camera:=<arg:use_camera>"


def test_reading_other_modules_is_bounded(tmp_path):
    # a chain of 40 modules each importing the next, and functions calling themselves forever
    files = {"p/package.xml": PACKAGE.format("p"), "p/p/__init__.py": ""}
    for index in range(40):
        files[f"p/p/m{index}.py"] = (f"from p.m{index + 1} import f as g\n"
                                     "def f():\n    return g() + f() + f()\n")
    files["p/launch/a.launch.py"] = ("from p.m0 import f\ndef generate_launch_description():\n"
                                     "    return [Node(package='x', executable=f())]\n")
    root = _repo(tmp_path, files)
    read = _read(root, "p/launch/a.launch.py")
    [start] = [a for a in read.actions if isinstance(a, Start)]
    assert start.executable.parts[0][0] == "unknown"


def test_what_follows_a_guard_returning_early_is_read_under_its_negation(tmp_path):
    # TurtleBot3 manipulation's model.launch.py: if not is_valid_to_launch(): return LaunchDescription([])
    root = _repo(tmp_path, {"p/launch/a.launch.py": '''
def generate_launch_description():
    if not is_valid_to_launch():
        return LaunchDescription([])
    if LaunchConfiguration("mode") == "none":
        pass
    else:
        return [Node(package="robot_state_publisher", executable="robot_state_publisher",
                     parameters=[{"robot_description": Command(["xacro ", "a.urdf.xacro"])}]),
                Node(package="x", executable="y")]
    return [Node(package="z", executable="none_mode")]
'''})
    read = _read(root, "p/launch/a.launch.py")
    [described] = _described(read)
    assert [c.text for c in described.when] == ["not (not is_valid_to_launch())",
                                                "not (LaunchConfiguration('mode') == 'none')"]
    starts = {s.executable.literal: [c.kind for c in s.when] for s in read.actions
              if isinstance(s, Start)}
    assert starts == {"robot_state_publisher": ["unknown", "differs"], "y": ["unknown", "differs"],
                      "none_mode": ["unknown", "equals"]}


def test_a_helper_returning_one_of_two_texts_is_unknown_unless_its_test_is_decided(tmp_path):
    # tiago_robot's get_tiago_hw_suffix: a guard returns '_' + arm for 'no-arm', the rest
    # another suffix; it was read as the guard's value whatever the arm (the first found)
    root = _repo(tmp_path, {"p/package.xml": PACKAGE.format("p"), "p/launch/a.launch.py": '''
from launch.substitutions import Command, LaunchConfiguration

def suffix(arm):
    if arm in ["no-arm"]:
        return "_" + arm
    return "_gripper"

def generate_launch_description():
    given = suffix("tiago-arm")
    unknown_arm = suffix(LaunchConfiguration("arm"))
    return LaunchDescription([
        Node(package="robot_state_publisher", executable="robot_state_publisher",
             parameters=[{"robot_description": Command(["xacro ", "a" + given + ".urdf.xacro"])}]),
        Node(package="robot_state_publisher", executable="robot_state_publisher",
             parameters=[{"robot_description": Command(["xacro ", "b" + unknown_arm + ".urdf.xacro"])}]),
    ])
'''})
    first, second = _described(_read(root, "p/launch/a.launch.py"))
    assert _text(first.command) == "xacro a_gripper.urdf.xacro"  # decided: the arm is given
    assert _text(second.command).startswith("xacro b<unknown:")  # either suffix, not the first
    assert "_no-arm" not in _text(second.command)


def test_a_process_running_xacro_into_a_pipe_builds_the_file_it_names(tmp_path):
    # a2s-institute/solo12_robot's sim_gazebo.launch.py: ExecuteProcess(cmd=["xacro",
    # .../stand.urdf, "|", "ros2", "run", "gazebo_ros", "spawn_entity.py", "-stdin", ...],
    # shell=True): the .urdf holding $(find ...) is expanded by xacro, a note not U007's error
    from urdftool.description.runtime import builds
    from urdftool.lint.engine import CheckOptions, load_and_check

    root = _repo(tmp_path, {
        "p/package.xml": PACKAGE.format("p"),
        "p/urdf/stand.urdf": "<robot name='stand'><link name='s'><visual><geometry>"
                             "<mesh filename='file://$(find p)/meshes/stand.stl'/></geometry>"
                             "</visual></link></robot>",
        "p/launch/sim.launch.py": '''
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, ExecuteProcess
from launch.conditions import IfCondition
from launch.substitutions import LaunchConfiguration, PathJoinSubstitution
from launch_ros.substitutions import FindPackageShare

def generate_launch_description():
    spawn_stand = ExecuteProcess(
        cmd=["xacro", PathJoinSubstitution([FindPackageShare("p"), "urdf", "stand.urdf"]),
             "|", "ros2", "run", "gazebo_ros", "spawn_entity.py", "-stdin", "-entity", "stand"],
        shell=True, condition=IfCondition(LaunchConfiguration("stand")))
    return LaunchDescription([DeclareLaunchArgument("stand", default_value="true"), spawn_stand])
'''})
    [described] = _described(_read(root, "p/launch/sim.launch.py"))
    assert _text(described.command) == "xacro <find:p>/urdf/stand.urdf"  # not the pipe's words
    assert [c.kind for c in described.when] == ["if"]
    [build] = builds(str(root / "p/urdf/stand.urdf"))
    assert build.xacro and build.launch.endswith("sim.launch.py")
    [note] = load_and_check(str(root / "p/urdf/stand.urdf"), CheckOptions()).robot.notes
    assert note.kind == "xacro-in-urdf" and note.severity.name == "INFO"


def test_a_process_running_another_program_builds_nothing(tmp_path):
    root = _repo(tmp_path, {"p/package.xml": PACKAGE.format("p"), "p/launch/x.launch.py": '''
from launch import LaunchDescription
from launch.actions import ExecuteProcess

def generate_launch_description():
    return LaunchDescription([ExecuteProcess(cmd=["cat", "urdf/r.urdf", "|", "xacro", "-"])])
'''})
    assert _described(_read(root, "p/launch/x.launch.py")) == []


def test_a_node_s_source_is_what_ast_unparse_writes():
    """_source writes the calls launch files write most without ast.unparse (names, dotted
    names, calls, lists, keywords, non-negative integers, plain texts): as unparse writes
    them, and leaves every other node (quotes, backslashes, u'', negative or huge numbers,
    ``**kwargs``, other expressions) to unparse."""
    import ast

    from urdftool.description.launch_python import _plain_source, _source

    text = '''
LaunchConfiguration("prefix")
FindPackageShare(package="p")
launch_ros.substitutions.FindPackageShare("p", other=[1, "b", x.y])
Node(package="controller_manager", executable="spawner", arguments=["a", "--inactive"])
f()
f(u"x")
f("it's")
f('say "x"')
f("a\\\\b")
f("tab\\t")
f(-1)
f(2 ** 70)
f(18446744073709551616)
f(True)
f(None)
f(1.5)
f(**kw)
f(*a)
f(a)(b)
"x".join(y)
f([a for a in b])
'''
    plain = 0
    for node in ast.walk(ast.parse(text)):
        written = _plain_source(node, 0)
        plain += written is not None
        assert written is None or written == ast.unparse(node), ast.dump(node)
        assert _source(node) == (lambda t: t if len(t) <= 200 else t[:197] + "...")(
            ast.unparse(node))
    assert plain >= 40
    for source in ("f(u'x')", "f(\"it's\")", "f('a\\\\b')", "f(-1)", "f(True)", "f(**kw)",
                   "f(18446744073709551616)", "f(1.5)", "f(None)"):
        assert _plain_source(ast.parse(source).body[0].value, 0) is None, source


def test_a_python_launch_file_too_deep_for_the_parser_says_why():
    """200,000 unary minus signs or 3,000 nested lambdas: ``ast.parse`` raises MemoryError or
    RecursionError with no text, and U620 said "not valid Python: MemoryError: " (nothing
    after the colon)."""
    from urdftool.description.launch_python import read_python_launch

    for text in ("x = " + "-" * 200_000 + "1\n", "x = " + "lambda: " * 3000 + "1\n"):
        launch = read_python_launch(Path("a.launch.py"), "a.launch.py", text)
        assert launch.problem == "not valid Python: nested too deeply for Python's parser"


def test_a_node_in_nested_conditional_groups_carries_every_groups_condition(tmp_path):
    """A ``GroupAction`` with a condition inside another: the node runs only when both hold,
    the outer group's first (as ``<group if>`` nested in XML and YAML reads); a ``SetRemap``
    in a conditional group keeps only its own condition (its group's are the node's)."""
    root = _repo(tmp_path, {"q/package.xml": PACKAGE.format("q"), "q/launch/a.launch.py": """
from launch import LaunchDescription
from launch.actions import GroupAction
from launch.conditions import IfCondition, UnlessCondition
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node, SetRemap

def generate_launch_description():
    return LaunchDescription([
        GroupAction(actions=[
            GroupAction(actions=[
                SetRemap("a", "b"),
                Node(package="controller_manager", executable="spawner", arguments=["arm"],
                     condition=IfCondition(LaunchConfiguration("arm"))),
            ], condition=UnlessCondition(LaunchConfiguration("fake"))),
        ], condition=IfCondition(LaunchConfiguration("sim"))),
    ])
"""})
    read = _read(root, "q/launch/a.launch.py")
    [start] = [a for a in read.actions if isinstance(a, Start)]
    assert [c.kind for c in start.when] == ["if", "unless", "if"]
    assert [_text(c.value) for c in start.when] == ["<arg:sim>", "<arg:fake>", "<arg:arm>"]
    assert [r.when for r in start.remaps] == [()]


def test_a_set_remap_under_a_python_if_holds_under_its_test(tmp_path):
    """A ``SetRemap`` appended under a Python ``if`` holds for the nodes after it only when
    the test does."""
    root = _repo(tmp_path, {"q/package.xml": PACKAGE.format("q"), "q/launch/a.launch.py": """
from launch import LaunchDescription
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node, SetRemap

def generate_launch_description():
    actions = []
    if LaunchConfiguration("ns") == "arm":
        actions.append(SetRemap("a", "b"))
    actions.append(Node(package="q", executable="move_group"))
    return LaunchDescription(actions)
"""})
    read = _read(root, "q/launch/a.launch.py")
    [start] = [a for a in read.actions if isinstance(a, Start)]
    assert start.when == () and [[c.kind for c in r.when] for r in start.remaps] == [["equals"]]


def test_a_description_built_for_a_node_under_a_condition_has_that_condition(tmp_path):
    """A ``Command`` running xacro is evaluated when the node given it runs: the real robot's
    description given only to a robot_state_publisher under ``UnlessCondition(use_mock)`` is
    built under it; the mock's, given to move_group too, is built always but reaches the
    controller manager (through the robot_state_publisher) only under ``IfCondition``. So the
    real robot's controllers file, loaded under ``UnlessCondition``, is not the mock's
    companion, nor the mock's the real one's (dg5f_ros2's dg5f_right_moveit.launch.py: 60
    false U604 errors, each hand's controllers checked against the other build). A
    description held by nodes of different conditions keeps its own."""
    import urdftool
    from urdftool.description.runtime import runtime

    joint = ("<robot name='h'><link name='a'/><link name='b'/><joint name='j' type='revolute'>"
             "<parent link='a'/><child link='b'/><limit effort='1' velocity='1' lower='-1' "
             "upper='1'/></joint>{}</robot>")
    control = ("<ros2_control name='s' type='system'><hardware><plugin>{}</plugin></hardware>"
               "<joint name='j'><command_interface name='{}'/></joint></ros2_control>")
    controllers = ("controller_manager:\n  ros__parameters:\n    c:\n      type: "
                   "joint_trajectory_controller/JointTrajectoryController\n"
                   "c:\n  ros__parameters:\n    joints: [j]\n    command_interfaces: [{}]\n")
    root = _repo(tmp_path, {
        "p/package.xml": PACKAGE.format("p"),
        "p/urdf/mock.urdf.xacro": joint.format(control.format("mock_components/GenericSystem",
                                                              "position")),
        "p/urdf/real.urdf.xacro": joint.format(control.format("v/Hardware", "effort")),
        "p/urdf/other.urdf.xacro": joint.format(""),
        "p/config/mock.yaml": controllers.format("position"),
        "p/config/real.yaml": controllers.format("effort"),
        "p/launch/hand.launch.py": '''
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.conditions import IfCondition, UnlessCondition
from launch.substitutions import Command, FindExecutable, LaunchConfiguration, PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.substitutions import FindPackageShare

def generate_launch_description():
    use_mock = LaunchConfiguration("use_mock")
    mock = Command([PathJoinSubstitution([FindExecutable(name="xacro")]), " ",
                    PathJoinSubstitution([FindPackageShare("p"), "urdf", "mock.urdf.xacro"])])
    real = Command([PathJoinSubstitution([FindExecutable(name="xacro")]), " ",
                    PathJoinSubstitution([FindPackageShare("p"), "urdf", "real.urdf.xacro"])])
    shared = Command(["xacro ", PathJoinSubstitution([FindPackageShare("p"), "urdf",
                                                      "other.urdf.xacro"])])
    return LaunchDescription([
        DeclareLaunchArgument("use_mock", default_value="true"),
        Node(package="controller_manager", executable="ros2_control_node",
             parameters=[PathJoinSubstitution([FindPackageShare("p"), "config", "mock.yaml"])],
             condition=IfCondition(use_mock)),
        Node(package="robot_state_publisher", executable="robot_state_publisher",
             parameters=[{"robot_description": mock}], condition=IfCondition(use_mock)),
        Node(package="controller_manager", executable="ros2_control_node",
             parameters=[PathJoinSubstitution([FindPackageShare("p"), "config", "real.yaml"])],
             condition=UnlessCondition(use_mock)),
        Node(package="robot_state_publisher", executable="robot_state_publisher",
             parameters=[{"robot_description": real}], condition=UnlessCondition(use_mock)),
        Node(package="moveit_ros_move_group", executable="move_group",
             parameters=[{"robot_description": mock}]),
        Node(package="rviz2", executable="rviz2", parameters=[{"robot_description": shared}],
             condition=IfCondition(use_mock)),
        Node(package="a", executable="b", parameters=[{"robot_description": shared}]),
    ])
'''})
    described = {_text(d.command).split("/")[-1]: ([c.kind for c in d.when],
                                                   d.published and [c.kind for c in d.published])
                 for d in _described(_read(root, "p/launch/hand.launch.py"))}
    # MoveIt plans with the mock unconditionally; it reaches a controller manager only with
    # use_mock, through the robot_state_publisher publishing it
    assert described == {"mock.urdf.xacro": ([], ["if"]), "real.urdf.xacro": (["unless"], None),
                         "other.urdf.xacro": ([], None)}
    for robot, own in (("mock", "mock.yaml"), ("real", "real.yaml")):
        checked = urdftool.load(str(root / f"p/urdf/{robot}.urdf.xacro"))
        loaded = {load.path.name for configuration, _ in runtime(checked).configurations
                  for load in configuration.loaded}
        assert loaded == {own}, robot


def test_a_node_assigned_to_a_name_never_read_is_not_started(tmp_path):
    """A spawner built into a variable the launch description never takes is never started
    (wearable_robot_eval's eduexo_only.launch.py: a U619 error said it started together with
    the trajectory controller); one the file reads, in a list or ``add_action``, is."""
    root = _repo(tmp_path, {"p/package.xml": PACKAGE.format("p"), "p/launch/a.launch.py": '''
from launch import LaunchDescription
from launch_ros.actions import Node

def generate_launch_description():
    unused = Node(package="controller_manager", executable="spawner",
                  arguments=["forward_position_controller"])
    listed = Node(package="controller_manager", executable="spawner",
                  arguments=["joint_trajectory_controller"])
    added = Node(package="controller_manager", executable="spawner",
                 arguments=["joint_state_broadcaster"])
    ld = LaunchDescription([listed])
    ld.add_action(added)
    return ld
'''})
    started = [a for a in _read(root, "p/launch/a.launch.py").actions if isinstance(a, Start)]
    assert sorted(_text(s.arguments[0]) for s in started) == [
        "joint_state_broadcaster", "joint_trajectory_controller"]
