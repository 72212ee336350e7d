"""``$(find NAME)`` / ``package://NAME/...`` name the installed share/NAME: a package's build
description, read without running it, says which source folder each installed path comes from
(description/install_layout.py), and the one resolver (PackageResolver) answers from it."""

from __future__ import annotations

import os

import pytest

from urdftool.description.install_layout import cmake_commands, layout
from urdftool.description.packages import PackageResolver


def package(repo, relative, name, **files):
    """A package ``name`` at ``repo/relative`` holding ``files`` (path -> text)."""
    folder = repo / relative
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "package.xml").write_text(f"<package><name>{name}</name></package>")
    for path, text in files.items():
        (folder / path).parent.mkdir(parents=True, exist_ok=True)
        (folder / path).write_text(text)
    return folder


@pytest.fixture
def repo(tmp_path):
    (tmp_path / ".git").mkdir()
    return tmp_path


def resolve(repo, uri):
    return PackageResolver(start=repo, environ={}).resolve_uri(uri, repo)


def test_cmake_directory_without_slash_installs_the_folder(repo):
    package(repo, "example_1", "demo_1", **{
        "CMakeLists.txt": "project(demo_1)\ninstall(\n  DIRECTORY description/launch "
                          "description/ros2_control description/urdf\n"
                          "  DESTINATION share/${PROJECT_NAME}\n)\n",
        "description/ros2_control/rrbot.ros2_control.xacro": "<robot/>"})
    found = resolve(repo, "package://demo_1/ros2_control/rrbot.ros2_control.xacro")
    assert found == repo / "example_1/description/ros2_control/rrbot.ros2_control.xacro"


def test_cmake_directory_with_slash_installs_its_contents(repo):
    package(repo, "pkg", "pkg", **{
        "CMakeLists.txt": "project(pkg)\n"
                          "install(DIRECTORY src/pkg/resources/ DESTINATION "
                          "share/${PROJECT_NAME}/resources)  # contents\n",
        "src/pkg/resources/meshes/base.stl": "solid"})
    assert resolve(repo, "package://pkg/resources/meshes/base.stl").is_file()
    # the slash matters: the folder itself is not at resources/resources
    assert not resolve(repo, "package://pkg/resources/resources/meshes/base.stl").is_file()


def test_cmake_files_with_rename_and_catkin_destination(repo):
    package(repo, "pkg", "pkg", **{
        "CMakeLists.txt": "project(pkg)\ninstall(FILES models/arm.stl DESTINATION "
                          "${CATKIN_PACKAGE_SHARE_DESTINATION}/meshes)\n"
                          'install(FILES "models/old name.stl" DESTINATION '
                          "share/pkg/meshes RENAME hand.stl)\n",
        "models/arm.stl": "solid", "models/old name.stl": "solid"})
    assert resolve(repo, "package://pkg/meshes/arm.stl") == repo / "pkg/models/arm.stl"
    assert resolve(repo, "package://pkg/meshes/hand.stl") == repo / "pkg/models/old name.stl"


def test_cmake_foreach_over_literal_items_and_ament_auto(repo):
    package(repo, "a", "a", **{
        "CMakeLists.txt": "project(a)\nforeach(dir IN ITEMS urdf meshes)\n"
                          "  install(DIRECTORY desc/${dir} DESTINATION share/${PROJECT_NAME})\n"
                          "endforeach()\n",
        "desc/meshes/m.stl": "solid"})
    package(repo, "b", "b", **{
        "CMakeLists.txt": "project(b)\nament_auto_package(INSTALL_TO_SHARE desc/meshes)\n",
        "desc/meshes/m.stl": "solid"})
    assert resolve(repo, "package://a/meshes/m.stl").is_file()
    assert resolve(repo, "package://b/meshes/m.stl").is_file()


def test_setup_py_data_files_with_glob_join_and_concatenation(repo):
    package(repo, "pkg", "pkg", **{
        "setup.py": "import os\nfrom glob import glob\npackage_name = 'pkg'\n"
                    "files = [(os.path.join('share', package_name, 'urdf'), glob('urdf/*'))]\n"
                    "files.append(('share/' + package_name + '/meshes', "
                    "glob(os.path.join('models', '*.stl'))))\n"
                    "setup(name=package_name, data_files=files + "
                    "[(f'share/{package_name}/cfg', ['config/c.yaml'])])\n",
        "urdf/r.urdf.xacro": "<robot/>", "models/m.stl": "solid", "models/m.dae": "<x/>",
        "config/c.yaml": "a: 1"})
    assert resolve(repo, "package://pkg/meshes/m.stl") == repo / "pkg/models/m.stl"
    assert not resolve(repo, "package://pkg/meshes/m.dae").is_file()  # not matched by *.stl
    assert resolve(repo, "package://pkg/cfg/c.yaml") == repo / "pkg/config/c.yaml"


def test_setup_cfg_data_files_and_python_package_of_the_same_name(repo):
    package(repo, "cfg", "cfg", **{
        "setup.cfg": "[options.data_files]\nshare/cfg/meshes =\n    assets/palm.stl\n",
        "assets/palm.stl": "solid"})
    # robot_properties_bolt: package.xml at the top, resources in the Python package src/NAME
    package(repo, "bolt", "bolt", **{
        "setup.py": "from os import path\npackage_name = 'bolt'\n"
                    "setup(package_dir={package_name: path.join('src', package_name)},\n"
                    "      data_files=[(path.join('share', package_name), ['package.xml'])])\n",
        "src/bolt/resources/meshes/body.stl": "solid"})
    assert resolve(repo, "package://cfg/meshes/palm.stl") == repo / "cfg/assets/palm.stl"
    assert resolve(repo, "package://bolt/resources/meshes/body.stl") == \
        repo / "bolt/src/bolt/resources/meshes/body.stl"


def test_the_source_layout_comes_first_and_find_is_the_source_folder(repo):
    folder = package(repo, "pkg", "pkg", **{
        "CMakeLists.txt": "install(DIRECTORY other/meshes DESTINATION share/pkg)\n",
        "meshes/m.stl": "source", "other/meshes/m.stl": "installed"})
    resolver = PackageResolver(start=repo, environ={})
    assert resolver.find("pkg") == folder
    assert resolver.resolve_uri("package://pkg/meshes/m.stl", repo) == folder / "meshes/m.stl"


def test_xacro_find_includes_and_yaml_resolve_through_the_install_rules(repo):
    from urdftool.description.load import load

    package(repo, "pkg", "pkg", **{
        "CMakeLists.txt": "project(pkg)\ninstall(DIRECTORY description/urdf "
                          "description/config DESTINATION share/${PROJECT_NAME})\n",
        "description/urdf/part.xacro":
            '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="'
            "${xacro.load_yaml('$(find pkg)/config/names.yaml')['link']}\"/></robot>",
        "description/config/names.yaml": "link: from_yaml\n"})
    robot_file = repo / "robot.urdf.xacro"
    robot_file.write_text('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
                          '<xacro:include filename="$(find pkg)/urdf/part.xacro"/></robot>')
    robot = load(str(robot_file))
    assert [link.get("name") for link in robot.root.iter("link")] == ["from_yaml"]


def test_a_missing_file_is_uncertain_only_where_rules_were_not_read(repo):
    package(repo, "read", "read", **{
        "CMakeLists.txt": "install(DIRECTORY meshes DESTINATION share/read)\n"
                          "install(DIRECTORY ${CMAKE_CURRENT_BINARY_DIR}/doc/ "
                          "DESTINATION share/read/doc)\n"})
    resolver = PackageResolver(start=repo, environ={})
    missing = resolver.locate_uri("package://read/meshes/none.stl", repo)
    assert missing.doubt is None  # the rules for meshes/ are read: certainly missing
    generated = resolver.locate_uri("package://read/doc/index.html", repo)
    assert "install rules could not be read" in generated.doubt  # built, not in the source


@pytest.mark.parametrize("build, text", [
    ("CMakeLists.txt", "foreach(d ${DIRS})\ninstall(DIRECTORY ${d} DESTINATION share/p)\n"
                       "endforeach()\n"),
    ("CMakeLists.txt", "install(DIRECTORY meshes DESTINATION ${SOMEWHERE})\n"),
    ("CMakeLists.txt", "function(add_models d)\ninstall(DIRECTORY ${d} DESTINATION share/p)\n"
                       "endfunction()\n"),
    ("setup.py", "import os\nfiles = []\nfor root, _, names in os.walk('m'):\n"
                 "    files.append(('share/p/' + root, names))\nsetup(data_files=files)\n"),
    ("setup.py", "setup(**config)\n"),
    ("setup.py", "setup(data_files=[('share/p', glob('m/**/*.stl', recursive=True))])\n"),
    ("setup.py", "def broken(:\n"),
])
def test_rules_not_read_make_a_missing_file_uncertain(repo, build, text):
    package(repo, "p", "p", **{build: text})
    located = PackageResolver(start=repo, environ={}).locate_uri("package://p/m/x.stl", repo)
    assert located.doubt and "could not be read" in located.doubt


def test_hostile_install_sources_and_destinations_are_refused(repo, tmp_path_factory):
    secret = tmp_path_factory.mktemp("elsewhere") / "etc"
    (secret / "meshes").mkdir(parents=True)
    (secret / "meshes" / "passwd.stl").write_text("secret")
    depth = "../" * len(repo.parts)
    folder = package(repo, "pkg", "pkg", **{
        "CMakeLists.txt": f"install(DIRECTORY ../../etc {depth}{secret}/meshes/ "
                          f"DESTINATION share/pkg/meshes)\n"
                          f"install(DIRECTORY {secret}/ DESTINATION share/pkg/abs)\n"
                          "install(DIRECTORY inside/ DESTINATION share/pkg/../../../x)\n",
        "setup.py": f"setup(data_files=[('share/pkg/py', ['{depth}{secret}/meshes/passwd.stl'])])\n",
        "linked/.keep": ""})
    os.symlink(secret / "meshes", folder / "linked" / "meshes")
    (folder / "CMakeLists.txt").write_text((folder / "CMakeLists.txt").read_text() +
                                           "install(DIRECTORY linked/meshes/ DESTINATION "
                                           "share/pkg/viasymlink)\n")
    found = layout(folder, "pkg", repo)
    assert all(not rule.source.startswith("../") for rule in found.rules), found.rules
    assert any("leads outside the repository; refused" in why for _, why in found.unread)
    resolver = PackageResolver(start=repo, environ={})
    for uri in ("package://pkg/meshes/passwd.stl", "package://pkg/abs/meshes/passwd.stl",
                "package://pkg/py/passwd.stl", "package://pkg/viasymlink/passwd.stl",
                "package://pkg/../../x/passwd.stl"):
        path = resolver.resolve_uri(uri, repo)
        assert str(secret) not in os.path.realpath(path), uri


def test_build_files_are_bounded(repo):
    folder = package(repo, "big", "big", **{
        "CMakeLists.txt": "#" * (600 * 1024) + "\ninstall(DIRECTORY m DESTINATION share/big)\n"})
    found = layout(folder, "big", repo)
    assert not found.rules and found.doubt("m/x.stl")
    # CMake's grammar: bracket comments and arguments, quoted arguments, nested parentheses
    commands = cmake_commands('#[[ install(FILES a DESTINATION share/x) ]]\n'
                              'install(FILES "a b" [=[c]=] DESTINATION share/x) # (\n'
                              'if((A) AND B)\n')
    assert [(name, [a.text for a in args]) for name, args, _ in commands] == [
        ("install", ["FILES", "a b", "c", "DESTINATION", "share/x"]),
        ("if", ["(A)", "AND", "B"])]


def test_a_package_xml_without_a_build_file_leaves_its_share_folder_uncertain(repo):
    """icub-models: iCub_manual/package.xml ('a placeholder so that share/iCub is found') has no
    build file beside it; the repository's CMake copies iCub/, iCub_manual/ and
    iCub_creo2urdf/ into share/iCub, so package://iCub/meshes/... is there after the build."""
    package(repo, "iCub_manual", "iCub")
    located = PackageResolver(start=repo, environ={}).locate_uri(
        "package://iCub/meshes/chest.stl", repo)
    assert located.doubt and "another build makes its share folder" in located.doubt
    package(repo, "built", "built", **{"CMakeLists.txt": "project(built)\n"})
    located = PackageResolver(start=repo, environ={}).locate_uri(
        "package://built/meshes/chest.stl", repo)
    assert located.doubt is None


def test_a_share_folder_the_repository_cmake_copies_and_installs_is_read(repo):
    """icub-models' layout: the root CMake copies iCub/ into its build folder, globs
    iCub_manual/ and iCub_creo2urdf/ and copies each entry's contents there too, then installs
    the build folder's iCub as share/iCub; the placeholder package.xml is in iCub_manual/."""
    (repo / "CMakeLists.txt").write_text(
        "project(icub-models)\n"
        "file(COPY ${CMAKE_CURRENT_SOURCE_DIR}/iCub DESTINATION ${CMAKE_CURRENT_BINARY_DIR})\n"
        "file(GLOB manual RELATIVE ${CMAKE_CURRENT_SOURCE_DIR}/iCub_manual "
        "${CMAKE_CURRENT_SOURCE_DIR}/iCub_manual/*)\n"
        "foreach(manual ${manual})\n"
        "  file(COPY ${CMAKE_CURRENT_SOURCE_DIR}/iCub_manual/${manual}/ "
        "DESTINATION ${CMAKE_CURRENT_BINARY_DIR}/iCub/${manual})\n"
        "endforeach()\n"
        "file(GLOB creo RELATIVE ${CMAKE_CURRENT_SOURCE_DIR}/iCub_creo2urdf "
        "${CMAKE_CURRENT_SOURCE_DIR}/iCub_creo2urdf/*)\n"
        "foreach(creo ${creo})\n"
        "  file(COPY ${CMAKE_CURRENT_SOURCE_DIR}/iCub_creo2urdf/${creo}/ "
        "DESTINATION ${CMAKE_CURRENT_BINARY_DIR}/iCub/${creo})\n"
        "endforeach()\n"
        "install(DIRECTORY ${CMAKE_CURRENT_BINARY_DIR}/iCub DESTINATION share)\n")
    package(repo, "iCub_manual", "iCub", **{"meshes/hand.stl": "solid"})
    for path in ("iCub/meshes/chest.stl", "iCub_creo2urdf/meshes_creo2urdf/head.stl"):
        (repo / path).parent.mkdir(parents=True, exist_ok=True)
        (repo / path).write_text("solid")
    resolver = PackageResolver(start=repo, environ={})
    for uri, there in (("package://iCub/meshes/chest.stl", "iCub/meshes/chest.stl"),
                       ("package://iCub/meshes/hand.stl", "iCub_manual/meshes/hand.stl"),
                       ("package://iCub/meshes_creo2urdf/head.stl",
                        "iCub_creo2urdf/meshes_creo2urdf/head.stl")):
        located = resolver.locate_uri(uri, repo)
        assert located.path == repo / there, uri
    missing = resolver.locate_uri("package://iCub/meshes/none.stl", repo)
    assert missing.doubt  # what else the build writes there is not read: not certain


@pytest.mark.parametrize("end", ["\n", "\r\n"])
def test_cmake_commands_are_at_the_files_lines_whatever_ends_them(end):
    """(A CR alone ends no CMake line: its lexer's line end is LF, so a comment runs on.)"""
    commands = cmake_commands("# x\u2028y\nproject(p)\n\ninstall(DIRECTORY urdf DESTINATION share)\n"
                              .replace("\n", end))
    assert [(name, line) for name, _, line in commands] == [("project", 2), ("install", 4)]
