"""readers: who reads a robot's file when urdfdom does not, decided from its files, both ways
for each reader."""

from __future__ import annotations

from pathlib import Path

from urdftool.description.load import load
from urdftool.description.readers import other_reader

DRAKE = ('<robot name="r" xmlns:drake="http://drake.mit.edu"><link name="a"/></robot>')
PLAIN = '<robot name="r"><link name="a"/></robot>'
MANIFEST = ('<package format="2"><name>{name}</name><version>0.0.0</version>'
            '<description>d</description><maintainer email="a@b.c">a</maintainer>'
            '<license>MIT</license>{tools}</package>')
FETCH = "const robot = await loader.loadAsync('/urdf/rover/rover.urdf');\n"


def _write(root: Path, files: dict) -> None:
    for name, text in files.items():
        (root / name).parent.mkdir(parents=True, exist_ok=True)
        (root / name).write_text(text)


def test_a_drake_namespaced_robot_no_ros_evidence_names_is_drakes(tmp_path):
    """drake_models: a package.xml naming no build tool says nothing of ROS; the namespace on
    <robot>, or a drake: element alone, says Drake reads it."""
    _write(tmp_path, {"package.xml": MANIFEST.format(name="drake_models", tools=""),
                      "r.urdf": DRAKE,
                      "e.urdf": '<robot name="r"><link name="a"><collision><drake:x '
                                'xmlns:drake="http://drake.mit.edu"/></collision></link></robot>'})
    reader = other_reader(load(str(tmp_path / "r.urdf")))
    assert reader.kind == "drake" and 'xmlns:drake="http://drake.mit.edu"' in reader.why
    assert "nothing says ROS runs this robot" in reader.why
    assert "<drake:x>" in other_reader(load(str(tmp_path / "e.urdf"))).why
    _write(tmp_path, {"r.urdf": PLAIN})
    assert other_reader(load(str(tmp_path / "r.urdf"))) is None


def test_a_drake_namespaced_robot_of_a_ros_package_is_urdfdoms(tmp_path):
    """A package building with catkin or ament (or a launch file, ros2_control...) says ROS
    runs it: Drake's namespace in it decides nothing."""
    for tools in ("<buildtool_depend>catkin</buildtool_depend>",
                  "<buildtool_depend>ament_cmake</buildtool_depend>"):
        _write(tmp_path, {"package.xml": MANIFEST.format(name="bot", tools=tools),
                          "urdf/r.urdf": DRAKE})
        assert other_reader(load(str(tmp_path / "urdf" / "r.urdf"))) is None
    _write(tmp_path / "alone", {"r.urdf": DRAKE.replace(
        "</robot>", '<ros2_control name="s" type="system"/></robot>')})
    assert other_reader(load(str(tmp_path / "alone" / "r.urdf"))) is None


def _web(root: Path, source: str = FETCH, extra: dict | None = None) -> Path:
    _write(root, {"package.xml": MANIFEST.format(
                      name="rover", tools="<buildtool_depend>ament_cmake</buildtool_depend>"),
                  "gui/frontend/package.json": "{}",
                  "gui/frontend/src/model.ts": source,
                  "gui/frontend/public/urdf/rover/rover.urdf": PLAIN, **(extra or {})})
    return root / "gui/frontend/public/urdf/rover/rover.urdf"


def test_a_web_applications_served_copy_its_source_fetches_is_a_browsers(tmp_path):
    """mrover's web GUI: the ament package around the application says nothing of its served
    copy; its source naming the file does."""
    reader = other_reader(load(str(_web(tmp_path))))
    assert reader.kind == "browser" and "model.ts fetches '/urdf/rover/rover.urdf'" in reader.why


def test_a_served_copy_nothing_fetches_is_urdfdoms(tmp_path):
    assert other_reader(load(str(_web(tmp_path, "const x = '/urdf/other.urdf';\n")))) is None


def test_a_served_copy_a_launch_file_describes_is_urdfdoms(tmp_path):
    """ROS evidence besides the package around it keeps the file urdfdom's: a launch file
    giving it as the robot description."""
    launch = ("<launch><param name=\"robot_description\" textfile=\"$(find rover)/gui/frontend/"
              "public/urdf/rover/rover.urdf\"/><node name=\"rsp\" pkg=\"robot_state_publisher\" "
              "type=\"robot_state_publisher\"/></launch>")
    path = _web(tmp_path, extra={"launch/rsp.launch": launch})
    assert other_reader(load(str(path))) is None


def test_a_served_copy_in_a_ros_package_of_its_own_is_urdfdoms(tmp_path):
    """A package.xml between the file and the web application: the file is that package's."""
    path = _web(tmp_path, extra={"gui/frontend/public/urdf/package.xml": MANIFEST.format(
        name="copy", tools="<buildtool_depend>catkin</buildtool_depend>")})
    assert other_reader(load(str(path))) is None


def test_a_web_application_above_the_robots_repository_says_nothing_of_it(tmp_path):
    """A repository cloned into some web application's ``public`` folder: the application and
    its sources are not the repository's, and were walked and read (up to 2,000 folders of
    whatever lies above the clone) to make its errors warnings."""
    _write(tmp_path, {"package.json": "{}", "src/model.ts": "fetch('/clone/r.urdf');\n",
                      "public/clone/r.urdf": PLAIN})
    (tmp_path / "public" / "clone" / ".git").mkdir()
    assert other_reader(load(str(tmp_path / "public" / "clone" / "r.urdf"))) is None


def test_a_file_in_genesis_assets_is_genesis_read(tmp_path):
    """Genesis-arter (a copy of the Genesis simulator): genesis/assets/urdf/... are read by
    genesis/utils/urdf.py, whose urdfpy takes a <limit> without effort or velocity (a false
    U203 error on PartNet-Mobility's mobility.urdf) and a link without <inertial> (U303).
    Without the loader, or a folder of another name, or with ROS running it, it is urdfdom's."""
    limitless = ('<robot name="r"><link name="a"/><link name="b"/><joint name="j" '
                 'type="prismatic"><parent link="a"/><child link="b"/><axis xyz="0 1 0"/>'
                 '<limit lower="-0.1" upper="0"/></joint></robot>')
    (tmp_path / ".git").mkdir()  # (a clone: the repository the walk stays within)
    _write(tmp_path, {"genesis/__init__.py": "", "genesis/utils/urdf.py": "import urdfpy\n",
                      "genesis/assets/urdf/3763/mobility.urdf": limitless})
    robot = load(str(tmp_path / "genesis/assets/urdf/3763/mobility.urdf"))
    reader = other_reader(robot)
    assert reader.kind == "genesis" and "the assets of the Genesis package" in reader.why
    from urdftool.lint.engine import check_robot
    [u203] = [f for f in check_robot(robot) if f.code == "U203"]
    assert u203.severity.value == "warning" and u203.urdfdom_refuses
    (tmp_path / "genesis/utils/urdf.py").unlink()
    assert other_reader(load(str(tmp_path / "genesis/assets/urdf/3763/mobility.urdf"))) is None
    _write(tmp_path, {"genesis/utils/urdf.py": "", "other/__init__.py": "",
                      "other/utils/urdf.py": "", "other/assets/m.urdf": limitless,
                      "genesis/assets/ros/package.xml": MANIFEST.format(
                          name="bot", tools="<buildtool_depend>catkin</buildtool_depend>"),
                      "genesis/assets/ros/m.urdf": limitless})
    assert other_reader(load(str(tmp_path / "other/assets/m.urdf"))) is None
    assert other_reader(load(str(tmp_path / "genesis/assets/ros/m.urdf"))) is None
