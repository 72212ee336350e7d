"""Dynamics against a hand-computed two-link arm, and the humanoid's gravity margins."""

from __future__ import annotations

import json
import math
import re

import numpy as np
import pytest

from conftest import ROBOTS
from urdftool.physics.dynamics import build, gravity_loads, gravity_variables, state
from urdftool.description.load import load

G0 = 9.81
M1, M2, L1, L2 = 2.0, 1.0, 0.5, 0.4  # point-like masses at the link ends, arm in the x-z plane

ARM = f"""<robot name="arm">
  <link name="base"><inertial><mass value="3"/>
    <inertia ixx="1e-3" ixy="0" ixz="0" iyy="1e-3" iyz="0" izz="1e-3"/></inertial></link>
  <link name="fixed_tool"/>
  <joint name="tool" type="fixed"><parent link="base"/><child link="fixed_tool"/></joint>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/>
    <axis xyz="0 1 0"/><limit lower="-3" upper="3" effort="20" velocity="1"/></joint>
  <link name="upper"><inertial><origin xyz="{L1} 0 0"/><mass value="{M1}"/>
    <inertia ixx="1e-9" ixy="0" ixz="0" iyy="1e-9" iyz="0" izz="1e-9"/></inertial></link>
  <joint name="elbow" type="revolute"><parent link="upper"/><child link="fore"/>
    <origin xyz="{L1} 0 0"/><axis xyz="0 1 0"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <link name="fore"><inertial><origin xyz="{L2} 0 0"/><mass value="{M2}"/>
    <inertia ixx="1e-9" ixy="0" ixz="0" iyy="1e-9" iyz="0" izz="1e-9"/></inertial></link>
</robot>"""


@pytest.fixture(scope="module")
def arm(tmp_path_factory):
    path = tmp_path_factory.mktemp("arm") / "arm.urdf"
    path.write_text(ARM)
    return build(load(path))


def _hand_gravity(q1, q2):
    # Rotation about +y pitches a link along x downwards: heights z1 = -L1 sin q1 and
    # z2 = -L1 sin q1 - L2 sin(q1 + q2). G = dV/dq with V = g (M1 z1 + M2 z2): the torque the
    # joint must apply to hold the pose (tau = M a + C v + G).
    g2 = -M2 * G0 * L2 * math.cos(q1 + q2)
    g1 = -(M1 + M2) * G0 * L1 * math.cos(q1) + g2
    return np.array([g1, g2])


@pytest.mark.parametrize("q1,q2", [(0.0, 0.0), (0.3, -0.7), (1.2, 0.4)])
def test_gravity_matches_hand_computation(arm, q1, q2):
    result = state(arm, {"shoulder": q1, "elbow": q2})
    assert np.allclose(result.G, _hand_gravity(q1, q2), atol=1e-9)


def test_total_mass_counts_root_and_fixed_links(arm):
    assert math.isclose(state(arm, {}).mass, 3 + M1 + M2)


def test_whole_body_com(arm):
    result = state(arm, {})
    assert np.allclose(result.com, [(M1 * L1 + M2 * (L1 + L2)) / (3 + M1 + M2), 0, 0])


def test_tau_matches_rnea(arm):
    result = state(arm, {"shoulder": 0.2}, {"shoulder": 1.0, "elbow": -2.0}, {"elbow": 3.0})
    assert result.rnea_residual < 1e-9
    assert result.C.shape == (2, 2) and np.allclose(result.M, result.M.T)


def test_gravity_loads_flag_a_weak_joint(arm):
    loads = {load.joint: load for load in gravity_loads(arm, 50)}
    assert math.isclose(loads["elbow"].zero_pose, M2 * G0 * L2)
    assert not loads["elbow"].holds  # 3.9 N m against a 1 N m limit
    assert loads["shoulder"].holds


def test_humanoid_holds_itself_with_mx28(run_cli):
    result = run_cli("dynamics", ROBOTS / "humanoid" / "humanoid.urdf.xacro", "--samples", "100",
                     "--format", "json")
    assert result.exit_code == 0, result.output
    loads = json.loads(result.output)["gravity_loads"]
    assert {load["effort"] for load in loads} == {2.5}
    assert all(load["holds"] for load in loads)
    hips = [l for l in loads if "hip_pitch" in l["joint"]]
    assert all(0.3 < l["worst"] < 2.5 for l in hips)


def test_dynamics_unknown_joint_is_usage_error(run_cli):
    result = run_cli("dynamics", ROBOTS / "humanoid" / "humanoid.urdf.xacro", "--q", "l_kne=1")
    assert result.exit_code == 2 and "l_knee" in result.output
    assert result.stderr.startswith("urdftool: error: --q: unknown joint 'l_kne'")
    result = run_cli("dynamics", ROBOTS / "humanoid" / "humanoid.urdf.xacro", "--v", "l_el=x")
    assert result.stderr == ("urdftool: error: --v: value 'x' for joint 'l_el' is not a "
                             "number\n")


@pytest.mark.parametrize("ask", ["configuration", "velocity"])
def test_a_name_the_model_lacks_is_a_dynamics_error_not_an_index_error(arm, ask):
    """Model.configuration/velocity called from a script with a name the model lacks (the
    command line checks names first): Pinocchio's index one past the last was an IndexError."""
    from urdftool.errors import DynamicsError

    with pytest.raises(DynamicsError,
                       match="'wrist' is not a joint of the model \\(shoulder, elbow"):
        getattr(arm, ask)({"shoulder": 0.1, "wrist": 0.2})
    assert getattr(arm, ask)({"shoulder": 0.1}).shape == (arm.model.nq if ask == "configuration"
                                                          else arm.model.nv,)


def test_joint_values_say_which_input_is_wrong(tmp_path):
    from urdftool.kinematics.configuration import ConfigError, joint_values

    path = tmp_path / "arm.urdf"
    path.write_text(ARM)
    robot = load(path)
    values = joint_values(robot, {"shoulder": "90"}, None, {"elbow": "1"}, degrees=True)
    assert values.q == {"shoulder": pytest.approx(math.pi / 2)} and values.v is None
    assert values.a == {"elbow": pytest.approx(math.radians(1))}
    with pytest.raises(ConfigError, match="^unknown joint 'elbw'") as caught:
        joint_values(robot, {}, {"elbw": "1"})
    assert caught.value.argument == "v"


def test_a_robot_without_mass_gets_a_warning(tmp_path):
    from urdftool.physics.dynamics import build, state

    path = tmp_path / "massless.urdf"
    path.write_text('<robot name="r"><link name="a"/><link name="b"/><joint name="j" '
                    'type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>'
                    '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>')
    result = state(build(load(str(path))), {})
    assert result.warnings and result.warnings[0].startswith("no link has a mass")


def test_a_singular_mass_matrix_is_said_and_why(tmp_path):
    """Masses of 0 are said as such (the message said "no <inertial>" of links that each had
    one); M(q) with a joint that moves nothing, or two joints moving one body the same way, is
    said singular (it was printed without a word: forward dynamics does not exist)."""
    zero = ARM.replace(f'<mass value="{M1}"/>', '<mass value="0"/>') \
        .replace(f'<mass value="{M2}"/>', '<mass value="0"/>').replace('<mass value="3"/>',
                                                                       '<mass value="0"/>')
    massless_tip = ARM.replace(f'<mass value="{M2}"/>', '<mass value="0"/>').replace(
        '<inertia ixx="1e-9" ixy="0" ixz="0" iyy="1e-9" iyz="0" izz="1e-9"/></inertial></link>\n'
        '</robot>', '<inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial>'
        '</link>\n</robot>')
    coaxial = ARM.replace(f'<origin xyz="{L1} 0 0"/><axis xyz="0 1 0"/>', '<axis xyz="0 1 0"/>') \
        .replace(f'<mass value="{M1}"/>', '<mass value="0"/>').replace(
        '<inertia ixx="1e-9" ixy="0" ixz="0" iyy="1e-9" iyz="0" izz="1e-9"/></inertial></link>\n'
        '  <joint name="elbow"', '<inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/>'
        '</inertial></link>\n  <joint name="elbow"')
    said = {}
    for name, text in (("zero", zero), ("tip", massless_tip), ("coaxial", coaxial), ("arm", ARM)):
        path = tmp_path / f"{name}.urdf"
        path.write_text(text)
        said[name] = state(build(load(str(path))), {"shoulder": 0.3, "elbow": 0.2}).warnings
    assert said["zero"] == [said["zero"][0]] and "every <inertial> is missing or of mass 0" \
        in said["zero"][0]
    assert said["tip"] == ["M(q) is singular: joint elbow moves no mass or inertia at this "
                           "configuration (a zero row of M(q)), so forward dynamics (M(q)^-1) "
                           "does not exist; give the links it carries an <inertial>"]
    assert said["coaxial"] and said["coaxial"][0].startswith("M(q) is singular: rank 1 of 2")
    assert said["arm"] == []


MIMIC_ARM = ARM.replace('<limit lower="-3" upper="3" effort="1" velocity="1"/></joint>',
                        '<limit lower="-3" upper="3" effort="1" velocity="1"/>'
                        '<mimic joint="shoulder" multiplier="-1" offset="0.2"/></joint>')


@pytest.fixture(scope="module")
def mimic_arm(tmp_path_factory):
    path = tmp_path_factory.mktemp("mimic") / "arm.urdf"
    path.write_text(MIMIC_ARM)
    return build(load(path))


@pytest.mark.parametrize("q1", [0.0, 0.7, -1.1])
def test_mimic_joint_follows_its_variable(mimic_arm, q1):
    # elbow = -shoulder + 0.2: the forearm keeps a fixed pitch of 0.2 rad
    result = state(mimic_arm, {"shoulder": q1}, {"shoulder": 1.5}, {})
    assert np.allclose(result.G, _hand_gravity(q1, -q1 + 0.2), atol=1e-9)
    assert result.rnea_residual < 1e-9
    assert np.allclose(mimic_arm.velocity({"shoulder": 1.5}), [1.5, -1.5])


@pytest.mark.parametrize("multiplier, offset", [("-1", "0.2"), ("2", "0.3")])
def test_a_leader_with_its_mimic_joints_is_pinocchios_mimic_model(tmp_path, run_cli, multiplier,
                                                                  offset):
    """One actuator driving the shoulder and the elbow that mimics it supplies J^T of their
    columns: Pinocchio's model read with mimic=True has it as its G and rnea (urdftool gave
    only the per-joint columns, of a model where each joint has an actuator)."""
    import pinocchio as pin

    path = tmp_path / "arm.urdf"
    path.write_text(MIMIC_ARM.replace('multiplier="-1" offset="0.2"',
                                      f'multiplier="{multiplier}" offset="{offset}"'))
    result = state(build(load(str(path))), {"shoulder": 0.7}, {"shoulder": 1.5},
                   {"shoulder": -0.4})
    model = pin.buildModelFromUrdf(str(path), mimic=True)
    data = model.createData()
    q, v, a = np.array([0.7]), np.array([1.5]), np.array([-0.4])
    [leader] = result.leaders().items()
    assert leader[0] == "shoulder" and leader[1]["followers"] == {"elbow": float(multiplier)}
    assert leader[1]["G"] == pytest.approx(pin.computeGeneralizedGravity(model, data, q)[0],
                                           abs=1e-12)
    assert leader[1]["tau"] == pytest.approx(pin.rnea(model, data, q, v, a)[0], abs=1e-12)
    shown = run_cli("dynamics", path, "--q", "shoulder=0.7", "--v", "shoulder=1.5", "--a",
                    "shoulder=-0.4")
    assert f"shoulder (itself + {multiplier} x elbow): G " in shown.stdout, shown.output
    data = json.loads(run_cli("dynamics", path, "--q", "shoulder=0.7", "-f", "json").stdout)
    assert set(data["mimic_leaders"]) == {"shoulder"}


def test_gravity_loads_judge_a_mimic_joint_in_its_leaders_actuator(mimic_arm, tmp_path,
                                                                  run_cli):
    """A mimic joint is driven by the actuator of the joint it follows: that actuator's load
    is its own torque plus the follower's times the multiplier (J^T, Pinocchio's mimic model's
    G), judged against the leader's effort limit; the follower's own limit judges nothing (the
    elbow was judged on its own torque and the shoulder on its own, as if each had a motor,
    where the dynamics already gave the leader the group's torque)."""
    import pinocchio as pin

    from urdftool.physics.gravity_bound import worst_loads

    loads = {load.joint: load for load in gravity_loads(mimic_arm, 30, seed=3)}
    for load in loads.values():
        assert set(load.worst_pose) == {"shoulder"}  # the mimic joint is not drawn
    # the forearm's pitch never changes, so neither does the elbow's own torque: shown, not
    # judged
    elbow = loads["elbow"]
    assert math.isclose(elbow.worst, M2 * G0 * L2 * math.cos(0.2), rel_tol=1e-9)
    assert elbow.driven_by == "shoulder" and elbow.margin is None and elbow.holds is None
    path = tmp_path / "arm.urdf"
    path.write_text(MIMIC_ARM)
    model = pin.buildModelFromUrdf(str(path), mimic=True)
    data = model.createData()

    def actuator(q):
        return abs(float(pin.computeGeneralizedGravity(model, data, np.array([q]))[0]))

    shoulder = loads["shoulder"]
    assert shoulder.followers == {"elbow": -1.0}
    assert math.isclose(shoulder.worst, actuator(shoulder.worst_pose["shoulder"]),
                        rel_tol=1e-9)
    climbed = {load.joint: load for load in worst_loads(mimic_arm, 30, seed=3)}["shoulder"]
    assert math.isclose(climbed.worst, max(actuator(q) for q in np.linspace(-3, 3, 6001)),
                        rel_tol=1e-6)
    shown = run_cli("dynamics", path, "--samples", "30")
    assert "not judged (mimic joints: the actuator of the joint each follows holds its " \
        "load, judged in that joint's row): elbow (by shoulder)" in shown.stdout, shown.output
    assert "shoulder (itself + -1 x elbow)" in shown.stdout


def test_samples_text_reports_margins_without_the_zero_pose_matrices(run_cli, tmp_path):
    path = tmp_path / "arm.urdf"
    path.write_text(ARM)
    result = run_cli("dynamics", path, "--samples", "20")
    assert result.exit_code == 1, result.output
    assert "M(q)" not in result.output and "G(q)" not in result.output
    assert "1 joint cannot hold itself: elbow" in result.output
    with_q = run_cli("dynamics", path, "--samples", "20", "--q", "shoulder=0.5")
    assert "M(q): joint-space mass matrix" in with_q.output


def test_a_vertical_axis_carries_no_gravity_load(run_cli):
    result = run_cli("dynamics", ROBOTS / "humanoid" / "humanoid.urdf.xacro", "--samples", "20",
                     "--format", "json")
    loads = {load["joint"]: load for load in json.loads(result.output)["gravity_loads"]}
    assert loads["l_hip_yaw"]["worst"] == 0.0 and loads["r_hip_yaw"]["worst"] == 0.0


def test_a_massless_robot_is_warned_about(run_cli, tmp_path):
    path = tmp_path / "massless.urdf"
    path.write_text(re.sub(r"<inertial>.*?</inertial>", "", ARM, flags=re.S))
    result = run_cli("dynamics", path, "--samples", "5")
    assert result.exit_code == 0
    assert "warning: no link has a mass" in result.stderr
    path.write_text(ARM)
    assert "warning" not in run_cli("dynamics", path, "--samples", "5").stderr


def test_gravity_variables_are_the_branch_of_the_joint(mimic_arm):
    humanoid = build(load(ROBOTS / "humanoid" / "humanoid.urdf.xacro"))
    assert gravity_variables(humanoid, "r_knee") == {
        "r_hip_yaw", "r_hip_roll", "r_hip_pitch", "r_knee", "r_ank_pitch", "r_ank_roll"}
    assert gravity_variables(humanoid, "head_pan") == {"head_pan", "head_tilt"}
    assert gravity_variables(mimic_arm, "elbow") == {"shoulder"}  # through the mimic


@pytest.mark.parametrize("q2,v1,v2", [(0.4, 1.0, -2.0), (-1.1, 0.5, 0.3)])
def test_coriolis_matrix_matches_the_two_link_closed_form(arm, q2, v1, v2):
    # point masses: h = -M2 L1 L2 sin q2, C = [[h v2, h (v1 + v2)], [-h v1, 0]] (Christoffel)
    result = state(arm, {"shoulder": 0.3, "elbow": q2}, {"shoulder": v1, "elbow": v2}, {})
    h = -M2 * L1 * L2 * math.sin(q2)
    np.testing.assert_allclose(result.C, [[h * v2, h * (v1 + v2)], [-h * v1, 0.0]], atol=1e-6)
    np.testing.assert_allclose(result.tau - result.G, result.C @ [v1, v2], atol=1e-12)


UNLIMITED = """<robot name="arm">
  <link name="base"><inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
  <link name="l1"><inertial><origin xyz="0.2 0 0"/><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
  <link name="l2"><inertial><origin xyz="0.2 0 0"/><mass value="0.1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
  <joint name="j1" type="continuous"><parent link="base"/><child link="l1"/><axis xyz="0 1 0"/></joint>
  <joint name="j2" type="revolute"><parent link="l1"/><child link="l2"/><origin xyz="0.4 0 0"/>
    <axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="100" velocity="1"/></joint>
</robot>"""


def test_a_joint_without_an_effort_limit_is_not_the_smallest_margin(run_cli, tmp_path):
    """j1 (continuous, no <limit>) has effort inf: its margin is not computed (it was picked as
    the smallest margin, 'inf of inf'), and the joints that have a limit are judged."""
    from urdftool.physics.dynamics import JointLoad
    from urdftool.report.dynamics import weakest

    (tmp_path / "arm.urdf").write_text(UNLIMITED)
    result = run_cli("dynamics", tmp_path / "arm.urdf", "--samples", "10")
    assert result.exit_code == 0, result.output
    assert "smallest margin: j2 (" in result.stdout and "inf" not in result.stdout
    assert "not judged (no effort limit in the URDF, so no margin): j1" in result.stdout
    assert "every joint with an effort limit holds" in result.stdout
    assert weakest([JointLoad("j", math.inf, 2.0)]) is None
    data = json.loads(run_cli("dynamics", tmp_path / "arm.urdf", "--samples", "10",
                              "--format", "json").stdout)
    [j1] = [load for load in data["gravity_loads"] if load["joint"] == "j1"]
    assert (j1["effort"], j1["margin"], j1["holds"]) == (None, None, None)


# a pendulum hanging from a joint 1 m up, with <dynamics damping friction>; the root's own
# 3 kg sit 0.5 m up
PM, PL, PI, PB, PF, H = 1.5, 0.4, 0.02, 0.3, 0.05, 1.0
PENDULUM = f"""<robot name="pendulum">
  <link name="root"><inertial><origin xyz="0 0 0.5"/><mass value="3"/>
    <inertia ixx="1e-3" ixy="0" ixz="0" iyy="1e-3" iyz="0" izz="1e-3"/></inertial></link>
  <joint name="swing" type="revolute"><parent link="root"/><child link="bob"/>
    <origin xyz="0 0 {H}"/><axis xyz="0 1 0"/>
    <limit lower="-3" upper="3" effort="20" velocity="9"/>
    <dynamics damping="{PB}" friction="{PF}"/></joint>
  <link name="bob"><inertial><origin xyz="0 0 {-PL}"/><mass value="{PM}"/>
    <inertia ixx="1e-3" ixy="0" ixz="0" iyy="{PI}" iyz="0" izz="1e-3"/></inertial></link>
</robot>"""


@pytest.mark.parametrize("q,qd,qdd", [(0.3, 1.2, -0.5), (-1.0, -0.7, 2.0), (0.5, 0.0, 0.0)])
def test_energies_and_joint_damping_friction_by_hand(tmp_path, q, qd, qdd):
    path = tmp_path / "pendulum.urdf"
    path.write_text(PENDULUM)
    result = state(build(load(path)), {"swing": q}, {"swing": qd}, {"swing": qdd})
    inertia = PI + PM * PL ** 2  # about the joint axis
    assert result.kinetic == pytest.approx(0.5 * inertia * qd ** 2, abs=1e-12)
    # the bob at (-PL sin q, 0, H - PL cos q), the root's mass at 0.5 m
    assert result.potential == pytest.approx(G0 * (PM * (H - PL * math.cos(q)) + 3 * 0.5),
                                             abs=1e-12)
    assert result.lagrangian == pytest.approx(result.kinetic - result.potential)
    assert result.tau[0] == pytest.approx(inertia * qdd + PM * G0 * PL * math.sin(q), abs=1e-12)
    assert result.damping[0] == pytest.approx(PB * qd)
    assert result.friction[0] == pytest.approx(PF * np.sign(qd))
    assert result.total[0] == pytest.approx(result.tau[0] + PB * qd + PF * np.sign(qd))


def test_energies_agree_with_pinocchio_on_the_humanoid():
    import pinocchio as pin

    model = build(load(ROBOTS / "humanoid" / "humanoid.urdf.xacro"))
    q = {"l_knee": 0.7, "r_hip_pitch": -0.4, "head_tilt": 0.2}
    v = {"l_knee": 1.1, "l_hip_pitch": -0.6, "r_el": 0.9}
    result = state(model, q, v)
    pq, pv = model.configuration(q), model.velocity(v)
    data = model.model.createData()
    assert result.kinetic == pytest.approx(pin.computeKineticEnergy(model.model, data, pq, pv),
                                           rel=1e-12)
    root = model.model.inertias[0]  # the fixed root's mass, which Pinocchio's energy leaves out
    fixed = root.mass * G0 * root.lever[2]
    assert result.potential == pytest.approx(
        pin.computePotentialEnergy(model.model, data, pq) + fixed, rel=1e-12)
    assert np.allclose(result.damping, 0.1 * pv)  # every servo: damping 0.1


def test_cli_energies_and_damping(run_cli):
    result = run_cli("dynamics", ROBOTS / "humanoid" / "humanoid.urdf.xacro", "--q", "l_knee=0.5",
                     "--qd", "l_knee=1", "-f", "json")
    assert result.exit_code == 0, result.output
    document = json.loads(result.output)
    assert document["lagrangian"] == pytest.approx(document["kinetic_energy"]
                                                   - document["potential_energy"])
    knee = document["joints"].index("l_knee")
    assert document["damping_torque"][knee] == pytest.approx(0.1)
    assert document["tau_total"][knee] == pytest.approx(document["tau"][knee] + 0.1)
    text = run_cli("dynamics", ROBOTS / "humanoid" / "humanoid.urdf.xacro", "--qd", "l_knee=1")
    assert re.search(r"energy: K = \S+ J, P = \S+ J .*, L = K - P = \S+ J", text.output)


def test_a_robot_whose_pinocchio_data_cannot_fit_is_refused_before_allocating(tmp_path,
                                                                              monkeypatch):
    # Pinocchio's Data holds nv^3 tensors: 300 joints ~1.7 GB; with 1 GiB allowed it is refused
    import resource

    from conftest import synthetic_robot
    from urdftool.errors import DynamicsError

    robot = load(str(synthetic_robot(tmp_path, 301)))
    monkeypatch.setattr(resource, "getrlimit", lambda _: (1024 ** 3, resource.RLIM_INFINITY))
    with pytest.raises(DynamicsError, match="300 joint variables.*cube of the joints"):
        build(robot)



# a base and a camera on a fixed joint: nothing moves (a sensor's own URDF, BlueROV2's of the
# sweep); `--samples` raised "cannot reshape array of size 0" from sampled_loads, a traceback
RIGID = """<robot name="rigid">
  <link name="base"><inertial><mass value="2"/>
    <inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link>
  <link name="cam"><inertial><mass value="0.1"/>
    <inertia ixx="0.001" iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="cam_joint" type="fixed"><parent link="base"/><child link="cam"/>
    <origin xyz="0.3 0 0"/></joint>
</robot>"""


def test_a_robot_without_a_moving_joint_has_no_gravity_load(tmp_path, run_cli):
    from urdftool.physics.dynamics import sampled_loads

    path = tmp_path / "rigid.urdf"
    path.write_text(RIGID)
    loads, poses, torques = sampled_loads(build(load(path)), 5)
    assert loads == [] and poses.shape == (6, 0) and torques.shape == (6, 0)
    for words in ((), ("--support", "base")):
        result = run_cli("dynamics", path, "--samples", "5", *words)
        assert result.exit_code == 0, result.output
        assert "no moving joint: no gravity load to judge" in result.output
        assert "no pose drawn stands" not in result.output  # it stands: the margin is 85.7 mm
    document = json.loads(run_cli("dynamics", path, "--samples", "5", "-f", "json").output)
    assert document["gravity_loads"] == []


def test_a_floating_joint_below_the_base_is_modelled_as_its_free_flyer(tmp_path):
    """A floating joint below a base with a mass (a camera on a free mount) was refused ('is
    floating, of 6 degrees of freedom'); Pinocchio models it as a free flyer, and so does
    dynamics, its rows named as fk names them. Oracle: the camera alone under dynamics'
    --floating root (the path already held to Pinocchio), 0.3 m further along x: its local
    twist, M, C, G and tau are the same."""
    path = tmp_path / "flying.urdf"
    path.write_text(RIGID.replace('type="fixed"', 'type="floating"'))
    model = build(load(path))
    assert model.root is None and model.joints == [f"cam_joint.{c}" for c in
                                                   ("x", "y", "z", "roll", "pitch", "yaw")]
    alone = tmp_path / "cam.urdf"
    alone.write_text('<robot name="cam"><link name="cam"><inertial><mass value="0.1"/><inertia '
                     'ixx="0.001" iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial>'
                     '</link></robot>')
    free = build(load(alone), floating=True)
    pose, twist, accel = [0.1, -0.2, 0.5, 0.4, -0.3, 1.2], [0.5, -0.1, 0.2, 0.3, -0.6, 0.9], \
        [0.2, 0.1, -0.3, 0.5, 0.0, -0.4]
    shifted = [pose[0] + 0.3, *pose[1:]]
    mine = state(model, dict(zip(model.joints, pose)), dict(zip(model.joints, twist)),
                 dict(zip(model.joints, accel)))
    theirs = state(free, dict(zip(free.joints, shifted)), dict(zip(free.joints, twist)),
                   dict(zip(free.joints, accel)))
    for matrix in ("M", "G", "C", "tau"):
        assert np.allclose(getattr(mine, matrix), getattr(theirs, matrix), atol=1e-12), matrix
    assert mine.kinetic == pytest.approx(theirs.kinetic) and mine.rnea_residual < 1e-12


# a tilted planar base carrying an arm, and the same motion as a chain of one-variable joints:
# travel along x, travel along y, a turn about z (massless links between)
PLANAR = """<robot name="planar">
  <link name="world"/>
  <link name="base"><inertial><mass value="2"/><origin xyz="0.1 0.05 0"/>
    <inertia ixx="0.1" iyy="0.2" izz="0.3" ixy="0.01" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.4 0.3 0.1"/></geometry></collision></link>
  <link name="arm"><inertial><mass value="1"/><origin xyz="0 0.2 0.05"/>
    <inertia ixx="0.01" iyy="0.02" izz="0.03" ixy="0" ixz="0" iyz="0"/></inertial></link>
  {base}
  <joint name="elbow" type="revolute"><parent link="base"/><child link="arm"/>
    <origin xyz="0.2 0 0.1"/><axis xyz="1 0 0"/>
    <limit lower="-2" upper="2" effort="10" velocity="1"/></joint>
</robot>"""
PLACED = '<origin xyz="0.1 -0.2 0.3" rpy="0.3 -0.2 0.1"/>'
PLANE = (f'<joint name="slide" type="planar"><parent link="world"/><child link="base"/>{PLACED}'
         '<axis xyz="0 0 1"/></joint>')
CHAIN = ('<link name="m1"/><link name="m2"/>'
         f'<joint name="px" type="prismatic"><parent link="world"/><child link="m1"/>{PLACED}'
         '<axis xyz="1 0 0"/><limit lower="-9" upper="9" effort="1" velocity="1"/></joint>'
         '<joint name="py" type="prismatic"><parent link="m1"/><child link="m2"/>'
         '<axis xyz="0 1 0"/><limit lower="-9" upper="9" effort="1" velocity="1"/></joint>'
         '<joint name="pyaw" type="continuous"><parent link="m2"/><child link="base"/>'
         '<axis xyz="0 0 1"/></joint>')


def test_a_planar_joint_is_its_x_y_yaw_against_a_chain_of_the_same_motion(tmp_path):
    """A planar joint was refused ('is planar, of 3 degrees of freedom'); Pinocchio models it
    (JointModelPlanar, q = x, y, cos yaw, sin yaw). Its variables are fk's, NAME.x, .y, .yaw;
    its velocity the child's twist in its own frame. Oracle: the same motion as prismatic x,
    prismatic y, revolute z, whose rates are T v (the twist's x, y turned by yaw into the
    plane's axes): M = T^T M' T, G = T^T G', tau = T^T tau' at rest, K equal."""
    (tmp_path / "plane.urdf").write_text(PLANAR.format(base=PLANE))
    (tmp_path / "chain.urdf").write_text(PLANAR.format(base=CHAIN))
    plane, chain = build(load(tmp_path / "plane.urdf")), build(load(tmp_path / "chain.urdf"))
    assert plane.joints == ["slide.x", "slide.y", "slide.yaw", "elbow"]
    assert chain.joints == ["px", "py", "pyaw", "elbow"]
    x, y, yaw, elbow = 0.4, -0.7, 2.2, 0.6
    turn = np.array([[math.cos(yaw), -math.sin(yaw)], [math.sin(yaw), math.cos(yaw)]])
    T = np.eye(4)
    T[:2, :2] = turn
    twist, accel = np.array([0.3, -0.5, 0.8, 1.1]), np.array([0.2, 0.4, -0.6, 0.9])
    mine = state(plane, dict(zip(plane.joints, (x, y, yaw, elbow))),
                 dict(zip(plane.joints, twist)), dict(zip(plane.joints, accel)))
    theirs = state(chain, dict(zip(chain.joints, (x, y, yaw, elbow))),
                   dict(zip(chain.joints, T @ twist)))
    assert np.allclose(mine.M, T.T @ theirs.M @ T, atol=1e-12)
    assert np.allclose(mine.G, T.T @ theirs.G, atol=1e-12)
    assert mine.kinetic == pytest.approx(theirs.kinetic, abs=1e-12)
    assert mine.potential == pytest.approx(theirs.potential) and mine.rnea_residual < 1e-12
    still = state(plane, dict(zip(plane.joints, (x, y, yaw, elbow))), {},
                  dict(zip(plane.joints, accel)))
    at_rest = state(chain, dict(zip(chain.joints, (x, y, yaw, elbow))), {},
                    dict(zip(chain.joints, T @ accel)))
    assert np.allclose(still.tau, T.T @ at_rest.tau, atol=1e-12)


def test_a_planar_joints_coordinates_are_held_by_the_gravity_margins(tmp_path, run_cli):
    """They have no range: drawn 1 m out and climbed to 3 m, a floating object made the arm
    carrying it "unable to hold". Held at 0 in every pose, said once; the arm's margin is over
    its own range; the planar rows are not judged (no effort limit)."""
    path = tmp_path / "plane.urdf"
    path.write_text(PLANAR.format(base=PLANE))
    result = run_cli("dynamics", path, "--samples", "20", "-f", "json")
    assert result.exit_code == 0, result.output
    loads = {load["joint"]: load for load in json.loads(result.stdout)["gravity_loads"]}
    assert [name for name, load in loads.items() if load["judged"]] == ["elbow"]
    assert all(load["worst_pose"].get(f"slide.{c}", 0.0) == 0.0
               for load in loads.values() for c in ("x", "y", "yaw"))
    assert "'slide.x', 'slide.y', 'slide.yaw' have no range (the coordinates of a planar or " \
        "floating joint): held at 0" in result.stderr
    stood = run_cli("dynamics", path, "--support", "base", "--q", "slide.yaw=0.5")
    assert stood.exit_code in (0, 1) and "Traceback" not in stood.output, stood.output
    assert "slide.yaw" in stood.stdout


def _own_free_base(text: str) -> str:
    """``text``'s robot hung from a ``world`` link by a floating joint of its own, ``free``."""
    return text.replace("</robot>", '<link name="world"/><joint name="free" type="floating">'
                                    '<parent link="world"/><child link="base"/></joint></robot>')


def test_a_robots_own_free_base_is_its_free_base(arm, tmp_path):
    """A robot hung from ``world`` by a floating joint of its own: ``floating`` uses that joint
    as the free base, named as the robot names it (it was refused, 'of 6 degrees of freedom',
    with or without --floating); M(q), G(q) and tau are those of the free flyer added to the
    robot without it; held fixed, the robot without it."""
    path = tmp_path / "own.urdf"
    path.write_text(_own_free_base(ARM))
    own = build(load(path), floating=True)
    assert own.root == "free" and own.joints == [
        "free.x", "free.y", "free.z", "free.roll", "free.pitch", "free.yaw", "shoulder", "elbow"]
    assert [v.name for v in own.variables][:6] == own.joints[:6]
    (tmp_path / "arm.urdf").write_text(ARM)
    added = build(load(tmp_path / "arm.urdf"), floating=True)
    pose = [0.3, -0.2, 1.1, 0.4, -0.3, 1.2, 0.7, -0.5]
    twist, accel = [0.5, -0.1, 0.2, 0.3, -0.6, 0.9, 1.5, -2.0], [0.1] * 8
    results = [state(model, dict(zip(model.joints, pose)), dict(zip(model.joints, twist)),
                     dict(zip(model.joints, accel))) for model in (own, added)]
    for matrix in ("M", "G", "C", "tau"):
        assert np.allclose(getattr(results[0], matrix), getattr(results[1], matrix),
                           atol=1e-12), matrix
    held, fixed = state(build(load(path)), {"elbow": 0.4}), state(arm, {"elbow": 0.4})
    assert held.joints == ["shoulder", "elbow"] and held.root is None
    assert np.allclose(held.M, fixed.M) and np.allclose(held.G, fixed.G)
    assert held.mass == pytest.approx(fixed.mass)


def test_cli_dynamics_of_a_robots_own_free_base(run_cli, tmp_path):
    path = tmp_path / "own.urdf"
    path.write_text(_own_free_base(ARM))
    result = run_cli("dynamics", path, "--floating", "--q", "free.z=2", "-f", "json")
    assert result.exit_code == 0, result.output
    data = json.loads(result.stdout)
    assert data["base"] == "floating" and data["joints"][:6] == [
        "free.x", "free.y", "free.z", "free.roll", "free.pitch", "free.yaw"]
    assert "root_joint.x" not in data["joints"] and data["com"][2] == pytest.approx(2.0)
    held = run_cli("dynamics", path, "--q", "free.z=2")  # held fixed: no coordinates to set
    assert held.exit_code == 2 and "unknown joint 'free.z'" in held.output


PASSIVE_ARM = UNLIMITED.replace(
    '<joint name="j1" type="continuous">', '<joint name="j1" type="revolute">').replace(
    '<child link="l1"/><axis xyz="0 1 0"/></joint>',
    '<child link="l1"/><axis xyz="0 1 0"/>'
    '<limit lower="-1" upper="1" effort="0" velocity="0"/></joint>')


def test_an_effort_limit_of_0_is_a_passive_joint_not_judged(run_cli, tmp_path):
    """Cassie's knee-to-shin springs are effort="0": a joint no actuator drives. Its gravity load
    is shown but not held against a limit of 0 (it made the command exit 1, 'cannot hold
    itself'); the joints with a limit are judged as before."""
    from urdftool.physics.dynamics import JointLoad, judged_effort

    (tmp_path / "arm.urdf").write_text(PASSIVE_ARM)
    result = run_cli("dynamics", tmp_path / "arm.urdf", "--samples", "10")
    assert result.exit_code == 0, result.output
    assert "ERROR" not in result.stdout
    assert re.search(r"not judged \(effort 0 in the URDF: no actuator torque declared.*\): j1$",
                     result.stdout, re.M)
    assert "every joint with an effort limit holds" in result.stdout
    data = json.loads(run_cli("dynamics", tmp_path / "arm.urdf", "--samples", "10",
                              "--format", "json").stdout)
    j1, j2 = data["gravity_loads"]
    assert (j1["effort"], j1["judged"], j1["margin"], j1["holds"]) == (0, False, None, None)
    assert j1["worst"] > 0 and (j2["judged"], j2["holds"]) == (True, True)
    assert [judged_effort(e) for e in (math.inf, 0.0, -1.0, 2.0)] == [False, False, False, True]
    assert JointLoad("j", 0.0, 5.0).holds is None


def test_a_free_base_matches_pinocchios_free_flyer(arm, tmp_path):
    """build(robot, floating=True) is Pinocchio's JointModelFreeFlyer root: M(q) (crba), the
    nonlinear effects C v + G and tau against Pinocchio called directly at a base pose given as
    x, y, z, roll, pitch, yaw (the quaternion of pinocchio.rpy) and a base twist in its frame."""
    import pinocchio as pin

    path = tmp_path / "arm.urdf"
    path.write_text(ARM)
    model = build(load(path), floating=True)
    assert model.joints == ["root_joint.x", "root_joint.y", "root_joint.z", "root_joint.roll",
                            "root_joint.pitch", "root_joint.yaw", "shoulder", "elbow"]
    pose = {"root_joint.x": 0.3, "root_joint.y": -0.2, "root_joint.z": 1.1,
            "root_joint.roll": 0.4, "root_joint.pitch": -0.3, "root_joint.yaw": 1.2,
            "shoulder": 0.7, "elbow": -0.5}
    twist = dict(zip(model.joints, [0.5, -0.1, 0.2, 0.3, -0.6, 0.9, 1.5, -2.0]))
    accel = dict(zip(model.joints, [0.1, 0.2, -0.3, 0.4, 0.5, -0.6, 0.7, 0.8]))
    result = state(model, pose, twist, accel)

    reference = pin.buildModelFromXML(ARM, pin.JointModelFreeFlyer())
    data = reference.createData()
    q = np.concatenate([[0.3, -0.2, 1.1],
                        pin.Quaternion(pin.rpy.rpyToMatrix(0.4, -0.3, 1.2)).coeffs(),
                        [0.7, -0.5]])
    v = np.array(list(twist.values()))
    a = np.array(list(accel.values()))
    crba = pin.crba(reference, data, q)
    assert np.allclose(result.M, np.triu(crba) + np.triu(crba, 1).T, atol=1e-12)
    nle = pin.nonLinearEffects(reference, data, q, v)
    assert np.allclose(result.C @ v + result.G, nle, atol=1e-10)
    assert np.allclose(result.tau, pin.rnea(reference, data, q, v, a), atol=1e-10)
    assert result.mass == pytest.approx(M1 + M2 + 3.0)
    # the weight on the base: with the base level and the arm's links too, G's z row is m g
    level = state(model, {})
    assert level.G[2] == pytest.approx((M1 + M2 + 3.0) * G0, rel=1e-3)
    assert level.potential == pytest.approx(state(build(load(path)), {}).potential)


def test_cli_floating_dynamics(run_cli, tmp_path):
    (tmp_path / "arm.urdf").write_text(ARM)
    result = run_cli("dynamics", tmp_path / "arm.urdf", "--floating", "--q", "root_joint.z=2",
                     "--v", "root_joint.yaw=1", "-f", "json")
    assert result.exit_code == 0, result.output
    data = json.loads(result.stdout)
    assert data["base"] == "floating" and data["joints"][:2] == ["root_joint.x", "root_joint.y"]
    assert data["com"][2] == pytest.approx(2.0)  # the masses sit at the base's height
    text = run_cli("dynamics", tmp_path / "arm.urdf", "--floating").stdout
    assert "in the world frame (free base)" in text and "root_joint.roll" in text
    for extra in (["--samples", "5"], ["--support", "base"]):
        refused = run_cli("dynamics", tmp_path / "arm.urdf", "--floating", *extra)
        assert refused.exit_code == 2 and "--floating does not go with" in refused.output


def test_a_limit_that_holds_times_its_transmissions_reduction_is_said(run_cli, tmp_path):
    """Cassie's hips: effort 4.5 N m behind a 25:1 transmission cannot hold 20.9 N m, but 4.5 is
    the motor's torque: the joint's is 112.5. The verdict stays (URDF's limit is the joint's),
    and the reading that would hold is said; JSON gives each joint's reduction."""
    from urdftool.physics.dynamics import reductions

    transmission = ('<transmission name="t"><type>transmission_interface/SimpleTransmission'
                    '</type><joint name="elbow"/><actuator name="m">'
                    '<mechanicalReduction>10</mechanicalReduction></actuator></transmission>')
    (tmp_path / "arm.urdf").write_text(ARM.replace("</robot>", transmission + "</robot>"))
    assert reductions(load(tmp_path / "arm.urdf")) == {"elbow": 10.0}
    result = run_cli("dynamics", tmp_path / "arm.urdf", "--samples", "10")
    assert result.exit_code == 1, result.output
    assert "effort limits that may be the motor's" in result.stdout
    assert "elbow 1 x 10 = 10 would hold 3.92" in result.stdout
    data = json.loads(run_cli("dynamics", tmp_path / "arm.urdf", "--samples", "10",
                              "-f", "json").stdout)
    assert [load["reduction"] for load in data["gravity_loads"]] == [1.0, 10.0]


def test_a_velocity_or_torque_over_a_limit_is_warned_where_the_limit_is_one(run_cli, tmp_path):
    """--v over <limit velocity>, tau (with damping, friction) over <limit effort>: a warning
    naming the joint, value and limit with units; a limit of 0 (PASSIVE_ARM's j1) is none."""
    (tmp_path / "arm.urdf").write_text(ARM)
    result = run_cli("dynamics", tmp_path / "arm.urdf", "--v", "shoulder=2", "--v", "elbow=0.5")
    assert result.exit_code == 0
    assert ("urdftool: warning: joint 'shoulder': velocity 2 rad/s is over its <limit velocity> "
            "of 1 rad/s") in result.stderr
    assert "joint 'elbow': torque 3.924 N m is over its <limit effort> of 1 N m" in result.stderr
    assert "'elbow': velocity" not in result.stderr
    (tmp_path / "passive.urdf").write_text(PASSIVE_ARM)
    quiet = run_cli("dynamics", tmp_path / "passive.urdf", "--v", "j1=9", "--a", "j1=90")
    assert "over its" not in quiet.stderr, quiet.stderr


@pytest.mark.parametrize("inertial, said", [
    ('<mass value="1e308"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>',
     "link 'b': <inertial><mass> 1e+308 kg is past the 1e+30 kg"),
    ('<mass value="1"/><inertia ixx="1e308" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>',
     "link 'b': <inertial><inertia ixx> 1e+308 kg m^2 is past"),
])
def test_an_inertial_past_the_mass_bounds_is_refused_not_an_energy_of_inf(tmp_path, inertial,
                                                                          said):
    """attack25: a mass of 1e308 printed "P = inf J, L = -inf J" (JSON: null, silently); the
    bounds of physics.mass refuse it where the model is built."""
    from conftest import load_text
    from urdftool.errors import DynamicsError

    robot = load_text(tmp_path, '<robot name="r"><link name="a"/><joint name="j" '
                      'type="revolute"><parent link="a"/><child link="b"/><origin xyz="0 0 1"/>'
                      '<axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/>'
                      f'</joint><link name="b"><inertial>{inertial}</inertial></link></robot>')
    with pytest.raises(DynamicsError, match=re.escape(said)):
        build(robot)


def test_a_derived_quantity_past_the_float_range_is_refused_by_name(tmp_path, run_cli):
    """attack25: velocities (each within numbers.SQUARABLE) on a heavy link gave "K = inf J"
    and "L = inf J" in text, null in JSON; the state refuses what overflowed, by its name,
    and the command says it is the values given (exit 2), without numpy's warnings."""
    robot = tmp_path / "r.urdf"
    robot.write_text('<robot name="r"><link name="a"/><joint name="j" type="revolute">'
                     '<parent link="a"/><child link="b"/><origin xyz="0 0 1"/><axis xyz="0 1 0"/>'
                     '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint><link name="b">'
                     '<inertial><origin xyz="1 0 0"/><mass value="1e29"/><inertia ixx="1" '
                     'ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link></robot>')
    for words in ((), ("-f", "json")):
        result = run_cli("dynamics", robot, "--v", "j=1e150", *words)
        assert result.exit_code == 2, result.output
        assert "the kinetic energy K is past what a float holds" in result.output
        assert "inf" not in result.output.replace("info", "") and "RuntimeWarning" not in \
            result.output
    assert run_cli("dynamics", robot, "--v", "j=1").exit_code == 0


def test_a_negative_total_mass_is_said_as_negative_not_as_no_mass(tmp_path, run_cli):
    """attack25: a robot whose one link declares -1 kg was warned "no link has a mass (every
    <inertial> is missing or of mass 0)"."""
    robot = tmp_path / "r.urdf"
    robot.write_text('<robot name="r"><link name="a"/><joint name="j" type="revolute">'
                     '<parent link="a"/><child link="b"/><origin xyz="0 0 1"/><axis xyz="0 1 0"/>'
                     '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint><link name="b">'
                     '<inertial><mass value="-1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" '
                     'iyz="0" izz="1"/></inertial></link></robot>')
    result = run_cli("dynamics", robot)
    assert "the robot's mass is negative (-1 kg)" in result.output, result.output
    assert "missing or of mass 0" not in result.output


def test_rows_over_the_limit_are_refused_before_the_model_is_built(tmp_path, monkeypatch):
    """attack25: a 10,000-link chain ran out of the 2 GiB memory budget (U018, 23 s) building
    the Pinocchio model that state() then refused for its rows; build counts them from the
    text first (a mimic joint's velocity is one of the model's)."""
    from conftest import load_text
    from urdftool.errors import OverLimit
    from urdftool.kinematics import native

    joints = "".join(
        f'<joint name="j{i}" type="revolute"><parent link="l{i}"/><child link="l{i + 1}"/>'
        '<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/>'
        + ('<mimic joint="j0"/>' if i == 5 else "") + f'</joint><link name="l{i + 1}"/>'
        for i in range(12))
    robot = load_text(tmp_path, f'<robot name="r"><link name="l0"/>{joints}</robot>')
    monkeypatch.setattr(native, "build_model", lambda *a: pytest.fail("built"))
    with pytest.raises(OverLimit, match="12 rows, over the limit of 11"):
        build(robot, max_rows=11)
    monkeypatch.undo()
    assert len(build(robot, max_rows=12).joints) == 12


def test_the_q_help_names_the_coordinates_dynamics_takes(tmp_path, run_cli):
    """``dynamics --help`` said "Joint position (repeatable)" alone: how a planar joint's and a
    floating joint's values are given was in the docs only. Each name the help gives is taken
    (and moves the robot: P changes)."""
    from urdftool.kinematics.configuration import FLOATING_COORDINATES, PLANAR_COORDINATES

    said = " ".join(run_cli("dynamics", "--help").stdout.split())
    assert "A planar joint is three: JOINT.x, JOINT.y [m]" in said and "JOINT.yaw" in said
    assert "floating joint (and --floating's root_joint) six: JOINT.x, .y, .z [m] and " \
        ".roll, .pitch, .yaw [rad]" in said
    assert PLANAR_COORDINATES == ("x", "y", "yaw")
    assert FLOATING_COORDINATES == ("x", "y", "z", "roll", "pitch", "yaw")
    path = tmp_path / "plane.urdf"
    path.write_text(PLANAR.format(base=PLANE))
    for coordinate in PLANAR_COORDINATES:
        result = run_cli("dynamics", path, "--q", f"slide.{coordinate}=0.5", "-f", "json")
        assert result.exit_code == 0, result.output
        assert json.loads(result.stdout)["q"] == {f"slide.{coordinate}": 0.5}
    for coordinate in FLOATING_COORDINATES:
        result = run_cli("dynamics", path, "--floating", "--q", f"root_joint.{coordinate}=0.5",
                         "-f", "json")
        assert result.exit_code == 0, result.output


@pytest.mark.parametrize("floating", [False, True])
def test_the_total_mass_counts_the_root_link_that_pinocchios_leaves_out(floating):
    """urdftool's total mass and centre of mass count every link; Pinocchio's computeTotalMass
    and centerOfMass leave out the body fixed to the universe (the root link and the links
    fixed to it: the humanoid's 0.95 kg). Both ways: ours is Pinocchio's plus ``fixed_mass``
    (its centre of mass weighted in), and with a free base, where nothing is fixed to the
    universe, the two are equal and ``fixed_mass`` is 0."""
    import pinocchio as pin

    humanoid = load(str(ROBOTS / "humanoid" / "humanoid.urdf.xacro"))
    model = build(humanoid, floating=floating)
    joints = [name for name in model.joints if not name.startswith("root_joint.")]
    values = dict(zip(joints, np.linspace(-0.4, 0.4, len(joints))))
    if floating:
        values.update({"root_joint.z": 0.3, "root_joint.yaw": 0.5})
    result = state(model, values)
    q = model.configuration(values)
    m, d = model.model, model.model.createData()
    theirs = pin.computeTotalMass(m)
    com = pin.centerOfMass(m, d, q)
    fixed = m.inertias[0]
    assert result.fixed_mass == pytest.approx(0.0 if floating else 0.95)
    assert result.mass == pytest.approx(theirs + result.fixed_mass)
    expected = (theirs * com + result.fixed_mass * fixed.lever) / result.mass
    assert np.allclose(result.com, expected, atol=1e-12)
    if floating:
        assert np.allclose(result.com, com, atol=1e-12)
    assert json.loads(json.dumps(result.as_dict()))["fixed_mass"] == result.fixed_mass
