"""``fk``, ``inertia`` and ``dynamics`` on the corpus's plain URDFs (46 robots), against oracles
that read each file themselves: Pinocchio's own URDF parser for every link's pose at drawn
configurations and for M(q) and G(q); the ``<mass>`` values summed for the total mass; trimesh
for the inertia of a link whose geometry is one closed mesh. Each command's core is called as
the command calls it (the CLI only parses words around it). A few seconds in all."""

from __future__ import annotations

import math
import xml.etree.ElementTree as ElementTree
from functools import lru_cache

import numpy as np
import pytest

from conftest import CORPUS, corpus_entry_points

ROBOTS = sorted(path for path, args in corpus_entry_points()
                if not args and not path.endswith(".xacro"))

pytestmark = [pytest.mark.integration,
              pytest.mark.skipif(not ROBOTS, reason="corpus not available")]

SEED, DRAWS = 7, 4
COMPARED_AT_LEAST = 250  # links of one closed STL or OBJ mesh: 283 in the 46 robots


@lru_cache(maxsize=None)
def _robot(path: str):
    from urdftool.description.load import load

    return load(CORPUS / path)


@lru_cache(maxsize=None)
def _text(path: str) -> str:
    """The file's text; for a xacro file named .urdf (sam_bot's), urdftool's expansion of it:
    the only URDF there is (urdfdom refuses its ``${...}``)."""
    robot = _robot(path)
    return robot.urdf if robot.from_xacro else (CORPUS / path).read_text()


@lru_cache(maxsize=None)
def _oracle(path: str):
    """Pinocchio's model of the URDF, as its own parser reads it (mimic joints independent)."""
    import pinocchio as pin

    return pin.buildModelFromXML(_text(path))


def _mimic_values(path: str, values: dict[str, float]) -> dict[str, float]:
    """``values`` with every mimic joint's value, from the file's ``<mimic>`` elements."""
    follows = {}
    for joint in ElementTree.fromstring(_text(path)).iter("joint"):
        mimic = joint.find("mimic")
        if mimic is not None:
            follows[joint.get("name")] = (mimic.get("joint"),
                                          float(mimic.get("multiplier", "1")),
                                          float(mimic.get("offset", "0")))
    full = dict(values)

    def value(name, depth=0):
        if name not in full:
            leader, multiplier, offset = follows[name]
            full[name] = multiplier * value(leader, depth + 1) + offset
        return full[name]

    for name in follows:
        value(name)
    return full


def _oracle_q(model, values: dict[str, float]) -> np.ndarray:
    """Pinocchio's q of joint values by name (continuous joints as cos, sin)."""
    import pinocchio as pin

    q = pin.neutral(model)
    for joint_id in range(1, model.njoints):
        joint, value = model.joints[joint_id], values.get(model.names[joint_id], 0.0)
        if joint.nq == 2:
            q[joint.idx_q:joint.idx_q + 2] = (math.cos(value), math.sin(value))
        else:
            assert joint.nq == 1, model.names[joint_id]  # (no floating or planar joint here)
            q[joint.idx_q] = value
    return q


def _drawn(path: str):
    """(urdftool's kinematic model, its drawn configurations, each as {variable: value} and
    with the mimic joints' values too: [(variables, joints)])."""
    from urdftool.kinematics import configuration as config
    from urdftool.kinematics.fk import KinematicModel

    model = KinematicModel(_robot(path))
    drawn = config.random(model.variables, DRAWS, SEED)
    rows = [{v.name: float(x) for v, x in zip(drawn.variables, row)} for row in drawn.values]
    named = [(row, _mimic_values(path, row)) for row in rows]
    return model, drawn, named


@pytest.mark.parametrize("path", ROBOTS)
def test_fk_poses_every_link_as_pinocchio_does(path):
    import pinocchio as pin

    from urdftool.kinematics.fk import forward_kinematics

    model, drawn, named = _drawn(path)
    result = forward_kinematics(model, drawn)
    oracle = _oracle(path)
    data = oracle.createData()
    assert set(result.frames) == {frame.name for frame in oracle.frames
                                  if frame.type == pin.FrameType.BODY}
    for row, (_, values) in enumerate(named):
        pin.framesForwardKinematics(oracle, data, _oracle_q(oracle, values))
        for column, link in enumerate(result.frames):
            expected = data.oMf[oracle.getFrameId(link, pin.FrameType.BODY)].homogeneous
            assert np.allclose(result.matrices[row, column], expected, atol=1e-9), (link, row)


@pytest.mark.parametrize("path", ROBOTS)
def test_dynamics_matches_pinocchio_on_the_file(path):
    import pinocchio as pin

    from urdftool.errors import DynamicsError
    from urdftool.physics.dynamics import build, state

    try:
        model = build(_robot(path))
    except DynamicsError as error:
        pytest.fail(f"dynamics refuses a robot Pinocchio builds: {error}")
    _, _, named = _drawn(path)
    oracle = _oracle(path)
    data = oracle.createData()
    order = [oracle.joints[oracle.getJointId(name)].idx_v for name in model.joints]
    assert sorted(order) == list(range(oracle.nv))
    masses = [float(mass.get("value")) for mass in
              ElementTree.fromstring(_text(path)).iter("mass")]
    for variables, values in named[:2]:
        result = state(model, variables)
        q = _oracle_q(oracle, values)
        crba = pin.crba(oracle, data, q)
        crba = np.triu(crba) + np.triu(crba, 1).T
        scale = max(1.0, float(np.abs(crba).max(initial=0.0)))
        assert np.allclose(result.M, crba[np.ix_(order, order)], atol=1e-9 * scale)
        gravity = pin.computeGeneralizedGravity(oracle, data, q)[order]
        assert np.allclose(result.G, gravity,
                           atol=1e-9 * max(1.0, np.abs(gravity).max(initial=0.0)))
        assert result.mass == pytest.approx(math.fsum(masses), rel=1e-12)


def _rotation(rpy) -> np.ndarray:
    roll, pitch, yaw = rpy
    x = np.array([[1, 0, 0], [0, math.cos(roll), -math.sin(roll)],
                  [0, math.sin(roll), math.cos(roll)]])
    y = np.array([[math.cos(pitch), 0, math.sin(pitch)], [0, 1, 0],
                  [-math.sin(pitch), 0, math.cos(pitch)]])
    z = np.array([[math.cos(yaw), -math.sin(yaw), 0], [math.sin(yaw), math.cos(yaw), 0],
                  [0, 0, 1]])
    return z @ y @ x


def _one_closed_mesh(robot, link, source: str):
    """(trimesh of the link's one ``source`` element's mesh, scaled; its origin's xyz, rpy),
    or None: another shape, several, a format other than STL or OBJ, a mesh that is not a
    closed solid (urdftool counts its hull)."""
    import trimesh

    elements = link.findall(source)
    if len(elements) != 1 or elements[0].find("geometry/mesh") is None:
        return None
    mesh_element = elements[0].find("geometry/mesh")
    uri = mesh_element.get("filename")
    if not uri.lower().endswith((".stl", ".obj")):
        return None
    mesh = trimesh.load(robot.resolve_uri(uri), force="mesh")
    scale = [float(v) for v in mesh_element.get("scale", "1 1 1").split()]
    mesh.apply_transform(np.diag([*scale, 1.0]))
    if not mesh.is_volume:
        return None
    origin = elements[0].find("origin")
    xyz = [float(v) for v in (origin.get("xyz", "0 0 0") if origin is not None
                              else "0 0 0").split()]
    rpy = [float(v) for v in (origin.get("rpy", "0 0 0") if origin is not None
                              else "0 0 0").split()]
    return mesh, np.array(xyz), np.array(rpy)


def test_inertia_of_a_closed_mesh_is_trimeshs():
    """Every link of the corpus whose inertia ``inertia`` computes from one closed STL or OBJ
    mesh (the declared mass kept, or 1000 kg/m^3): its centre of mass and tensor in the link
    frame are trimesh's of that mesh, scaled, turned and moved by the element's origin."""
    from urdftool.physics.inertia_compare import compare

    compared = []
    for path in ROBOTS:
        robot = _robot(path)
        for result in compare(robot):
            if result.computed is None or result.source not in ("collision", "visual"):
                continue
            found = _one_closed_mesh(robot, robot.links[result.link], result.source)
            if found is None:
                continue
            mesh, xyz, rpy = found
            volume, com, inertia = mesh.volume, mesh.center_mass, mesh.moment_inertia
            if volume < 0:  # inside out
                volume, inertia = -volume, -inertia
            mass = result.declared.mass if result.declared is not None and \
                result.declared.mass > 0 else 1000.0 * volume
            rotation = _rotation(rpy)
            expected = rotation @ (inertia * mass / volume) @ rotation.T
            where = f"{path}: {result.link}"
            assert result.computed.mass == pytest.approx(mass, rel=1e-9), where
            size = float(np.ptp(mesh.vertices, axis=0).max())
            assert np.allclose(result.computed.com, rotation @ com + xyz, atol=1e-6 * size), \
                where
            assert np.allclose(result.computed.inertia, expected,
                               atol=1e-6 * float(np.abs(expected).max())), where
            compared.append(where)
    assert len(compared) >= COMPARED_AT_LEAST, compared
