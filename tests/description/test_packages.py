"""Package resolution without ROS: the documented search order."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from urdftool.errors import PackageNotFound
from urdftool.description.packages import PackageResolver

pytestmark = pytest.mark.worker  # budgets and deaths: run_cli's commands in the forked worker


def make_package(folder, name):
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "package.xml").write_text(f"<package><name>{name}</name></package>")
    return folder


def test_explicit_then_ros_package_path_then_ament(tmp_path):
    explicit = make_package(tmp_path / "a" / "pkg", "pkg")
    ros = make_package(tmp_path / "ros" / "deep" / "pkg", "pkg")
    ament = tmp_path / "ament"
    (ament / "share" / "pkg").mkdir(parents=True)
    env = {"ROS_PACKAGE_PATH": str(tmp_path / "ros"), "AMENT_PREFIX_PATH": str(ament)}
    assert PackageResolver({"pkg": explicit}, environ=env).find("pkg") == explicit
    assert PackageResolver(environ=env).find("pkg") == ros
    assert PackageResolver(environ={"AMENT_PREFIX_PATH": str(ament)}).find("pkg") == ament / "share" / "pkg"


def test_walks_up_to_sibling_packages_and_down_from_repository_root(tmp_path):
    (tmp_path / ".git").mkdir()
    here = make_package(tmp_path / "src" / "robot_description", "robot_description")
    sibling = make_package(tmp_path / "src" / "robot_meshes", "robot_meshes")
    nested = make_package(tmp_path / "third_party" / "vendor" / "arm_pkg", "arm_pkg")
    resolver = PackageResolver(start=here / "urdf", environ={})
    assert resolver.find("robot_description") == here
    assert resolver.find("robot_meshes") == sibling
    assert resolver.find("arm_pkg") == nested


def test_package_name_comes_from_package_xml_not_folder(tmp_path):
    folder = make_package(tmp_path / "checkout-name", "real_name")
    assert PackageResolver(start=folder, environ={}).find("real_name") == folder


def test_a_commented_out_name_is_not_the_package_s_name(tmp_path):
    """catkin_pkg and ament read package.xml as XML: a <name> in a comment (a fork's old
    name kept for reference) is not the package's name."""
    folder = tmp_path / "fork"
    folder.mkdir()
    (folder / "package.xml").write_text(
        '<package format="3">\n  <!-- <name>upstream_description</name> -->\n'
        '  <name>fork_description</name>\n</package>\n')
    resolver = PackageResolver(start=folder, environ={})
    assert resolver.find("fork_description") == folder
    with pytest.raises(PackageNotFound):
        resolver.find("upstream_description")


def test_not_found_lists_where_it_looked(tmp_path):
    with pytest.raises(PackageNotFound) as error:
        PackageResolver(start=tmp_path, environ={"ROS_PACKAGE_PATH": str(tmp_path)}).find("ghost")
    assert "ROS_PACKAGE_PATH" in str(error.value) and "--package ghost=PATH" in str(error.value)
    # a rosbuild manifest.xml makes a package too: the places say so (they said package.xml)
    (tmp_path / ".git").mkdir()
    with pytest.raises(PackageNotFound) as error:
        PackageResolver(start=tmp_path, environ={}).find("ghost")
    assert error.value.searched == [f"package.xml or manifest.xml above {tmp_path} up to "
                                    f"{tmp_path}", f"package.xml or manifest.xml below {tmp_path}"]


def test_mesh_uris(tmp_path):
    pkg = make_package(tmp_path / "pkg", "pkg")
    resolver = PackageResolver({"pkg": pkg}, environ={})
    assert resolver.resolve_uri("package://pkg/meshes/a.stl", tmp_path) == pkg / "meshes" / "a.stl"
    assert str(resolver.resolve_uri("file:///abs/b.stl", tmp_path)) == "/abs/b.stl"
    assert resolver.resolve_uri("meshes/c.stl", tmp_path) == tmp_path / "meshes" / "c.stl"


def test_one_containment_root_for_loader_meshes_and_include_graph(tmp_path):
    """Repository, else the nearest package, else the folder; ``check``'s include graph agrees
    (a macro in a package without .git is looked for in the package's robots)."""
    from urdftool.description.packages import containment_root
    from urdftool.lint.targets import project_root

    loose = tmp_path / "loose" / "urdf"
    package = tmp_path / "pkg"
    (package / "macros").mkdir(parents=True)
    loose.mkdir(parents=True)
    (package / "package.xml").write_text("<package><name>pkg</name></package>")
    assert containment_root(loose) == loose
    assert containment_root(package / "macros") == package
    assert project_root(package / "macros" / "leg.xacro") == package
    (tmp_path / ".git").mkdir()
    assert containment_root(package / "macros") == tmp_path == containment_root(loose)
    assert project_root(package / "macros" / "leg.xacro") == tmp_path


def test_macro_in_a_package_without_a_repository_checks_its_robot(run_cli, tmp_path):
    package = tmp_path / "pkg"
    (package / "macros").mkdir(parents=True)
    (package / "urdf").mkdir()
    (package / "package.xml").write_text("<package><name>pkg</name></package>")
    (package / "macros" / "leg.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<xacro:macro name="leg"><link name="leg"/></xacro:macro></robot>')
    (package / "urdf" / "robot.urdf.xacro").write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<xacro:include filename="../macros/leg.xacro"/><xacro:leg/></robot>')
    result = run_cli("check", package / "macros" / "leg.xacro", "--format", "json")
    assert "included by" in result.stderr and "robot.urdf.xacro" in result.stderr
    assert '"files": 1' in result.stdout


def _workspace(folder):
    """src/my_description with a macro; robot.xacro including it through $(find)."""
    (folder / "src" / "my_description" / "urdf").mkdir(parents=True)
    (folder / "src" / "my_description" / "urdf" / "arm.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="arm"/>'
        '<joint name="j" type="fixed"><parent link="base"/><child link="arm"/></joint></robot>')
    robot = ('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="base"/>'
             '<xacro:include filename="$(find my_description)/urdf/arm.xacro"/></robot>')
    (folder / "robot.xacro").write_text(robot)
    (folder / "robots").mkdir()
    (folder / "robots" / "robot.xacro").write_text(robot)


def test_a_relative_package_folder_is_relative_to_the_working_directory(tmp_path, monkeypatch):
    _workspace(tmp_path)
    monkeypatch.chdir(tmp_path)
    resolver = PackageResolver({"my_description": "src/my_description"},
                               start=tmp_path / "robots")
    assert resolver.find("my_description") == tmp_path / "src" / "my_description"


def test_the_documented_package_example_runs_as_written(run_cli, tmp_path, monkeypatch):
    """docs/check.md's line, word for word; then the same robot from another folder, whose
    includes once resolved the package against robots/ instead of the working directory."""
    import shlex
    from pathlib import Path

    readme = (Path(__file__).parents[2] / "docs" / "check.md").read_text()
    [line] = [line for line in readme.splitlines() if "--package my_description=" in line
              and line.startswith("urdftool check")]
    words = shlex.split(line.split("#")[0])[1:]
    _workspace(tmp_path)
    monkeypatch.chdir(tmp_path)
    result = run_cli(*words)
    assert result.exit_code == 0, result.stdout
    result = run_cli(*[word if word != "robot.xacro" else "robots/robot.xacro" for word in words])
    assert result.exit_code == 0, result.stdout


def test_an_empty_package_name_is_read_as_pinocchio_does(tmp_path):
    """package:///NAME/PATH: Pinocchio appends the path after package:// to each package
    directory, so NAME is the package folder."""
    from urdftool.description.packages import package_uri_parts

    (tmp_path / "talos_data" / "meshes").mkdir(parents=True)
    (tmp_path / "talos_data" / "package.xml").write_text("<package><name>talos_data</name></package>")
    assert package_uri_parts("package:///talos_data/meshes/a.stl") == ("talos_data", "meshes/a.stl")
    assert package_uri_parts("package://talos_data/meshes/a.stl") == ("talos_data", "meshes/a.stl")
    resolver = PackageResolver(start=tmp_path / "talos_data" / "meshes")
    assert resolver.resolve_uri("package:///talos_data/meshes/a.stl", tmp_path) == \
        tmp_path / "talos_data" / "meshes" / "a.stl"


# ---- a package's manifest: dependencies declared, packages named -------------------------------

def test_declared_dependencies_are_every_dependency_tag_out_of_comments(tmp_path):
    from urdftool.description.packages import declared_dependencies

    (tmp_path / "package.xml").write_text(
        '<package format="3"><name>me</name>\n<depend>a</depend><exec_depend>b</exec_depend>\n'
        '<run_depend>c</run_depend><build_depend>d</build_depend>\n'
        '<exec_depend condition="$ROS_VERSION == 2"> e </exec_depend>\n'
        '<test_depend>f</test_depend>\n<!-- <exec_depend>hidden</exec_depend> -->\n'
        '<description>g</description><export><h/></export></package>\n')
    assert declared_dependencies(tmp_path) == set("abcdef")
    assert declared_dependencies(tmp_path / "none") is None


def test_package_references_are_literal_names_out_of_comments_and_conditions_at_their_column():
    from urdftool.description.packages import package_references

    data = ('<robot>\n  <!-- $(find commented) package://commented/x -->\n'
            '  <include filename="$(find  one)/urdf/a.xacro"/> <mesh filename="package://two/m.stl"/>\n'
            '  <x value="$(find ${built})" uri="package://${built}/m.stl" é="package://three/m"/>\n'
            '  <xacro:if value="${sim}"><x v="$(find optional)"/><xacro:unless value="1"/>\n'
            '    <if value="1">package://optional/m.stl</if> $(find optional)</xacro:if>\n'
            '  <x v="$(find four)"/>\n'
            '</robot>\n').encode()
    assert package_references(data) == [(3, 22, "one"), (3, 67, "two"), (4, 65, "three"),
                                         (7, 9, "four")]  # é: 2 bytes, 1 column


def test_package_references_without_conditions_are_found_as_the_one_pattern_finds_them():
    """A file without conditional tags is searched for each kind of reference apart: the same
    (offset, name) as the one pattern's matches, on documents of every mix of references,
    names built by xacro, comments and near misses."""
    import random

    from urdftool.description import packages

    pieces = [b"$(find a)", b"$(find  b_2.x )", b"$(find ${c})", b"package://d/m.stl",
              b"package://${e}/m", b"package:///f/m", b"$(find", b"package://", b"<!-- $(find g) -->",
              b"<link>", b"\n", b"$(find h)package://i/", b"$(findj)", b"p", b"$", b" ", b"/"]
    rng = random.Random(5)
    for _ in range(2000):
        text = b"".join(rng.choice(pieces) for _ in range(rng.randint(0, 30)))
        if any(word in text for word in packages._CONDITIONAL):
            continue
        expected = [(match.start(), match.group(1) or match.group(2))
                    for match in packages._REFERENCE.finditer(text)]
        assert packages._named(text) == expected, text


def test_the_package_of_a_file_stays_in_its_repository(tmp_path):
    from urdftool.description.packages import package_of

    (tmp_path / ".git").mkdir()
    make_package(tmp_path / "pkg", "pkg")
    (tmp_path / "pkg" / "urdf").mkdir()
    assert package_of(tmp_path / "pkg" / "urdf" / "r.urdf") == tmp_path / "pkg"
    assert package_of(tmp_path / "loose.urdf") is None
    make_package(tmp_path.parent / "outer", "outer")  # above the repository: not its package
    (tmp_path.parent / "outer" / "repo" / ".git").mkdir(parents=True)
    assert package_of(tmp_path.parent / "outer" / "repo" / "r.urdf") is None


def test_undeclared_dependencies_are_judged_per_file_by_its_own_package(run_cli, tmp_path):
    """U019 at the first use of each undeclared package in each file of the repository, by the
    package.xml above that file; a package not found is U006's, not U019's; an installed
    package's files (outside the repository) are not judged."""
    (tmp_path / "repo" / ".git").mkdir(parents=True)
    installed = tmp_path / "opt" / "share" / "vendor_description"
    make_package(installed, "vendor_description")
    (installed / "vendor.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><xacro:macro name="vendor">'
        '<xacro:property name="p" value="$(find cell)"/><link name="v"/></xacro:macro></robot>')
    cell, parts = tmp_path / "repo" / "cell", tmp_path / "repo" / "parts"
    make_package(cell, "cell")
    make_package(parts, "parts")
    (cell / "package.xml").write_text(
        "<package><name>cell</name><depend>vendor_description</depend></package>")
    (parts / "parts.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><xacro:macro name="parts">\n'
        '<xacro:property name="p" value="$(find cell)"/>\n<link name="p"/>'
        '</xacro:macro></robot>\n')
    (cell / "robot.urdf.xacro").write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '<xacro:include filename="$(find vendor_description)/vendor.xacro"/>\n'
        '<xacro:include filename="$(find parts)/parts.xacro"/>\n'
        '<xacro:property name="again" value="$(find parts)"/>\n'
        '<xacro:vendor/><xacro:parts/><link name="b"/>\n'
        '<joint name="j" type="fixed"><parent link="b"/><child link="v"/></joint>\n'
        '<joint name="k" type="fixed"><parent link="b"/><child link="p"/></joint>\n'
        '</robot>\n')
    result = run_cli("check", "--format", "json", "--select", "U019,U006", "--no-cache",
                     "--package", f"vendor_description={installed}", cell / "robot.urdf.xacro")
    found = [(d["file"].split("/")[-2:], d["line"], d["code"])
             for d in json.loads(result.stdout)["diagnostics"]]
    assert found == [(["cell", "robot.urdf.xacro"], 3, "U019"),
                     (["parts", "parts.xacro"], 2, "U019")], result.output


def test_the_package_walk_lists_each_folder_once(tmp_path):
    """packages_below: a folder's subfolders and its package.xml come from one listing (the
    launch index walks every folder of a repository), and the packages found are the same."""
    from urdftool.description.packages import packages_below
    from urdftool.description.record import SEARCH, recording

    for name in ("a", "b/c", "b/d", "e"):
        (tmp_path / name).mkdir(parents=True)
    for name in ("a", "b/c"):
        (tmp_path / name / "package.xml").write_text(f"<package><name>p_{name[-1]}</name></package>")
    (tmp_path / "e" / "package.xml").mkdir()  # a folder named so: no package
    with recording() as record:
        found = packages_below(tmp_path)
    assert found == {"p_a": tmp_path / "a", "p_c": tmp_path / "b" / "c"}
    listed = [key[0] for kind, key in record.entries if kind == SEARCH]
    assert sorted(listed) == sorted({str(tmp_path / f) for f in ("", "a", "b", "b/c", "b/d", "e",
                                                               "e/package.xml")})


def test_a_package_manifest_is_read_once_per_run_and_answers_as_read_each_time(tmp_path,
                                                                                 monkeypatch):
    """package_name and manifest_text read each package.xml once in a run, whoever asks (the
    resolvers of every robot of a repository, the rules reading dependencies), with the
    answers of a read each time: a declared name, none (the folder's), an unreadable or
    too large manifest, none at all; every later asker's record has the read."""
    from urdftool.description import files, packages
    from urdftool.description.record import READ, recording
    from urdftool.description.run_memo import one_run

    manifests = {"named": b"<package><name> real_name </name><depend>a</depend></package>",
                 "unnamed": b"<package><!-- a comment --><depend>b</depend></package>",
                 "big": b"<package><name>big</name>" + b" " * packages._MAX_MANIFEST +
                        b"</package>",
                 "folder_only": None, "dots": b"<package><name>d</name></package>"}
    folders = []
    for name, text in manifests.items():
        folder = tmp_path / name
        (folder / "package.xml").mkdir(parents=True) if text is None else \
            folder.mkdir() or (folder / "package.xml").write_bytes(text)
        folders.append(folder)
    folders += [tmp_path / "dots" / ".." / "named", tmp_path / "missing"]
    alone = [(packages.package_name(f), packages.package_name(f, tmp_path),
              packages.manifest_text(f)) for f in folders]
    assert alone[0][0] == "real_name" and alone[1][0] == "unnamed" and alone[2][0] is None
    reads = []
    disk = files._read_disk
    monkeypatch.setattr(files, "_read_disk", lambda *a: reads.append(a[0]) or disk(*a))
    with one_run():
        for _ in range(3):
            with recording() as record:
                assert [(packages.package_name(f), packages.package_name(f, tmp_path),
                         packages.manifest_text(f)) for f in folders] == alone
            assert {key for kind, key in record.entries if kind == READ} >= \
                {str(tmp_path / n / "package.xml") for n in ("named", "unnamed", "dots")}
    # (a folder with no readable package.xml: its rosbuild manifest.xml asked for too, once)
    assert sorted(reads) == sorted(set(reads)) and len(reads) == len(folders) + 3


def test_the_shallowest_package_of_a_name_wins_below_a_root(tmp_path):
    """packages_below walks as catkin's crawler does, level by level: of two package.xml
    naming one package, the shallower one is the package, though the deeper one's folder
    sorts first."""
    from urdftool.description.packages import packages_below

    for folder in ("a/deeper", "b"):
        (tmp_path / folder).mkdir(parents=True)
        (tmp_path / folder / "package.xml").write_text("<package><name>same</name></package>")
    assert packages_below(tmp_path) == {"same": tmp_path / "b"}


def test_a_search_path_naming_a_folder_again_walks_it_once(tmp_path):
    """A ``setup.bash`` sourced twice repeats ROS_PACKAGE_PATH's entries; ``/usr`` given 5,000
    times was walked 5,000 times (U015 at the 60 s budget). The places said are cut: 8,000
    entries made each U407 a 240 KB message."""
    from urdftool.description.record import SEARCH, recording

    (tmp_path / "pkgs" / "deep").mkdir(parents=True)
    repeated = ":".join([str(tmp_path / "pkgs"), str(tmp_path / "pkgs") + "/", str(tmp_path / "pkgs/.")] * 300)
    with recording() as record, pytest.raises(PackageNotFound) as error:
        PackageResolver(environ={"ROS_PACKAGE_PATH": repeated}).find("ghost")
    listed = [key[0] for kind, key in record.entries if kind == SEARCH]
    assert listed.count(str(tmp_path / "pkgs")) == 1, len(listed)
    assert error.value.searched == [f"ROS_PACKAGE_PATH entry {tmp_path / 'pkgs'}"]
    many = [f"ROS_PACKAGE_PATH entry /nope{i}" for i in range(8000)]
    message = str(PackageNotFound("ghost", many))
    assert len(message) < 1000 and "/nope11, ... (8000 places in all)" in message


@pytest.mark.parametrize("end", ["\n", "\r\n", "\r"])
def test_package_references_are_at_the_files_lines_whatever_ends_them(end):
    from urdftool.description.packages import package_references

    data = ('<robot>\n  <!-- x\u2028y -->\n'
            '  <mesh filename="package://two/m.stl"/>\n</robot>\n').replace("\n", end).encode()
    assert package_references(data) == [(3, 19, "two")]


def test_packages_below_after_the_launch_walk_are_those_its_own_walk_finds(tmp_path):
    """After the launch-file walk of a repository (``files.tree``), packages_below takes its
    listings rather than listing every folder again: the same packages (breadth first, the
    shallowest of a name, no deeper than its own walk goes, a folder named package.xml and a
    link leading out not packages), and a record that holds every folder it took."""
    from urdftool.description import files, launch_configs, packages
    from urdftool.description.record import SEARCH, recording
    from urdftool.description.run_memo import one_run

    (tmp_path / "outside").mkdir()
    (tmp_path / "outside" / "package.xml").write_text("<package><name>out</name></package>")
    root = tmp_path / "repo"
    for folder, name in (("a/deeper", "same"), ("b", "same"), ("c", None), ("d/e/f/g/h/i", "deep"),
                         ("d/e/f/g/h/i/j", "too_deep"), ("n", ""), ("z", "last")):
        (root / folder).mkdir(parents=True)
        if name is not None:
            (root / folder / "package.xml").write_text(f"<package><name>{name}</name></package>")
    (root / "c" / "package.xml").mkdir()  # a folder named so: no package
    (root / "l").mkdir()
    (root / "l" / "package.xml").symlink_to(tmp_path / "outside" / "package.xml")
    with one_run():
        alone = packages.packages_below(root)
    assert alone == {"same": root / "b", "deep": root / "d/e/f/g/h/i", "n": root / "n",
                     "last": root / "z"}
    with one_run():
        with recording() as walked:
            launch_configs.launch_files(root)
        assert files.tree_made(root, "package.xml|[!.]*/", 7, packages.SKIP_DIRS) is not None
        with recording() as record:
            assert packages.packages_below(root) == alone
    listed = {key[0] for kind, key in walked.entries if kind == SEARCH}
    assert listed == {key[0] for kind, key in record.entries if kind == SEARCH} and \
        str(root / "d/e/f/g/h/i/j") in listed


def test_a_walk_is_taken_only_from_a_tree_listing_all_it_lists(tmp_path):
    """tree_made: a tree walked in this run answers a walk of fewer names (package.xml after
    the launch files' names), as deep or less, with the same folders skipped; none other, and
    none outside a run."""
    from urdftool.description.files import tree, tree_made
    from urdftool.description.run_memo import one_run

    (tmp_path / "a").mkdir()
    launch = "*.launch|*.py|*.xml|*.yaml|*.yml|[!.]*/"
    skip = frozenset({"build"})
    assert tree_made(tmp_path, "package.xml|[!.]*/", 7, skip) is None
    tree(tmp_path, launch, 11, skip)  # (outside a run: not kept)
    assert tree_made(tmp_path, "package.xml|[!.]*/", 7, skip) is None
    with one_run():
        tree(tmp_path, launch, 11, skip)
        assert set(tree_made(tmp_path, "package.xml|[!.]*/", 7, skip)) == {
            str(tmp_path), str(tmp_path / "a")}
        assert tree_made(tmp_path, "x.xml|*.py|[!.]*/", 11, skip) is not None
        for pattern, depth, other_skip in (("*.urdf|[!.]*/", 7, skip),  # a name not listed
                                           ("package.xml|.*/", 7, skip),  # hidden folders
                                           ("package.xml|[!.]*/", 12, skip),  # deeper
                                           ("package.xml|[!.]*/", 7, frozenset())):
            assert tree_made(tmp_path, pattern, depth, other_skip) is None, pattern


def make_rosbuild_package(folder, *depends):
    """A rosbuild package (ROS 1): a manifest.xml, no package.xml, its name its folder's."""
    folder.mkdir(parents=True, exist_ok=True)
    tags = "".join(f'  <depend package="{name}" />\n' for name in depends)
    (folder / "manifest.xml").write_text(
        f'<package>\n  <description brief="x">x</description>\n{tags}'
        '  <!-- <depend package="hidden"/> -->\n  <depend stack="a_stack"/>\n</package>\n')
    return folder


def test_a_rosbuild_manifest_makes_its_folder_a_package_of_its_folder_s_name(tmp_path):
    """rospack takes a folder holding manifest.xml (and no package.xml) as the package of the
    folder's name: found walking up, below the repository, by package_of and packages_below;
    its <depend package=.../> are its dependencies; package.xml wins beside one."""
    from urdftool.description import packages
    from urdftool.description.run_memo import one_run

    (tmp_path / ".git").mkdir()
    here = make_rosbuild_package(tmp_path / "src" / "cool5000_description", "gazebo", "urdf")
    (here / "robots").mkdir()
    other = make_rosbuild_package(tmp_path / "vendor" / "deep" / "arm_meshes")
    both = make_rosbuild_package(tmp_path / "both" / "folder_name", "rosbuild_only")
    make_package(both, "catkin_name")
    resolver = PackageResolver(start=here / "robots", environ={})
    assert resolver.find("cool5000_description") == here
    assert resolver.find("arm_meshes") == other
    assert resolver.find("catkin_name") == both
    with pytest.raises(PackageNotFound):
        resolver.find("folder_name")
    assert packages.package_of(here / "robots" / "r.urdf") == here
    assert packages.declared_dependencies(here) == {"gazebo", "urdf"}
    assert packages.declared_dependencies(both) == set()
    assert packages.declaring_package(here / "robots" / "r.urdf", "gazebo") == \
        ("cool5000_description", True, "manifest.xml")
    assert packages.declaring_package(both / "r.urdf", "rosbuild_only") == \
        ("catkin_name", False, "package.xml")
    with one_run():
        assert packages.packages_below(tmp_path) == {
            "cool5000_description": here, "catkin_name": both, "arm_meshes": other}


def test_a_rosbuild_package_is_built_by_ros_1(tmp_path):
    """ROS 2 has no rosbuild: a manifest.xml package's build tool says ROS 1."""
    from urdftool.description.packages import build_tools
    from urdftool.description.ros_version import package_build_tool

    (tmp_path / ".git").mkdir()
    folder = make_rosbuild_package(tmp_path / "bot_description")
    path = folder / "urdf" / "bot.urdf"
    assert build_tools(path) == ((1, "rosbuild", folder / "manifest.xml"),)
    assert package_build_tool(str(path))[0] == 1


def test_a_rosbuild_package_s_messages_name_its_manifest_xml_and_u019_leaves_it(run_cli, tmp_path):
    """A package a rosbuild package's file needs and its manifest.xml does not declare: U006
    names the manifest.xml and its <depend package=.../>; U019 (binary installs) leaves a
    rosbuild package, built from source only, alone."""
    (tmp_path / ".git").mkdir()
    rosbuild = make_rosbuild_package(tmp_path / "rb_description")
    make_package(tmp_path / "sibling", "sibling")
    (rosbuild / "robot.urdf.xacro").write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '<xacro:property name="p" value="$(find sibling)"/>\n'
        '<xacro:include filename="$(find missing_pkg)/x.xacro"/>\n<link name="b"/>\n</robot>\n')
    result = run_cli("check", "--format", "json", "--select", "U019,U006", "--no-cache",
                     rosbuild / "robot.urdf.xacro")
    found = json.loads(result.stdout)["diagnostics"]
    assert [(d["line"], d["code"]) for d in found] == [(3, "U006")], result.output
    assert "the manifest.xml of 'rb_description' does not declare it" in found[0]["message"]
    assert '<depend package="missing_pkg"/>' in found[0]["message"]


def test_a_launch_files_package_is_the_one_package_of_says():
    """launch_configs.launch_file_packages answers package_of for every launch file of a
    repository from the launch walk's listings (asking package_of of each cost 3 % of a check
    of r2d2, session 20): the twin must give package_of's answers."""
    from urdftool.description.launch_configs import launch_file_packages
    from urdftool.description.packages import package_of

    cases = Path(__file__).resolve().parents[1] / "cases"
    for case in sorted(cases.glob("U6*")) + sorted(cases.glob("U0*")):
        if not case.is_dir():
            continue
        for launch, holder in launch_file_packages(case).items():
            folder = package_of(launch)
            expected = None if folder is None or not str(folder).startswith(str(case)) \
                else str(folder)
            assert holder == expected, (launch, holder, folder)


def test_a_path_written_for_a_tool_run_from_a_folder_above_is_found_from_one_place(tmp_path):
    """written_from_above: the one walk from a file's folder up to its repository's root
    asking from where a relative path names a file (xacro's $(cwd) in a mesh or an include, an
    include written from the repository's root), three walks until session 21."""
    from urdftool.description.packages import written_from_above

    (tmp_path / "repo" / ".git").mkdir(parents=True)
    deep = tmp_path / "repo" / "pkg" / "urdf"
    deep.mkdir(parents=True)
    (tmp_path / "repo" / "meshes").mkdir()
    (tmp_path / "repo" / "meshes" / "a.stl").write_text("solid a\nendsolid a\n")
    (tmp_path / "meshes").mkdir()
    (tmp_path / "meshes" / "b.stl").write_text("solid b\nendsolid b\n")
    (deep / "meshes").mkdir()
    (deep / "meshes" / "a.stl").write_text("solid a\nendsolid a\n")
    assert written_from_above(deep, "meshes/a.stl") == str(deep)
    assert written_from_above(deep, "meshes/a.stl", above=True) == str(tmp_path / "repo")
    assert written_from_above(deep, "meshes/a.stl", skip=str(deep)) == str(tmp_path / "repo")
    assert written_from_above(deep, "meshes/b.stl") is None  # (outside the repository)
    assert written_from_above(tmp_path / "repo", "meshes/a.stl", above=True) is None


def test_manifest_said_names_what_a_folder_holds_not_always_no_package_xml(tmp_path):
    """A message saying a folder has "no package.xml" when it has one that is no ROS package
    manifest (another tool's file of that name) or names another package misleads whoever
    opens the folder: manifest_said says what is there."""
    from urdftool.description.packages import manifest_said

    assert manifest_said(None) == "no package.xml or manifest.xml"
    assert manifest_said(tmp_path) == "no package.xml or manifest.xml"
    (tmp_path / "package.xml").write_text("<project><name>web</name></project>")
    assert manifest_said(tmp_path) == manifest_said(tmp_path, "web") == (
        "a package.xml that is not a ROS package manifest (no <package> element)")
    (tmp_path / "package.xml").write_text(
        "<package format='2'><name>drake_models</name></package>")
    assert manifest_said(tmp_path) == ("a package.xml ('drake_models') naming no ROS build "
                                       "tool (catkin, ament)")
    assert manifest_said(tmp_path, "drake_models") == ""
    assert manifest_said(tmp_path, "iiwa") == "its package.xml naming package 'drake_models'"
    (tmp_path / "package.xml").write_text(
        "<package format='3'><name>arm</name><buildtool_depend condition='$ROS_VERSION == 1'>"
        "catkin</buildtool_depend></package>")
    assert manifest_said(tmp_path) == "a package.xml ('arm') naming its build tools under conditions"
    (tmp_path / "package.xml").write_text(
        "<package format='2'><name>arm</name><buildtool_depend>catkin</buildtool_depend></package>")
    assert manifest_said(tmp_path) == ""
