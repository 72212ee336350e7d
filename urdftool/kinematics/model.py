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
    """``pinocchio.buildModelFromXML(robot.urdf[, root_joint, root_name])`` on a deep stack.

    Raises what Pinocchio raises (ValueError, RuntimeError) and MemoryError.
    """
    import pinocchio

    urdf = robot.urdf
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
