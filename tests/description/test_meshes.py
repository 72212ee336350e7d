"""Mesh resolution, limits and cache (the corpus's missing meshes are checked in
tests/integration/test_corpus_meshes.py)."""

from __future__ import annotations

import os
import re
import struct

import numpy as np
import pytest

from gltf_nodes import column_major as _columns, glb_with_node as _glb
from urdftool.description.load import load
from urdftool.description.meshes import MeshLimits, MeshProblem, load_mesh, resolve, triangle_count


def _robot(tmp_path, filename="m.stl"):
    (tmp_path / ".git").mkdir(exist_ok=True)
    path = tmp_path / "r.urdf"
    path.write_text(f'<robot name="r"><link name="a"><visual><geometry>'
                    f'<mesh filename="{filename}"/></geometry></visual></link></robot>')
    return load(path)


def test_binary_stl_triangle_count_read_from_header(tmp_path):
    path = tmp_path / "big.stl"
    path.write_bytes(b"x" * 80 + struct.pack("<I", 3_000) + bytes(50 * 3_000))
    assert triangle_count(path) == 3_000
    robot = _robot(tmp_path, "big.stl")
    robot.mesh_limits = MeshLimits(max_triangles=2_000)
    with pytest.raises(MeshProblem) as error:
        load_mesh(robot, "big.stl")
    assert error.value.kind == "too-large"


def test_a_binary_stl_cut_short_is_counted_as_trimesh_reads_it(tmp_path):
    """A header whose count does not fit the file's length is no binary STL to trimesh
    (HeaderError): it reads the file as text, and fails. Its header's 5,000,000 triangles were
    counted, and an 84-byte file was refused as too large, not as the broken file it is."""
    path = tmp_path / "cut.stl"
    path.write_bytes(b"x" * 80 + struct.pack("<I", 5_000_000))
    assert triangle_count(path) == 0
    with pytest.raises(MeshProblem) as error:
        load_mesh(_robot(tmp_path, "cut.stl"), "cut.stl")
    assert error.value.kind != "too-large", error.value


def test_relative_path_escaping_the_repository_is_refused(tmp_path):
    inner = tmp_path / "repo"
    inner.mkdir()
    (tmp_path / "secret.stl").write_text("solid x\nendsolid x\n")
    robot = _robot(inner, "../secret.stl")
    with pytest.raises(MeshProblem) as error:
        resolve(robot, "../secret.stl")
    assert error.value.kind == "outside"


def test_a_name_too_long_for_the_file_system_is_a_problem_not_a_crash(tmp_path):
    # pathlib's is_file() raised ENAMETOOLONG: every mesh rule crashed (U900), found by make
    # fuzz; the lookup goes through description.files.kind_of, which finds nothing there
    name = "9" * 400 + ".stl"
    with pytest.raises(MeshProblem) as error:
        resolve(_robot(tmp_path, name), name)
    assert error.value.kind == "missing" and "cannot be reached: file name too long" in \
        str(error.value)


def test_non_mesh_extension_is_never_opened(tmp_path):
    (tmp_path / "notes.txt").write_text("hello")
    with pytest.raises(MeshProblem) as error:
        resolve(_robot(tmp_path, "notes.txt"), "notes.txt")
    assert error.value.kind == "format"


def test_each_mesh_loads_once_per_scale(tmp_path, monkeypatch):
    trimesh = pytest.importorskip("trimesh")
    trimesh.creation.box(extents=(1, 1, 1)).export(tmp_path / "m.stl")
    robot = _robot(tmp_path)
    calls = []
    real = trimesh.load
    monkeypatch.setattr(trimesh, "load", lambda *a, **k: calls.append(a) or real(*a, **k))
    first = load_mesh(robot, "m.stl")
    assert load_mesh(robot, "m.stl") is first
    half = load_mesh(robot, "m.stl", (0.5, 0.5, 0.5))
    assert len(calls) == 1 and max(half.extents) == pytest.approx(0.5)


def test_corrupt_mesh_is_a_problem_not_a_traceback(tmp_path):
    (tmp_path / "m.stl").write_bytes(b"\x00\x01garbage" * 3)
    with pytest.raises(MeshProblem) as error:
        load_mesh(_robot(tmp_path), "m.stl", limits=MeshLimits())
    assert error.value.kind in ("corrupt", "too-large")


def test_a_zip_is_told_as_zipfile_tells_it():
    """What zipfile.is_zipfile says, without zipfile for a file without the end record's
    signature where zipfile looks for it (its last 64 kB + 22 bytes)."""
    import io
    import zipfile

    from urdftool.description.meshes.reading import _zipped

    archive = io.BytesIO()
    with zipfile.ZipFile(archive, "w") as written:
        written.writestr("robot.dae", "<COLLADA/>")
    plain = archive.getvalue()
    commented = plain[:-2] + (100).to_bytes(2, "little") + b"x" * 100  # a 100-byte comment
    xml = b'<?xml version="1.0"?><COLLADA>' + b"1 2 3 " * 20000 + b"</COLLADA>"
    end = zipfile.stringEndArchive
    for data in (plain, commented, xml, xml + end, end + xml, end + b"x" * 70000,
                 plain + b"x" * 70000, b"", end, b"x" * 65536 + end + b"x" * 20):
        assert _zipped(data) == zipfile.is_zipfile(io.BytesIO(data))
    assert _zipped(plain) and _zipped(commented) and not _zipped(xml)


def test_collada_unit_is_applied(tmp_path):
    trimesh = pytest.importorskip("trimesh")
    pytest.importorskip("collada")
    text = trimesh.creation.box(extents=(100, 100, 100)).export(file_type="dae").decode()
    if "<unit" in text:
        import re

        text = re.sub(r'<unit[^>]*/>', '<unit meter="0.001" name="millimeter"/>', text)
    else:
        text = text.replace("<asset>", '<asset><unit meter="0.001" name="millimeter"/>', 1)
    (tmp_path / "m.dae").write_text(text)
    mesh = load_mesh(_robot(tmp_path, "m.dae"), "m.dae")
    assert max(mesh.extents) == pytest.approx(0.1)


def test_max_triangles_option_refuses_a_large_mesh(tmp_path, run_cli):
    import trimesh

    trimesh.creation.icosphere(subdivisions=3).export(tmp_path / "ball.stl")  # 1280 triangles
    (tmp_path / ".git").mkdir()
    robot = tmp_path / "r.urdf"
    robot.write_text('<robot name="r"><link name="a"><collision><geometry>'
                     '<mesh filename="ball.stl"/></geometry></collision></link></robot>')
    assert "U411" not in run_cli("check", robot).output
    limited = run_cli("check", robot, "--max-triangles", "1000")
    assert "U411" in limited.output and "1280 triangles" in limited.output


def _malformed_collada(folder, extents=(0.1, 0.2, 0.3)):
    """A box exported to COLLADA, then broken as real exporters break it: a ``<`` inside an
    attribute value (``<node id="<STL_BINARY>">``), which assimp reads and pycollada refuses."""
    import re

    trimesh = pytest.importorskip("trimesh")
    pytest.importorskip("collada")
    text = trimesh.creation.box(extents=extents).export(file_type="dae").decode()
    text, replaced = re.subn(r'<node id="[^"]*"', '<node id="<STL_BINARY>"', text, count=1)
    assert replaced == 1
    (folder / "m.dae").write_text(text)
    return folder / "m.dae"


def test_collada_that_is_not_well_formed_loads_as_recovered(tmp_path):
    from urdftool.description.meshes import NOT_WELL_FORMED

    _malformed_collada(tmp_path)
    mesh = load_mesh(_robot(tmp_path, "m.dae"), "m.dae", scale=(2, 2, 2))
    assert sorted(mesh.extents) == pytest.approx([0.2, 0.4, 0.6])
    assert "line " in mesh.metadata[NOT_WELL_FORMED] and "'<'" in mesh.metadata[NOT_WELL_FORMED]


def test_collada_that_is_not_well_formed_is_still_counted_before_loading(tmp_path):
    path = _malformed_collada(tmp_path)
    assert triangle_count(path) == 12
    with pytest.raises(MeshProblem) as error:
        load_mesh(_robot(tmp_path, "m.dae"), "m.dae", limits=MeshLimits(max_triangles=11))
    assert error.value.kind == "too-large"


def test_collada_that_is_not_well_formed_is_measured_as_recovered_without_trimesh(tmp_path):
    """mesh_facts reads the recovered document with lxml (read_collada), as load_mesh reads
    it with trimesh: the same box, marked as repaired (U416); neither trimesh nor pycollada
    is imported."""
    from conftest import without_heavy_imports

    _malformed_collada(tmp_path)
    _robot(tmp_path, "m.dae")
    output = without_heavy_imports(
        "from urdftool.description.load import load\n"
        "from urdftool.description.meshes import NOT_WELL_FORMED, mesh_facts\n"
        f"facts = mesh_facts(load({str(tmp_path / 'r.urdf')!r}), 'm.dae', (2, 2, 2))\n"
        "print(sorted(round(float(e), 6) for e in facts.extents), facts.is_watertight,\n"
        "      facts.metadata[NOT_WELL_FORMED])")
    assert output.startswith("[0.2, 0.4, 0.6] True line ") and "'<'" in output


def test_collada_over_the_triangle_limit_is_refused_when_measured(tmp_path):
    from urdftool.description import meshes

    _malformed_collada(tmp_path)
    meshes.run_cache.clear()
    with pytest.raises(MeshProblem) as error:
        meshes.mesh_facts(_robot(tmp_path, "m.dae"), "m.dae",
                          limits=MeshLimits(max_triangles=11))
    assert error.value.kind == "too-large" and "11 triangles" in str(error.value)


def _count_reads(monkeypatch) -> list:
    """The paths of every mesh file read from now on, by trimesh or without it."""
    from urdftool.description import mesh_arrays, meshes

    reads = []
    real, light = meshes.reading._read_mesh, mesh_arrays.read_unmerged
    monkeypatch.setattr(meshes.reading, "_read_mesh", lambda path, *rest: reads.append(path) or
                        real(path, *rest))
    monkeypatch.setattr(mesh_arrays, "read_unmerged", lambda path, *rest: reads.append(path) or
                        light(path, *rest))
    monkeypatch.setattr(meshes.run_cache, "_RUN_CACHE", meshes.run_cache.new_cache())
    return reads


def _mesh_robot(folder, name: str, mesh: str, links: int = 3) -> str:
    body = "".join(f'<link name="l{i}"><inertial><mass value="1"/><inertia ixx="0.01" ixy="0" '
                   'ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial><visual><geometry>'
                   f'<mesh filename="{mesh}"/></geometry></visual><collision><geometry>'
                   f'<mesh filename="{mesh}"/></geometry></collision></link>'
                   for i in range(links))
    body += "".join(f'<joint name="j{i}" type="fixed"><parent link="l0"/><child link="l{i}"/>'
                    '</joint>' for i in range(1, links))
    path = folder / name
    path.write_text(f'<robot name="{name}">{body}</robot>')
    return str(path)


def test_a_mesh_is_read_once_per_run_across_links_rules_and_robots(tmp_path, monkeypatch):
    import trimesh

    from urdftool.lint.engine import CheckOptions, load_and_check

    trimesh.creation.box((0.1, 0.1, 0.1)).export(tmp_path / "part.stl")
    reads = _count_reads(monkeypatch)
    options = CheckOptions()
    for name in ("one.urdf", "two.urdf"):
        load_and_check(_mesh_robot(tmp_path, name, "part.stl"), options)
    assert [p.name for p in reads] == ["part.stl"]


@pytest.mark.parametrize("name", ["part.stl", "part.obj", "part.dae"])
def test_a_mesh_file_is_opened_once_when_measured(tmp_path, monkeypatch, name):
    """Its size, archive and triangle limits are checked in the bytes read for its arrays."""
    import builtins
    import io
    import os

    import trimesh

    from urdftool.description import meshes

    trimesh.creation.box((0.1, 0.2, 0.3)).export(tmp_path / name)
    robot = _robot(tmp_path, name)
    resolve(robot, name)
    opened = []
    real_open, real_io_open, real_os_open = builtins.open, io.open, os.open
    for module, attribute, real in ((builtins, "open", real_open), (io, "open", real_io_open),
                                    (os, "open", real_os_open)):
        monkeypatch.setattr(module, attribute, lambda file, *rest, real=real, **named: (
            opened.append(os.fspath(file)) if isinstance(file, (str, os.PathLike)) else None)
            or real(file, *rest, **named))
    monkeypatch.setattr(meshes.run_cache, "_RUN_CACHE", meshes.run_cache.new_cache())
    facts = meshes.mesh_facts(robot, name)
    assert facts.faces == 12 and facts.is_watertight
    assert [os.path.basename(path) for path in opened] == [name]


@pytest.mark.parametrize("joined", [False, True])
def test_a_plain_obj_over_the_triangle_limit_is_refused_with_its_count(tmp_path, joined):
    """Counted exactly, also when backslashes join lines into more "f " rows than it shows."""
    import trimesh

    from urdftool.description import meshes

    text = trimesh.exchange.obj.export_obj(trimesh.creation.box((0.1, 0.2, 0.3)))
    if joined:
        text = text.replace("\nf ", "\nf\\\n ")
    (tmp_path / "m.obj").write_text(text)
    meshes.run_cache.clear()
    for limit, refused in ((11, True), (12, False)):
        try:
            meshes.mesh_facts(_robot(tmp_path, "m.obj"), "m.obj",
                              limits=MeshLimits(max_triangles=limit))
        except MeshProblem as error:
            assert refused and error.kind == "too-large" and "has 12 triangles" in str(error)
        else:
            assert not refused


def test_a_changed_mesh_is_read_again(tmp_path, monkeypatch):
    import os

    import trimesh

    from urdftool.description.meshes import load_mesh

    mesh = tmp_path / "part.stl"
    trimesh.creation.box((0.1, 0.1, 0.1)).export(mesh)
    reads = _count_reads(monkeypatch)
    path = _mesh_robot(tmp_path, "r.urdf", "part.stl")
    assert load_mesh(load(path), "part.stl").extents[0] == pytest.approx(0.1)
    trimesh.creation.box((0.3, 0.1, 0.1)).export(mesh)
    os.utime(mesh, ns=(1, 1))  # even with an old modification time: the size differs
    assert load_mesh(load(path), "part.stl").extents[0] == pytest.approx(0.3)
    assert len(reads) == 2


def test_a_uri_is_resolved_and_checked_once_per_robot(tmp_path, monkeypatch):
    import trimesh

    from urdftool.description import meshes
    from urdftool.lint.engine import CheckOptions, load_and_check

    trimesh.creation.box((0.1, 0.1, 0.1)).export(tmp_path / "part.stl")
    calls = []
    real = meshes.uris._resolve
    monkeypatch.setattr(meshes.uris, "_resolve", lambda robot, uri: calls.append(uri) or
                        real(robot, uri))
    load_and_check(_mesh_robot(tmp_path, "one.urdf", "part.stl", links=5), CheckOptions())
    assert calls == ["part.stl"]


@pytest.mark.parametrize("name", ["m.dae", "m.stl"])
def test_mesh_facts_measure_what_load_mesh_loads(tmp_path, name):
    import numpy as np
    import trimesh

    from urdftool.description.meshes import mesh_facts

    mesh = trimesh.creation.icosphere(subdivisions=2, radius=0.1)
    mesh.apply_translation((0.3, 0.0, -0.2))
    mesh.export(tmp_path / name)
    robot = _robot(tmp_path, name)
    for scale in ((1.0, 1.0, 1.0), (2.0, -1.0, 0.5)):
        loaded, facts = load_mesh(robot, name, scale), mesh_facts(robot, name, scale)
        assert np.allclose(facts.bounds, loaded.bounds, rtol=1e-12, atol=0)
        assert np.allclose(facts.extents, loaded.extents, rtol=1e-12, atol=0)
        assert facts.faces == len(loaded.faces) and facts.is_watertight == loaded.is_watertight
        assert facts.mass_properties["volume"] == pytest.approx(loaded.volume, rel=1e-12)
        assert facts.convex_hull.mass_properties["volume"] == pytest.approx(
            loaded.convex_hull.volume, rel=1e-12)


@pytest.mark.parametrize("data", [b"\0" * 80 + struct.pack("<I", 3) + b"\0" * 70, b""])
def test_a_bad_stl_is_the_same_problem_measured_or_loaded(tmp_path, data):
    from urdftool.description import meshes

    (tmp_path / "m.stl").write_bytes(data)
    robot = _robot(tmp_path)
    with pytest.raises(MeshProblem) as loaded:
        load_mesh(robot, "m.stl")
    meshes.run_cache.clear()
    with pytest.raises(MeshProblem) as measured:
        meshes.mesh_facts(_robot(tmp_path), "m.stl")
    assert (measured.value.kind, str(measured.value)) == (loaded.value.kind, str(loaded.value))
    assert loaded.value.kind == "corrupt"


def _boxes(tmp_path, count: int) -> list:
    import trimesh

    robots = []
    for index in range(count):
        trimesh.creation.box((0.1, 0.1, 0.1 + index)).export(tmp_path / f"p{index}.stl")
        robots.append(_robot(tmp_path, f"p{index}.stl"))
    return robots


def test_the_run_cache_keeps_to_its_byte_limit(tmp_path, monkeypatch):
    from urdftool.description import meshes

    cache = meshes.run_cache.new_cache(5000)
    monkeypatch.setattr(meshes.run_cache, "_RUN_CACHE", cache)
    for index, robot in enumerate(_boxes(tmp_path, 4)):  # arrays and scaled facts: 1152 B each
        meshes.mesh_facts(robot, f"p{index}.stl", (2, 2, 2))
        held = sum(entry[0] for entry in cache.values())
        assert 0 < held == cache.currsize <= 5000
    assert len(cache) == 4  # of 8: the others were let go


def test_the_run_cache_keeps_a_mesh_once_for_equal_limits_and_apart_for_others(tmp_path,
                                                                              monkeypatch):
    """Its keys hold the limits' numbers (run_cache.limits_key), not the record: robots whose
    limits are equal records share the mesh read; other limits read it under their own."""
    from urdftool.description import meshes

    cache = meshes.run_cache.new_cache()
    monkeypatch.setattr(meshes.run_cache, "_RUN_CACHE", cache)
    robots = _boxes(tmp_path, 1) + [_robot(tmp_path, "p0.stl")]
    for robot in robots:
        meshes.mesh_facts(robot, "p0.stl", limits=MeshLimits(max_triangles=12))
    assert len(cache) == 2  # the arrays and the facts at scale 1, once
    with pytest.raises(MeshProblem) as error:
        meshes.mesh_facts(robots[0], "p0.stl", limits=MeshLimits(max_triangles=11))
    assert error.value.kind == "too-large"


def test_the_run_cache_lets_the_least_recently_used_go(monkeypatch):
    from urdftool.description.meshes import run_cache

    monkeypatch.setattr(run_cache, "_RUN_CACHE", run_cache.new_cache(300))
    computed = []

    def kept(name: str, size: int = 100):
        return run_cache.once((name, "stamp"), name,
                              lambda: computed.append(name) or (name.upper(), size))

    assert [kept(name) for name in "abac"] == ["A", "B", "A", "C"]
    assert computed == ["a", "b", "c"]  # a was kept
    kept("d")  # b, the least recently used, goes; a, used after it, stays
    assert sorted(key[0] for key in run_cache._RUN_CACHE) == ["a", "c", "d"]
    assert kept("x", 301) == "X" and ("x", "stamp") not in run_cache._RUN_CACHE  # over the bound


def test_a_mesh_path_in_a_symbolic_link_loop_is_a_missing_mesh(tmp_path):
    (tmp_path / "loop.stl").symlink_to(tmp_path / "loop.stl")
    with pytest.raises(MeshProblem) as error:
        resolve(_robot(tmp_path, "loop.stl"), "loop.stl")
    assert error.value.kind == "missing"  # Path.resolve raised OSError (ELOOP): a crash, U900


def test_symbolic_links_are_followed_once_per_run(tmp_path, monkeypatch):
    import os

    from urdftool.description.run_memo import one_run

    mesh = tmp_path / "m.stl"
    mesh.write_text("solid x\nendsolid x\n")
    robots = [_robot(tmp_path) for _ in range(3)]  # each resolves the URI itself
    looked = []
    real = os.lstat
    monkeypatch.setattr(os, "lstat", lambda p, *a, **k: looked.append(str(p)) or real(p, *a, **k))
    with one_run():
        for robot in robots:
            assert resolve(robot, "m.stl") == mesh
    assert looked.count(str(mesh)) == 1


@pytest.mark.parametrize("scale", [(1.0, 1.0, 1.0), (0.5, -2.0, 1.0)])
def test_a_mesh_measured_for_its_box_only_is_not_merged(tmp_path, monkeypatch, scale):
    import trimesh

    from urdftool.description import mesh_arrays, meshes

    trimesh.creation.icosphere(2).export(tmp_path / "m.stl")
    merges = []
    real = mesh_arrays.merged
    monkeypatch.setattr(mesh_arrays, "merged", lambda *a: merges.append(1) or real(*a))
    monkeypatch.setattr(meshes.run_cache, "_RUN_CACHE", meshes.run_cache.new_cache())
    facts = meshes.mesh_facts(_robot(tmp_path), "m.stl", scale)
    assert facts.faces == 320 and not merges
    loaded = load_mesh(_robot(tmp_path), "m.stl", scale)
    assert [list(corner) for corner in facts.bounds] == loaded.bounds.tolist()
    assert facts.is_watertight and len(merges) == 1
    assert facts.vertices.tolist() == loaded.vertices.tolist()


def test_a_mesh_uri_is_checked_once_per_run_for_robots_of_one_folder(tmp_path, monkeypatch):
    from urdftool.description import meshes
    from urdftool.description.run_memo import one_run

    (tmp_path / "m.stl").write_text("solid x\nendsolid x\n")
    robots = [_robot(tmp_path) for _ in range(3)]
    looked = []
    real = meshes.uris.real_inside
    monkeypatch.setattr(meshes.uris, "real_inside", lambda *a: looked.append(a) or real(*a))
    with one_run():
        assert {resolve(robot, "m.stl") for robot in robots} == {tmp_path / "m.stl"}
        with pytest.raises(MeshProblem) as first:
            resolve(robots[0], "gone.stl")
        with pytest.raises(MeshProblem) as second:
            resolve(robots[1], "gone.stl")
    assert len(looked) == 2 and first.value is not second.value
    assert (first.value.kind, str(first.value)) == (second.value.kind, str(second.value))


def test_a_meshs_inner_points_lie_within_their_slack_of_its_merged_vertices(tmp_path,
                                                                           monkeypatch):
    """Corners as read that merge (each within 1e-8 of the first of them on every axis, in
    the file's unit) and a scale: every inner point (found from the corners, not merged) is
    within the facts' inner_slack of a merged vertex, and the slack is that small."""
    import numpy as np

    from urdftool.description import meshes

    rng = np.random.default_rng(3)
    grid = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]]) * 0.12345678
    grid = np.round(grid * 1e8) / 1e8  # on the merge's grid: moved by < 0.5e-8, they merge
    rows = []
    inward = np.sign(grid.mean(axis=0) - grid)  # a corner moved into the solid (its box
    # then decided without merging: each extreme is first had by the corner that is kept)
    seen = set()
    for face in ((0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)):
        corners = grid[list(face)] + rng.uniform(0, 0.45e-8, size=(3, 3)) * \
            inward[list(face)] * [[i in seen] for i in face]  # a vertex's first: on the grid
        seen.update(face)
        rows.append("facet normal 0 0 0\nouter loop\n" + "".join(
            f"vertex {float(x)!r} {float(y)!r} {float(z)!r}\n" for x, y, z in corners) + "endloop\nendfacet\n")
    (tmp_path / "m.stl").write_text("solid t\n" + "".join(rows) + "endsolid t\n")
    monkeypatch.setattr(meshes.run_cache, "_RUN_CACHE", meshes.run_cache.new_cache())
    scale = (1000.0, -2.0, 0.5)
    facts = meshes.mesh_facts(_robot(tmp_path), "m.stl", scale)
    inner = np.array(facts.inner_points)  # before merging: from the corners as read
    assert 0 < facts.inner_slack <= 4e-8 * 1000
    merged = facts.vertices
    assert len(merged) == 4
    gaps = np.sqrt(((inner[:, None, :] - merged[None, :, :]) ** 2).sum(axis=2)).min(axis=1)
    assert gaps.max() > 0 and (gaps <= facts.inner_slack).all()


def test_a_package_mesh_is_located_once_per_run_for_robots_of_several_folders(tmp_path,
                                                                              monkeypatch):
    """Robots in two folders of one package name its mesh: where the file is (an install
    rule's source, or missing and why) is worked out once per run, each robot still told."""
    from urdftool.description import meshes
    from urdftool.description.run_memo import one_run

    (tmp_path / ".git").mkdir()
    (tmp_path / "package.xml").write_text("<package><name>pkg</name></package>")
    (tmp_path / "m.stl").write_text("solid x\nendsolid x\n")
    robots = []
    for folder in ("a", "b"):
        (tmp_path / folder).mkdir()
        path = tmp_path / folder / "r.urdf"
        path.write_text('<robot name="r"><link name="l"/></robot>')
        robots.append(load(path))
    located = []
    real = meshes.uris.installed
    monkeypatch.setattr(meshes.uris, "installed", lambda *a: located.append(a) or real(*a))
    with one_run():
        assert {resolve(robot, "package://pkg/m.stl") for robot in robots} == \
            {tmp_path / "m.stl"}
        problems = []
        for robot in robots:
            with pytest.raises(MeshProblem) as problem:
                resolve(robot, "package://pkg/gone.stl")
            problems.append(problem.value)
    assert len(located) == 2  # m.stl once, gone.stl once
    assert problems[0] is not problems[1] and problems[0].kind == "missing"
    assert str(problems[0]) == str(problems[1])


@pytest.mark.parametrize("name", ["m.stl", "m.dae", "m.obj"])
def test_a_git_lfs_pointer_is_said_to_be_one(tmp_path, name):
    # a clone without git-lfs holds pointers: read as meshes, an STL's was '1647534901
    # triangles, over the limit; decimate it', a COLLADA's 'XML Parsing Error', an OBJ's
    # 'holds no triangles' (NVIDIA-Omniverse/urdf-importer-extension's Franka and UR10)
    (tmp_path / name).write_bytes(
        b"version https://git-lfs.github.com/spec/v1\n"
        b"oid sha256:4d7a214614ab2935c943f9e0ff69d22eadbb8f32b1258daaa5e2ca24d17e2393\n"
        b"size 1234567\n")
    with pytest.raises(MeshProblem) as error:
        load_mesh(_robot(tmp_path, name), name)
    assert error.value.kind == "corrupt" and "Git LFS pointer" in str(error.value)


def test_a_mesh_that_starts_as_a_git_lfs_pointer_does_is_read_as_the_mesh(tmp_path):
    # a binary STL's 80-byte header is free text: one forged to open as a pointer is a mesh
    # every viewer reads (docs/attacks.md, session 8, second wave)
    import struct

    header = b"version https://git-lfs.github.com/spec/v1\noid sha256:0\nsize 1\n".ljust(80)
    triangles = [((0, 0, 0), (1, 0, 0), (0, 1, 0)), ((0, 0, 0), (0, 1, 0), (0, 0, 1)),
                 ((0, 0, 0), (0, 0, 1), (1, 0, 0)), ((1, 0, 0), (0, 0, 1), (0, 1, 0))]
    (tmp_path / "m.stl").write_bytes(header + struct.pack("<I", 4) + b"".join(
        struct.pack("<12f", 0, 0, 0, *a, *b, *c) + b"\0\0" for a, b, c in triangles))
    mesh = load_mesh(_robot(tmp_path, "m.stl"), "m.stl")
    assert len(mesh.faces) == 4


def test_a_missing_mesh_named_by_its_full_path_is_not_named_twice(tmp_path):
    # xacro expands file://$(find pkg)/meshes/trunk.dae to the very path looked at: the
    # message read "mesh 'file:///.../trunk.dae' not found (looked at /.../trunk.dae)"
    (tmp_path / "meshes").mkdir()
    named = f"file://{(tmp_path / 'meshes' / 'trunk.dae').resolve()}"
    with pytest.raises(MeshProblem) as error:
        resolve(_robot(tmp_path, named), named)
    assert str(error.value) == f"mesh '{named}' not found"
    with pytest.raises(MeshProblem) as error:
        resolve(_robot(tmp_path, "meshes/gone.stl"), "meshes/gone.stl")
    assert "(looked at " in str(error.value)


def test_a_mesh_path_written_with_windows_backslashes_says_so(tmp_path):
    # DingoQuadruped's klp.urdf (a Windows export for Webots) names 'meshes\collision\x.stl':
    # 'not found (looked at .../meshes\collision\x.stl)' left the reader to spot the separators
    (tmp_path / "meshes" / "collision").mkdir(parents=True)
    (tmp_path / "meshes" / "collision" / "base.stl").write_bytes(b"solid s\nendsolid s\n")
    with pytest.raises(MeshProblem) as error:
        resolve(_robot(tmp_path, "meshes\\collision\\base.stl"), "meshes\\collision\\base.stl")
    assert str(error.value).endswith(
        "; backslashes are no path separators on Linux, where a backslash is part of a file "
        "name: write 'meshes/collision/base.stl'")
    # a backslash path with no such file, or leading up out of its folder, gets no advice
    for named in ("meshes\\collision\\gone.stl", "..\\meshes\\collision\\base.stl"):
        with pytest.raises(MeshProblem) as error:
            resolve(_robot(tmp_path, named), named)
        assert "backslashes" not in str(error.value)


def test_a_mesh_named_as_only_the_windows_machine_it_was_exported_on_names_it_says_so(
        tmp_path):
    """A CAD exporter on Windows writes the mesh as that machine names it: a path with its
    drive letter (as written, or as a file:// URI), or a package:// URI with backslashes, whose
    package name is then all of it. 'not found (looked at .../urdf/C:\\Users\\...)', 'is an
    absolute path, outside ...', and 'add <exec_depend>pkg\\meshes\\arm.stl</exec_depend>'
    said none of that: each says it, and the URI to write when the repository holds the file
    the path ends with."""
    (tmp_path / "pkg" / "meshes").mkdir(parents=True)
    (tmp_path / "pkg" / "package.xml").write_text("<package><name>pkg</name></package>")
    (tmp_path / "pkg" / "meshes" / "arm.stl").write_bytes(b"solid s\nendsolid s\n")
    (tmp_path / ".git").mkdir()
    robot = tmp_path / "pkg" / "urdf" / "r.urdf"
    robot.parent.mkdir()

    def robot_naming(named):
        robot.write_text(f'<robot name="r"><link name="a"><visual><geometry><mesh filename='
                         f'"{named}"/></geometry></visual></link></robot>')
        return load(robot)

    wanted = ("; the repository holds its end, pkg/meshes/arm.stl: write "
              "'package://pkg/meshes/arm.stl'")
    for named in ("C:\\Users\\me\\ros\\pkg\\meshes\\arm.stl",
                  "file://D:\\ros\\pkg\\meshes\\arm.stl",
                  "file:///C:/Users/me/ros/pkg/meshes/arm.stl", "c:/pkg/meshes/arm.stl"):
        with pytest.raises(MeshProblem) as error:
            resolve(robot_naming(named), named)
        drive = named.removeprefix("file:///").removeprefix("file://")[0]
        assert str(error.value) == (f"mesh '{named}' is a path of a Windows machine (drive "
                                    f"{drive}:), the one the robot was exported on, there on "
                                    f"no other{wanted}"), str(error.value)
        assert error.value.kind == "missing" and error.value.certain
    named = "package://pkg\\meshes\\arm.stl"
    with pytest.raises(MeshProblem) as error:
        resolve(robot_naming(named), named)
    assert str(error.value) == (f"mesh '{named}' names a package 'pkg\\meshes\\arm.stl': "
                                "backslashes are no path separators on Linux, where a "
                                "backslash is part of a name, and no package is named so"
                                f"{wanted}")
    # a file the repository does not hold: said without advice
    with pytest.raises(MeshProblem) as error:
        resolve(robot_naming("C:\\x\\gone.stl"), "C:\\x\\gone.stl")
    assert str(error.value).endswith("there on no other")


def test_a_missing_mesh_named_with_the_words_of_the_backslash_advice_gets_its_own(tmp_path):
    """Where the repository has a file of a missing mesh's name is said unless the Windows
    separators' advice is (one advice); which one was read back from the message's words, and
    a file named with those words got neither."""
    named = "backslashes are no path separators.stl"
    (tmp_path / "collision").mkdir()
    (tmp_path / "collision" / named).write_bytes(b"solid s\nendsolid s\n")
    with pytest.raises(MeshProblem) as error:
        resolve(_robot(tmp_path, named), named)
    assert str(error.value).endswith(f"; the repository's one file of that name is "
                                     f"collision/{named}"), str(error.value)


def test_a_mesh_written_with_cwd_is_not_certain_when_there_from_a_folder_xacro_may_run_in(
        tmp_path, monkeypatch):
    # pybullet_simplified_fetch: file://$(cwd)/meshes/table.stl, its README saying to run
    # xacro in the robot's folder; xacro run from the repository's root misses it
    robot_folder = tmp_path / "sim" / "resources"
    (robot_folder / "meshes").mkdir(parents=True)
    (tmp_path / ".git").mkdir()
    (robot_folder / "meshes" / "table.stl").write_bytes(b"solid s\nendsolid s\n")
    path = robot_folder / "fetch.urdf.xacro"
    path.write_text('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="a">'
                    '<visual><geometry><mesh filename="file://$(cwd)/meshes/table.stl"/>'
                    '</geometry></visual></link></robot>')
    monkeypatch.chdir(tmp_path)
    named = f"file://{tmp_path.resolve()}/meshes/table.stl"
    with pytest.raises(MeshProblem) as error:
        resolve(load(path), named)
    assert not error.value.certain and str(error.value) == (
        f"mesh '{named}' not found: written with $(cwd), the folder xacro runs from; it is "
        "there when xacro runs from 'sim/resources'")
    # a mesh there from no folder between the robot file and the root stays missing
    (robot_folder / "meshes" / "table.stl").unlink()
    with pytest.raises(MeshProblem) as error:
        resolve(load(path), named)
    assert error.value.certain


def test_a_missing_mesh_whose_folder_holds_it_deeper_than_the_repository_listing_names_that_one(
        tmp_path):
    # allegro_hand_ros2: 'palm.stl' beside description/urdf/x.urdf, six folders down, is in
    # its meshes/; the listing from the root stops above it, and the advice named another
    # package's copy as "the repository's one file of that name"
    deep = tmp_path / "src" / "utils" / "utils" / "description" / "urdf"
    for folder in (deep / "meshes", tmp_path / "src" / "controllers" / "meshes"):
        folder.mkdir(parents=True)
        (folder / "palm.stl").write_bytes(b"solid s\nendsolid s\n")
    (tmp_path / ".git").mkdir()
    (deep / "hand.urdf").write_text('<robot name="r"><link name="a"><visual><geometry>'
                                    '<mesh filename="palm.stl"/></geometry></visual></link></robot>')
    with pytest.raises(MeshProblem) as error:
        resolve(load(deep / "hand.urdf"), "palm.stl")
    assert str(error.value).endswith(
        "; of the repository's 2 files of that name, the one below the folder looked in is "
        "meshes/palm.stl there")


def test_an_absolute_path_meaning_a_file_beside_the_robot_says_so(tmp_path):
    # Blind-Us/Tancho_URDF's Tencho_v1.urdf (StackForce SimReady): '/meshes/base_link.stl' for
    # the meshes/base_link.stl beside it; an absolute path naming nothing here keeps the advice
    (tmp_path / "meshes").mkdir()
    (tmp_path / "meshes" / "base_link.stl").write_text("solid x\nendsolid x\n")
    with pytest.raises(MeshProblem) as error:
        resolve(_robot(tmp_path, "/meshes/base_link.stl"), "/meshes/base_link.stl")
    assert error.value.kind == "outside" and error.value.certain
    # (session 21: not also "use package://PKG/... for files of another package", which the
    # file beside it is not)
    assert str(error.value).endswith("outside the robot's repository: the leading '/' makes it "
                                     "absolute: 'meshes/base_link.stl', relative to the robot's "
                                     "folder, is there"), str(error.value)
    with pytest.raises(MeshProblem) as error:
        resolve(_robot(tmp_path, "/meshes/other.stl"), "/meshes/other.stl")
    assert str(error.value).endswith("for files of another package")


def test_a_mesh_in_a_ros_distributions_install_is_outside_but_not_certainly_missing(tmp_path):
    # a cuRobo URDF generated on a Humble machine names /opt/ros/humble/share/ur_description/...:
    # there wherever Humble and ur_description are installed, so not an error; a /home path is
    named = "/opt/ros/humble/share/ur_description/meshes/ur5/visual/base.dae"
    with pytest.raises(MeshProblem) as error:
        resolve(_robot(tmp_path, named), named)
    assert error.value.kind == "outside" and not error.value.certain
    assert str(error.value) == (
        f"mesh '{named}' is in ROS humble's install of 'ur_description' (outside the repository: "
        "not opened), there only where ROS humble and ur_description are installed; write "
        "'package://ur_description/meshes/ur5/visual/base.dae'")
    with pytest.raises(MeshProblem) as error:
        resolve(_robot(tmp_path, "/home/me/ws/meshes/base.dae"), "/home/me/ws/meshes/base.dae")
    assert error.value.kind == "outside" and error.value.certain
    # the path written is the path meant: said once (it was "mesh '/home/...' resolves to
    # /home/..., outside ..." in delta_robot_simulation's and uned_crazyflie_ros_pkg's URDFs)
    for written in ("/home/me/ws/meshes/base.dae", "file:///home/me/ws/meshes/base.dae"):
        with pytest.raises(MeshProblem) as error:
            resolve(_robot(tmp_path, written), written)
        assert str(error.value).startswith(f"mesh '{written}' is an absolute path, outside ")
        assert str(error.value).count("/home/me/ws/meshes/base.dae") == 1


def test_a_mesh_path_holding_no_file_says_what_is_there(tmp_path):
    """A mesh named where a named pipe or a folder is was "not found (looked at ...)": it is
    there, never opened (U412, as session 6 had it); a link loop cannot be reached, said so;
    a mesh truly missing is still not found (U408)."""
    import os

    os.mkfifo(tmp_path / "pipe.stl")
    (tmp_path / "folder.stl").mkdir()
    (tmp_path / "loop.stl").symlink_to(tmp_path / "loop.stl")
    said = {}
    for name in ("pipe.stl", "folder.stl", "loop.stl", "gone.stl"):
        with pytest.raises(MeshProblem) as error:
            resolve(_robot(tmp_path, name), name)
        said[name] = (error.value.kind, str(error.value).split(" (looked")[0])
    assert said == {
        "pipe.stl": ("corrupt", "mesh 'pipe.stl' is a named pipe, not a file"),
        "folder.stl": ("corrupt", "mesh 'folder.stl' is a folder, not a file"),
        "loop.stl": ("missing", "mesh 'loop.stl' cannot be reached: too many levels of "
                                "symbolic links"),
        "gone.stl": ("missing", "mesh 'gone.stl' not found")}, said


@pytest.mark.parametrize("declared", [0, 10])
def test_a_binary_stl_whose_header_miscounts_says_so(tmp_path, declared):
    """A binary STL holding 12 triangles whose header says 10 (or 0): trimesh reads it as ASCII
    and finds none, and the finding said only "holds no triangles"."""
    triangle = struct.pack("<12fH", 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0)
    (tmp_path / "m.stl").write_bytes(b"\0" * 80 + struct.pack("<I", declared) + triangle * 12)
    with pytest.raises(MeshProblem) as error:
        load_mesh(_robot(tmp_path), "m.stl")
    assert str(error.value).endswith(
        f"holds no triangles: its binary STL header says {declared} triangles "
        f"({84 + 50 * declared} bytes), the file has 684 bytes")


def test_a_binary_stl_named_dae_names_pycolladas_error_once(tmp_path):
    triangle = struct.pack("<12fH", 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0)
    (tmp_path / "m.dae").write_bytes(b"\0" * 80 + struct.pack("<I", 2) + triangle * 2)
    with pytest.raises(MeshProblem) as error:
        load_mesh(_robot(tmp_path, "m.dae"), "m.dae")
    assert "does not load: DaeMalformedError: XML Parsing Error" in str(error.value)


@pytest.mark.parametrize("path", ["/a/b.stl", "/a.b/c", "/a/.stl", "/a/b.", "/a/b.tar.DAE",
                                  "/a/b", "/a.v1/b/c.obj"])
def test_a_real_paths_extension_is_the_one_pathlib_gives(path):
    """uris._suffix reads a real path's extension from the string (no Path made for each
    candidate): the same as ``Path.suffix``, a folder's dot never taken."""
    from pathlib import Path

    from urdftool.description.meshes.uris import _suffix

    assert _suffix(os.path.normpath(path)) == Path(path).suffix



I4 = ((1, 0, 0, 0), (0, 1, 0, 0), (0, 0, 1, 0), (0, 0, 0, 1))


@pytest.mark.parametrize("node, said, extents", [
    ({"matrix": _columns((2, 0, 0, 0), (0, 2, 0, 0), (0, 0, 2, 0), (0, 0, 0, 1))}, None, 0.2),
    ({"matrix": _columns((-1, 0, 0, 0), (0, 1, 0, 0), (0, 0, 1, 0), (0, 0, 0, 1))}, None, 0.1),
    ({"scale": [1, 1, 3]}, None, 0.3),
    ({"rotation": [0, 0, 0.7071068, 0.7071068]}, None, 0.1),
    ({"matrix": _columns((1, 0.5, 0, 0), (0, 1, 0, 0), (0, 0, 1, 0), (0, 0, 0, 1))},
     "its matrix shears", 0.15),
    ({"matrix": _columns((1, 0, 0, 0), (0, 1, 0, 0), (0, 0, 1, 0), (0.5, 0, 0, 1))},
     "bottom row is 0.5 0 0 1, not 0 0 0 1", 0.1),
    ({"rotation": [0, 0, 0, 2]}, "is no unit quaternion (length 2): trimesh, and urdftool, "
                                 "normalise it; assimp (Gazebo, RViz) does not", 0.1),
    ({"scale": [1, 0, 1]}, "its scale 1 0 1 has a 0", 0.1),
])
def test_a_gltf_node_transform_glTF_does_not_allow_is_said_with_what_is_assumed(
        tmp_path, node, said, extents):
    """attack25: a GLB node's matrix that shears, projects, flattens, or a rotation that is no
    unit quaternion, was applied (or ignored) silently; trimesh applies a matrix's affine part
    (as assimp, Gazebo's and RViz's reader, does) and normalises a quaternion (which assimp
    does not). urdftool measures as trimesh does and says so; translation, rotation and scale
    (a mirror too), which every loader applies alike, are said nothing of."""
    from urdftool.description.meshes import NODE_TRANSFORM

    _glb(tmp_path / "m.glb", **node)
    mesh = load_mesh(_robot(tmp_path, "m.glb"), "m.glb")
    assert max(mesh.extents) == pytest.approx(extents)
    found = mesh.metadata.get(NODE_TRANSFORM)
    if said is None:
        assert found is None, found
    else:
        assert found.startswith("glTF node 'n': ") and said in found, found


def test_a_gltf_node_matrix_that_is_not_finite_is_named_in_its_refusal(tmp_path):
    """attack25: "has a coordinate of nan, past the 4.612e+10": the refusal says the coordinate
    is not finite, and which node's matrix made it so."""
    _glb(tmp_path / "m.glb", matrix=_columns((float("nan"), 0, 0, 0), *I4[1:]))
    with pytest.raises(MeshProblem, match=r"has a coordinate that is not finite, not within the "
                                          r".*\(glTF node 'n': its matrix holds a number that "
                                          r"is not finite\)"):
        load_mesh(_robot(tmp_path, "m.glb"), "m.glb")


def test_a_gltf_scene_nested_deeper_than_a_collada_one_may_be_is_not_opened(tmp_path):
    """attack25: a 60 KB GLB of 20,000 nodes each the child of the one before took trimesh 4.7 s
    a load (it walks every node's parents), 13.6 s a check; 100,000 ran out the time budget.
    A glTF scene is held to a COLLADA scene's bounds (256 deep, 100,000 nodes)."""
    from gltf_nodes import glb_with_chain

    glb_with_chain(tmp_path / "m.glb", 256)
    assert len(load_mesh(_robot(tmp_path, "m.glb"), "m.glb").faces) == 12
    glb_with_chain(tmp_path / "d.glb", 257)
    with pytest.raises(MeshProblem, match=r"mesh 'd.glb': its scene has 257 nodes nested 257 "
                                          r"deep, over 100000 nodes or 256 deep; not opened"):
        load_mesh(_robot(tmp_path, "d.glb"), "d.glb")


def test_an_obj_of_many_materials_is_read_as_one_mesh_in_time_linear_in_its_size(tmp_path,
                                                                                monkeypatch):
    """trimesh makes a mesh of each material an OBJ names (``usemtl``) and joins them: each
    piece named by ``util.unique_name`` without a memo (the k-th named alike tries k names:
    10,000 materials were 5 x 10^7 ``str.format`` calls, 13 s a load), each masking the whole
    vertex array (999 materials over 4 million vertices, 18 s a check); past 1,000 materials the
    file was refused (U411). urdftool reads no material file: the faces are read as one mesh,
    the same triangles, whatever the encoding trimesh decodes."""
    import trimesh.util

    named = []
    original = trimesh.util.unique_name
    monkeypatch.setattr(trimesh.util, "unique_name", lambda *args, **kwargs: (
        named.append(args[0]), original(*args, **kwargs))[1])
    count = 5_000
    obj = "".join(f"v {i} 0 0\nv {i} 1 0\nv {i} 0 1\n" for i in range(count)) + "".join(
        f"usemtl m{i}\nf {3 * i + 1} {3 * i + 2} {3 * i + 3}\n" for i in range(count))
    (tmp_path / "m.obj").write_text(obj)
    loaded = load_mesh(_robot(tmp_path, "m.obj"), "m.obj")
    assert len(loaded.faces) == count and len(named) <= 1  # one piece, named once
    plain = tmp_path / "plain"
    plain.mkdir()
    (plain / "m.obj").write_text(re.sub(r"usemtl [^\n]*\n", "", obj))
    assert np.array_equal(np.asarray(loaded.vertices)[np.asarray(loaded.faces)],
                          np.asarray(load_mesh(_robot(plain, "m.obj"), "m.obj").vertices)[
                              np.asarray(load_mesh(_robot(plain, "m.obj"), "m.obj").faces)])
    (tmp_path / "u.obj").write_text(obj.encode("utf-16").decode("latin-1"), encoding="latin-1")
    named.clear()
    assert len(load_mesh(_robot(tmp_path, "u.obj"), "u.obj").faces) == count and len(named) <= 1


def test_a_mesh_trimesh_would_build_from_more_pieces_than_the_bound_is_not_opened(tmp_path):
    """attack26: trimesh builds a mesh of each primitive each glTF node places and of each
    solid of an ASCII STL, then joins them: a GLB of 99,000 nodes each placing a triangle took
    34 s a check; an ASCII STL of 20,000 solids 21 s a load. One judge of pieces for both, said
    as U411's too-large, the file never given to trimesh; the bound itself is read. (An OBJ's
    materials are read as one mesh: the next test.)"""
    import json
    import struct

    from urdftool.description.meshes.counting import MAX_TEXT_PIECES, MAX_PIECES

    over = MAX_TEXT_PIECES + 1
    solid = "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n" \
        "endloop\nendfacet\nendsolid s\n"
    (tmp_path / "m.stl").write_text(solid.upper() * over)
    with pytest.raises(MeshProblem, match=rf"mesh 'm.stl': it holds {over} solids \(endsolid\), "
                                          rf"each a mesh of its own to build and join, over "
                                          rf"{MAX_TEXT_PIECES}; not opened"):
        load_mesh(_robot(tmp_path, "m.stl"), "m.stl")
    (tmp_path / "ok.stl").write_text(solid * (over - 1))
    assert len(load_mesh(_robot(tmp_path, "ok.stl"), "ok.stl").faces) == over - 1
    # a binary STL (its header's count fits its length) is one mesh to trimesh, whatever its
    # bytes spell: "endsolid" in its header and in each record's normal is no solid (and a
    # binary file is not scanned for solids in every check: 2.4 % of the corpus's)
    records = b"".join(b"endsolid\0\0\0\0" + struct.pack("<9f", i, 0, 0, i + 1, 0, 0, i, 1, 0)
                       + b"\0\0" for i in range(over))
    (tmp_path / "b.stl").write_bytes(b"endsolid".ljust(80) + struct.pack("<I", over) + records)
    assert len(load_mesh(_robot(tmp_path, "b.stl"), "b.stl").faces) == over

    over = MAX_PIECES + 1
    header = {"asset": {"version": "2.0"}, "nodes": [{"mesh": 0}] * over,
              "scenes": [{"nodes": list(range(over))}], "scene": 0,
              "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}]}
    text = json.dumps(header).encode()
    text += b" " * (-len(text) % 4)
    glb = b"glTF" + struct.pack("<II", 2, 20 + len(text)) + struct.pack("<I", len(text)) + \
        b"JSON" + text
    (tmp_path / "m.glb").write_bytes(glb)
    with pytest.raises(MeshProblem, match=rf"mesh 'm.glb': its nodes place {over} primitives, "
                                          rf"each a mesh of its own to build and join, over "
                                          rf"{MAX_PIECES}; not opened"):
        load_mesh(_robot(tmp_path, "m.glb"), "m.glb")


def test_every_command_computing_with_a_mesh_read_assuming_says_so(tmp_path):
    """attack26: U416 (check) said a glTF node that shears, a mesh whose triangles were left out
    for not finite vertices, a repaired COLLADA; render, collisions (pose and matrix) and
    inertia computed with the same mesh in silence. One wording
    (``meshes.read_as_assumed``), said by each."""
    from urdftool.collision.geometry import build
    from urdftool.description.meshes import read_as_assumed
    from urdftool.kinematics.scene import posed
    from urdftool.physics.inertia_compare import compare_link

    _glb(tmp_path / "m.glb", matrix=_columns((1, 0.5, 0, 0), (0, 1, 0, 0), (0, 0, 1, 0),
                                             (0, 0, 0, 1)))
    (tmp_path / ".git").mkdir(exist_ok=True)
    (tmp_path / "r.urdf").write_text(
        '<robot name="r"><link name="a"><visual><geometry><mesh filename="m.glb"/></geometry>'
        '</visual><collision><geometry><mesh filename="m.glb"/></geometry></collision></link>'
        '</robot>')
    robot = load(tmp_path / "r.urdf")
    said = read_as_assumed(load_mesh(robot, "m.glb").metadata)
    assert len(said) == 1 and "its matrix shears" in said[0]
    expected = f"mesh 'm.glb'{said[0]}"
    assert f"link 'a': {expected}" in posed(robot, {})[0].problems  # render
    assert build(robot).assumed == [f"link 'a': {expected}"]  # collisions, pose and matrix
    assert expected in compare_link(robot, robot.links["a"]).notes  # inertia
