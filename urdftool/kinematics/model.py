"""Pinocchio models built from a robot's URDF, on a stack deep enough for the robot.

Pinocchio's URDF parser recurses once per link depth in C++ (about 1.6 kB of stack a level): a
5,000-link chain overflows the main thread's 8 MB stack and kills the process (SIGSEGV, no
exception). The parse therefore runs in a thread whose stack is sized for the number of links;
its exceptions are raised in the caller.
"""

from __future__ import annotations

import threading

BASE_STACK = 64 * 1024 * 1024  # [bytes]
STACK_PER_LINK = 8 * 1024  # [bytes]: five times what a level of the parser was measured to use


def stack_size(links: int) -> int:
    """The stack [bytes] the parse of a robot with ``links`` links gets."""
    return BASE_STACK + STACK_PER_LINK * links


def build_model(robot, root_joint=None, root_name: str | None = None):
    """``pinocchio.buildModelFromXML(robot.urdf[, root_joint, root_name])`` on a deep stack
    (a negative effort or velocity limit given as 0: :func:`_limits_pinocchio_takes`).

    Raises what Pinocchio raises (ValueError, RuntimeError) and MemoryError.
    """
    import pinocchio

    urdf = _limits_pinocchio_takes(robot)
    arguments = (urdf,) if root_joint is None else (urdf, root_joint, root_name)
    outcome: list = []

    def parse():
        try:
            outcome.append((True, pinocchio.buildModelFromXML(*arguments)))
        except BaseException as error:  # handed to the caller's thread
            outcome.append((False, error))

    previous = threading.stack_size(stack_size(len(robot.links)))
    try:
        thread = threading.Thread(target=parse, name="pinocchio-urdf")
        thread.start()
    finally:
        threading.stack_size(previous)
    thread.join()
    ok, value = outcome[0]
    if not ok:
        raise value
    return value


DATA_BYTES_PER_NV_CUBED = 64  # [bytes]: pinocchio.Data holds second-order derivative tensors
# (nv x nv x nv each); measured 59 bytes per nv^3 at nv = 200 and 400 with Pinocchio 4.1


def data_size(nv: int) -> int:
    """What ``model.createData()`` allocates for ``nv`` velocity variables, about [bytes]."""
    from urdftool.numbers import power

    return DATA_BYTES_PER_NV_CUBED * power(nv, 3)


def oversized_data(nv: int, fewer: str) -> str | None:
    """Why Pinocchio's Data of ``nv`` velocity variables cannot be made (it cannot fit the
    memory this process may use: its address-space cap, else the machine's), else None, with
    its remedies: ``fewer`` (how the command takes fewer joints; "" when it cannot), and more
    memory when the cap is the budget's and the machine has it. Every command that makes one
    asks first: a 1,500-joint robot would need ~200 GB and be killed instead of reported; ik
    and workspace on a 999-joint limb ran out of a 2 GiB budget and advised raising it (to 60
    GiB), where dynamics said what this says. A refusal by design, as a size limit checked
    before the work is: the question's, exit 2 (ik, workspace and dynamics exited 1)."""
    import os
    import resource

    from urdftool.budget import format_memory

    machine = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    cap, _ = resource.getrlimit(resource.RLIMIT_AS)
    capped = cap != resource.RLIM_INFINITY
    cap = cap if capped else machine
    needed = data_size(nv)
    if needed <= cap // 2:
        return None
    remedies = [fewer] * bool(fewer) + ["raise --max-memory"] * (capped and needed <= machine // 2)
    return (f"{nv} joint variables: Pinocchio's data (where its algorithms compute) would "
            f"need about {format_memory(needed)} (it grows with the cube of the joints) and "
            f"this process may use {format_memory(cap)}" +
            (f"; {' or '.join(remedies)}" if remedies else ""))


def _limits_pinocchio_takes(robot) -> str:
    """``robot.urdf``, with each ``<limit>``'s negative ``effort`` or ``velocity`` written 0:
    Pinocchio refuses the model ("Some components of min_effort are greater than max_effort")
    where urdfdom, and so ROS, loads it (the linter warns: Gazebo enforces no limit then, the
    URDF specification reads the absolute value), and fk, ik, collisions and dynamics refused
    Halodi's EVE (every joint's ``effort="-1.0" velocity="-1.0"``) as if urdfdom had. Poses,
    M(q) and G(q) do not depend on them; dynamics judges a torque only against a limit above
    0 (physics.dynamics.judged_effort), so -1 and 0 are both no limit to it. The text as it
    is when no limit is negative (the usual case: one pass over the joints)."""
    import copy

    def negative(value) -> bool:
        try:
            return float(value) < 0
        except (TypeError, ValueError):  # (a malformed number: urdfdom refuses it)
            return False

    limits = [(limit, name) for joint in robot.children("joint")
              for limit in joint.iterchildren("limit") for name in ("effort", "velocity")
              if negative(limit.get(name))]
    if not limits:
        return robot.urdf
    from lxml import etree

    root = copy.deepcopy(robot.root)  # (the robot's own tree is every rule's: left as read)
    twins = dict(zip(map(id, robot.root.iter()), root.iter()))
    for limit, name in limits:
        twins[id(limit)].set(name, "0")
    return etree.tostring(root, encoding="unicode", pretty_print=False)
