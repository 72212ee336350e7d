"""Pinocchio's URDF parser (urdfdom, C++) called without letting it write to the terminal.

urdfdom reports what it rejects through console_bridge, straight to file descriptor 2 ("Error:
Joint [j] is of type REVOLUTE but it does not specify limits / at line 607 in
/project/urdfdom/..."), then Pinocchio raises "The XML stream does not contain a valid URDF
model". Both are kept here and handed over in a :class:`~urdftool.errors.ModelBuildError`; the
command line then reports the cause at its line with urdftool's own message.
"""

from __future__ import annotations

import os
import re
import sys
from contextlib import contextmanager

from urdftool.description.files import scratch_file
from urdftool.errors import ModelBuildError

MAX_CAPTURED = 64 * 1024  # [bytes] of urdfdom's messages kept


@contextmanager
def captured_stderr():
    """Redirect file descriptor 2 (where C++ libraries write) into a buffer for the block; yields
    a list that holds the text written once the block ends."""
    sys.stderr.flush()
    text: list[str] = []
    with scratch_file() as buffer:
        saved = os.dup(2)
        try:
            os.dup2(buffer.fileno(), 2)
            yield text
        finally:
            sys.stderr.flush()
            os.dup2(saved, 2)
            os.close(saved)
            buffer.seek(0)
            text.append(buffer.read(MAX_CAPTURED).decode("utf-8", "replace"))


def urdfdom_messages(text: str) -> list[str]:
    """urdfdom's console_bridge lines without their C++ source positions ("at line 607 in
    /project/urdfdom/...")."""
    found = []
    for line in text.splitlines():
        line = line.strip()
        if not line or re.match(r"at line \d+ in ", line):
            continue
        found.append(re.sub(r"^(Error|Warning|Info|Debug):\s*", "", line))
    return found


def build_model(robot, *root_joint):
    """``pinocchio.buildModelFromXML(robot.urdf, *root_joint)`` on a stack deep enough for the
    robot (:mod:`urdftool.kinematics.model`), quietly; ModelBuildError (at the robot's root
    element) with urdfdom's reasons when it refuses the robot."""
    from urdftool.kinematics.model import build_model as parse

    with captured_stderr() as noise:
        try:
            return parse(robot, *root_joint)
        except (ValueError, RuntimeError) as error:
            failure = error
    reasons = urdfdom_messages(noise[0]) or [str(failure).strip().splitlines()[-1]]
    error = ModelBuildError(f"Pinocchio (urdfdom) cannot build a model: {'; '.join(reasons)}",
                            robot.root)
    error.robot = robot  # for the command line to find the cause with the linter
    raise error
