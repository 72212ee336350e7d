"""Rigid-body dynamics of a robot with a fixed base, or with a free-flying one, through Pinocchio.

Joint values are by joint name: angles in [rad], travel in [m]; velocities in [rad/s] or [m/s];
accelerations in [rad/s^2] or [m/s^2]; torques in [N m] or forces in [N]. Continuous joints,
which Pinocchio stores as (cos, sin), take one angle here like any revolute joint.

A free-flying base (``build(robot, floating=True)``: Pinocchio's ``JointModelFreeFlyer`` as the
root joint ``root_joint``, as ``fk --floating``) is six variables, named as fk names them:
``root_joint.x``, ``.y``, ``.z`` [m] and ``.roll``, ``.pitch``, ``.yaw`` [rad] place the root
link in the world (roll, pitch, yaw about the fixed x, y, z axes, as URDF's ``rpy``). Its
velocity and acceleration are Pinocchio's: the root link's twist in its own frame, linear
(``.x``, ``.y``, ``.z`` [m/s]) then angular (``.roll``, ``.pitch``, ``.yaw``: about its own x, y,
z axes [rad/s], not rates of the angles); its rows of M(q), G(q), C(q, v) and tau are that
frame's force [N] and moment [N m] on the base: what a floating robot's contacts must supply.

A joint of several variables in the robot (``planar``; ``floating`` below a root with a mass)
is modelled as Pinocchio reads it (``JointModelPlanar``, ``JointModelFreeFlyer``) and named as
fk names it: a planar joint's ``NAME.x``, ``.y`` [m] in its frame's xy plane and ``.yaw``
[rad] about its z (Pinocchio's q: x, y, cos yaw, sin yaw); its velocity and acceleration are
Pinocchio's, the twist of its child in the child's own frame (``.x``, ``.y`` [m/s] along the
child's axes, ``.yaw`` [rad/s]), and its rows are the force [N] and moment [N m] on it, with no
effort limit to judge.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from urdftool.description.urdf import DEGREES
from urdftool.errors import DynamicsError
from urdftool.kinematics.configuration import FLOATING_COORDINATES
from urdftool.kinematics.model import oversized_data

_ROUND_OFF = 1e-12  # [N m] or [N]: gravity torques below this are floating-point noise


@dataclass
class Model:
    """Pinocchio model and data, and the actuated joints in velocity order."""

    model: object
    data: object
    joints: list[str]  # one per velocity variable (1-dof joints; a free root's six first)
    variables: list = field(default_factory=list)  # the settable ones: mimic joints follow
    mimics: dict = field(default_factory=dict)  # joint -> (variable, multiplier, offset)
    root: str | None = None  # the free-flyer root joint's name, or None for a fixed base
    reductions: dict = field(default_factory=dict)  # joint -> its transmission's reduction
    # the joints of several variables (the free root, planar and floating joints): joint ->
    # its coordinate names, in Pinocchio's order of its velocity
    multiple: dict = field(default_factory=dict)

    def coordinate(self, name: str) -> tuple[str, int] | None:
        """(joint, index in its velocity) of a row name of a joint of several variables
        (``slide.yaw``: ('slide', 2)), or None for a joint of one."""
        joint, dot, coordinate = name.rpartition(".")
        names = self.multiple.get(joint) if dot else None
        return (joint, names.index(coordinate)) if names and coordinate in names else None

    def row(self, name: str) -> int:
        """The velocity index (row of M(q), G(q), tau) of ``name``, a joint of one variable or
        a coordinate of one of several (``slide.x``)."""
        found = self.coordinate(name)
        if found is not None:
            return self.model.joints[self._joint_id(found[0])].idx_v + found[1]
        return self.model.joints[self._joint_id(name)].idx_v

    def linear(self, name: str) -> bool:
        """Whether ``name``'s row is a travel [m] (a force [N]), not an angle (a moment)."""
        found = self.coordinate(name)
        if found is not None:
            return name.rpartition(".")[2] in ("x", "y", "z")
        return self.model.joints[self._joint_id(name)].shortname().startswith("JointModelP")

    def _expanded(self, values: dict[str, float], offsets: bool) -> dict[str, float]:
        """Variable values plus every mimic joint's (unnamed variables count as 0)."""
        full = dict(values)
        for joint, (variable, multiplier, offset) in self.mimics.items():
            full[joint] = multiplier * values.get(variable, 0.0) + (offset if offsets else 0.0)
        return full

    def _joint_id(self, name: str) -> int:
        """The model's index of joint ``name``; DynamicsError for a name it does not have (Pinocchio
        answers njoints, one past the last, and the caller's lookup was an IndexError: the
        command line checks names first, :func:`joint_values`, a script calling the API did not)."""
        joint_id = self.model.getJointId(name)
        if not 0 < joint_id < self.model.njoints:
            raise DynamicsError(f"'{name}' is not a joint of the model "
                                f"({', '.join(self.model.names[1:]) or 'no joints'})")
        return joint_id

    def configuration(self, values: dict[str, float]) -> np.ndarray:
        """Pinocchio's q for variable values by name; mimic joints follow their variable."""
        import pinocchio as pin

        q = pin.neutral(self.model)
        for name, coordinates in self.multiple.items():
            start = self.model.joints[self._joint_id(name)].idx_q
            block = coordinates_q([values.get(f"{name}.{c}", 0.0) for c in coordinates])
            q[start:start + len(block)] = block
        for name, value in self._expanded(values, offsets=True).items():
            if self.coordinate(name) is not None:
                continue
            joint = self.model.joints[self._joint_id(name)]
            if joint.nq == 2:  # continuous: (cos, sin)
                q[joint.idx_q:joint.idx_q + 2] = (math.cos(value), math.sin(value))
            else:
                q[joint.idx_q] = value
        return q

    def velocity(self, values: dict[str, float]) -> np.ndarray:
        """Pinocchio's v (or a) by name; a mimic joint moves at multiplier times its variable."""
        v = np.zeros(self.model.nv)
        for name, value in self._expanded(values, offsets=False).items():
            v[self.row(name)] = value  # a coordinate of a joint of several: its twist's
        return v


def coordinates_q(pose) -> np.ndarray:
    """Pinocchio's q of a joint of several variables from its coordinates' values: a planar
    joint's (x, y, yaw) as (x, y, cos yaw, sin yaw); a free flyer's (x, y, z, roll, pitch, yaw)
    as its position and the quaternion (x, y, z, w) of roll, pitch, yaw."""
    import pinocchio as pin

    if len(pose) == 3:
        return np.array([pose[0], pose[1], math.cos(pose[2]), math.sin(pose[2])])
    return np.concatenate([pose[:3], pin.Quaternion(pin.rpy.rpyToMatrix(*pose[3:])).coeffs()])


def build(robot, floating: bool = False, max_rows: int | None = None) -> Model:
    """A Pinocchio model of the robot (planar and floating joints as its coordinates), its base
    fixed, or with ``floating`` free: a free-flyer root joint ``root_joint`` (as ``fk
    --floating``), whose six velocity variables come first. A robot with its own free base
    (:func:`urdftool.kinematics.tree.own_free_base`) has that joint as its free root, named
    as it is, and no second; fixed, it is held where its origin puts the base (Pinocchio's
    reduced model). OverLimit, before Pinocchio builds anything, when the model's joint
    velocities (the rows of M(q)) are over ``max_rows`` (None: no limit): a 10,000-link chain
    ran out of the 2 GiB memory budget building the model that :func:`state` then refused."""
    import pinocchio as pin

    from urdftool.errors import FKError
    from urdftool.kinematics.configuration import (PLANAR_COORDINATES, MimicError, mimic_source,
                                                   mimics_of, variables_of)
    from urdftool.kinematics.fk import FLOATING_ROOT, placed_within
    from urdftool.kinematics.native import build_model
    from urdftool.kinematics.tree import own_free_base

    try:  # (a joint's origin at 1e200: torques of NaN)
        placed_within(robot)
    except FKError as error:
        raise DynamicsError(str(error), error.element) from None
    _inertials_within(robot)
    own = own_free_base(robot)
    if max_rows is not None:
        rows = _velocity_rows(robot) + (6 if floating and not own else 0) \
            - (6 if own and not floating else 0)
        if rows > max_rows:
            from urdftool.errors import OverLimit

            raise OverLimit("M(q) and C(q, v) of the robot's joint velocities", rows, max_rows,
                            "rows")
    root = (own or FLOATING_ROOT) if floating else None
    model = build_model(robot, *((pin.JointModelFreeFlyer(), root) if floating and not own
                                 else ()))
    if own and not floating:  # its free flyer locked at the neutral pose: a fixed base
        model = pin.buildReducedModel(model, [model.getJointId(own)], pin.neutral(model))
    joints = [f"{root}.{c}" for c in FLOATING_COORDINATES] if floating else []
    multiple = {root: FLOATING_COORDINATES} if floating else {}
    for joint_id in range(2 if floating else 1, model.njoints):
        axis = getattr(model.joints[joint_id].extract(), "axis", None)  # unaligned joints
        if axis is not None and not abs(np.linalg.norm(axis) - 1) <= 1e-6:
            raise DynamicsError(_axis_problem(robot.joints.get(model.names[joint_id]),
                                              model.names[joint_id], axis),
                                robot.joints.get(model.names[joint_id]))
        name = model.names[joint_id]
        coordinates = {3: PLANAR_COORDINATES, 6: FLOATING_COORDINATES}.get(
            model.joints[joint_id].nv)
        if coordinates is not None:  # planar, floating: rows named as fk names them
            multiple[name] = coordinates
            joints += [f"{name}.{c}" for c in coordinates]
        elif model.joints[joint_id].nv != 1:  # (Pinocchio reads no other from a URDF)
            element = robot.joints.get(name)
            raise DynamicsError(f"joint '{name}' has {model.joints[joint_id].nv} degrees of "
                                "freedom, which dynamics does not name", element)
        else:
            joints.append(name)
    variables = variables_of(robot, None if own else root)
    if own:  # its coordinates first when free, none when held
        variables = [v for v in variables if v.joint == own and floating] + \
            [v for v in variables if v.joint != own]
    names = {variable.name for variable in variables}
    try:
        known: dict = {}  # each joint's source found once along a chain of mimics
        mimics = {joint: mimic_source(robot, joint, names, known=known)
                  for joint in mimics_of(robot) if joint in joints}
    except MimicError as error:
        raise DynamicsError(str(error), error.element) from None
    oversized = oversized_data(model.nv, "")
    if oversized:  # (the question's, as --max-matrix-rows: a size limit before the work)
        raise DynamicsError(oversized, robot.root, asked=True)
    return Model(model, model.createData(), joints, variables, mimics, root, reductions(robot),
                 multiple)


def reductions(robot) -> dict[str, float]:
    """Joint -> the ``<mechanicalReduction>`` of the transmission that drives it, where it is
    a number other than 1 (in the transmission, its joint or its actuator, as ROS 1 and ROS 2
    transmissions write it). URDF's ``<limit effort>`` is the joint's; ros_control's
    SimpleTransmission gives the joint the actuator's effort times the reduction, so a limit
    written for the motor (Cassie: 4.5 N m at 25:1) is the reduction times too small."""
    from urdftool.description.actuation import transmission_joints, transmissions
    from urdftool.description.values import parse_numbers

    found = {}
    for transmission in transmissions(robot):
        texts = [e.text for e in transmission.iter("mechanicalReduction")]
        values, _ = parse_numbers((texts[0] or "").strip(), 1) if texts else (None, None)
        if not values or not math.isfinite(values[0]) or values[0] in (0.0, 1.0):
            continue
        for joint in transmission_joints(robot, transmission):
            if joint.name:
                found[joint.name] = abs(values[0])
    return found


def total_mass(model: Model) -> float:
    """Sum of every link's mass, including links fixed to the root (Pinocchio keeps them in
    ``inertias[0]``, which ``computeTotalMass`` leaves out)."""
    return float(sum(inertia.mass for inertia in model.model.inertias))


def fixed_mass(model: Model) -> float:
    """The mass [kg] of :func:`total_mass` that no joint moves: the root link's and the links
    fixed to it (Pinocchio's ``inertias[0]``, the universe's body; 0 with a free base, whose
    root link rides the free flyer). urdftool counts it in the total and the centre of mass, as
    the robot weighs it; Pinocchio's ``computeTotalMass`` and ``centerOfMass`` leave it out
    (a fixed base carries it): the two differ by it, said so."""
    return float(model.model.inertias[0].mass)


def centre_of_mass(model: Model, q: np.ndarray) -> np.ndarray:
    """Whole-body centre of mass [m] in the root frame, counting the root's own inertia."""
    import pinocchio as pin

    pin.forwardKinematics(model.model, model.data, q)
    weighted, mass = np.zeros(3), 0.0
    for joint_id, inertia in enumerate(model.model.inertias):
        placement = model.data.oMi[joint_id]
        weighted += inertia.mass * (placement.act(inertia.lever))
        mass += inertia.mass
    return weighted / mass if mass > 0 else np.zeros(3)


@dataclass
class State:
    """Dynamics at one state: M(q), G(q), and with v, a also C(q, v) and tau."""

    joints: list[str]
    q: dict
    mass: float
    com: np.ndarray  # [m] in the root link's frame, or with a free root the world's
    M: np.ndarray
    G: np.ndarray
    C: np.ndarray | None = None
    tau: np.ndarray | None = None
    rnea_residual: float | None = None
    kinetic: float = 0.0  # K = v^T M v / 2 [J]
    potential: float = 0.0  # P = m g z of the centre of mass, root frame [J]
    damping: np.ndarray | None = None  # <dynamics damping> * v [N m or N]
    friction: np.ndarray | None = None  # <dynamics friction> * sign(v)
    warnings: list[str] = field(default_factory=list)  # not in as_dict: the CLI prints them
    root: str | None = None  # the free-flyer root joint, None for a fixed base
    mimics: dict = field(default_factory=dict)  # joint -> (variable, multiplier, offset)
    fixed_mass: float = 0.0  # [kg] of ``mass``: the root link's and the links fixed to it

    @property
    def lagrangian(self) -> float:
        """L = K - P [J]."""
        return self.kinetic - self.potential

    @property
    def total(self) -> np.ndarray | None:
        """tau with the joints' damping and friction: what the actuators supply [N m or N]."""
        return None if self.tau is None else self.tau + self.damping + self.friction

    def as_dict(self) -> dict:
        def listed(a):
            return None if a is None else np.asarray(a).tolist()

        return {"joints": self.joints, "q": self.q, "base": "floating" if self.root else "fixed",
                "total_mass": self.mass, "fixed_mass": self.fixed_mass,
                "com": listed(self.com), "M": listed(self.M), "G": listed(self.G),
                "C": listed(self.C), "tau": listed(self.tau),
                "rnea_residual": self.rnea_residual, "kinetic_energy": self.kinetic,
                "potential_energy": self.potential, "lagrangian": self.lagrangian,
                "damping_torque": listed(self.damping), "friction_torque": listed(self.friction),
                "tau_total": listed(self.total), "mimic_leaders": self.leaders()}

    def leaders(self) -> dict:
        """For each joint that mimic joints follow: its followers with their multipliers, and
        G and tau (with damping and friction) as one actuator driving them all supplies them,
        J^T of the per-joint columns (the leader's plus each follower's times its multiplier:
        the power v^T tau is the same) [N m or N]: Pinocchio's model of a URDF read with its
        mimic joints (``mimic=True``) has these as its G and rnea."""
        found: dict = {}
        index = {name: i for i, name in enumerate(self.joints)}
        for joint, (leader, multiplier, _) in self.mimics.items():
            if joint in index and leader in index:
                found.setdefault(leader, {})[joint] = multiplier

        def reduced(column):
            return {leader: float(column[index[leader]] + sum(
                m * column[index[j]] for j, m in followers.items()))
                for leader, followers in found.items()}
        G = reduced(self.G)
        tau = reduced(self.total) if self.tau is not None else {}
        return {leader: {"followers": followers, "G": G[leader], "tau": tau.get(leader)}
                for leader, followers in found.items()}


MAX_MATRIX_SIZE = 1000  # rows of M(q): 8 MB each matrix, 11 MB of text; 10,000 were 0.8 GB


def state(model: Model, q_values: dict, v_values: dict | None = None,
          a_values: dict | None = None, max_rows: int | None = MAX_MATRIX_SIZE) -> State:
    """M(q) (crba), G(q) (computeGeneralizedGravity), the energies K = v^T M v / 2 and
    P = m g z_com (the fixed root's own mass included, so P is the whole robot's), and, given v
    or a, C(q, v) and tau = M a + C v + G, checked against rnea (``rnea_residual``, max abs
    difference), and the URDF's ``<dynamics damping friction>`` torques ``damping v`` and
    ``friction sign(v)`` that the actuators supply on top (Pinocchio's rnea has neither); a
    robot without mass gets a warning. OverLimit, before any is computed, when M(q) and
    C(q, v) would be over ``max_rows`` rows (None: no limit; their memory and text grow with the
    square)."""
    import pinocchio as pin

    from urdftool.errors import OverLimit

    m, d = model.model, model.data
    if max_rows is not None and m.nv > max_rows:
        raise OverLimit("M(q) and C(q, v) of the robot's joint velocities", m.nv, max_rows,
                        "rows")
    q = model.configuration(q_values)
    with np.errstate(all="ignore"):  # (what overflows is refused below, by its name)
        result = _computed(model, q, q_values, v_values, a_values)
    overflowed = _overflowed(result)
    if overflowed:
        from urdftool.errors import DynamicsError

        raise DynamicsError(f"{overflowed} is past what a float holds (the joint velocities or "
                            "accelerations given, times the robot's masses and lengths): "
                            "nothing to print; give smaller values")
    return result


def _computed(model: Model, q: np.ndarray, q_values: dict, v_values: dict | None,
              a_values: dict | None) -> State:
    """:func:`state`'s quantities, as computed."""
    import pinocchio as pin

    m, d = model.model, model.data
    mass_matrix = pin.crba(m, d, q)
    mass_matrix = np.triu(mass_matrix) + np.triu(mass_matrix, 1).T
    gravity = pin.computeGeneralizedGravity(m, d, q).copy()
    result = State(model.joints, dict(q_values), total_mass(model), centre_of_mass(model, q),
                   mass_matrix.copy(), gravity, root=model.root, mimics=model.mimics,
                   fixed_mass=fixed_mass(model))
    result.warnings.extend(singular(model, mass_matrix, result.mass))
    if v_values is not None or a_values is not None:
        v = model.velocity(v_values or {})
        a = model.velocity(a_values or {})
        coriolis = pin.computeCoriolisMatrix(m, d, q, v).copy()
        tau = mass_matrix @ a + coriolis @ v + gravity
        result.C, result.tau = coriolis, tau
        result.rnea_residual = float(np.max(np.abs(pin.rnea(m, d, q, v, a) - tau), initial=0.0))
        result.kinetic = float(0.5 * v @ mass_matrix @ v)
        result.damping = np.asarray(m.damping) * v
        result.friction = np.asarray(m.friction) * np.sign(v) + 0.0  # no -0
        result.warnings.extend(over_limits(model, v, result.total))
    result.potential = float(result.mass * -m.gravity.linear @ result.com)
    return result


def _velocity_rows(robot) -> int:
    """The joint velocities Pinocchio's model of the robot has, read from the text: each
    joint's, a mimic joint's too (the model keeps it, its leader's multiple)."""
    return sum(DEGREES.get(joint.get("type"), 0) for joint in robot.joints.values())


def _inertials_within(robot) -> None:
    """DynamicsError for the first link whose inertial is past the bounds of
    :func:`urdftool.physics.mass.problem` (an ``<inertial><origin>`` at 1e200 gave torques of
    NaN and "M(q) is singular", a mass of 1e308 "P = inf J"); Pinocchio reads it as written."""
    from urdftool.physics.mass import problem_at

    for name, link in robot.links.items():
        found = problem_at(link)  # (not finite, or not a number: urdfdom refuses)
        if found:
            raise DynamicsError(f"link '{name}': <inertial>{found[1]}",
                                link.find(f"inertial/{found[0]}"))


def _overflowed(result: State) -> str | None:
    """The first of a state's derived quantities that is not finite, by its name, or None:
    velocities and accelerations are bounded by ``numbers.SQUARABLE`` and the inertials by
    :mod:`urdftool.physics.mass`'s bounds, each alone, but a velocity of 1e150 on a link of
    1e29 kg gave "K = inf J" (and JSON's null, silently)."""
    for name, value in (("the total mass", result.mass), ("the centre of mass", result.com),
                        ("M(q)", result.M), ("G(q)", result.G), ("C(q, v)", result.C),
                        ("tau", result.tau), ("the damping torque", result.damping),
                        ("the friction torque", result.friction),
                        ("the kinetic energy K", result.kinetic),
                        ("the potential energy P", result.potential),
                        ("L = K - P", result.lagrangian),
                        ("tau with damping and friction", result.total)):
        if value is not None and not np.all(np.isfinite(value)):
            return name
    return None


def over_limits(model: Model, v: np.ndarray, total: np.ndarray) -> list[str]:
    """Joints given a velocity over their ``<limit velocity>``, or needing a torque (tau with
    damping and friction) over their ``<limit effort>``, in words; only where the limit is one
    to judge against (:func:`judged_effort`: finite and above 0: a limit of 0 is no limit
    declared, Cassie's springs, an exporter's "unknown")."""
    from urdftool.numbers import number

    m, said = model.model, []
    for row, name in enumerate(model.joints):
        if model.coordinate(name) is not None:  # a free root's or planar joint's: no limits
            continue
        linear = model.linear(name)
        for kind, value, limit, unit in (
                ("velocity", v[row], m.velocityLimit[row], "m/s" if linear else "rad/s"),
                ("torque", total[row], m.effortLimit[row], "N" if linear else "N m")):
            if judged_effort(float(limit)) and abs(value) > limit:
                said.append(f"joint '{name}': {kind} {number(abs(value))} {unit} is over its "
                            f"<limit {'effort' if kind == 'torque' else kind}> of "
                            f"{number(limit)} {unit}")
    return said


def singular(model: Model, mass_matrix: np.ndarray, mass: float) -> list[str]:
    """What makes ``mass_matrix`` (M(q)) singular, in words, or nothing: no link with a mass
    (every ``<inertial>`` missing or of mass 0), or joints that move no mass or inertia (their
    rows are zero: M(q)^-1, forward dynamics, does not exist), or rows that depend on each
    other (joints moving the same body the same way). M(q) is symmetric positive semidefinite:
    a joint's row is zero exactly when its diagonal entry is, and its rank is that of its
    eigenvalues above round-off."""
    if mass < 0:  # (a link of mass -1 was "every <inertial> is missing or of mass 0")
        from urdftool.numbers import number

        return [f"the robot's mass is negative ({number(mass)} kg): a link declares a negative "
                "mass, and M(q), G(q) and the energies mean nothing; 'urdftool check' says "
                "which"]
    if mass <= 0:
        return ["no link has a mass (every <inertial> is missing or of mass 0): M(q) and every "
                "gravity torque are zero; check the description (xacro arguments?) with "
                "'urdftool check'"]
    size = len(mass_matrix)
    if not size:
        return []
    diagonal = np.abs(np.diag(mass_matrix))
    floor = float(diagonal.max()) * size * np.finfo(float).eps
    still = [name for name, entry in zip(model.joints, diagonal) if entry <= floor]
    if still:
        return [f"M(q) is singular: {_listed(still)} move{'s' if len(still) == 1 else ''} no "
                "mass or inertia at this configuration (a zero row of M(q)), so forward "
                "dynamics (M(q)^-1) does not exist; give the links "
                f"{'it carries' if len(still) == 1 else 'they carry'} an <inertial>"]
    values = np.linalg.eigvalsh(mass_matrix)
    rank = int((values > float(np.abs(values).max()) * size * np.finfo(float).eps).sum())
    if rank < size:
        return [f"M(q) is singular: rank {rank} of {size} (joints moving the same mass the "
                "same way at this configuration), so forward dynamics (M(q)^-1) does not exist"]
    return []


def _listed(names: list[str]) -> str:
    from urdftool.errors import shown_word

    shown = ", ".join(shown_word(name) for name in names[:12])
    return ("joint " if len(names) == 1 else "joints ") + shown + (
        f" and {len(names) - 12} more" if len(names) > 12 else "")


def judged_effort(effort: float) -> bool:
    """Whether an effort limit [N m or N] is one a torque can be judged against: finite and
    above 0. ``inf`` is no ``<limit effort>`` (a continuous joint without ``<limit>``); 0 (or
    below) is no actuator torque declared: a passive joint (Cassie's knee-to-shin springs), a
    spring, a mimic, or the ROS-Industrial exporters' "unknown" (Fanuc, Motoman). Pinocchio
    reads 0 as ``effortLimit`` 0, Gazebo and PyBullet clamp a commanded force to it (the joint
    gets none), MuJoCo's URDF import ignores it: gravity on such a joint is carried by the
    structure or a spring, never by a motor of 0, so it has no margin."""
    return math.isfinite(effort) and effort > 0


@dataclass
class JointLoad:
    """Worst static gravity torque of one joint over the sampled poses, against its limit.

    A joint without a usable effort limit (:func:`judged_effort`: ``effort`` inf, no ``<limit
    effort>``; or 0, a passive joint) has no margin (None) and is not judged (``holds``
    None)."""

    joint: str
    effort: float
    worst: float  # [N m] or [N], absolute: over the ranges when refined, else the samples'
    worst_pose: dict = field(default_factory=dict)
    zero_pose: float = 0.0
    sampled: float | None = None  # the worst of the samples, when ``worst`` was refined
    evaluations: int = 0  # of G(q) while refining
    reduction: float = 1.0  # of the transmission driving the joint (:func:`reductions`)
    # a mimic joint: the joint it follows, whose actuator drives it and carries its load (its
    # ``worst`` is its own torque, not judged); a joint mimic joints follow: them, with their
    # multipliers (its ``worst`` is its actuator's: its own torque plus theirs, J^T)
    driven_by: str | None = None
    followers: dict = field(default_factory=dict)

    @property
    def held_at_the_motor(self) -> bool:
        """It cannot hold with its effort limit, but could with that limit times its
        transmission's reduction: the limit may be the motor's, not the joint's."""
        return self.holds is False and self.reduction > 1 and \
            self.worst <= self.effort * self.reduction

    @property
    def limited(self) -> bool:
        """Judged against its effort limit: a usable one, and no mimic joint (its leader's
        actuator holds it, and is judged with its load)."""
        return judged_effort(self.effort) and self.driven_by is None

    @property
    def passive(self) -> bool:
        """``<limit effort="0">`` (or below): no actuator torque declared."""
        return self.effort <= 0 and self.driven_by is None

    @property
    def margin(self) -> float | None:
        return self.effort - self.worst if self.limited else None

    @property
    def holds(self) -> bool | None:
        return self.worst <= self.effort if self.limited else None

    def as_dict(self) -> dict:
        return {"joint": self.joint, "effort": None if math.isinf(self.effort) else self.effort,
                "judged": self.limited,
                "worst": self.worst, "sampled_worst": self.sampled,
                "margin": self.margin, "holds": self.holds, "reduction": self.reduction,
                "zero_pose": self.zero_pose,
                "worst_pose": self.worst_pose, "driven_by": self.driven_by,
                "followers": self.followers}


def gravity_variables(model: Model, joint: str) -> set[str]:
    """The variables that can change ``joint``'s gravity torque: those of the joints that carry
    it (they turn gravity relative to its axis) and of the joints it carries (they move its
    load). Joints on other branches cannot."""
    m = model.model
    joint_id = m.getJointId((model.coordinate(joint) or (joint,))[0])
    ids = set(m.supports[joint_id]) | set(m.subtrees[joint_id])
    names = {m.names[i] for i in ids}
    names |= {f"{name}.{c}" for name in names for c in model.multiple.get(name, ())}
    for follower in followers_of(model).get(joint, {}):  # its actuator carries theirs too
        follower_id = m.getJointId(follower)
        names |= {m.names[i] for i in (*m.supports[follower_id], *m.subtrees[follower_id])}
    variables = {variable.name for variable in model.variables}
    return {model.mimics.get(name, (name,))[0] for name in names} & variables


def held_coordinates(model: Model) -> list[int]:
    """The columns of ``model.variables`` that gravity margins hold at their default: the
    coordinates of joints of several variables (planar, floating), which have no range (a
    floating object's position drawn 1 m or 3 m out made any arm carrying it "unable to
    hold"); the margins are over the ranges of the joints that have one."""
    return [k for k, variable in enumerate(model.variables)
            if model.coordinate(variable.name) is not None]


def followers_of(model: Model) -> dict:
    """joint -> {mimic joint that follows it: multiplier}, for the joints of ``model.joints``
    whose actuator drives mimic joints (a follower's leader is the variable it follows in the
    end, through a chain of mimics)."""
    joints = set(model.joints)
    found: dict = {}
    for joint, (leader, multiplier, _) in model.mimics.items():
        if joint in joints and leader in joints and joint != leader:
            found.setdefault(leader, {})[joint] = float(multiplier)
    return found


def actuated(model: Model, torques: np.ndarray) -> np.ndarray:
    """``torques`` (per joint, ``model.joints`` order; or [poses, joints]) as the actuators
    supply them: a joint that mimic joints follow supplies its own plus each follower's times
    its multiplier (J^T: the power is the same); a follower's own torque is kept, for showing."""
    result = np.array(torques, dtype=float, copy=True)
    index = {name: i for i, name in enumerate(model.joints)}
    for leader, followers in followers_of(model).items():
        for follower, multiplier in followers.items():
            result[..., index[leader]] += multiplier * np.asarray(torques)[..., index[follower]]
    return result


def gravity_loads(model: Model, samples: int, seed: int = 0, torques=None,
                  progress=None) -> list[JointLoad]:
    """Per joint, the largest |G(q)| over the zero pose (mid-range for a variable whose range
    leaves 0 out) and ``samples`` random poses drawn by
    ``configuration.random`` (within the limits, continuous joints over a full turn; mimic
    joints follow their variable). ``torques(pose)``: the torques to use instead of G(q), in
    ``model.joints`` order (a standing robot's, urdftool.physics.statics), or None to leave the
    pose out. ``progress``: called with (poses done, poses) as they are.
    :func:`urdftool.physics.gravity_bound.worst_loads` climbs from them to the worst over the
    joint ranges."""
    return sampled_loads(model, samples, seed, torques, progress)[0]


def sampled_loads(model: Model, samples: int, seed: int = 0, torques=None, progress=None):
    """(:func:`gravity_loads`' loads, the poses judged [poses, variables] in
    ``model.variables`` order, their torques [poses, joints] in ``model.joints`` order)."""
    import pinocchio as pin

    from urdftool.kinematics.configuration import random

    m, d = model.model, model.data
    names = [variable.name for variable in model.variables]
    drawn = random(model.variables, samples, seed).values if samples else np.zeros((0, len(names)))
    for k in held_coordinates(model):  # no range to draw from: held where the zero pose has them
        drawn[:, k] = model.variables[k].default
    # the zero pose, or mid-range for a variable whose range leaves 0 out: every pose judged is
    # one the robot can take
    poses = [{variable.name: variable.default for variable in model.variables}]
    poses += [dict(zip(names, (float(v) for v in row))) for row in drawn]
    rows = [model.row(name) for name in model.joints]
    followers = followers_of(model)
    leaders = {follower: leader for leader, found in followers.items() for follower in found}
    loads = [JointLoad(name, float(m.effortLimit[row]), 0.0,
                       reduction=model.reductions.get(name, 1.0), driven_by=leaders.get(name),
                       followers=dict(followers.get(name, {})))
             for name, row in zip(model.joints, rows)]
    if torques is None:

        def torques(pose):
            return pin.computeGeneralizedGravity(m, d, model.configuration(pose))[rows]

    table, kept = [], []
    for number, pose in enumerate(poses):
        values = torques(pose)
        kept.append(values)
        if values is None:  # a pose the caller leaves out
            continue
        values = actuated(model, values) if followers else np.asarray(values, dtype=float)
        table.append(values)
        for load, torque in zip(loads, np.abs(values)):
            torque = float(torque)
            torque = 0.0 if torque < _ROUND_OFF else torque  # a vertical axis: 1e-16, not load
            if number == 0:
                load.zero_pose = torque
            if torque > load.worst or number == 0:
                load.worst, load.worst_pose = torque, pose
        if progress is not None:
            progress(number + 1, len(poses))
    judged_rows = [[pose[name] for name in names] for pose, values in zip(poses, kept)
                   if values is not None]
    judged = np.array(judged_rows, dtype=float).reshape(len(judged_rows), len(names))  # 0 joints
    return loads, judged, (np.vstack(table) if table else np.zeros((0, len(loads))))


def _axis_problem(element, name: str, modelled) -> str:
    """Why Pinocchio's axis of joint ``name`` is not a unit vector: the file's has no direction,
    or Eigen's ``normalized`` (the sum of squares, unscaled) overflowed or underflowed on it:
    ``1e308 1e308 1e308`` becomes ``0 0 0`` there, a joint that never moves."""
    from urdftool.description.values import axis_xyz
    from urdftool.numbers import numbers, unit

    axis = element.find("axis") if element is not None else None
    written = axis.get("xyz") if axis is not None else None
    values = axis_xyz(element) if element is not None else (1.0, 0.0, 0.0)  # (<axis/>: 0 0 0)
    direction = unit(values) if values else None
    if direction is None:
        return f"joint '{name}': <axis> has no direction; give a unit vector such as '0 0 1'"
    return (f"joint '{name}': Pinocchio's model of <axis xyz='{written}'> is "
            f"'{numbers(modelled)}', not a unit vector: Eigen normalises it by the sum of its "
            f"squares, which {'overflows' if max(map(abs, values)) > 1 else 'underflows'}; "
            f"write xyz='{numbers(direction)}'")
