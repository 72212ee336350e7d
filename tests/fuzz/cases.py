"""Whole-repository fuzz cases: a mutated robot in a throw-away repository, run through every
command.

A :class:`Case` is a seed robot, the bytes that replace it, and what else the hostile repository
holds: extra files (YAML bombs, crafted meshes, sparse giant files for the folder walk), symbolic
links (out of the repository: in the walk, as a package folder for ``$(find)``, as an include,
as a mesh, at an output path), a settings file (``urdftool.toml`` or ``[tool.urdftool]`` naming
/etc/passwd, /dev/zero, ``../..``; every key of the settings, limits raised, nesting too deep),
include patterns reaching outside, a real git repository with a bare repository committed in the
robot's folder or a hostile ``.git/config`` (``diff --rev``; git is traced with strace), and how
output paths are given (plain, a symbolic link to a file outside, a missing folder, a folder, a
folder that is a link leading outside, ``..`` after such a link). :func:`case_strategy` draws
them; :func:`materialize` writes one under a temporary folder::

    <tmp>/repo/       the case's repository (has .git): the robot, settings, links
    <tmp>/outside/    files the repository must not reach: secret.xacro, evil_pkg/, victim.txt
    <tmp>/scratch/    the children's temporary files and output captures; markers/ (what a
                      planted git config runs writes there), bin/git (git under strace)

A bundled robot (robots/NAME) is copied into ``repo/NAME``; a corpus robot is fed on stdin with
its own folder as the working directory (so its includes resolve), and only the hostile
additions that need no copy of its repository apply to it. The corpus is laid out as one ROS
workspace (packages find their siblings), so for a corpus robot the whole corpus may be read.
"""

from __future__ import annotations

import base64
import os
import re
import shutil
import tempfile
import zipfile
from dataclasses import dataclass, field
from pathlib import Path

from hypothesis import strategies as st

from .child import SECRET_NAME
from .mutate import CORPUS, MESHES, ROOT, Seed, byte_mutation, mesh_mutation, tree_mutation

XACRO_NS = "http://www.ros.org/wiki/xacro"
OUTSIDE = "<outside>"  # replaced by the case's outside folder when materialized
SECRET_LINK = "OUTSIDE_SECRET_LINK"

# $(eval ...) payloads; ${l} and ${r} are properties holding "(" and ")" (the trick:
# ${} is expanded inside $() before the $( lexer looks for its closing parenthesis).
EVAL_PAYLOADS = [
    "$(eval exec('open(\"PWNED_exec\",\"w\"${r}.write(\"x\"${r}'${r})",
    "$(eval __import__${l}'os'${r}.system${l}'touch PWNED_system'${r})",
    "$(eval __import__${l}'subprocess'${r}.run${l}['touch','PWNED_run']${r})",
    "$(eval open${l}'/etc/passwd'${r}.read${l}${r})",
    "$(eval open${l}'PWNED_open','w'${r})",
    "$(eval env${l}'" + SECRET_NAME + "'${r})",
    "$(eval optenv${l}'" + SECRET_NAME + "','none'${r})",
    "$(eval xacro.load_yaml${l}'/etc/passwd'${r})",
    "$(eval str${l}[c.__name__ for c in ().__class__.__base__.__subclasses__${l}${r}][:3]${r})",
    "$(eval 'a'*10**9)",
    "$(eval [0]*10**9)",
    "$(env " + SECRET_NAME + ")",
    "$(optenv " + SECRET_NAME + " none)",
]
# ${...} reaching the evaluator from other entry points, and size/time bombs.
EXPRESSION_PAYLOADS = [
    "${xacro.load_yaml.__globals__['__builtins__']['open']('/etc/passwd').read()}",
    "${xacro.dotify({}).__class__.__init__.__globals__}",
    "${[c for c in ().__class__.__base__.__subclasses__() if c.__name__ == 'Popen']}",
    "${['a'*999999]*999999}",
    "${len([[0]*1000 for i in range(10**6)])}",
    "${len([i for i in range(10**6) for j in range(10**6)])}",
    "${'%02000000000d' % 0}",
    "${'x'.ljust(3000000000)}",
    "${'x'.zfill(3000000000)}",
    "${'x'.center(3000000000)}",
    "${len(str(factorial(10**7)))}",
    "${10**10**8}",
    "${'a' * 10**8 + 'b' * 10**8}",
]
# names that try to forge report lines (text and GitHub formats)
FORGED_NAMES = ["x&#10;::error file=robot.urdf,line=1::forged&#10;"
                "1 file checked: no problems found",
                "x&#13;1 file checked: no problems found&#10;", "x&#27;[2J&#10;::warning::y"]
SETTINGS_VALUES = ["/etc/passwd", "/dev/zero", "../../../../../../../../etc/passwd",
                   OUTSIDE + "/limits.yaml", "zero_link", "passwd_link", "/proc/self/environ",
                   "", ".", ".."]
SETTINGS_KEYS = ["spec", "srdf", "controllers", "packages"]
# every key of the settings (urdftool.lint.settings.KEYS) with values naming outside paths,
# limits raised above the built-in ones, and nesting past the depth read
OUTSIDE_TEXTS = ["/etc/passwd", OUTSIDE + "/secret.xacro", "../../../../../../etc/passwd",
                 "~/.ssh/id_rsa", "file:///etc/passwd", "C:\\Windows", "..", "a/../../.."]
SETTINGS_ANY_KEY = {
    "select": 'select = ["{v}"]\n', "ignore": 'ignore = ["{v}"]\n',
    "per-file-ignores": '[per-file-ignores]\n"{v}" = ["U2"]\n',
    "per-file-args": '[per-file-args]\n"*" = {{ cfg = "{v}", inc = "{v}" }}\n',
    "packages": '[packages]\nevil_pkg = "{v}"\n', "spec": 'spec = "{v}"\n',
    "srdf": 'srdf = "{v}"\n', "controllers": 'controllers = ["{v}"]\n',
    "strict": '"{v}" = true\n', "max-file-size": 'max-file-size = "{v}"\n',
    "max-memory": 'max-memory = "{v}"\n', "targets": 'targets = ["{v}"]\n',
}
RAISED_LIMITS = ["max-file-size = 16777217", "max-file-size = 1099511627776",
                 'max-memory = "0"', "max-memory = 0", 'max-memory = "64G"',
                 'max-memory = "2049M"']
DEEP_SETTINGS = ["a = " + "[" * 3000 + "]" * 3000, "a" + ".a" * 100_000 + " = 1",
                 "[" + "a." * 50_000 + "a]", "x = " + "{a = " * 2000 + "1" + "}" * 2000]
# the robot reads what per-file-args name (an include and a YAML), so an argument that became
# a readable root would show the outside file's content
ARG_READER = ('\n  <xacro:arg name="cfg" default="none.yaml"/><xacro:arg name="inc" '
              'default="none.xacro"/>\n  <xacro:include filename="$(arg inc)" optional="true"/>'
              '\n  <xacro:property name="y" value="${xacro.load_yaml(\'$(arg cfg)\')}"/>\n')
# include patterns that reach outside: directly, through a linked folder, climbing after a
# wildcard, through a package that is a link; "linkdir" and "parts/evil" lead to <outside>
GLOB_PATTERNS = [OUTSIDE + "/*.xacro", OUTSIDE + "/*", "linkdir/*.xacro", "linkdir/*",
                 "parts/*/*.xacro", "parts/*/*", "parts/*/../../linkdir/*.xacro",
                 "../../*/*.xacro", "../*/../../outside/*", "../../outside/*.xacro",
                 "$(find evil_pkg)/*.xacro",
                 "/etc/*", "/*/*.xacro", "parts/[ge]*/*.xacro"]
GIT_VARIANTS = ["embedded", "config", "partial", "environment", "gitfile", "include"]
OUTPUT_MODES = ["plain", "symlink", "missing", "folder", "dangling", "linked_folder",
                "linked_dotdot"]
CORPUS_KINDS = ["plain", "eval", "expression", "output", "forge"]
REPO_KINDS = CORPUS_KINDS + ["settings", "symlink", "walk", "yaml", "mesh_bomb", "git", "glob"]


@dataclass
class Case:
    seed: Seed
    data: bytes
    kind: str = "plain"
    files: dict[str, bytes] = field(default_factory=dict)  # repo-relative path -> content
    sparse: dict[str, int] = field(default_factory=dict)  # repo-relative path -> size [bytes]
    links: dict[str, str] = field(default_factory=dict)  # repo-relative path -> link target
    generated: dict[str, str] = field(default_factory=dict)  # repo-relative path -> GENERATORS key
    output: str = "plain"
    commands: tuple[str, ...] | None = None  # None: all
    git: str = ""  # a GIT_VARIANTS entry: the repository is a real one (diff --rev)
    forbidden: tuple[str, ...] = ()  # text no command may print (names found outside)
    expect: str = ""  # text every check command must print (a settings file refused)

    @property
    def bundled(self) -> bool:
        return ROOT / "robots" in self.seed.path.resolve().parents

    def to_json(self) -> dict:
        return {"kind": self.kind, "output": self.output, "commands": self.commands,
                "files": {k: base64.b64encode(v).decode() for k, v in self.files.items()},
                "sparse": self.sparse, "links": self.links, "generated": self.generated,
                "git": self.git, "forbidden": list(self.forbidden), "expect": self.expect}

    @classmethod
    def from_json(cls, seed: Seed, data: bytes, meta: dict) -> "Case":
        return cls(seed, data, meta["kind"], {k: base64.b64decode(v) for k, v in
                                              meta["files"].items()},
                   meta["sparse"], meta["links"], meta.get("generated", {}), meta["output"],
                   tuple(meta["commands"]) if meta.get("commands") else None,
                   meta.get("git", ""), tuple(meta.get("forbidden", ())),
                   meta.get("expect", ""))


@dataclass
class Layout:
    """Where a materialized case lives, and how commands name the robot."""

    top: Path
    repo: Path
    outside: Path
    scratch: Path
    cwd: Path
    robot: str  # the path commands get ("-" for stdin)
    stdin: bytes | None
    reads: list[Path]  # folders outside ``repo`` that may be read (a corpus seed's repository)

    def output(self, mode: str, name: str) -> str:
        """An output path in ``mode`` (planted by :func:`materialize`)."""
        folder = self.repo / "out"
        if mode == "linked_dotdot":  # out/linked leads outside: out/linked/sub/.. is there
            return f"{(folder / 'linked' / 'sub').as_posix()}/../{name}"
        return {"plain": folder / name, "symlink": folder / f"link-{name}",
                "dangling": folder / f"dangling-{name}",
                "missing": self.repo / "no" / "such" / name,
                "folder": folder, "linked_folder": folder / "linked" / name}[mode].as_posix()


def materialize(case: Case) -> Layout:
    top = Path(tempfile.mkdtemp(prefix="urdffuzz-"))
    repo, outside, scratch = top / "repo", top / "outside", top / "scratch"
    for folder in (repo / ".git", repo / "out", outside / "evil_pkg", scratch):
        folder.mkdir(parents=True)
    _plant_outside(outside)
    if case.bundled:
        name = case.seed.path.parent.name
        shutil.copytree(case.seed.path.parent, repo / name)
        robot_file = repo / name / case.seed.path.name
        robot_file.write_bytes(case.data.replace(OUTSIDE.encode(), str(outside).encode()))
        layout = Layout(top, repo, outside, scratch, repo, robot_file.relative_to(repo).as_posix(),
                        None, [])
    else:
        layout = Layout(top, repo, outside, scratch, case.seed.path.parent, "-", case.data,
                        [CORPUS] + [Path(v) for v in case.seed.args.values() if os.path.isabs(v)])
    for relative, content in case.files.items():
        target = repo / relative
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_bytes(content.replace(OUTSIDE.encode(), str(outside).encode()))
    for relative, recipe in case.generated.items():
        target = repo / relative
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_bytes(GENERATORS[recipe]())
    for relative, size in case.sparse.items():
        target = repo / relative
        target.parent.mkdir(parents=True, exist_ok=True)
        with open(target, "wb") as handle:
            handle.write(b'<robot name="big">\n')
            handle.truncate(size)
    for relative, target in case.links.items():
        where = repo / relative
        where.parent.mkdir(parents=True, exist_ok=True)
        if where.is_symlink() or where.exists():  # the link replaces a file of the seed
            where.unlink()
        os.symlink(target.replace(OUTSIDE, str(outside)), where)
    for name in OUTPUT_NAMES:
        if case.output == "symlink":
            os.symlink(outside / "victim.txt", repo / "out" / f"link-{name}")
        elif case.output == "dangling":
            os.symlink(outside / "nowhere" / name, repo / "out" / f"dangling-{name}")
    if case.output in ("linked_folder", "linked_dotdot"):
        (outside / "outdir" / "sub").mkdir(parents=True)
        os.symlink(outside / "outdir", repo / "out" / "linked")
    if case.git:
        _make_git(case, layout)
    return layout


OUTPUT_NAMES = ("report.json", "robot.urdf", "graph.dot", "inertia.urdf", "diff.json",
                "render.svg")
GIT_WRAPPER = """#!/bin/sh
# git as urdftool starts it, traced: every file it opens and every program it starts (without
# strace, untraced: the markers a planted configuration writes still tell what ran)
command -v strace >/dev/null || exec {git} "$@"
exec strace -f -qq -e trace=openat,open,creat,execve,rename,unlink,mkdir \\
    -o "$URDFFUZZ_STRACE.$$" {git} "$@"
"""


def _make_git(case: Case, layout: Layout) -> None:
    """Make the case's repository a real one (everything committed), then plant what the
    variant says; git as urdftool starts it goes through scratch/bin/git, traced by strace."""
    from tests.hostile_git import (config, embed_bare_repository, git, hooks, including,
                                   make_partial)

    markers = layout.scratch / "markers"
    markers.mkdir()
    hooks(markers)
    shutil.rmtree(layout.repo / ".git")
    (layout.repo / ".gitattributes").write_text("* filter=evil diff=evil merge=evil\n")
    git(layout.repo, "init", "-q")
    git(layout.repo, "add", "-A")
    git(layout.repo, "commit", "-qm", "robot")
    robot_dir = layout.repo / Path(layout.robot).parent
    variant = case.git
    if variant in ("embedded", "environment") and (robot_dir / "config").exists():
        variant = "gitfile"  # the robot's folder has a config/ of its own
    if variant in ("embedded", "environment"):
        embed_bare_repository(robot_dir, markers)
        git(layout.repo, "add", "-f", "-A")
        git(layout.repo, "commit", "-qm", "a repository in the robot's folder")
    if variant == "gitfile":  # an unpacked archive: a .git file in the robot's folder naming
        (layout.repo / "hostile.git").mkdir()  # a hostile repository (git refuses to commit it)
        embed_bare_repository(layout.repo / "hostile.git", markers)
        (robot_dir / ".git").write_text("gitdir: ../hostile.git\n")
    if case.git == "partial":  # committed before the config below names its filter
        (layout.repo / "other.urdf").write_text("<robot name='o'/>\n")
        git(layout.repo, "add", "other.urdf")
        git(layout.repo, "commit", "-qm", "another")
        make_partial(layout.repo, "other.urdf")
    if case.git == "include":  # the config includes a file outside: git would read it
        (layout.outside / "outside.gitconfig").write_text(config(markers))
        with open(layout.repo / ".git" / "config", "a") as handle:
            handle.write(including(layout.outside / "outside.gitconfig"))
    if case.git in ("config", "partial", "environment"):
        text = config(markers)
        if case.git != "partial":
            text = text.replace("[extensions]\n\tpartialClone = origin\n", "")
        with open(layout.repo / ".git" / "config", "a") as handle:
            handle.write(text)
    wrapper = layout.scratch / "bin" / "git"
    wrapper.parent.mkdir()
    wrapper.write_text(GIT_WRAPPER.format(git=shutil.which("git") or "/usr/bin/git"))
    wrapper.chmod(0o755)


def git_environment(case: Case, layout: Layout) -> dict[str, str]:
    """What the children's environment needs for a git case: the traced git first on PATH,
    and (the "environment" variant) the caller's GIT_* variables pointing git elsewhere."""
    if not case.git:
        return {}
    found = {"PATH": f"{layout.scratch / 'bin'}{os.pathsep}{os.environ.get('PATH', '')}",
             "URDFFUZZ_STRACE": str(layout.scratch / "strace")}
    if case.git == "environment":
        robot_dir = layout.repo / Path(layout.robot).parent
        found.update(GIT_DIR=str(robot_dir), GIT_WORK_TREE=str(robot_dir),
                     GIT_EXTERNAL_DIFF=f"touch {layout.scratch / 'markers'}/GIT_EXTERNAL_DIFF",
                     GIT_CONFIG_PARAMETERS="'core.fsmonitor'='touch /dev/null'")
    return found


def _plant_outside(outside: Path) -> None:
    (outside / "victim.txt").write_text("VICTIM\n")
    secret = (f'<?xml version="1.0"?>\n<robot xmlns:xacro="{XACRO_NS}">\n'
              f'  <xacro:macro name="secret"><link name="{SECRET_LINK}"/></xacro:macro>\n'
              f'  <link name="{SECRET_LINK}_2"/>\n</robot>\n')
    (outside / "secret.xacro").write_text(secret)
    (outside / "secret.urdf").write_text(f'<robot name="secret"><link name="{SECRET_LINK}"/>'
                                         '</robot>\n')
    (outside / "limits.yaml").write_text("joint_limits: {}\n")
    (outside / "evil_pkg" / "package.xml").write_text("<package><name>evil_pkg</name></package>\n")
    (outside / "evil_pkg" / "secret.xacro").write_text(secret)
    shutil.copy(MESHES / "box.stl", outside / "evil_pkg" / "box.stl")
    shutil.copy(MESHES / "box.stl", outside / "box.stl")


def cleanup(layout: Layout) -> None:
    shutil.rmtree(layout.top, ignore_errors=True)


def commands(case: Case, layout: Layout) -> dict[str, list[str]]:
    """The commands a case runs, by short name, as urdftool argv."""
    robot = layout.robot
    words = [robot, *(f"{k}:={v}" for k, v in case.seed.args.items())]
    out = case.output
    names = re.findall(rb'<link\s+name="([A-Za-z0-9_]+)"', case.data)
    base, tip = (names[0].decode(), names[-1].decode()) if names else ("base_link", "tool0")
    joints = re.findall(rb'<joint\s+name="([A-Za-z0-9_]+)"', case.data)
    pose = [f"{joints[-1].decode()}=0.3"] if joints else []
    limit = ("--timeout", "4")  # [s] per command: within the replay's time limit
    table = {
        "check": ["check", *words, "--no-env", "-j", "2", *limit, "-f", "json",
                  "-o", layout.output(out, "report.json")],
        "check-text": ["check", *words, "--no-env", *limit, "-f", "text"],
        "xacro": ["xacro", *limit, *words, "--no-env", "-o", layout.output(out, "robot.urdf")],
        "tree": ["tree", *limit, *words],
        "graph": ["graph", *limit, *words, "-o", layout.output(out, "graph.dot")],
        "fk": ["fk", *limit, *words, "--random", "2"],
        "dh": ["dh", *limit, *words, "--base", base, "--tip", tip],
        "inertia": ["inertia", *limit, *words, "--write", layout.output(out, "inertia.urdf")],
        "dynamics": ["dynamics", *limit, *words],
        "collisions": ["collisions", *limit, *words, *(w for q in pose for w in ("--q", q))],
        "fk-q": ["fk", *limit, *words, "--q-file", (layout.repo / "q_file").as_posix()],
        "diff-rev": ["diff", *limit, "--rev", "HEAD", *words, "--samples", "2",
                     "--no-collisions", "-f", "json", "-o", layout.output(out, "diff.json")],
        "render": ["render", *limit, *words, "-o", layout.output(out, "render.svg")],
    }
    if case.bundled:
        table["check-walk"] = ["check", ".", "--no-env", "-j", "2", *limit]
    chosen = case.commands or tuple(n for n in table if n not in ("fk-q", "diff-rev",
                                                                  "render"))
    return {name: table[name] for name in chosen if name in table}


# ---------------------------------------------------------------- strategies


def _insert_after_root(data: bytes, text: str, with_namespace: bool = True) -> bytes:
    """``text`` right after the root ``<robot ...>`` start tag (adding the xacro namespace)."""
    match = re.search(rb"<robot\b[^>]*?(/?)>", data)
    if not match:
        return data + text.encode()
    tag = match.group(0)
    if with_namespace and b"xmlns:xacro" not in tag:
        tag = tag.replace(b"<robot", f'<robot xmlns:xacro="{XACRO_NS}"'.encode(), 1)
    if match.group(1):  # <robot .../>: open it
        tag = tag[:-2] + b">"
        return data[:match.start()] + tag + text.encode() + b"</robot>" + data[match.end():]
    return data[:match.start()] + tag + text.encode() + data[match.end():]


def _attr(text: str) -> str:
    return (text.replace("&", "&amp;").replace('"', "&quot;").replace("<", "&lt;")
            .replace(">", "&gt;"))


PROPERTIES = ('\n  <xacro:property name="l" value="("/>\n  <xacro:property name="r" value=")"/>\n')


# Where xacro evaluates a payload (PAYLOAD is replaced): a link name, a property used later, a
# macro parameter default, xacro:element / xacro:attribute names, xacro:if, an arg default.
PLACES = {
    "link": '  <link name="PAYLOAD"/>\n',
    "property": '  <xacro:property name="p" value="PAYLOAD"/>\n  <link name="${p}"/>\n',
    "macro": ('  <xacro:macro name="m" params="a:=PAYLOAD"><link name="${a}"/></xacro:macro>\n'
              '  <xacro:m/>\n'),
    "element": '  <xacro:element xacro:name="PAYLOAD"/>\n',
    "attribute": '  <link name="x"><xacro:attribute name="PAYLOAD" value="1"/></link>\n',
    "if": '  <xacro:if value="PAYLOAD"><link name="y"/></xacro:if>\n',
    "arg": '  <xacro:arg name="z" default="PAYLOAD"/>\n  <link name="$(arg z)"/>\n',
}


@st.composite
def eval_text(draw, payloads: list[str]) -> str:
    """One of ``payloads`` in one of PLACES, after the ``l`` and ``r`` properties."""
    payload = _attr(draw(st.sampled_from(payloads)))
    return PROPERTIES + draw(st.sampled_from(sorted(PLACES.values()))).replace("PAYLOAD", payload)


def _bomb_yaml(kind: str) -> bytes:
    if kind == "anchors":  # 10**5 aliases of a 10,000-character string: 1 GB of characters
        lines = ["a: &a " + "x" * 10_000, "b: &b [" + ", ".join(["*a"] * 100) + "]",
                 "c: &c [" + ", ".join(["*b"] * 100) + "]",
                 "d: &d [" + ", ".join(["*c"] * 10) + "]"]
        return ("\n".join(lines) + "\n").encode()
    if kind == "deep":  # 50,000 levels
        return b"x: " + b"[" * 50_000 + b"]" * 50_000 + b"\n"
    if kind == "digits":  # past int()'s 4,300 digits: ValueError, not a YAMLError
        return b"x: " + b"9" * 5_000 + b"\ny: [1, -" + b"7" * 4_400 + b"]\n"
    return b"a: &a [" + b", ".join([b"*a"] * 3) + b"]\n"  # a recursive alias


def _zae_bomb() -> bytes:
    """A COLLADA zip (ZAE) whose one entry inflates to 1 GiB (1 MiB compressed)."""
    cache = Path(tempfile.gettempdir()) / "urdffuzz-zae-1g.dae"
    if not cache.is_file():
        partial = cache.with_suffix(f".{os.getpid()}")
        with zipfile.ZipFile(partial, "w", zipfile.ZIP_DEFLATED, compresslevel=9) as archive:
            with archive.open("model.dae", "w", force_zip64=True) as entry:
                entry.write(b'<?xml version="1.0"?><COLLADA xmlns="http://www.collada.org/'
                            b'2005/11/COLLADASchema" version="1.4.1">')
                chunk = b" " * (1 << 20)
                for _ in range(1024):
                    entry.write(chunk)
                entry.write(b"</COLLADA>")
        os.replace(partial, cache)
    return cache.read_bytes()


GENERATORS = {"zae": _zae_bomb}  # big files kept in regressions by name, made when needed


def _obj_fan(corners: int, separator: str) -> bytes:
    """An OBJ with 3 vertices and one face line of ``corners`` corners (a triangle fan)."""
    face = separator.join(str(1 + i % 3) for i in range(corners))
    return f"v 0 0 0\nv 1 0 0\nv 0 1 0\nf{separator}{face}\n".encode()


def _mesh_link(filename: str) -> str:
    return (f'\n  <link name="bomb"><collision><geometry><mesh filename="{filename}"/></geometry>'
            '</collision><visual><geometry><mesh filename="' + filename + '"/></geometry></visual>'
            '<inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" '
            'iyz="0"/></inertial></link>\n')


def _hostile_settings(draw, case: Case, data: bytes) -> None:
    """A settings file every check must refuse: any key naming a path outside, a limit raised
    above the built-in one, or nesting past what is read; the robot reads what per-file-args
    would give it."""
    how = draw(st.sampled_from(["outside", "raised", "deep"]))
    if how == "outside":
        key = draw(st.sampled_from(sorted(SETTINGS_ANY_KEY)))
        body = SETTINGS_ANY_KEY[key].format(v=draw(st.sampled_from(OUTSIDE_TEXTS)))
        if key == "per-file-args":
            case.data = _insert_after_root(data, ARG_READER)
    else:
        body = draw(st.sampled_from(RAISED_LIMITS if how == "raised" else DEEP_SETTINGS)) + "\n"
    if draw(st.booleans()):
        case.files["urdftool.toml"] = body.encode()
    else:
        body = body.replace("[per-file-ignores]", "[tool.urdftool.per-file-ignores]") \
            .replace("[per-file-args]", "[tool.urdftool.per-file-args]") \
            .replace("[packages]", "[tool.urdftool.packages]")
        if not body.startswith("[tool"):
            body = "[tool.urdftool]\n" + body
        case.files["pyproject.toml"] = body.encode()
    case.expect = "urdftool: error: "


@st.composite
def case_strategy(draw, seed_list: list[Seed], kinds: list[str] | None = None):
    """A :class:`Case` (see the module docstring)."""
    kind = draw(st.sampled_from(kinds or REPO_KINDS))
    pool = seed_list
    if kind not in CORPUS_KINDS:
        pool = [s for s in seed_list if (ROOT / "robots") in s.path.resolve().parents]
    seed = draw(st.sampled_from(pool))
    data = seed.path.read_bytes()
    case = Case(seed, data, kind)
    robot_dir = seed.path.parent.name  # bundled robots live in repo/<robot_dir>
    if kind == "plain":
        mutation = draw(st.sampled_from(["tree", "bytes", "mesh", "none"]))
        if mutation == "tree":
            case.data = draw(tree_mutation(data))
        elif mutation == "bytes":
            case.data = draw(byte_mutation(data))
        elif mutation == "mesh":
            case.data = draw(mesh_mutation(data, seed.path))
    elif kind == "eval":
        case.data = _insert_after_root(data, draw(eval_text(EVAL_PAYLOADS)))
    elif kind == "expression":
        case.data = _insert_after_root(data, draw(eval_text(EXPRESSION_PAYLOADS)))
    elif kind == "forge":
        name = draw(st.sampled_from(FORGED_NAMES))
        case.data = _insert_after_root(data, f'\n  <link name="{name}"/>\n  <joint name="{name}" '
                                             'type="fixed"><parent link="nowhere"/>'
                                             '<child link="nowhere2"/></joint>\n', False)
    elif kind == "settings" and draw(st.booleans()):
        _hostile_settings(draw, case, data)
    elif kind == "settings":
        key = draw(st.sampled_from(SETTINGS_KEYS + ["max-file-size"]))
        value = draw(st.sampled_from(SETTINGS_VALUES))
        if key == "packages":
            body = f'[packages]\nevil_pkg = "{value}"\n'
            case.data = _insert_after_root(data, '\n  <xacro:include filename="$(find evil_pkg)/'
                                                 'secret.xacro"/>\n')
        elif key == "controllers":
            body = f'controllers = ["{value}"]\n'
        elif key == "max-file-size":
            body = f"max-file-size = {draw(st.sampled_from(['-1', '0', '10**20', '1e400']))}\n"
            body = body.replace("10**20", str(10 ** 20))
        else:
            body = f'{key} = "{value}"\n'
        if draw(st.booleans()):
            case.files["urdftool.toml"] = body.encode()
        else:
            table = body.replace("[packages]", "[tool.urdftool.packages]")
            if not table.startswith("[tool"):
                table = "[tool.urdftool]\n" + table
            case.files["pyproject.toml"] = table.encode()
        case.links.update({"zero_link": "/dev/zero", "passwd_link": "/etc/passwd"})
    elif kind == "symlink":
        where = draw(st.sampled_from(["walk", "package", "include", "mesh", "companion", "robot"]))
        if where == "walk":
            case.links[draw(st.sampled_from(["evil.urdf", "deep/evil.urdf.xacro", "etc",
                                             "zero.urdf", "loop"]))] = draw(st.sampled_from(
                                                 [OUTSIDE + "/secret.urdf", "/etc", "/dev/zero",
                                                  ".", OUTSIDE]))
        elif where == "package":
            case.links["evil_pkg"] = OUTSIDE + "/evil_pkg"
            case.data = _insert_after_root(data, draw(st.sampled_from([
                '\n  <xacro:include filename="$(find evil_pkg)/secret.xacro"/>\n',
                _mesh_link("package://evil_pkg/box.stl")])))
        elif where == "include":
            case.links[f"{robot_dir}/inc.xacro"] = OUTSIDE + "/secret.xacro"
            case.data = _insert_after_root(data, '\n  <xacro:include filename="inc.xacro"/>\n'
                                                 '  <xacro:secret/>\n')
        elif where == "mesh":
            case.links[f"{robot_dir}/m.stl"] = draw(st.sampled_from([OUTSIDE + "/box.stl",
                                                                     "/dev/zero"]))
            case.data = _insert_after_root(data, _mesh_link("m.stl"))
        elif where == "companion":
            name = draw(st.sampled_from(["joint_limits.yaml", seed.path.name.split(".")[0]
                                         + ".srdf"]))
            case.links[f"{robot_dir}/{name}"] = draw(st.sampled_from(["/dev/zero", "/etc/passwd",
                                                                      OUTSIDE + "/limits.yaml"]))
        else:  # the folder walk meets a robot-named link to a secret robot outside
            case.links["other.urdf.xacro"] = OUTSIDE + "/secret.xacro"
    elif kind == "walk":
        count = draw(st.sampled_from([3, 20, 90]))
        size = draw(st.sampled_from([1 << 20, 15 << 20, 32 << 20]))
        suffix = draw(st.sampled_from([".urdf", ".urdf.xacro", ".xacro"]))
        case.sparse.update({f"big/f{i}{suffix}": size for i in range(count)})
        if draw(st.booleans()):
            deep = "/".join(["d"] * draw(st.sampled_from([50, 200])))
            case.files[f"{deep}/x.urdf"] = b'<robot name="x"><link name="a"/></robot>\n'
        case.commands = ("check-walk",)
    elif kind == "yaml":
        bomb = draw(st.sampled_from(["anchors", "deep", "recursive", "digits"]))
        target = draw(st.sampled_from(["load_yaml", "joint_limits.yaml", "controllers"]))
        if target == "load_yaml":
            case.files[f"{robot_dir}/bomb.yaml"] = _bomb_yaml(bomb)
            case.data = _insert_after_root(data, draw(st.sampled_from([
                '\n  <xacro:property name="y" value="${xacro.load_yaml(\'bomb.yaml\')}"/>\n'
                '  <link name="${str(y)[:20]}"/>\n',
                '\n  <xacro:property name="y" value="${xacro.load_yaml(\'bomb.yaml\')}"/>\n'
                '  <link name="${len(str(y))}"/>\n'])))
        elif target == "joint_limits.yaml":
            case.files[f"{robot_dir}/joint_limits.yaml"] = _bomb_yaml(bomb)
        else:
            case.files[f"{robot_dir}/config/controllers.yaml"] = _bomb_yaml(bomb)
    elif kind == "mesh_bomb":
        bomb = draw(st.sampled_from(["zae", "obj_spaces", "obj_tabs", "q_file", "q_digits"]))
        if bomb == "zae":
            case.generated[f"{robot_dir}/bomb.dae"] = "zae"
            case.data = _insert_after_root(data, _mesh_link("bomb.dae"))
        elif bomb == "q_digits":  # JSON past int()'s digits, or nested past the recursion
            case.files["q_file"] = draw(st.sampled_from([
                b'[{"j": ' + b"9" * 5_000 + b"}]", b"[" * 100_000, b'{"j": -' + b"1" * 4_400 + b"}"]))
            case.commands = ("fk-q",)
        elif bomb == "q_file":
            case.links["q_file"] = draw(st.sampled_from(["/dev/zero", "/etc/passwd",
                                                         OUTSIDE + "/victim.txt"]))
            case.commands = ("fk-q",)
        else:
            corners = draw(st.sampled_from([200_000, 1_500_000]))
            case.files[f"{robot_dir}/fan.obj"] = _obj_fan(corners, "\t" if bomb == "obj_tabs"
                                                          else " ")
            case.data = _insert_after_root(data, _mesh_link("fan.obj"))
    elif kind == "git":
        case.git = draw(st.sampled_from(GIT_VARIANTS))
        case.commands = ("diff-rev",)
    elif kind == "glob":
        pattern = draw(st.sampled_from(GLOB_PATTERNS))
        case.links.update({f"{robot_dir}/linkdir": OUTSIDE, f"{robot_dir}/parts/evil": OUTSIDE,
                           "evil_pkg": OUTSIDE + "/evil_pkg"})
        case.files[f"{robot_dir}/parts/good/ok.xacro"] = (
            f'<robot xmlns:xacro="{XACRO_NS}"><xacro:macro name="ok"/></robot>\n').encode()
        case.data = _insert_after_root(data, f'\n  <xacro:include filename="{_attr(pattern)}"/>\n')
        case.forbidden = ("secret.xacro", "secret.urdf", "victim.txt", "limits.yaml",
                          "box.stl")
        case.commands = ("check", "check-text", "xacro")  # --no-env: outside is refused
    elif kind == "output":
        case.output = draw(st.sampled_from(OUTPUT_MODES[1:]))
        case.commands = ("check", "xacro", "graph", "inertia", "render")
    if kind != "output" and draw(st.integers(0, 4)) == 0:
        case.output = draw(st.sampled_from(OUTPUT_MODES))
    return case
