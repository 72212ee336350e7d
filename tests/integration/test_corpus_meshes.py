"""The corpus's missing meshes are exactly the ones OMITTED.tsv lists: every mesh every corpus
robot names (robots from the shared ``corpus_run``) resolves, or is one the corpus left out."""

from __future__ import annotations

import csv

import pytest

from conftest import corpus_args, corpus_entry_points
from urdftool.description.meshes import MeshProblem, resolve


def _checks_rows(corpus) -> set[tuple[str, tuple]]:
    """(path, sorted xacro args) of every CHECKS.tsv row."""
    rows = set()
    with open(corpus / "CHECKS.tsv") as handle:
        for row in csv.DictReader(handle, delimiter="\t"):
            rows.add((row["path"], tuple(sorted(corpus_args(row["xacro_args"] or "").items()))))
    return rows


def test_missing_meshes_on_the_corpus_are_exactly_the_omitted_ones(corpus, corpus_run):
    # the shared run covers every robot CHECKS.tsv lists, and nothing else
    assert _checks_rows(corpus) == {(path, tuple(sorted(args.items())))
                                    for path, args in corpus_entry_points()}
    found = set()
    for (path, _), result in corpus_run.values():
        robot = result.robot
        if robot is None:
            continue
        for mesh in robot.root.iter("mesh"):
            uri = mesh.get("filename")
            if uri.startswith("package:///"):
                # OMITTED.tsv lists every empty package name as unresolvable (by ROS, which
                # U415 warns of); urdftool resolves them as Pinocchio does (tested below)
                found.add((uri, path))
                continue
            try:
                resolve(robot, uri)
            except MeshProblem as problem:
                if problem.kind == "missing":
                    target = str(robot.resolve_uri(uri).resolve().relative_to(corpus.resolve()))
                elif problem.kind in ("package", "outside"):
                    target = uri
                else:
                    continue
                found.add((target, path))
    with open(corpus / "OMITTED.tsv") as handle:
        omitted = {(row["referenced_path"], by.strip())
                   for row in csv.DictReader(handle, delimiter="\t")
                   for by in row["referenced_by"].split(",")}
    assert found == omitted


def test_empty_package_names_resolve_as_pinocchio_does_with_a_warning(corpus):
    """Talos (example-robot-data) names its meshes package:///example-robot-data/...: each is a
    U415 warning, never U407 (package '' not found); the few the corpus left out are U408."""
    from collections import Counter

    from urdftool.lint.engine import CheckOptions, Selection, load_and_check

    omitted = {row["referenced_path"] for row in csv.DictReader(
        open(corpus / "OMITTED.tsv"), delimiter="\t")}
    talos = corpus / "example-robot-data/robots/talos_data/robots/talos_full_v2.urdf"
    result = load_and_check(str(talos), CheckOptions(selection=Selection(("U407", "U408", "U415"))))
    codes = Counter(f.code for f in result.findings)
    assert codes["U407"] == 0 and codes["U415"] == 93
    missing = [f.message.split("'")[3] for f in result.findings if f.code == "U408"]
    assert missing and all(uri in omitted and not (corpus / uri[len("package:///"):]).exists()
                           for uri in missing)


def _of_kind(corpus_meshes, suffix: str) -> list:
    """The corpus meshes whose name ends in ``suffix`` (any case), with what mesh_arrays read."""
    return [(path, arrays) for path, arrays in corpus_meshes.items()
            if path.suffix.lower() == suffix]


def test_stl_read_without_trimesh_measures_as_trimesh_on_every_corpus_stl(corpus_meshes):
    """Every corpus STL read by mesh_arrays (no trimesh) gives trimesh's processed mesh:
    the same vertices and faces, bounds, triangle count, watertightness and mass properties
    (within 1e-9 relative), unscaled and mirrored-scaled."""
    import numpy as np
    import trimesh

    from urdftool.description import mesh_arrays

    files = _of_kind(corpus_meshes, ".stl")
    assert len(files) > 200
    light = 0
    for path, arrays in files:
        try:
            mesh = trimesh.load(str(path), force="mesh", process=True)
        except Exception:  # a file trimesh refuses must not be read light either
            assert arrays is None, path
            continue
        if arrays is None:
            continue
        light += 1
        vertices, faces = arrays
        assert np.array_equal(vertices, mesh.vertices) and np.array_equal(faces, mesh.faces), path
        for scale in ((1.0, 1.0, 1.0), (0.001, -0.002, 0.001)):
            if scale != (1.0, 1.0, 1.0):
                mesh = mesh.copy()
                mesh.apply_scale(scale)
            v, f = mesh_arrays.scaled(vertices, faces, scale)
            low, high = mesh_arrays.bounds(v, f)
            assert np.allclose([low, high], mesh.bounds, rtol=1e-9, atol=0), path
            assert len(f) == len(mesh.faces)
            assert mesh_arrays.is_watertight(f) == mesh.is_watertight, path
            ours, theirs = mesh_arrays.mass_properties(v, f), mesh.mass_properties
            scale_of = abs(theirs["volume"]) + 1e-300
            assert abs(ours["volume"] - theirs["volume"]) <= 1e-9 * scale_of, path
            if abs(theirs["volume"]) > 1e-12:
                assert np.allclose(ours["center_mass"], theirs["center_mass"], rtol=1e-9,
                                   atol=1e-9 * float(np.abs(mesh.bounds).max())), path
                size = float(np.abs(theirs["inertia"]).max())
                assert np.allclose(ours["inertia"], theirs["inertia"], rtol=1e-9,
                                   atol=1e-9 * size), path
    assert light == len(files)  # every corpus STL is read without trimesh


def test_convex_hulls_without_trimesh_measure_as_trimeshs_on_every_corpus_mesh(corpus_meshes):
    """The hull of every corpus STL, DAE and OBJ (what an open mesh's volume is taken from) has
    trimesh's volume, centre of mass and inertia within 1e-9 relative, built without trimesh."""
    import numpy as np
    import trimesh

    from urdftool.description import mesh_arrays

    built = 0
    for path, arrays in corpus_meshes.items():
        hull = mesh_arrays.convex_hull(arrays[0])
        theirs = trimesh.convex.convex_hull(arrays[0]).mass_properties
        assert hull is not None, path
        built += 1
        ours = hull[2]
        assert abs(ours["volume"] - theirs["volume"]) <= 1e-9 * abs(theirs["volume"]), path
        size = float(np.abs(arrays[0]).max())
        assert np.allclose(ours["center_mass"], theirs["center_mass"], rtol=1e-9,
                           atol=1e-9 * size), path
        assert np.allclose(ours["inertia"], theirs["inertia"], rtol=1e-9,
                           atol=1e-9 * float(np.abs(theirs["inertia"]).max())), path
    assert built == len(corpus_meshes) > 300


def _by_position(path):
    """trimesh's mesh of a file with its corners merged by position alone."""
    import trimesh

    mesh = trimesh.load(str(path), force="mesh", process=True)
    was = mesh.is_watertight
    mesh.merge_vertices(merge_tex=True, merge_norm=True)
    return mesh, was


def _same_merged_mesh(path, arrays, mesh) -> None:
    import numpy as np

    from urdftool.description import mesh_arrays

    vertices, faces = arrays
    assert len(vertices) == len(mesh.vertices) and len(faces) == len(mesh.faces), path
    assert np.array_equal(np.array(mesh_arrays.bounds(vertices, faces)), mesh.bounds), path
    assert mesh_arrays.is_watertight(faces) == mesh.is_watertight, path
    ours, theirs = mesh_arrays.mass_properties(vertices, faces), mesh.mass_properties
    assert abs(ours["volume"] - theirs["volume"]) <= 1e-9 * abs(theirs["volume"]), path


def test_collada_read_without_trimesh_is_trimeshs_merged_on_every_corpus_dae(corpus_meshes):
    """Every corpus COLLADA file read by mesh_arrays (read_collada, no trimesh, no pycollada)
    is trimesh.load(force="mesh")'s mesh with its corners merged by position: vertex and
    triangle count, bounds, watertightness, volume. trimesh alone keeps corners apart where
    normals or texture coordinates differ, and so calls most of these closed meshes open."""
    import logging

    logging.getLogger("trimesh").setLevel(logging.CRITICAL)
    files = _of_kind(corpus_meshes, ".dae")
    assert len(files) > 90
    seams = 0
    for path, arrays in files:
        assert arrays is not None, path
        mesh, was = _by_position(path)
        _same_merged_mesh(path, arrays, mesh)
        seams += mesh.is_watertight and not was
    assert seams >= 60  # closed meshes trimesh alone calls open (63 when written)


def test_obj_read_without_trimesh_measures_as_trimesh_on_every_corpus_obj(corpus_meshes):
    """Every corpus OBJ read by mesh_arrays gives trimesh's triangles (the same coordinates,
    face by face) merged by position: vertex count, bounds, watertightness and volume."""
    import logging

    import numpy as np

    logging.getLogger("trimesh").setLevel(logging.CRITICAL)
    files = _of_kind(corpus_meshes, ".obj")
    assert files
    for path, arrays in files:
        assert arrays is not None, path
        mesh, _ = _by_position(path)
        _same_merged_mesh(path, arrays, mesh)
        assert np.array_equal(arrays[0][arrays[1]], mesh.vertices[mesh.faces]), path


def _sweep_objs(count: int) -> list:
    """``count`` OBJ files of the real sweep (URDFTOOL_REAL_SWEEP or ../sweep-repos), spread
    over its sorted list (every repository's exporters, not the first one's 2,000 files)."""
    import os
    from pathlib import Path

    sweep = Path(os.environ.get("URDFTOOL_REAL_SWEEP",
                                Path(__file__).resolve().parents[2].parent / "sweep-repos"))
    found = sorted(path for path in sweep.glob("*/**/*") if path.suffix.lower() == ".obj"
                   and path.is_file() and not path.is_symlink()) if sweep.is_dir() else []
    if len(found) < count:
        pytest.skip(f"the real sweep is not restored at {sweep} (make real-sweep-setup)")
    return found[::len(found) // count][:count]


def test_obj_read_without_trimesh_is_trimeshs_on_200_sweep_objs():
    """200 OBJ files of the real sweep: each that mesh_arrays reads (no trimesh) holds
    trimesh's triangles, corner by corner, to the bit; the others are left to trimesh. The
    reader is numpy over the whole text (a slice of the text for each kind of row where its
    rows follow one another), so this is its oracle on what exporters really write."""
    import logging

    import numpy as np
    import trimesh

    from urdftool.description import mesh_arrays

    logging.getLogger("trimesh").setLevel(logging.CRITICAL)
    read = 0
    for path in _sweep_objs(200):
        data = path.read_bytes()
        try:
            arrays = mesh_arrays.read_unmerged(path, data)
        except Exception as error:  # noqa: BLE001 - the reader raises nothing on an OBJ
            raise AssertionError(path) from error
        if arrays is None:
            continue
        read += 1
        mesh = trimesh.load(str(path), force="mesh", process=False)
        corners, faces = arrays
        assert faces is None, path
        assert corners.dtype == np.float64 and corners.flags.c_contiguous, path
        assert np.array_equal(corners.reshape(-1, 3, 3), mesh.vertices[mesh.faces]), path
    assert read >= 120  # most are plain (132 of the 200, from 23 repositories, when written)
