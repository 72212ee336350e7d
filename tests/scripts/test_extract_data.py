"""urdftool's data files: well-formed, with their sources, and reproduced by their scripts.

``urdftool/data/ros2_controllers.json``, ``ros_controllers.json`` and ``gazebo_plugins.json`` are
generated once by ``scripts/extract_controller_parameters.py``,
``scripts/extract_ros1_controller_parameters.py`` and ``scripts/extract_gazebo_plugins.py`` from
the upstream repositories and committed. The fixtures under ``fixtures/`` hold a few of
the same facts (names, types, defaults: no upstream text) laid out as the repositories lay
them out; the scripts must read them into exactly what the committed data says of them.
"""

from __future__ import annotations

import importlib.util
import json
import sys
from pathlib import Path

import pytest

from urdftool.description import controller_parameters as schema

ROOT = Path(__file__).resolve().parents[2]
FIXTURES = Path(__file__).resolve().parent / "fixtures"
DATA = ROOT / "urdftool" / "data"
TYPES = {"bool", "int", "double", "string", "bool_array", "int_array", "double_array",
         "string_array", "none", "string_or_array"}


def _script(name: str):
    sys.path.insert(0, str(ROOT / "scripts"))
    try:
        spec = importlib.util.spec_from_file_location(name, ROOT / "scripts" / f"{name}.py")
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        return module
    finally:
        sys.path.remove(str(ROOT / "scripts"))


def _load(name: str) -> dict:
    return json.loads((DATA / name).read_text(encoding="utf-8"))


def test_ros2_data_is_well_formed():
    data = _load("ros2_controllers.json")
    assert data["licence"]["spdx"] == "Apache-2.0" and "Apache License" in data["licence"]["notice"]
    for source in data["sources"].values():
        assert source["repository"].startswith("ros-controls/")
        for ref in source["refs"].values():
            assert len(ref["commit"]) == 40 and ref["ref"]
    used = set()
    for name, per_distribution in data["classes"].items():
        assert name.count("/") == 1, name
        assert set(per_distribution) <= set(data["distributions"])
        for idents in per_distribution.values():
            used.update(idents)
    used.update(data["controller"].values())
    used.update(data["controller_manager"].values())
    assert used == set(data["schemas"]), "every schema is used, every use has a schema"
    for ident, entry in data["schemas"].items():
        assert entry["source"] in data["sources"] and entry["path"] in ident
        assert set(entry["distributions"]) <= set(data["distributions"])
        for facts in entry["parameters"].values():
            assert facts["type"].split("_fixed_")[0] in TYPES, facts
            assert set(facts) <= {"type", "default", "read_only", "validation"}
    # the distributions the checks rely on are there, with the classes everybody uses
    jtc = data["classes"]["joint_trajectory_controller/JointTrajectoryController"]
    assert {"humble", "jazzy", "rolling"} <= {d for d, ids in jtc.items() if ids}


def test_ros1_data_is_well_formed():
    data = _load("ros_controllers.json")
    assert data["licence"]["spdx"] == "BSD-3-Clause"
    assert data["source"]["repository"] == "ros-controls/ros_controllers"
    assert len(data["source"]["commit"]) == 40
    for name, parameters in data["classes"].items():
        assert name.count("/") == 1, name
        for facts in parameters.values():
            assert facts["type"] in TYPES and facts["line"] > 0 and facts["path"]
    assert "default" not in data["classes"]["joint_state_controller/JointStateController"]["publish_rate"]


def test_ros2_script_reproduces_the_committed_facts_from_a_fixture(tmp_path):
    script = _script("extract_controller_parameters")
    output = tmp_path / "out.json"
    trees = [f"--tree={d}={FIXTURES / 'ros2_controllers' / d}" for d in ("humble", "jazzy")]
    controls = [f"--control-tree={d}={FIXTURES / 'ros2_control' / d}" for d in ("humble", "jazzy")]
    assert script.main([*trees, *controls, "-o", str(output)]) == 0
    made, committed = json.loads(output.read_text()), _load("ros2_controllers.json")

    def parameters(data, ident):
        return data["schemas"][ident]["parameters"]

    for name in ("forward_command_controller/ForwardCommandController",
                 "position_controllers/JointGroupPositionController"):
        for distro in ("humble", "jazzy"):
            [ident] = made["classes"][name][distro]
            [real] = committed["classes"][name][distro]
            assert ident == real  # the same file, first seen in the same distribution
            assert parameters(made, ident) == parameters(committed, real)
    # the base parameters of every controller, and the manager's update_rate
    for distro in ("humble", "jazzy"):
        assert parameters(made, made["controller"][distro]) == \
            parameters(committed, committed["controller"][distro])
        assert parameters(made, made["controller_manager"][distro])["update_rate"]["type"] == "int"
    # one schema for a file that did not change between two distributions
    assert made["schemas"][made["classes"]["forward_command_controller/ForwardCommandController"]
                           ["humble"][0]]["distributions"] == ["humble", "jazzy"]


def test_ros2_script_refuses_a_fact_it_cannot_find(tmp_path):
    script = _script("extract_controller_parameters")
    empty = tmp_path / "control"
    (empty / "controller_manager" / "src").mkdir(parents=True)
    (empty / "controller_manager" / "src" / "controller_manager.cpp").write_text("// nothing\n")
    with pytest.raises(SystemExit, match="MANAGER_FACTS"):
        script.main([f"--control-tree=humble={empty}", f"--tree=humble={empty}",
                     "-o", str(tmp_path / "out.json")])


def test_ros1_script_reproduces_the_committed_facts_from_a_fixture(tmp_path):
    script = _script("extract_ros1_controller_parameters")
    name = "joint_state_controller/JointStateController"
    tree = script.DirTree(FIXTURES / "ros_controllers", script.REF)
    made = script.extract(tree, {name: script.FACTS[name]})
    assert made["classes"][name] == _load("ros_controllers.json")["classes"][name]


def test_ros1_script_refuses_a_required_parameter_it_does_not_see_required(tmp_path):
    script = _script("extract_ros1_controller_parameters")
    (tmp_path / "jsc" / "src").mkdir(parents=True)
    (tmp_path / "jsc" / "jsc_plugin.xml").write_text('<class name="jsc/JointStateController"/>')
    (tmp_path / "jsc" / "src" / "jsc.cpp").write_text(
        'controller_nh.getParam("publish_rate", publish_rate_);\n' + "\n" * 10 + "return false;\n")
    facts = {"jsc/JointStateController": {"publish_rate": ("double", True, "jsc/src/jsc.cpp",
                                                          r'getParam\("publish_rate"')}}
    with pytest.raises(SystemExit, match="still required"):
        script.extract(script.DirTree(tmp_path, script.REF), facts)


def test_the_reader_answers_from_the_data():
    jtc = schema.ros2_schemas("joint_trajectory_controller/JointTrajectoryController")
    assert jtc["humble"].find("gains.elbow.p").name == "gains.__map_joints.p"
    assert jtc["humble"].find("state_publish_rate") is not None
    assert jtc["rolling"].find("state_publish_rate") is None
    assert jtc["jazzy"].is_group("constraints") and not jtc["jazzy"].is_group("joints")
    assert "update_rate" in jtc["jazzy"].parameters  # every controller's
    assert set(schema.required("diff_drive_controller/DiffDriveController", 2)) == {
        "left_wheel_names", "right_wheel_names", "wheel_radius", "wheel_separation"}
    assert schema.required("joint_state_controller/JointStateController", 1)["publish_rate"].source.endswith(
        "(678b92adfd92)")


def test_gazebo_script_reproduces_the_committed_vocabulary_from_a_fixture(tmp_path):
    script = _script("extract_gazebo_plugins")
    output = tmp_path / "out.json"
    assert script.main([f"--tree=gazebo_ros_pkgs@noetic-devel={FIXTURES / 'gazebo_ros_pkgs'}",
                        "-o", str(output)]) == 0
    made = json.loads(output.read_text())["plugins"]["gazebo_ros_diff_drive"]["versions"]["ros1"]
    committed = _load("gazebo_plugins.json")["plugins"]["gazebo_ros_diff_drive"]["versions"]["ros1"]
    assert made["tags"] == committed["tags"]  # the helper's header and linked library included
    assert made["read"][0]["paths"] == committed["read"][0]["paths"]


def test_gazebo_data_is_well_formed():
    data = _load("gazebo_plugins.json")
    assert set(data["licence"]["licences"]) == {s["repository"] for s in data["sources"].values()}
    for source in data["sources"].values():
        assert len(source["commit"]) == 40
    for key, plugin in data["plugins"].items():
        assert plugin["family"] in ("classic", "gz")
        for version, entry in plugin["versions"].items():
            assert entry["tags"] == sorted(set(entry["tags"])) and entry["tags"], key
            assert all(r["source"] in data["sources"] and r["paths"] for r in entry["read"])
    assert data["plugins"]["gazebo_ros_diff_drive"]["versions"].keys() == {"ros1", "ros2"}
    assert "gz_ros2_control/GazeboSimSystem" in data["plugins"]["gz_ros2_control-system"]["hardware"]
