"""U9xx: urdftool itself. The engine reports U900 and the suppressions U901; both are declared
here, with the other families, so that the catalogue is complete without importing either."""

from urdftool.lint.catalogue import Severity, declare

U900 = declare("U900", "internal-error", Severity.ERROR, """
    A rule, the loader or a reader crashed on this file: a bug in urdftool, not in the robot.

    A reader is what reads a file besides the robot's (a launch file read while finding the
    robots to check, or for a rule, the settings). The run goes on with the other rules and
    files; a file whose reader crashed is taken as if it said nothing. Please report it with
    the file attached.
    """)

U901 = declare("U901", "unused-suppression", Severity.WARNING, """
    An ``<!-- urdftool: ignore ... -->`` comment silences nothing.

    The problem it once hid is fixed, the comment drifted away from its element, or a code is
    misspelled. A stale suppression will silently hide the next real problem at that place:
    delete it, or move it to the line just above the element the finding points at.

    Fix (safe): the comment deleted (its line, when nothing else is on it), unless it names an
    unknown code (a misspelling to correct by hand).

    Bad: ``<!-- urdftool: ignore U206 -->`` above a joint whose axis is a unit vector
    Good: no comment (or the comment above the element that really has the finding)
    """)

U902 = declare("U902", "analysis-unavailable", Severity.INFO, """
    A rule did not run because a library it needs is not installed.

    A lint-only install (urdftool without its ``analysis`` extra, as the pre-commit hook
    installs it) leaves out Pinocchio, FCL and the other analysis libraries; the rules that pose
    the robot or test collisions need them. The note names the library and the command that
    installs the extra. The other rules ran as usual.
    """)

