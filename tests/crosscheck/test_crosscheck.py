"""``urdftool crosscheck``: each loader in a process of its own, the JSON shape, the table, the
exit code, a loader that dies, and the install hints (valid extras of pyproject.toml)."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

from conftest import ROOT

from urdftool.crosscheck import crosscheck, loaders
from urdftool.crosscheck.loaders import LOADERS, available

ARM = """<robot name="arm">
  <link name="world"/>
  <joint name="fix" type="fixed"><parent link="world"/><child link="base"/></joint>
  <link name="base"><inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="j" type="revolute"><parent link="base"/><child link="arm"/><origin xyz="0.1 0.2 0.3" rpy="0.1 0.2 0.3"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <link name="arm"><inertial><origin xyz="0 0 0.05"/><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="k" type="prismatic"><parent link="arm"/><child link="tip"/><origin xyz="0 0 0.4" rpy="0.5 0 0"/>
    <axis xyz="1 0 0"/><limit lower="0" upper="0.2" effort="1" velocity="1"/></joint>
  <link name="tip"><inertial><mass value="0.5"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
</robot>
"""
KEYS = {"name", "version", "loaded", "error", "location", "mass", "dof", "floating_base",
        "links", "dropped_links", "frames"}


def _installed(*names):
    missing = [n for n in names if not available(n)]
    if missing:
        pytest.skip(f"{missing[0]} is not installed: {LOADERS[missing[0]].install}")


def test_loaders_agree_on_a_small_arm(tmp_path):
    _installed("pinocchio", "mujoco")
    path = tmp_path / "arm.urdf"
    path.write_text(ARM)
    report = crosscheck(str(path), [n for n in LOADERS if available(n)])
    assert not report.disagreements and not report.failed and report.exit_code == 0
    document = report.as_dict()
    for loader in document["loaders"]:
        assert KEYS <= set(loader)
        # MuJoCo fuses the base, fixed to the world, into the world: its 1 kg are not counted
        mass = 1.5 if loader["name"] == "mujoco" else 2.5
        assert loader["mass"] == pytest.approx(mass) and loader["dof"] == 2
        assert len(loader["frames"]) == 4  # zero and three configurations
    # the frames really moved between configurations (the comparison is not of zeros)
    mujoco = next(r for r in report.loaders if r.name == "mujoco")
    assert mujoco.frames[0]["tip"] != mujoco.frames[1]["tip"]


def test_a_mass_a_loaders_reading_accounts_for_is_said_how_and_one_it_does_not_disagrees(
        tmp_path):
    """Each loader's total mass against what its own importer makes of the URDF's (read in
    their sources: crosscheck.masses): PyBullet's 1 kg for a link without <inertial>, MuJoCo's
    links welded to the world fused into it and its mass from the geoms of a link without
    <inertial> are said, each with its kilograms; a tab inside an inertial's origin, over which
    Pinocchio drops the inertial (1.5 kg of 2.5), was explained "by design" and the loaders
    "agreed": it is a disagreement."""
    _installed("pinocchio", "mujoco", "pybullet")
    path = tmp_path / "arm.urdf"
    path.write_text(ARM.replace(
        '<link name="tip"><inertial><mass value="0.5"/><inertia ixx="0.01" iyy="0.01" '
        'izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>',
        '<link name="tip"><collision><geometry><box size="0.2 0.2 0.2"/></geometry>'
        '</collision></link>'))
    report = crosscheck(str(path), ["pinocchio", "mujoco", "pybullet"])
    assert not report.disagreements and report.exit_code == 0, report.disagreements
    assert report.differences[:3] == [
        "total mass [kg]: pinocchio 2, mujoco 9, pybullet 3 (the URDF declares 2)",
        "mujoco holds 9 kg: without the 1 kg of base (welded to the world, fused into it); "
        "8 kg computed from the geoms of tip (no <inertial>)",
        "pybullet holds 3 kg: 1 kg for each link without <inertial>: tip"]
    path.write_text(ARM.replace('<origin xyz="0 0 0.05"/>', '<origin xyz="0 0\t0.05"/>'))
    report = crosscheck(str(path), ["pinocchio", "mujoco", "pybullet"])
    assert report.disagreements == [
        "pinocchio holds 1.5 kg of mass, where its reading of the URDF accounts for 2.5 kg: it "
        "read an <inertial> otherwise ('urdftool check' says which may be misread)"]
    assert report.exit_code == 1


def test_a_file_named_with_bytes_that_are_not_utf8_is_loaded_by_every_loader(tmp_path):
    """The loaders take a file name as UTF-8 text: a robot named ``arm\\xff.urdf`` (U+DCFF to
    Python) failed in each with "UnicodeEncodeError", a file each would read; it is read from a
    copy with a name they take."""
    _installed("pinocchio", "mujoco")
    path = Path(os.fsdecode(bytes(tmp_path / "arm") + b"\xff.urdf"))
    path.write_text(ARM)
    report = crosscheck(str(path), [n for n in ("pinocchio", "mujoco") if available(n)])
    assert not report.failed and report.exit_code == 0
    assert {loader.name for loader in report.loaders} == {"pinocchio", "mujoco"}


def test_a_loader_that_dies_is_a_failure_not_a_crash(tmp_path, monkeypatch):
    path = tmp_path / "arm.urdf"
    path.write_text(ARM)
    def abort(job):
        import faulthandler

        faulthandler.disable()  # the test runner's handler would print the worker's stack
        os.abort()

    monkeypatch.setitem(loaders.LOAD, "pinocchio", abort)
    monkeypatch.setattr("urdftool.crosscheck.available", lambda name: True)
    [result] = crosscheck(str(path), ["pinocchio"]).loaders
    assert not result.loaded and "died" in result.error


def test_a_refusal_is_located_at_the_line(tmp_path):
    _installed("mujoco")
    path = tmp_path / "arm.urdf"
    path.write_text(ARM.replace('<link name="tip"><inertial><mass value="0.5"/>',
                                '<link name="tip"><inertial><mass value="0"/>'))
    report = crosscheck(str(path), ["mujoco"])
    [result] = report.loaders
    assert not result.loaded and "mjMINVAL" in result.error
    assert result.location.line == 10 and report.exit_code == 1


def test_missing_loaders_say_how_to_install_them(tmp_path, monkeypatch):
    path = tmp_path / "arm.urdf"
    path.write_text(ARM)
    monkeypatch.setattr("urdftool.crosscheck.available", lambda name: name == "pinocchio")
    report = crosscheck(str(path))
    assert set(report.missing) == set(LOADERS) - {"pinocchio"}
    from urdftool.origin import install_command

    assert report.missing["mujoco"] == install_command("sim")


def test_the_install_hints_name_extras_that_exist():
    """The printed command installs the loader: its extra is in pyproject.toml and lists the
    loader's distribution (the package is not on PyPI: the command works from a checkout)."""
    extras = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"][
        "optional-dependencies"]
    distributions = {"pinocchio": "pin", "mujoco": "mujoco", "pybullet": "pybullet",
                     "drake": "drake"}
    for name, loader in LOADERS.items():
        if name == "sdformat":
            assert "apt-get install ignition-tools libsdformat-dev" in loader.install
            continue
        extra = loader.extra
        assert extra in extras and f"[{extra}]" in loader.install
        assert any(requirement.startswith(distributions[name])
                   for requirement in extras[extra]), (extra, extras[extra])


def test_cli_json_and_exit_code(tmp_path):
    _installed("pinocchio")
    path = tmp_path / "arm.urdf"
    path.write_text(ARM)
    done = subprocess.run([sys.executable, "-m", "urdftool", "crosscheck", str(path), "-l",
                           "pinocchio", "-f", "json"], capture_output=True, text=True,
                          timeout=300, cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    document = json.loads(done.stdout)
    assert [loader["name"] for loader in document["loaders"]] == ["pinocchio"]
    text = subprocess.run([sys.executable, "-m", "urdftool", "crosscheck", str(path), "-l",
                           "pinocchio"], capture_output=True, text=True, timeout=300)
    assert "pinocchio" in text.stdout and "the loaders agree" in text.stdout
    bad = subprocess.run([sys.executable, "-m", "urdftool", "crosscheck", str(path), "-l",
                          "mujuco"], capture_output=True, text=True, timeout=300)
    assert bad.returncode == 2 and "did you mean 'mujoco'" in bad.stderr


def test_pybullet_finds_package_meshes_of_an_expanded_xacro(tmp_path):
    """xacro's output is written to a temporary folder; PyBullet finds a package:// mesh only
    below the folders above the file it reads, so each package is linked beside it (it failed
    with "Cannot load URDF file" on every xacro robot with package meshes, UR5 included).
    Removing the folder removes the links, never the package's files."""
    _installed("pybullet")
    package = _package(tmp_path / "src")
    (package / "urdf").mkdir()
    path = package / "urdf" / "arm.urdf.xacro"
    mesh = '<geometry><mesh filename="package://my_arm/meshes/box.stl"/></geometry>'
    path.write_text(ARM.replace('<robot name="arm">',
                                '<robot name="arm" xmlns:xacro="http://wiki.ros.org/xacro">')
                    .replace('<link name="tip">', f'<link name="tip"><visual>{mesh}</visual>'
                             f'<collision>{mesh}</collision>'))
    [result] = crosscheck(str(path), ["pybullet"]).loaders
    assert result.loaded, result.error
    assert (package / "meshes" / "box.stl").is_file()


def _package(folder):
    """Package my_arm in ``folder``, with meshes/box.stl."""
    import trimesh

    package = folder / "my_arm"
    (package / "meshes").mkdir(parents=True)
    (package / "package.xml").write_text(
        '<package format="3"><name>my_arm</name><version>1.0.0</version></package>')
    trimesh.creation.box((0.1, 0.1, 0.1)).export(package / "meshes" / "box.stl")
    return package


def _package_arm(tmp_path):
    """A plain URDF in one folder whose mesh is in package my_arm in another."""
    package = _package(tmp_path / "elsewhere")
    (tmp_path / "out").mkdir()
    path = tmp_path / "out" / "arm.urdf"
    mesh = '<geometry><mesh filename="package://my_arm/meshes/box.stl"/></geometry>'
    path.write_text(ARM.replace('<link name="tip">', f'<link name="tip"><visual>{mesh}</visual>'
                                f'<collision>{mesh}</collision>'))
    return path, package


def test_pybullet_finds_the_packages_of_a_urdf_outside_them(tmp_path):
    """A plain URDF (xacro's output in /tmp) whose package is given with --package: PyBullet
    looks for it only above the file, so it is read from the temporary folder with the
    package linked beside it (it failed with 'Cannot load URDF file.', nothing else)."""
    _installed("pybullet")
    path, package = _package_arm(tmp_path)
    [result] = crosscheck(str(path), ["pybullet"], packages={"my_arm": package}).loaders
    assert result.loaded, result.error


def test_pybullet_says_which_mesh_it_cannot_find_and_what_to_do(tmp_path):
    """Without the package, PyBullet's 'Cannot load URDF file.' says which mesh, and that the
    package is given with --package; with the package but not the file, to ask check."""
    _installed("pybullet")
    path, package = _package_arm(tmp_path)
    [result] = crosscheck(str(path), ["pybullet"]).loaders
    assert not result.loaded
    assert result.error == ("error: Cannot load URDF file: it cannot find mesh "
                            "'my_arm/meshes/box.stl'; "
                            "package 'my_arm' is not found by urdftool either: give it with "
                            "--package my_arm=PATH (urdftool links each package it knows beside "
                            "the file PyBullet reads)")
    (package / "meshes" / "box.stl").unlink()
    [result] = crosscheck(str(path), ["pybullet"], packages={"my_arm": package}).loaders
    assert result.error.endswith("it cannot find mesh 'my_arm/meshes/box.stl', which is not "
                                 "there; 'urdftool check' says where each mesh was looked for")


def test_pybullet_says_a_package_folder_named_otherwise_is_why_it_finds_no_mesh(tmp_path):
    """The robot in a package whose folder is not named as the package (a clone named for its
    repository: LimX's TRON1, package robot_description in 'robot-description'): urdftool
    finds the mesh through package.xml, PyBullet only as a folder of the package's name above
    the file, and it said the mesh "is not there"."""
    _installed("pybullet")
    package = _package(tmp_path)
    package = package.rename(tmp_path / "my-arm-repository")
    (package / "urdf").mkdir()
    path = package / "urdf" / "arm.urdf"
    mesh = '<geometry><mesh filename="package://my_arm/meshes/box.stl"/></geometry>'
    path.write_text(ARM.replace('<link name="tip">', f'<link name="tip"><visual>{mesh}</visual>'
                                f'<collision>{mesh}</collision>'))
    [result] = crosscheck(str(path), ["pybullet"]).loaders
    assert not result.loaded
    assert result.error.endswith(
        "it cannot find mesh 'my_arm/meshes/box.stl', which is there: PyBullet looks for "
        "package://my_arm/... as a folder named 'my_arm' above the file it reads, and package "
        f"'my_arm' is the folder 'my-arm-repository' ({package}), found by its package.xml; a "
        "workspace whose folder is named 'my_arm' loads"), result.error


def test_mujoco_says_it_resolves_no_package_uri_and_what_to_do(tmp_path):
    """MuJoCo failed every ROS robot with package:// meshes (G1, H1, iCub, Pepper of the
    sweep) with "Error opening file 'package:/...'", nothing more."""
    _installed("mujoco")
    from urdftool.crosscheck import MUJOCO_PACKAGES

    path, package = _package_arm(tmp_path)
    [result] = crosscheck(str(path), ["mujoco"], packages={"my_arm": package}).loaders
    assert not result.loaded and result.error.endswith(f"; {MUJOCO_PACKAGES}")
    from urdftool.crosscheck import _PACKAGE_OPENED  # the crazyflie's file:// meshes too

    assert _PACKAGE_OPENED.search("Error: Error opening file 'file:/work/m.dae'")


def test_pybullet_finds_the_meshes_a_package_installs_from_elsewhere(tmp_path):
    """Bolt's meshes are package://robot_properties_bolt/resources/..., which its build
    installs from src/robot_properties_bolt/resources: urdftool found them, but the package's
    source folder linked beside the expansion does not hold them, and PyBullet said "it cannot
    find mesh ..., which is not there"."""
    _installed("pybullet")
    import trimesh

    (tmp_path / ".git").mkdir()
    package = _package(tmp_path)
    (package / "CMakeLists.txt").write_text(
        "project(my_arm)\ninstall(DIRECTORY src/my_arm/resources/ DESTINATION "
        "share/${PROJECT_NAME}/resources)\n")
    (package / "src" / "my_arm" / "resources" / "stl").mkdir(parents=True)
    trimesh.creation.box((0.1, 0.1, 0.1)).export(
        package / "src" / "my_arm" / "resources" / "stl" / "part.stl")
    mesh = '<geometry><mesh filename="package://my_arm/resources/stl/part.stl"/></geometry>'
    path = package / "arm.urdf.xacro"
    path.write_text(ARM.replace('<link name="tip">', f'<link name="tip"><visual>{mesh}</visual>'
                                f'<collision>{mesh}</collision>'))
    [result] = crosscheck(str(path), ["pybullet"]).loaders
    assert result.loaded, result.error


def test_the_advice_for_mujoco_loads_the_package_meshes(tmp_path):
    """MUJOCO_PACKAGES's block, meshdir with strippath (MuJoCo 3.7+ reads the URI as a path
    without it: the advice said meshdir alone, which still failed)."""
    _installed("mujoco")
    path, package = _package_arm(tmp_path)
    meshdir = os.path.relpath(package / "meshes", path.parent)
    path.write_text(path.read_text().replace(
        '<robot name="arm">', f'<robot name="arm"><mujoco><compiler meshdir="{meshdir}" '
        'strippath="true"/></mujoco>'))
    [result] = crosscheck(str(path), ["mujoco"], packages={"my_arm": package}).loaders
    assert result.loaded, result.error
    from urdftool.crosscheck import MUJOCO_PACKAGES

    assert '<compiler meshdir="..." strippath="true"/>' in MUJOCO_PACKAGES


def test_a_robots_own_mujoco_element_is_honoured_and_said(tmp_path):
    """A xacro robot whose <mujoco><compiler> names its meshes' folder relative to itself and
    balances inertias: its expansion, read from a temporary folder, lost the folder (MuJoCo:
    "Error opening file '../meshes/box.stl'"), and the inertias MuJoCo changed went unsaid."""
    _installed("mujoco")
    import trimesh

    (tmp_path / "meshes").mkdir()
    (tmp_path / "urdf").mkdir()
    trimesh.creation.box((0.1, 0.1, 0.1)).export(tmp_path / "meshes" / "box.stl")
    mesh = '<geometry><mesh filename="box.stl"/></geometry>'
    text = ARM.replace('<robot name="arm">', '<robot name="arm" xmlns:xacro="http://www.ros.org'
                       '/wiki/xacro"><mujoco><compiler meshdir="../meshes" '
                       'balanceinertia="true"/></mujoco>')
    text = text.replace('<link name="tip"><inertial><mass value="0.5"/><inertia ixx="0.01" '
                        'iyy="0.01" izz="0.01"', f'<link name="tip"><collision>{mesh}</collision>'
                        '<inertial><mass value="0.5"/><inertia ixx="0.001" iyy="0.001" '
                        'izz="0.01"')
    path = tmp_path / "urdf" / "arm.urdf.xacro"
    path.write_text(text)
    report = crosscheck(str(path), ["mujoco"])
    [result] = report.loaders
    assert result.loaded, result.error
    assert report.differences == [
        "total mass [kg]: mujoco 1.5 (the URDF declares 2.5)",
        "mujoco holds 1.5 kg: without the 1 kg of base (welded to the world, fused into it)",
        "mujoco has no link world, base (fused, lumped or dropped)",
        "mujoco read the robot's <mujoco><compiler>: balanceinertia=\"true\" (principal moments "
        "that break the triangle inequality raised)",
        "mujoco holds another mass or inertia [kg m^2] than the URDF declares for 1 link(s): "
        "tip: URDF 0.5 kg, moments 0.001 0.001 0.01, MuJoCo 0.5 kg, moments 0.004 0.004 "
        "0.004"]


def test_pybullet_asks_the_working_folder_not_its_search_path_for_meshes(tmp_path):
    """The fact U932 and the links beside xacro's output rest on (PyBullet 3.2.7): a
    package:// mesh is found from the working folder, not from setAdditionalSearchPath."""
    _installed("pybullet")
    import trimesh

    (tmp_path / "a").mkdir()
    (tmp_path / "b" / "pkg").mkdir(parents=True)
    trimesh.creation.box((0.1, 0.1, 0.1)).export(tmp_path / "b" / "pkg" / "m.stl")
    urdf = tmp_path / "a" / "r.urdf"
    urdf.write_text('<robot name="r"><link name="l"><visual><geometry>'
                    '<mesh filename="package://pkg/m.stl"/></geometry></visual></link></robot>')
    script = ("import os, sys, pybullet as p\n"
              "c = p.connect(p.DIRECT)\n"
              "if sys.argv[1] == 'search': p.setAdditionalSearchPath(sys.argv[2])\n"
              "else: os.chdir(sys.argv[2])\n"
              "try: p.loadURDF(sys.argv[3]); print('LOADED')\n"
              "except Exception: print('REFUSED')\n")
    said = {}
    for how in ("search", "cwd"):
        done = subprocess.run([sys.executable, "-c", script, how, str(tmp_path / "b"), str(urdf)],
                              capture_output=True, text=True, timeout=60)
        said[how] = [word for word in ("LOADED", "REFUSED") if word in done.stdout]
    assert said == {"search": ["REFUSED"], "cwd": ["LOADED"]}


def _two_loaders(tmp_path, positions):
    """A report of two loaded loaders (made here, no loader run) over ARM's links, the second
    placing 'tip' at ``positions`` (one per configuration), and the robot."""
    from urdftool.crosscheck import Crosscheck, LoaderResult
    from urdftool.description.load import load

    path = tmp_path / "arm.urdf"
    path.write_text(ARM)
    robot = load(str(path))
    here = {"world": [0.0] * 3, "base": [0.0] * 3, "arm": [0.1, 0.2, 0.3], "tip": [0.1, 0.2, 0.7]}
    first = LoaderResult("pinocchio", "1", True, frames=[dict(here) for _ in positions])
    second = LoaderResult("pybullet", "1", True,
                          frames=[{**here, "tip": position} for position in positions])
    return Crosscheck(str(path), [first, second], {}, [{} for _ in positions]), robot


def test_a_link_a_loader_cannot_place_is_said_once_not_as_nan_metres(tmp_path):
    """PyBullet normalises a zero axis into NaN: that is the loader giving no position, said
    once with the configurations, not 'NaN m apart' from each other loader at each one."""
    from urdftool.crosscheck import _compare

    report, robot = _two_loaders(tmp_path, [[None] * 3, [float("nan")] * 3])
    _compare(report, robot)
    assert report.disagreements == [
        "pybullet gives link 'tip' no finite position (NaN) at every configuration"]
    report, robot = _two_loaders(tmp_path, [[0.1, 0.2, 0.7], [None] * 3, [0.1, 0.2, 0.9]])
    _compare(report, robot)
    assert report.disagreements == [
        "pybullet gives link 'tip' no finite position (NaN) at configuration 1",
        "pinocchio and pybullet place link 'tip' 0.2 m apart at configuration 2"]


def test_a_failed_loader_shows_no_figures_in_the_table(tmp_path):
    """sdformat's ``-p`` may print a model whose ``-k`` check fails: the row says NO, and no
    mass or degrees of freedom of a model that did not load."""
    from urdftool.crosscheck import Crosscheck, LoaderResult
    from urdftool.report.crosscheck import text

    failed = LoaderResult("sdformat", "12", False, "Error Code 16", mass=0.0, dof=6,
                          floating_base=True)
    table = text(Crosscheck(str(tmp_path / "arm.urdf"), [failed], {}, [{}]))
    [row] = [line for line in table.splitlines() if line.startswith("sdformat")]
    assert row.split() == ["sdformat", "12", "NO", "-", "-", "-", "-", "-"]


def test_a_joint_a_loader_names_locates_its_error(tmp_path):
    """MuJoCo names the joint it refuses ("Element name 'j'"): the error is located there."""
    from urdftool.crosscheck import _located
    from urdftool.description.load import load

    path = tmp_path / "arm.urdf"
    path.write_text(ARM)
    robot = load(str(path))
    where = _located(robot, {}, "Error: axis too small in joint Element name 'k', id 1", "",
                     str(path))
    assert where is not None and where.line == 8


def test_sdformat_says_each_error_once(tmp_path, monkeypatch):
    """``gz sdf -p`` and ``-k`` print the same errors: the failure lists each once."""
    twice = "Error Code 16: Msg: A model must have at least one link."

    class Done:
        def __init__(self, returncode, stdout="", stderr=""):
            self.returncode, self.stdout, self.stderr = returncode, stdout, stderr

    monkeypatch.setattr(loaders, "sdformat_command", lambda: ["gz", "sdf"])
    monkeypatch.setattr(loaders.subprocess, "run", lambda command, **kwargs: Done(
        1, "", twice + "\n") if "-k" in command else Done(1, "", twice + "\n"))
    job = loaders.Job(str(tmp_path / "arm.urdf"), configurations=({},))
    assert loaders.load_sdformat(job)["error"] == twice


def test_pinocchios_refusal_says_what_urdfdom_printed_located(tmp_path):
    """Pinocchio reports every parse failure as "does not contain a valid URDF model"; urdfdom
    printed the cause: it is shown, and located (the second root link)."""
    _installed("pinocchio")
    path = tmp_path / "arm.urdf"
    path.write_text(ARM.replace('<link name="world"/>', '<link name="world"/><link name="stray"/>'))
    report = crosscheck(str(path), ["pinocchio"])
    [result] = report.loaders
    assert not result.loaded and "it printed why: Failed to find root link: Two root links " \
        "found: [stray] and [world]" in result.error, result.error
    assert result.location is not None and result.location.line == 2


def test_a_librarys_own_source_line_is_never_a_line_of_the_robot(tmp_path):
    """console_bridge ends a message with "at line 274 in .../model.cpp": the line of urdfdom's
    source, which must not locate the error at line 274 of the robot's file."""
    from urdftool.crosscheck import _located
    from urdftool.crosscheck.loaders import printed_errors
    from urdftool.description.load import load

    path = tmp_path / "arm.urdf"
    path.write_text(ARM)
    robot = load(str(path))
    output = "Error:   Something is wrong\n         at line 5 in /project/urdfdom/src/model.cpp\n"
    assert _located(robot, {5: robot.joints["j"]}, "", output, str(path)) is None
    assert printed_errors(output) == ["Something is wrong"]


@pytest.mark.parametrize("shape", ["link out", "named pipe", "package named pipe"])
def test_a_mesh_urdftool_does_not_open_is_refused_before_any_loader_opens_it(
        tmp_path, monkeypatch, shape):
    # session 13: MuJoCo read /etc/passwd through a committed link and quoted its path; a named
    # pipe held PyBullet and MuJoCo to the end of their budget
    from urdftool.errors import UsageError

    (tmp_path / ".git").mkdir()
    (tmp_path / "meshes").mkdir()
    (tmp_path / "package.xml").write_text(
        '<package format="3"><name>p</name><version>0.0.0</version><description>x'
        '</description><maintainer email="a@b.c">a</maintainer><license>MIT</license>'
        '</package>\n')
    if shape == "link out":
        (tmp_path / "meshes/m.stl").symlink_to("/etc/passwd")
    else:
        os.mkfifo(tmp_path / "meshes/m.stl")
    uri = "package://p/meshes/m.stl" if shape.startswith("package") else "meshes/m.stl"
    robot = tmp_path / "r.urdf"
    robot.write_text(ARM.replace('<link name="tip">', f'<link name="tip"><visual><geometry>'
                                                      f'<mesh filename="{uri}"/></geometry>'
                                                      '</visual>'))

    def run(*_):
        raise AssertionError("a loader ran")

    monkeypatch.setattr("urdftool.crosscheck._run", run)
    with pytest.raises(UsageError, match=r"r\.urdf:\d+: mesh .*; the loaders would open it"):
        crosscheck(str(robot), packages={"p": str(tmp_path)})


@pytest.mark.parametrize("shape", ["mtllib out", "texture out", "texture link out",
                                   "texture pipe", "gltf buffer out", "glb image out", "inside"])
def test_a_file_a_mesh_names_that_urdftool_does_not_open_is_refused_before_any_loader(
        tmp_path, monkeypatch, shape):
    """An OBJ's material library and its texture maps, a glTF's buffers and images: the
    loaders open them (PyBullet read /etc/passwd as the texture of an OBJ whose MTL said
    ``map_Kd /etc/passwd``), urdftool never does; outside the repository or no regular file,
    the run is refused before any loader, as for the meshes the URDF names."""
    from urdftool.errors import UsageError

    (tmp_path / ".git").mkdir()
    (tmp_path / "meshes").mkdir()
    mtl, texture = "m.mtl", "tex.png"
    if shape == "mtllib out":
        mtl = "../../../../../../../etc/passwd"
    elif shape == "texture out":
        texture = "-clamp on /etc/passwd"
    elif shape == "texture link out":
        (tmp_path / "meshes/tex.png").symlink_to("/etc/passwd")
    elif shape == "texture pipe":
        os.mkfifo(tmp_path / "meshes/tex.png")
    (tmp_path / "meshes/m.mtl").write_text(f"newmtl a\r\nKd 1 1 1\r\nmap_Kd {texture}\r\n")
    (tmp_path / "meshes/m.obj").write_text(f"mtllib {mtl}\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                          "usemtl a\nf 1 2 3\n")
    (tmp_path / "meshes/m.gltf").write_text(
        '{"asset": {"version": "2.0"}, "buffers": [{"uri": "%s", "byteLength": 36}]}' %
        ("/etc/passwd" if shape == "gltf buffer out" else "m.bin"))
    chunk = b'{"asset": {"version": "2.0"}, "images": [{"uri": "../../../../etc/passwd"}]}'
    (tmp_path / "meshes/m.glb").write_bytes(
        b"glTF" + (2).to_bytes(4, "little") + (20 + len(chunk)).to_bytes(4, "little") +
        len(chunk).to_bytes(4, "little") + b"JSON" + chunk)
    mesh = "meshes/m.gltf" if shape.startswith("gltf") else "meshes/m.glb" if \
        shape.startswith("glb") else "meshes/m.obj"
    robot = tmp_path / "r.urdf"
    robot.write_text(ARM.replace('<link name="tip">', f'<link name="tip"><visual><geometry>'
                                                      f'<mesh filename="{mesh}"/></geometry>'
                                                      '</visual>'))
    ran = []
    monkeypatch.setattr("urdftool.crosscheck._run", lambda *_: ran.append(1) or
                        (_ for _ in ()).throw(KeyError("ran")))
    if shape == "inside":
        with pytest.raises(KeyError):
            crosscheck(str(robot))
        assert ran
        return
    with pytest.raises(UsageError, match=r"r\.urdf:\d+: mesh .*; the loaders would open it"):
        crosscheck(str(robot))
    assert not ran


INERTIA = '<inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/>'
EDGES = f"""<robot name="edges">
  <link name="world"><inertial><mass value="4"/>{INERTIA}</inertial></link>
  <link name="base"><inertial><mass value="1"/>{INERTIA}</inertial></link>
  <link name="arm"><inertial><mass value="2"/>{INERTIA}</inertial>
    <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link>
  <link name="ghost" drake_ignore="true"><inertial><mass value="7"/>{INERTIA}</inertial></link>
  <link name="bare"><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>
    <visual><geometry><box size="1 1 1"/></geometry></visual></link>
  <link name="hand"><collision><geometry><sphere radius="0.05"/></geometry></collision></link>
  <link name="finger"><collision><geometry><box size="0.1 0.1 0.2"/></geometry></collision></link>
  <joint name="w" type="fixed"><parent link="world"/><child link="base"/></joint>
  <joint name="j" type="revolute"><parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="g" type="fixed" drake_ignore="true"><parent link="arm"/><child link="ghost"/></joint>
  <joint name="b" type="fixed"><origin xyz="0 0 0.5"/><parent link="arm"/><child link="bare"/></joint>
  <joint name="h" type="revolute"><parent link="bare"/><child link="hand"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="f" type="fixed"><parent link="hand"/><child link="finger"/></joint>
</robot>
"""


@pytest.mark.parametrize("robot", ["r2d2/r2d2.urdf.xacro", "humanoid/humanoid.urdf.xacro",
                                   "diffbot/diffbot.urdf.xacro", "edges"])
def test_each_loaders_mass_rule_is_the_loaders_own(robot, tmp_path):
    """crosscheck.masses reads each importer's rules from its sources; here each is held to
    the loader itself (each installed: Drake too, when its extra is): on the bundled robots
    and on one of every case the rules name (a link named world with an <inertial>, a
    drake_ignore link, links without <inertial> fused by MuJoCo into a body of their parent,
    with and without an <inertial> of its own, one whose visual box would weigh 1000 kg).
    MuJoCo's fused links without <inertial> were 'not accounted for' (a difference without a
    number); its world body, which a link named world is and whose <inertial> it holds, was
    counted as lost."""
    from urdftool.crosscheck.masses import account
    from urdftool.description.load import load

    names = [name for name in ("pinocchio", "mujoco", "pybullet", "drake") if available(name)]
    if robot == "edges":
        path = tmp_path / "edges.urdf"
        path.write_text(EDGES)
    else:
        path = ROOT / "robots" / robot
    report = crosscheck(str(path), names)
    assert not report.disagreements, report.disagreements
    described = load(str(path))
    for result in report.loaders:
        assert result.loaded, result.error
        reading = account(result.name, result, described)
        assert reading.expected == pytest.approx(result.mass, rel=1e-6), (result.name,
                                                                         reading.why)
    if robot == "edges" and "mujoco" in names:
        said = next(d for d in report.differences if d.startswith("mujoco holds"))
        # 1 kg of bare's box fused into arm (its visual weighs nothing); hand's sphere and
        # finger's box fused into hand: 0.5236 + 2 kg
        assert said == ("mujoco holds 16.5236 kg: without the 1 kg of base (welded to the "
                        "world, fused into it); 3.5236 kg computed from the geoms of bare "
                        "(fused into arm), hand, finger (fused into hand) (no <inertial>)"), said
