"""Run rules over robots: select, stamp, and never let one rule's crash end the run."""

from __future__ import annotations

import traceback
from dataclasses import dataclass, field
from pathlib import Path

from urdftool.description.meshes import MeshLimits
from urdftool.description.robot import CompanionPaths
from urdftool.diagnostics import Finding, Location, Severity, display_path
from urdftool.errors import LoadError
from urdftool.lint.rules import REGISTRY, Rule, all_rules, declare, matches
from urdftool.lint import suppressions

declare("U900", "internal-error", Severity.ERROR, """
    A rule or the loader crashed on this file: a bug in urdftool, not in the robot.

    The run goes on with the other rules and files. Please report it with the file attached.
    """)


@dataclass(frozen=True)
class Selection:
    """Which rules run: codes, code prefixes (``U2``) or names (``inverted-limits``)."""

    select: tuple[str, ...] = ()
    ignore: tuple[str, ...] = ()

    def allows(self, code: str) -> bool:
        if self.select and not any(matches(code, s) for s in self.select):
            return False
        return not any(matches(code, s) for s in self.ignore)


@dataclass
class CheckOptions:
    """How to load and check each file."""

    xacro_args: dict[str, str] = field(default_factory=dict)
    packages: dict[str, Path] = field(default_factory=dict)
    selection: Selection = Selection()
    allow_env: bool = True
    max_file_size: int = 16 * 1024 * 1024
    companions: CompanionPaths = CompanionPaths()
    mesh_limits: MeshLimits = MeshLimits()


@dataclass
class FileResult:
    path: str
    findings: list[Finding]
    robot: object | None = None


def stamp(rule: Rule, where, message: str, robot) -> Finding:
    """A finding for ``rule`` at ``where`` (element, Location or None)."""
    location = where if isinstance(where, Location) else robot.locate(where)
    return rule.finding(message, location)


def _crash(what: str, error: BaseException, location: Location) -> Finding:
    """U900 for a crash in urdftool itself, naming the code line that raised."""
    frame = traceback.extract_tb(error.__traceback__)[-1] if error.__traceback__ else None
    where = f" [{Path(frame.filename).name}:{frame.lineno}]" if frame else ""
    return REGISTRY["U900"].finding(f"{what} crashed: {type(error).__name__}: {error}{where}",
                                    location)


def check_robot(robot, selection: Selection = Selection()) -> list[Finding]:
    """Run every selected rule over a loaded robot; a crashing rule becomes U900.

    Inline ``<!-- urdftool: ignore ... -->`` comments then filter the findings (see
    :mod:`urdftool.lint.suppressions`); unused ones become U901.
    """
    findings = [f for f in robot.options.get("load_findings", []) if selection.allows(f.code)]
    for rule in all_rules():
        if rule.check is None or not selection.allows(rule.code):
            continue
        try:
            for where, message in rule.check(robot):
                findings.append(stamp(rule, where, message, robot))
        except MemoryError:
            raise  # over the memory budget: the runner reports it (U018)
        except Exception as error:  # a bug in a rule must not hide the other findings
            findings.append(_crash(f"rule {rule.code} ({rule.name})", error, robot.locate(None)))
    findings = suppressions.apply(findings, robot.files, selection.allows)
    return sorted(set(findings), key=Finding.sort_key)


def check_file(path: str, options: CheckOptions, data: bytes | None = None) -> FileResult:
    """Load and check one file (``data``: its content, when not to be read from ``path``);
    load failures are findings too."""
    from urdftool.description.load import load

    try:
        robot = load(path, xacro_args=options.xacro_args, packages=options.packages,
                     allow_env=options.allow_env, max_file_size=options.max_file_size, data=data)
    except LoadError as error:
        # A file that cannot be loaded is never silently passed, whatever the selection.
        return FileResult(path, error.findings)
    except MemoryError:
        raise  # over the memory budget: the runner reports it where loading was (U018)
    except Exception as error:  # a loader bug (RecursionError too): a finding, not a traceback
        shown = display_path(path) if path != "-" else "<stdin>"
        return FileResult(path, [_crash("loading", error, Location(shown))])
    robot.companion_paths, robot.mesh_limits = options.companions, options.mesh_limits
    return FileResult(path, check_robot(robot, options.selection), robot)
