"""Pure-Python mass properties against numpy, and `check` without numpy."""

from __future__ import annotations

import subprocess
import sys

import numpy as np

from conftest import ROBOTS
from urdftool.physics import mass as mp
from urdftool.physics import mat3

RNG = np.random.default_rng(11)


def test_triangle_inequality_on_principal_moments():
    body = mp.Body(1.0, (0.0, 0.0, 0.0), mat3.diagonal([0.1, 0.1, 0.5]))
    assert mp.triangle_violation(body.principal_moments()) == "0.1 + 0.1 < 0.5"
    assert mp.triangle_violation(mp.box((0.1, 0.2, 0.3)).principal_moments()) is None


def test_transformed_and_combined_match_numpy_parallel_axis():
    parts, expected = [], []
    for _ in range(4):
        solid = mp.box(RNG.uniform(0.01, 1.0, 3))
        xyz, rpy = RNG.normal(size=3), RNG.uniform(-3, 3, 3)
        placed = mp.transformed(solid, xyz, mat3.rpy_matrix(rpy))
        r = np.array(mat3.rpy_matrix(rpy))
        assert np.allclose(placed.inertia, r @ np.array(solid.inertia) @ r.T, rtol=1e-12)
        parts.append(placed)
        expected.append((placed.mass, xyz, np.array(placed.inertia)))
    whole = mp.combine(parts)
    mass = sum(m for m, _, _ in expected)
    com = sum(m * c for m, c, _ in expected) / mass
    inertia = sum(i + m * ((c - com) @ (c - com) * np.eye(3) - np.outer(c - com, c - com))
                  for m, c, i in expected)
    assert np.isclose(whole.mass, mass) and np.allclose(whole.com, com, rtol=1e-12)
    assert np.allclose(whole.inertia, inertia, rtol=1e-12)


def test_primitives_bodies_are_what_inertia_wraps():
    from urdftool.physics import inertia

    for pure, wrapped in [(mp.box((0.1, 0.2, 0.3)), inertia.box((0.1, 0.2, 0.3))),
                          (mp.cylinder(0.05, 0.2), inertia.cylinder(0.05, 0.2)),
                          (mp.sphere(0.1), inertia.sphere(0.1))]:
        assert np.array_equal(np.array(pure.inertia), wrapped.inertia)
        assert wrapped.body() == pure


def test_relative_difference_of_scalars_and_matrices():
    a = _random = RNG.normal(size=(3, 3))
    b = a * 1.1
    assert np.isclose(mp.relative_difference(mat3.matrix(b), mat3.matrix(a)),
                      np.linalg.norm(b - a) / np.linalg.norm(a))
    assert mp.relative_difference(2.0, 1.0) == 1.0
    assert mp.relative_difference(0.0, 0.0) == 0.0 and mp.relative_difference(1.0, 0.0) == np.inf


def test_check_without_meshes_never_imports_numpy():
    code = ("import sys\n"
            "from urdftool.cli import main\n"
            f"sys.argv = ['urdftool', 'check', {str(ROBOTS / 'r2d2' / 'r2d2.urdf.xacro')!r}]\n"
            "try:\n    main()\nexcept SystemExit as exit:\n    assert exit.code == 0, exit.code\n"
            "heavy = [m for m in ('numpy', 'trimesh', 'yourdfpy', 'pinocchio', 'fcl')"
            " if m in sys.modules]\n"
            "assert not heavy, heavy\n")
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                            cwd=ROBOTS.parent)
    assert result.returncode == 0, result.stderr


def test_combine_is_the_parallel_axis_sum_to_the_bit():
    # the written-out sums are the loop they replaced: same terms, same order, same zeros
    def by_loop(parts):
        mass = sum(p.mass for p in parts)
        com = tuple(sum(p.mass * p.com[i] for p in parts) / mass for i in range(3))
        inertia = [[0.0] * 3 for _ in range(3)]
        for part in parts:
            m, c = part.mass, part.com
            d = (c[0] - com[0], c[1] - com[1], c[2] - com[2])
            squared = d[0] * d[0] + d[1] * d[1] + d[2] * d[2]
            for i, (row, own, di) in enumerate(zip(inertia, part.inertia, d)):
                for j in range(3):
                    row[j] += own[j] + m * ((squared if i == j else 0.0) - di * d[j])
        return mp.Body(mass, com, mat3.matrix(inertia))

    rng = np.random.default_rng(3)
    for count in (1, 2, 5):
        for _ in range(50):
            parts = [mp.transformed(mp.box(rng.uniform(0.01, 1, 3)), rng.choice([0.0, -0.0, 0.3],
                                                                                 3),
                                    mat3.rpy_matrix(rng.choice([0.0, 0.7], 3)))
                     for _ in range(count)]
            ours, loop = mp.combine(parts), by_loop(parts)
            assert [float(v).hex() for v in (ours.mass, *ours.com, *np.ravel(ours.inertia))] == \
                [float(v).hex() for v in (loop.mass, *loop.com, *np.ravel(loop.inertia))]


def test_declared_keeps_an_unturned_tensor_as_rotate_gives_it_back():
    """declared() takes an unturned tensor as it is where mat3.rotate would give it back to the
    bit; the same numbers as rotating it, over awkward values (zeros of either sign, subnormal,
    huge within mass.MAX_MOMENT) and origins turned or not; a term infinite, nan or past the
    bound gives no body."""
    import random
    import struct

    from lxml import etree

    from urdftool.physics import mass, mat3

    values = ["0", "-0.0", "5e-324", "1e-3", "-2.5", "2e51", "-2e51", "inf", "nan", "0.1",
              "1e308"]
    chance = random.Random(34)
    for _ in range(3000):
        terms = [chance.choice(values) for _ in range(6)]
        rpy = chance.choice(["0 0 0", "-0.0 0 0", "0.5 0 0", None])
        origin = f'<origin xyz="0 0 0" rpy="{rpy}"/>' if rpy else ""
        link = etree.fromstring(
            f'<link name="l"><inertial>{origin}<mass value="1"/><inertia ixx="{terms[0]}" '
            f'ixy="{terms[1]}" ixz="{terms[2]}" iyy="{terms[3]}" iyz="{terms[4]}" '
            f'izz="{terms[5]}"/></inertial></link>')
        xx, xy, xz, yy, yz, zz = (float(t) for t in terms)
        tensor = ((xx, xy, xz), (xy, yy, yz), (xz, yz, zz))
        turned = mat3.rotate(tensor, mat3.rpy_matrix(tuple(map(float, (rpy or "0 0 0").split()))))
        if not all(abs(float(t)) <= mass.MAX_MOMENT for t in terms):
            assert mass.declared(link) is None, terms
            continue
        found = mass.declared(link).inertia
        assert struct.pack("<9d", *sum(found, ())) == struct.pack("<9d", *sum(turned, ())), terms


def test_a_declared_inertial_gives_no_body_exactly_when_it_is_malformed_or_past_the_bounds():
    """declared() and problem_at() judge the bounds alike (one statement of them): an inertial
    whose numbers all parse as finite gives no body exactly when problem_at says why, and
    problem_at says nothing of one that gives a body or does not parse as finite numbers."""
    import math
    import random

    from lxml import etree

    from urdftool.physics import mass

    values = ["0", "1", "-0.0", "2e51", "-2.2e51", "1e30", "-1.1e30", "4e10", "-5e10", "inf",
              "nan", "x"]
    chance = random.Random(26)
    for _ in range(3000):
        m, *terms = (chance.choice(values) for _ in range(7))
        xyz = " ".join(chance.choice(values) for _ in range(3))
        rpy = chance.choice(["0 0 0", "0.5 0 nan", "inf 0 0", "1 2"])
        origin = chance.choice([f'<origin xyz="{xyz}" rpy="{rpy}"/>', f'<origin xyz="{xyz}"/>',
                                ""])
        link = etree.fromstring(
            f'<link name="l"><inertial>{origin}<mass value="{m}"/><inertia ixx="{terms[0]}" '
            f'ixy="{terms[1]}" ixz="{terms[2]}" iyy="{terms[3]}" iyz="{terms[4]}" '
            f'izz="{terms[5]}"/></inertial></link>')
        body, found = mass.declared(link), mass.problem_at(link)
        numbers = [m, *terms] + ((xyz.split() + rpy.split()) if "rpy" in origin else
                                 xyz.split() if origin else [])
        finite = all(v != "x" and math.isfinite(float(v)) for v in numbers) and \
            len(numbers) in (7, 10, 13)
        if not finite:
            assert found is None, (m, terms, origin)
            continue
        assert (body is None) == (found is not None), (m, terms, origin)
        if found is not None:
            assert found[0] in ("mass", "inertia", "origin") and found[1].startswith(f"<{found[0]}")


def _awkward_link(rng, i: int) -> str:
    """A link whose inertials, and their masses, tensors and origins, come none, once or
    several times, malformed or not, among comments and other children."""
    def some(text: str) -> str:
        return "".join(text for _ in range(rng.choice([0, 1, 1, 1, 2])))

    def inertial() -> str:
        parts = [some(f'<mass value="{rng.choice(["1", "0", "-2", "x", "1e400"])}"/>'),
                 some('<inertia ixx="1" ixy="0.1" ixz="0" iyy="{}" iyz="0" izz="1"/>'.format(
                     rng.choice(["2", "nan", "-0"]))),
                 some(f'<origin xyz="{rng.choice(["0 0 1", "1 2", "-0 0 0"])}" '
                      f'rpy="{rng.choice(["0 0 0", "0 1.5 0", "a b c"])}"/>'),
                 "<!-- c -->", "<origin/>" if rng.random() < 0.2 else ""]
        rng.shuffle(parts)
        return "<inertial>" + "".join(parts) + "</inertial>"

    parts = ["<!-- first -->"] + [inertial() for _ in range(rng.choice([0, 1, 1, 2]))] + \
        ['<visual><geometry><box size="1 1 1"/></geometry></visual>']
    rng.shuffle(parts)
    return f'<link name="l{i}">' + "".join(parts) + "</link>"


def test_the_inertial_read_from_the_grouped_children_is_the_inertial_read_alone(tmp_path):
    import random

    from urdftool.description.load import load

    rng = random.Random(34)
    for case in range(60):
        path = tmp_path / f"r{case}.urdf"
        path.write_text('<robot name="r">' + "".join(_awkward_link(rng, i) for i in range(20))
                        + "</robot>")
        robot = load(path)
        for link in robot.children("link"):
            assert repr(mp.declared_of(robot, link)) == repr(mp.declared(link)), \
                path.read_text()
