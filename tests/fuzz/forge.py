"""Forged output: hostile names through every command and every output format, and the judge of
what a command printed or wrote.

A name in a robot file (a link, joint, material, frame, robot, controller, SRDF group, file or
folder name) is the attacker's: it must never start a line of its own in a CI log (a GitHub
workflow command: ``::error``, ``::add-mask::``, ``::stop-commands::``), a Markdown heading,
image, link or raw HTML in a pull-request comment, an element in a JUnit or SVG document, markup
that rich interprets, or a terminal escape sequence. :func:`repository` writes a robot whose
names carry all of these; :func:`invocations` lists every command of the Typer app with every
format it declares (``FORMATS`` of its module) and every option that writes a file;
:func:`judge` says what in a command's output or files is forged.

Used by tests/integration/test_forged_output.py (every command, every format, once) and by the
fuzzer (tests/fuzz/run.py ``--kinds names``: random compositions of the payloads).
"""

from __future__ import annotations

import csv
import importlib
import io
import json
import os
import re
import unicodedata
from dataclasses import dataclass, field
from pathlib import Path

# What a name may carry in a robot file (XML 1.0: no C0 control but tab, line feed and carriage
# return, given as character references). Each is a way to forge output somewhere.
NAME_PAYLOADS = {
    "workflow": "\n::error file=robot.urdf,line=1::FORGED\n",
    "mask": "\n::add-mask::SECRET",
    "stop": "\r\n::stop-commands::TOKEN\n",
    "verdict": "\r## All checks passed\r\n1 file checked: no problems found\n",
    "lead": "::warning::LEAD",  # no line break: forged wherever a name starts a line
    "wide-lead": "\u3000::notice::WIDE",  # GitHub trims Unicode blanks before '::'
    "heading": "\n# HEADING\n",
    "image": "![IMAGE](https://evil.example/x.png)",
    "link": "[LINK](javascript:alert(1))",
    "html": "<img src=x onerror=alert(1)>",
    "script": "<script>alert(1)</script>",
    "table": "|CELL|CELL|",
    "tick": "`TICK` ``",
    "rich": "[bold red]RICHMARK[/]",
    "rich-link": "[link=https://evil.example]RICHLINK[/link]",
    "emoji": ":thumbs_up:",
    "bidi": "\u202eBIDI\u202c\u2066ISOLATE\u2069",
    "c1": "\x9b31mC1\x85NEL\u2028LINESEP",
    "tab": "\tTAB",
    "mention": "@everyone #1",
}
# Only where no XML is in the way: file and folder names, YAML, CSV, command-line words.
TERMINAL_PAYLOADS = {
    "csi": "\x1b[2J\x1b[31mCSI",
    "osc8": "\x1b]8;;https://evil.example\x1b\\OSC8\x1b]8;;\x1b\\",
    "osc52": "\x1b]52;c;ZWNobyBwd25lZA==\x07",
}
# Only in YAML, whose "\\ud800" escape makes a string no file of text can hold: a surrogate code
# point (a file name's undecodable byte is one too), which JSON must not write unpaired.
YAML_PAYLOADS = {"surrogate": "\ud800UNPAIRED\udcff"}
FORMULA = '=HYPERLINK("https://evil.example")'  # a spreadsheet formula: in link names only
# Text that appears only inside payloads: in Markdown it must stay inside code.
MARKERS = ("FORGED", "SECRET", "TOKEN", "All checks passed", "HEADING", "IMAGE", "LINK", "onerror",
           "<script>", "CELL", "RICHMARK", "RICHLINK", "@everyone", "evil.example")


def hostile(prefix: str, payloads=None) -> str:
    """A name: ``prefix`` (unique) then every payload."""
    return prefix + "".join((payloads or NAME_PAYLOADS).values())


def _attr(text: str) -> str:
    return (text.replace("&", "&amp;").replace('"', "&quot;").replace("<", "&lt;")
            .replace(">", "&gt;").replace("\n", "&#10;").replace("\r", "&#13;")
            .replace("\t", "&#9;"))


@dataclass
class Names:
    robot: str
    base: str
    link: str
    tip: str
    frame: str
    joint1: str
    joint2: str
    tool_joint: str
    material: str
    group: str
    controller: str


def names(payloads=None) -> Names:
    """The hostile names of the robot :func:`robot_urdf` writes. Joint names hold no '='
    (``--q NAME=VALUE``); link names hold a formula (they head CSV columns)."""
    link = {**(payloads or NAME_PAYLOADS), "formula": FORMULA}
    joint = {key: value for key, value in link.items() if "=" not in value}
    return Names(robot=hostile("R", joint), base=hostile("B", link), link=hostile("L", link),
                 tip=hostile("T", link), frame=hostile("F", link), joint1=hostile("J1", joint),
                 joint2=hostile("J2", joint), tool_joint=hostile("JF", joint),
                 material=hostile("M", joint), group=hostile("G", joint),
                 controller=hostile("C", {**joint, **TERMINAL_PAYLOADS}))


def _inertial(mass: float, ixx: float = 0.01) -> str:
    return (f'<inertial><mass value="{mass}"/><inertia ixx="{ixx}" iyy="0.01" izz="0.01" '
            'ixy="0" ixz="0" iyz="0"/></inertial>')


def _revolute(name, parent, child, xyz, axis, lower, upper) -> str:
    return (f'<joint name="{name}" type="revolute"><parent link="{parent}"/>'
            f'<child link="{child}"/><origin xyz="{xyz}"/><axis xyz="{axis}"/>'
            f'<limit lower="{lower}" upper="{upper}" effort="10" velocity="1"/></joint>')


def robot_urdf(n: Names, *, inverted: bool = True, renamed: bool = False,
               broken: bool = False, mesh: bool = False, massless_root: bool = False) -> str:
    """A three-link arm with a tool frame, every name hostile. inverted: the second joint's
    limits are swapped (an error naming it); renamed: the tip has another name and the first
    joint another limit (for diff); broken: a joint names a link that does not exist; mesh: the
    tip's visual is a missing mesh whose file name is hostile; massless_root: the root link has no
    inertial (the fixes of the simulator targets write its name)."""
    a = {key: _attr(value) for key, value in vars(n).items()}
    tip = _attr(hostile("T2")) if renamed else a["tip"]
    upper = "1.5" if renamed else "1"
    lower2, upper2 = ("1", "-1") if inverted else ("-1", "1")
    visual = (f'<mesh filename="{_attr(hostile("missing"))}.stl"/>' if mesh
              else '<cylinder radius="0.03" length="0.2"/>')
    child = _attr(hostile("NOWHERE")) if broken else a["frame"]
    return f"""<?xml version="1.0"?>
<robot name="{a['robot']}">
  <material name="{a['material']}"><color rgba="1 0 0 1"/></material>
  <link name="{a['base']}">
    {"" if massless_root else _inertial(1.0)}
    <visual><geometry><box size="0.1 0.1 0.1"/></geometry><material name="{a['material']}"/></visual>
    <collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>
  </link>
  {_revolute(a['joint1'], a['base'], a['link'], "0 0 0.1", "0 0 1", "-1", upper)}
  <link name="{a['link']}">
    {_inertial(1.0, ixx=0.05)}
    <visual><origin xyz="0 0 0.15"/><geometry><box size="0.05 0.05 0.3"/></geometry></visual>
    <collision><origin xyz="0 0 0.15"/><geometry><box size="0.05 0.05 0.3"/></geometry></collision>
  </link>
  {_revolute(a['joint2'], a['link'], tip, "0 0 0.3", "0 1 0", lower2, upper2)}
  <link name="{tip}">
    {_inertial(0.5)}
    <visual><origin xyz="0 0 0.1"/><geometry>{visual}</geometry></visual>
    <collision><origin xyz="0 0 0.1"/><geometry><cylinder radius="0.03" length="0.2"/></geometry></collision>
  </link>
  <joint name="{a['tool_joint']}" type="fixed">
    <parent link="{tip}"/><child link="{child}"/><origin xyz="0 0 0.2"/>
  </joint>
  <link name="{a['frame']}"/>
</robot>
"""


def srdf(n: Names) -> str:
    a = {key: _attr(value) for key, value in vars(n).items()}
    return f"""<?xml version="1.0"?>
<robot name="{a['robot']}">
  <group name="{a['group']}"><chain base_link="{a['base']}" tip_link="{a['tip']}"/></group>
  <group_state name="{a['group']}" group="{a['group']}"><joint name="{a['joint1']}" value="9"/></group_state>
  <disable_collisions link1="{a['base']}" link2="{_attr(hostile('GHOST'))}" reason="Never"/>
</robot>
"""


def _yaml(text: str) -> str:
    """A YAML double-quoted scalar (escapes: ESC as \\e, any other control as \\xNN)."""
    out = []
    for char in text:
        code = ord(char)
        if char in '"\\':
            out.append("\\" + char)
        elif code < 0x20 or 0x7f <= code < 0xa0 or code in (0x2028, 0x2029) \
                or 0xd800 <= code < 0xe000:
            out.append({"\n": "\\n", "\r": "\\r", "\t": "\\t", "\x1b": "\\e"}.get(char,
                                                                                f"\\x{code:02x}"
                                                                                if code < 0x100
                                                                                else f"\\u{code:04x}"))
        else:
            out.append(char)
    return '"' + "".join(out) + '"'


def controllers_yaml(n: Names, old: bool = False) -> str:
    """ROS 2 controllers: one named hostile, its joints an existing hostile joint and a missing
    one whose name holds terminal escape sequences; ``old`` (diff's old side): a parameter
    named hostile and another whose value is a set of a hostile word, which the new side
    changes (the key and the value are written by the diff)."""
    name = _yaml(n.controller)
    missing = _yaml(hostile("NOJOINT", {**NAME_PAYLOADS, **TERMINAL_PAYLOADS, **YAML_PAYLOADS}))
    changed = (f"""    {_yaml(hostile("KEY", {**NAME_PAYLOADS, **TERMINAL_PAYLOADS}))}: 1
    set_of: !!set {{{_yaml(hostile("SET", {**NAME_PAYLOADS, **TERMINAL_PAYLOADS}))}}}
""" if old else "")
    return f"""controller_manager:
  ros__parameters:
    update_rate: 50
    {name}:
      type: joint_trajectory_controller/JointTrajectoryController
{name}:
  ros__parameters:
    command_interfaces: [position]
    state_interfaces: [position]
    joints:
      - {_yaml(n.joint1)}
      - {missing}
{changed}"""


def configurations_csv(n: Names) -> str:
    """--q-file and --targets: a hostile column beside the joints."""
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow([n.joint1, n.joint2, hostile("COLUMN", {**NAME_PAYLOADS, **TERMINAL_PAYLOADS})])
    writer.writerow([0.1, 0.2, 0.3])
    return buffer.getvalue()


def targets_csv() -> str:
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(["name", "x", "y", "z"])
    writer.writerow([hostile("TARGET", {**NAME_PAYLOADS, **TERMINAL_PAYLOADS}), 0.0, 0.0, 0.55])
    writer.writerow([hostile("FAR", {**NAME_PAYLOADS, **TERMINAL_PAYLOADS}), 5.0, 0.0, 0.0])
    return buffer.getvalue()


def dh_yaml(n: Names) -> str:
    return f"""convention: standard
base_link: {_yaml(n.base)}
tip_link: {_yaml(hostile("DHTIP", {**NAME_PAYLOADS, **TERMINAL_PAYLOADS}))}
joints:
  - {{joint: {_yaml(hostile("DHJOINT", {**NAME_PAYLOADS, **TERMINAL_PAYLOADS, **YAML_PAYLOADS}))}, type: revolute, theta: 0, d: 0.1, a: 0, alpha: 0}}
"""


# A folder and a file name: what a file system allows (no '/', no NUL) reaches every message
# that names the robot's file; "\udcff" is the byte 0xff, not UTF-8 (os.fsencode), as Python
# names it: a surrogate code point in every string that holds the path.
FOLDER_NAME = "dir" + "\n::error::FOLDER\x1b[31m\u202e\udcff"
FILE_NAME = "r" + "\n::error file=x,line=1::FILE\r\x1b]8;;evil.example\x1b\\F\x07" \
            "[bold]RICHMARK<img src=x onerror=1>.urdf"

INCLUDED_NAME = "inc\n::error::INCLUDED\u202e[bold]RICHMARK.xacro"  # no ESC: XML names it


@dataclass
class Repository:
    root: Path
    robot: Path  # the hostile robot, in a hostile folder, under a hostile file name
    plain: Path  # the same robot as robot.urdf (commands that need a companion beside it)
    fixed: Path  # a copy that check --fix rewrites
    fixed_targets: Path  # another, rewritten by the fixes of every simulator target
    old: Path  # diff's old side (plain's folder)
    broken: Path  # a joint naming a missing link
    meshed: Path  # a missing mesh with a hostile file name
    xacro: Path  # a xacro including a hostile file name, its property values hostile
    broken_xacro: Path  # the same with an undefined property (its message lists the others)
    q_file: Path
    targets: Path
    dh_table: Path
    names: Names
    out: Path  # where commands write


def repository(root: Path, payloads=None) -> Repository:
    """The hostile repository under ``root`` (made a repository: it has a .git folder)."""
    n = names(payloads)
    (root / ".git").mkdir(parents=True, exist_ok=True)
    folder = root / FOLDER_NAME
    (folder / "config").mkdir(parents=True, exist_ok=True)
    robot = folder / FILE_NAME
    robot.write_text(robot_urdf(n, inverted=False))
    plain = folder / "robot.urdf"
    plain.write_text(robot_urdf(n))
    (folder / "robot.srdf").write_text(srdf(n))
    (folder / "config" / "controllers.yaml").write_text(controllers_yaml(n))
    old = root / "old"
    old.mkdir(exist_ok=True)
    (old / "robot.urdf").write_text(robot_urdf(n, inverted=False, renamed=True))
    (old / "config").mkdir(exist_ok=True)
    (old / "config" / "controllers.yaml").write_text(controllers_yaml(n, old=True))
    changed = root / "changed"  # diff's new side of old's controllers: its keys changed
    (changed / "config").mkdir(parents=True, exist_ok=True)
    (changed / "robot.urdf").write_text(robot_urdf(n))
    (changed / "config" / "controllers.yaml").write_text(controllers_yaml(n))
    broken = root / "broken.urdf"
    broken.write_text(robot_urdf(n, broken=True))
    meshed = root / "meshed.urdf"
    meshed.write_text(robot_urdf(n, mesh=True))
    (root / INCLUDED_NAME).write_text('<robot xmlns:xacro="http://www.ros.org/wiki/xacro">'
                                      '<xacro:property name="q" value="1"/></robot>\n')
    xacro, broken_xacro = root / "robot.urdf.xacro", root / "broken.urdf.xacro"
    for path, extra in ((xacro, ""), (broken_xacro, '<link name="${undefined}"/>')):
        path.write_text(f"""<?xml version="1.0"?>
<robot name="{_attr(n.robot)}" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="{_attr(INCLUDED_NAME)}"/>
  <xacro:property name="p" value="{_attr(n.link)}"/>
  <xacro:macro name="arm" params="who">
    <link name="${{who}}"/>
    <joint name="{_attr(n.joint1)}" type="revolute"><parent link="${{who}}"/><child link="${{p}}"/>
      <limit lower="1" upper="-1" effort="1" velocity="1"/></joint>
    {extra}
  </xacro:macro>
  <link name="${{p}}"><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <xacro:arm who="{_attr(n.base)}"/>
</robot>
""")
    q_file = root / "q.csv"
    q_file.write_text(configurations_csv(n))
    targets = root / "targets.csv"
    targets.write_text(targets_csv())
    dh_table = root / "dh.yaml"
    dh_table.write_text(dh_yaml(n))
    out = root / "out"
    out.mkdir(exist_ok=True)
    fixed, fixed_targets = root / "fixed.urdf", root / "fixed-targets.urdf"
    fixed.write_text(robot_urdf(n))
    fixed_targets.write_text(robot_urdf(n, massless_root=True))
    return Repository(root, robot, plain, fixed, fixed_targets, old / "robot.urdf", broken, meshed, xacro,
                      broken_xacro, q_file,
                      targets, dh_table, n, out)


# ---------------------------------------------------------------- every command, every format

# Options that never change which names are printed or how (numbers, budgets, switches of the
# analysis), or that read a file the invocations give elsewhere: each with why it is left out.
NOT_OUTPUT = {
    "--install-completion": "shell completion, no robot",
    "--show-completion": "shell completion, no robot",
    "--timeout": "a budget", "--max-memory": "a budget", "--jobs": "workers",
    "--workers": "workers", "--seed": "a number", "--samples": "a number",
    "--max-samples": "a number", "--tolerance": "a number", "--min-fraction": "a number",
    "--margin": "a number", "--tol": "a number", "--iterations": "a number",
    "--seeds": "a number", "--random": "a number", "--density": "a number",
    "--size": "a number", "--max-file-size": "a limit", "--max-triangles": "a limit",
    "--max-pairs": "a limit", "--max-scene-triangles": "a limit", "--max-matrix-rows": "a limit",
    "--deg": "units", "--keep-mass": "a number's source", "--view": "a camera",
    "--collision": "geometry drawn", "--frames": "lines drawn", "--axes": "lines drawn",
    "--floating": "an extra joint of ours", "--method": "a solver", "--point": "a number",
    "--rpy": "a number", "--quat": "a number", "--v": "numbers", "--a": "numbers",
    "--arg": "xacro arguments (the xacro robot's names are hostile)",
    "--package": "package folders", "--strict": "exit code", "--exit-zero": "exit code",
    "--allow-env": "environment", "--no-env": "environment", "--isolated": "settings",
    "--config": "settings (sec-core's)", "--select": "rule selection",
    "--ignore": "rule selection", "--no-cache": "cache", "--cache-dir": "cache",
    "--inorder": "accepted no-op", "--check-order": "accepted no-op", "-q": "quiet",
    "--stdio": "transport", "--log-file": "the server's log (server: tests/test_server.py)",
    "--until-converged": "more samples", "--no-collisions": "less work",
    "--no-companions": "less work", "--unsafe-fixes": "which fixes", "--spec": "companion",
    "--stdin-filename": "standard input's name", "--rev": "git (sec-core's tests)",
    "--controllers": "found beside the robot", "--srdf": "found beside the robot",
    "--dh": "with --verify (its table's names are hostile)", "--convention": "numbers",
    "--target-q": "numbers", "--check-srdf": "with --matrix (the SRDF beside it)",
}
NO_ROBOT = {"rules": "the catalogue: our own text", "server": "JSON-RPC (tests/test_server.py)"}


@dataclass
class Invocation:
    argv: list[str]
    kind: str  # what standard output is: text, json, json-lines, junit, github, markdown, csv,
    #            yaml, dot
    writes: list[Path] = field(default_factory=list)  # removed before, judged after the run
    checks: list[Path] = field(default_factory=list)  # judged after the run (rewritten by it)


_FORMAT_KINDS = {"json": "json", "sarif": "json", "gitlab": "json", "rdjson": "rdjson",
                 "json-lines": "json-lines", "junit": "junit", "github": "github",
                 "markdown": "markdown", "csv": "csv", "yaml": "yaml"}


def command_options(name: str) -> dict[str, object]:
    """The click command ``name`` of the app: {first option string: param}."""
    from urdftool.cli import command

    return {(param.opts[0] if param.opts else param.name): param
            for param in command(name).params}


def commands() -> list[str]:
    """Every command of the Typer app, as ``urdftool --help`` lists them."""
    from typer.main import get_command

    from urdftool.cli import app

    group = get_command(app)
    return sorted(group.list_commands(None))


def formats_of(name: str) -> tuple[str, ...] | None:
    """The --format values a command declares (its module's FORMATS); None when it has no
    --format option."""
    if "--format" not in command_options(name):
        return None
    module = importlib.import_module(f"urdftool.cli.{name}")
    if not hasattr(module, "FORMATS"):
        raise AssertionError(f"urdftool {name} has --format but its module declares no "
                             "FORMATS: the forged-output test cannot try each format")
    return tuple(module.FORMATS)


def invocations(repo: Repository) -> list[Invocation]:
    """Every command with every format it declares, the options that write files, the modes
    that print other things, and names that do not exist (their messages list those that do)."""
    n, out = repo.names, repo.out
    robot, plain = str(repo.robot), str(repo.plain)
    unknown = hostile("NOPE", {**NAME_PAYLOADS, **TERMINAL_PAYLOADS})
    limit = ["--timeout", "30"]
    required = {"--base": n.base, "--tip": n.tip, "--output": str(out / "picture.svg")}
    also = {"ik": ["--xyz", "0", "0", "0.55"],  # one of its targets
            "crosscheck": ["--loader", "pinocchio"]}  # one loader each format (the variants
    # below run two)
    words = {"diff": [str(repo.old), plain]}
    runs: list[Invocation] = []
    for name in commands():
        if name in NO_ROBOT:
            continue
        options = command_options(name)
        fill = [word for option, param in options.items() if getattr(param, "required", False)
                and option.startswith("-") for word in (option, required[option])]
        for fmt in formats_of(name) or (None,):
            argv = [name, *words.get(name, [robot]), *fill, *also.get(name, []), *limit]
            if fmt is not None:
                argv += ["--format", fmt]
            runs.append(Invocation(argv, _FORMAT_KINDS.get(fmt, "dot" if name == "graph"
                                                            else "text")))
    svg, png = out / "x.svg", out / "x.png"
    variants = [
        (["check", robot, "--verbose", "--statistics"], "text", []),
        (["check", robot, "--quiet"], "text", []),
        (["check", robot, "--notes"], "text", []),
        (["check", robot, *(w for t in ("gazebo", "gz", "mujoco", "drake", "pybullet", "isaac",
                                         "pinocchio") for w in ("--target", t))], "text", []),
        (["check", robot, "--target", "mujoco", "--format", "github"], "github", []),
        (["crosscheck", robot, "--loader", "pinocchio", "--loader", "mujoco"], "text", []),
        (["check", plain, "--diff", "--unsafe-fixes"], "text", []),
        (["check", str(repo.root), "--format", "text"], "text", []),
        (["check", str(repo.broken), str(repo.meshed), str(repo.broken_xacro), "--format", "text"],
         "text", []),
        (["check", str(repo.broken), str(repo.meshed), str(repo.broken_xacro), "--format", "github"],
         "github", []),
        (["check", str(repo.broken), str(repo.meshed), str(repo.broken_xacro), "--format", "junit"],
         "junit", []),
        (["check", robot, "--format", "junit", "--output", str(out / "report.xml")], "text",
         [out / "report.xml"]),
        (["check", robot, "--format", "sarif", "-o", str(out / "report.sarif")], "text",
         [out / "report.sarif"]),
        (["check", str(repo.fixed), "--format", "text", "--fix", "--unsafe-fixes"], "text", []),
        (["check", str(repo.fixed_targets), "--fix", "--unsafe-fixes",
          *(w for t in ("gazebo", "mujoco", "drake", "pybullet", "isaac") for w in ("--target", t))],
         "text", []),
        (["xacro", str(repo.xacro)], "text", []),
        (["xacro", robot, "-o", str(out / "expanded.urdf")], "text", [out / "expanded.urdf"]),
        (["xacro", str(repo.xacro), "--deps", "-o", str(out / "deps.txt")], "text",
         [out / "deps.txt"]),
        (["xacro", robot, "--deps"], "text", []),
        (["tree", str(repo.broken)], "text", []),
        (["tree", str(repo.xacro)], "text", []),
        (["tree", str(repo.broken_xacro)], "text", []),
        (["graph", robot, "--output", str(out / "graph.dot")], "text", [out / "graph.dot"]),
        (["graph", robot, "--output", str(out / "graph.svg")], "text", []),
        (["graph", str(repo.broken)], "dot", []),
        (["fk", robot, "--matrix", "--frame", n.tip, "--frame", n.frame, "--base", n.base],
         "text", []),
        (["fk", robot, "--q-file", str(repo.q_file), "--format", "csv"], "csv", []),
        (["fk", robot, "--q-file", str(repo.q_file)], "text", []),
        (["fk", robot, "--frame", unknown], "text", []),
        (["fk", robot, "--q", f"{unknown}=1"], "text", []),
        (["fk", robot, "--dh", str(repo.dh_table), "--verify", "--random", "5"], "text", []),
        (["dh", robot, "--base", unknown, "--tip", n.tip], "text", []),
        (["dh", robot, "--base", n.base, "--tip", unknown], "text", []),
        (["dh", robot, "--base", n.base, "--tip", n.tip, "--textbook"], "text", []),
        (["ik", robot, "--tip", n.tip, "--base", n.base, "--q", f"{n.joint1}=0.2", "--xyz", "0",
          "0", "0.55"], "text", []),
        (["ik", robot, "--tip", n.tip, "--xyz", "0", "0", "5"], "text", []),
        (["ik", robot, "--tip", n.tip, "--targets", str(repo.targets)], "text", []),
        (["ik", robot, "--tip", n.tip, "--targets", str(repo.targets), "--format", "csv"],
         "csv", []),
        (["ik", robot, "--tip", n.tip, "--check-reach", str(repo.targets)], "text", []),
        (["ik", robot, "--tip", n.tip, "--target-frame", n.frame], "text", []),
        (["ik", robot, "--tip", unknown, "--xyz", "0", "0", "1"], "text", []),
        (["inertia", robot, "--all", "--write", str(out / "inertia.urdf")], "text",
         [out / "inertia.urdf"]),
        (["inertia", str(repo.xacro), "--all", "--write", str(out / "inertia.diff")], "text",
         []),
        (["inertia", robot, "--link", unknown], "text", []),
        (["inertia", robot, "--link", n.link], "text", []),
        (["dynamics", robot, "--q", f"{n.joint1}=0.5", "--v", f"{n.joint2}=1", "--samples",
          "5"], "text", []),
        (["dynamics", robot, "--support", n.base, "--plot", str(svg), "--samples", "3"], "text",
         [svg]),
        (["dynamics", robot, "--support", n.base, "--plot", str(png)], "text", [png]),
        (["dynamics", robot, "--support", unknown], "text", []),
        (["dynamics", str(repo.broken)], "text", []),
        (["collisions", plain, "--q", f"{n.joint2}=2.5", "--render", str(out / "pose.svg")],
         "text", [out / "pose.svg"]),
        (["collisions", plain, "--q", f"{unknown}=1"], "text", []),
        (["collisions", plain, "--matrix", "--samples", "100", "--all", "--plot",
          str(out / "matrix.svg"), "--write-srdf", str(out / "matrix.srdf"), "--check-srdf",
          str(repo.plain.with_suffix(".srdf"))], "text",
         [out / "matrix.svg", out / "matrix.srdf"]),
        (["collisions", plain, "--matrix", "--samples", "100", "--format", "json"], "json", []),
        (["render", str(repo.meshed), "--output", str(out / "meshed.svg")], "text",
         [out / "meshed.svg"]),
        (["render", robot, "--output", str(png), "--frames", "--axes", "--q", f"{n.joint1}=1"],
         "text", [png]),
        (["workspace", robot, "--tip", n.tip, "--base", n.link, "--q", f"{n.joint1}=0.3",
          "--samples", "50", "--plot", str(svg)], "text", [svg]),
        (["workspace", robot, "--tip", unknown], "text", []),
        (["diff", str(repo.old), plain, "--format", "markdown", "--render",
          str(out / "diff.svg"), "--output", str(out / "diff.md")], "text",
         [out / "diff.md", out / "diff.svg"]),
        (["diff", str(repo.old), plain, "--chain", f"{unknown}:x"], "text", []),
        *((["diff", str(repo.old), str(repo.root / "changed" / "robot.urdf"), "--format", fmt],
           fmt, []) for fmt in ("text", "json", "markdown")),
        (["diff", str(repo.broken), plain, "--format", "markdown"], "markdown", []),
        (["diff", str(repo.old), robot, "--format", "markdown", "--no-collisions"], "markdown",
         []),
        ([*["check", "--timeout", "x" + NAME_PAYLOADS["workflow"], robot]], "text", []),
        (["tree", unknown + ".urdf"], "text", []),
    ]
    runs += [Invocation([*argv, *limit], kind, writes) for argv, kind, writes in variants]
    for run in runs:
        if "--fix" in run.argv:
            run.checks.append(Path(run.argv[1]))
    return runs


def uncovered(runs: list[Invocation]) -> list[str]:
    """Commands, formats and options no invocation tries and NOT_OUTPUT does not explain."""
    missing = []
    used = {(run.argv[0], word) for run in runs for word in run.argv[1:]}
    for name in commands():
        if name in NO_ROBOT:
            continue
        if not any(run.argv[0] == name for run in runs):
            missing.append(f"command {name}")
        for fmt in formats_of(name) or ():
            if not any(run.argv[0] == name and fmt in run.argv for run in runs):
                missing.append(f"{name} --format {fmt}")
        for option, param in command_options(name).items():
            if not option.startswith("-") or option in NOT_OUTPUT:
                continue
            spellings = set(param.opts) | set(getattr(param, "secondary_opts", []))
            if not any((name, spelling) in used for spelling in spellings):
                missing.append(f"{name} {option}")
    return missing


# ---------------------------------------------------------------- the judge

_WORKFLOW = re.compile(r"::(error|warning|notice) file=[^:,]*(,line=\d+)?(,col=\d+)?,"
                       r"title=[^:,]*::\S.*")
_RAW_HTML = re.compile(r"<[A-Za-z/!?]")


def _controls(text: str, allowed: str = "\n") -> list[str]:
    return sorted({repr(c) for c in text if unicodedata.category(c) in ("Cc", "Cf", "Cs", "Zl", "Zp")
                   and c not in allowed})


# How a line starts when a name's line break split one of ours (the name's text went on on a
# line of its own, its '::' escaped by the last guard, or a heading or verdict of the payloads)
SPLIT = ("\\x3a", "## All checks passed", "# HEADING")


def terminal(text: str, where: str, github: bool = False) -> list[str]:
    """What is forged in text shown in a terminal or a CI log: a raw control, format or
    separator character, a line GitHub reads as a workflow command (``::`` after blanks), rich
    markup or an emoji code that was interpreted."""
    found = []
    controls = _controls(text)
    if controls:
        found.append(f"{where}: raw control or format characters {', '.join(controls[:8])}")
    for line in text.split("\n"):
        start = line.lstrip()
        if start.startswith("::") and not (github and _WORKFLOW.fullmatch(line)):
            found.append(f"{where}: a line GitHub reads as a workflow command: {line[:120]!r}")
        elif start.startswith(SPLIT):
            found.append(f"{where}: a line a name started: {line[:120]!r}")
    for match in re.finditer("RICH(MARK|LINK)", text):
        before = text[max(0, match.start() - 40):match.start()]
        # the tag as written (escaped, percent-encoded in a URI, or a name made an identifier:
        # bold_red_RICHMARK; SARIF's escaped bracket, its backslash doubled by JSON: \\]), not
        # eaten
        if not re.search(r"(bold[ _]red|bold|link[=_]https[:/_]+evil[._]example)"
                         r"((\\\\)?\]|%5D|_+)$", before):
            found.append(f"{where}: rich markup around {match.group()} was interpreted")
            break
    if "\U0001f44d" in text:
        found.append(f"{where}: an emoji code was interpreted")
    return found


def markdown(text: str, where: str) -> list[str]:
    """Markdown (a pull-request comment, a job summary): every payload marker inside code,
    no heading but ours, no image, link or raw HTML, table rows as wide as their header."""
    from markdown_it import MarkdownIt

    found = terminal(text, where)
    tokens = MarkdownIt("commonmark").enable("table").parse(text)
    headings = 0
    for token in tokens:
        if token.type == "heading_open":
            headings += 1
        if token.type in ("html_block",):
            found.append(f"{where}: raw HTML block {token.content[:80]!r}")
        for child in token.children or ():
            if child.type in ("image", "html_inline", "link_open"):
                found.append(f"{where}: Markdown {child.type} {child.content[:80]!r}")
            if child.type == "text":
                hits = [m for m in MARKERS if m in child.content]
                if hits or _RAW_HTML.search(child.content):
                    found.append(f"{where}: payload outside code: {child.content[:80]!r}")
    if headings > 1:
        found.append(f"{where}: {headings} headings (ours is one)")
    widths = {}
    for line in text.split("\n"):
        if line.startswith("|"):
            cells = len(re.findall(r"(?<!\\)\|", line))
            widths.setdefault("header", cells)
            if cells != widths["header"]:
                found.append(f"{where}: a table row of {cells - 1} cells: {line[:80]!r}")
        else:
            widths.clear()
    return found


def xml_document(data: bytes, where: str, allowed: set[str] | None) -> list[str]:
    """XML that parses, whose elements are all expected, with no event attribute, script link
    or control character in any text."""
    from lxml import etree

    try:
        root = etree.fromstring(data, etree.XMLParser(resolve_entities=False, no_network=True))
    except etree.XMLSyntaxError as error:
        return [f"{where}: does not parse: {error}"]
    found = []
    for element in root.iter():
        if not isinstance(element.tag, str):
            continue
        tag = etree.QName(element).localname
        if allowed is not None and tag not in allowed:
            found.append(f"{where}: unexpected element <{tag}>")
        for key, value in element.attrib.items() if allowed is not None else ():
            local = etree.QName(key).localname
            if local.lower().startswith("on") or local == "href" and "javascript:" in value:
                found.append(f"{where}: <{tag} {local}={value[:60]!r}>")
            if _controls(value, allowed=""):
                found.append(f"{where}: control characters in <{tag} {local}>")
        for text in (element.text, element.tail):
            if text and tag in ("failure", "system-out", "title", "text"):
                found += terminal(text, f"{where} <{tag}>")
    return found


SVG_ELEMENTS = {"svg", "rect", "g", "title", "polygon", "circle", "line", "text", "path",
                "ellipse", "polyline", "defs", "a", "desc"}
JUNIT_ELEMENTS = {"testsuites", "testsuite", "testcase", "failure", "system-out", "error",
                  "skipped", "properties", "property", "system-err"}


def dot(text: str, where: str) -> list[str]:
    found = terminal(text, where)
    quoted = r'"(?:[^"\\]|\\.)*"'
    statement = re.compile(rf"  {quoted}( -> {quoted})?( \[\w+={quoted}(, \w+={quoted})*\])?;$")
    for line in text.split("\n")[4:]:
        if line and line != "}" and not statement.match(line):
            found.append(f"{where}: a DOT line not of ours: {line[:100]!r}")
    return found


def csv_text(text: str, where: str) -> list[str]:
    found = terminal(text, where)
    rows = list(csv.reader(io.StringIO(text)))
    if len(rows) != len(text.splitlines()):
        found.append(f"{where}: a CSV cell holds a line break")
    for row in rows:
        for cell in row:
            if cell[:1] in ("=", "+", "-", "@"):
                try:
                    float(cell)
                except ValueError:
                    found.append(f"{where}: a cell a spreadsheet runs as a formula: {cell[:40]!r}")
    return found


def file_written(path: Path, code: int = 0) -> list[str]:
    """What is forged in a file a command wrote; ``code``: its exit status (2, a usage error:
    a name the command line could not give, nothing to write)."""
    where = path.name
    if not path.exists():
        return [] if code == 2 else [f"{where}: was not written"]
    data = path.read_bytes()
    suffix = path.suffix.lower()
    if suffix == ".svg":
        return xml_document(data, where, SVG_ELEMENTS)
    if suffix in (".xml",):
        return xml_document(data, where, JUNIT_ELEMENTS)
    if suffix in (".urdf", ".srdf"):
        return xml_document(data, where, None)
    if suffix in (".sarif", ".json"):
        try:
            strict_json(data)
        except ValueError as error:
            return [f"{where}: not JSON: {error}"]
        return terminal(data.decode(), where) + unpaired(data.decode(), where)
    if suffix == ".png":
        return [] if data.startswith(b"\x89PNG") else [f"{where}: not a PNG"]
    if suffix == ".md":
        return markdown(data.decode(), where)
    if suffix == ".dot":
        return dot(data.decode(), where)
    return terminal(data.decode("utf-8", "replace"), where)


def strict_json(text):
    """JSON read as RFC 8259 defines it: ``NaN``, ``Infinity`` and ``-Infinity`` (which
    Python's reader takes and writes) are refused, as every other reader refuses them
    (session 9: `inertia -f json` of a robot of infinite mass wrote them)."""
    def refuse(word):
        raise ValueError(f"{word} is no JSON")

    return json.loads(text, parse_constant=refuse)


_UNPAIRED = re.compile(r"(?<!\\)((?:\\\\)*)\\u(d[89ab][0-9a-f]{2})(?!\\ud[c-f])"
                       r"|(?<!\\)((?:\\\\)*)(?<!\\ud[89ab][0-9a-f]{2})\\u(d[c-f][0-9a-f]{2})",
                       re.IGNORECASE)


def unpaired(text: str, where: str) -> list[str]:
    """JSON holding an unpaired surrogate escape (``"\\ud800"``): JSON's grammar allows it, but
    no strict reader (I-JSON, RFC 7493: SARIF uploads, serde, Go) takes it."""
    found = _UNPAIRED.search(text)
    return [f"{where}: an unpaired surrogate in JSON: {text[found.start():found.end() + 20]!r}"] \
        if found else []


def _exact(data, where: str) -> list[str]:
    """JSON keeps the names exact: a string holding a payload holds it as it was, not escaped
    for a terminal (``\\n`` for a line break)."""
    if isinstance(data, dict):
        return [problem for item in data.items() for part in item for problem in
                _exact(part, where)]
    if isinstance(data, list):
        return [problem for item in data for problem in _exact(item, where)]
    if isinstance(data, str) and "\\n::add-mask::SECRET" in data:
        return [f"{where}: a name escaped in JSON (it stays exact): {data[:80]!r}"]
    return []


def names_kept(path: Path, n: Names) -> list[str]:
    """A robot file a fix rewrote: still well formed, every hostile link name in it as it was
    (a name a fix wrote unescaped breaks the file or becomes another name)."""
    from lxml import etree

    try:
        root = etree.fromstring(path.read_bytes())
    except etree.XMLSyntaxError as error:
        return [f"{path.name}: a fix left it malformed: {error}"]
    links = {link.get("name") for link in root.iter("link")}
    lost = [name[:20] for name in (n.base, n.link, n.tip, n.frame) if name not in links]
    return [f"{path.name}: a fix changed link names {lost!r}"] if lost else []


def judge(kind: str, stdout: str, stderr: str, where: str) -> list[str]:
    """What is forged in a command's standard output (of ``kind``) and standard error."""
    found = terminal(stderr, f"{where} (stderr)")
    out = f"{where} (stdout)"
    if kind in ("json", "json-lines", "rdjson"):
        for document in ([stdout] if kind != "json-lines" and stdout else stdout.splitlines()):
            try:
                data = strict_json(document)
            except ValueError as error:
                found.append(f"{out}: not JSON: {error}")
                continue
            if kind == "rdjson":  # reviewdog posts each message as Markdown, not as data
                for diagnostic in data.get("diagnostics", []):
                    found += markdown(diagnostic.pop("message"), f"{out} message")
            found += _exact(data, out)
        found += terminal(stdout, out) + unpaired(stdout, out)
    elif kind == "junit":
        found += xml_document(stdout.encode(), out, JUNIT_ELEMENTS)
    elif kind == "github":
        found += terminal(stdout, out, github=True)
    elif kind == "markdown":
        found += markdown(stdout, out)
    elif kind == "csv":
        found += csv_text(stdout, out)
    elif kind == "yaml":
        import yaml

        try:
            yaml.safe_load(stdout)
        except yaml.YAMLError as error:
            found.append(f"{out}: not YAML: {error}")
        found += terminal(stdout, out)
    elif kind == "dot":
        found += dot(stdout, out)
    else:
        found += terminal(stdout, out)
    return found


def run_in_process(argv: list[str], cwd: Path) -> tuple[int, str, str]:
    """``urdftool ARGV`` in this process (click's runner), in ``cwd``; (exit code, stdout,
    stderr). A traceback is a finding of its own: it is returned in stderr."""
    import traceback

    from typer.testing import CliRunner

    from urdftool.cli import app

    runner = CliRunner()
    previous = os.getcwd()
    os.chdir(cwd)
    try:
        result = runner.invoke(app, argv, env={"COLUMNS": "120", "NO_COLOR": "1", "TERM": "dumb",
                                               "GITHUB_ACTIONS": "", "CI": ""})
    finally:
        os.chdir(previous)
    stderr = result.stderr
    if result.exception is not None and not isinstance(result.exception, SystemExit):
        stderr += "".join(traceback.format_exception(result.exception))
    return result.exit_code, result.stdout, stderr
