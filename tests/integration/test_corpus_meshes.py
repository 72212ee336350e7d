"""The corpus's missing meshes are exactly the ones OMITTED.tsv lists: every mesh every corpus
robot names (robots from the shared ``corpus_run``) resolves, or is one the corpus left out."""

from __future__ import annotations

import csv

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
    from urdftool.physics.solids import SHAPES  # noqa: F401 (shapes and meshes share the resolver)

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
