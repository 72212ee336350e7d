"""Shared fixtures: the corpus location and its one shared run, CLI runner settings, check_urdf."""

from __future__ import annotations

import functools
import os
import re
import shutil
import subprocess
import sys
import sysconfig
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
ROBOTS = ROOT / "robots"
CASES = Path(__file__).resolve().parent / "cases"
CORPUS = Path(os.environ.get("URDFTOOL_CORPUS", ROOT.parent / "shared" / "corpus"))
# `urdftool check` keeps results in .urdftool_cache by default; a test that patches urdftool's
# internals must see them run, so the tests use the cache only where they name --cache-dir.
os.environ["URDFTOOL_NO_CACHE"] = "1"
# the tests run as on a developer's machine, in the full mode: under CI (CI=true, as a CI job
# runs the suite) every reader of robots, load() too, takes the safe mode
# (description.files.env_allowed); a test of the safe mode sets CI itself
os.environ.pop("CI", None)
# a message's repeated parts dropped by an f-string fail (urdftool.errors.Said), in the
# commands and workers the tests start too
os.environ["URDFTOOL_STRICT_MESSAGES"] = "1"
import urdftool.errors  # noqa: E402 (imported already when pytest loaded urdftool's plugin)

urdftool.errors.STRICT_MESSAGES = True


@functools.cache
def parsed(source: str):
    """``ast.parse(source)``, once per text and test process: a dozen tests walk every module
    of urdftool (all of them parsed: 1 s of CPU), each for its own rule. The tree is shared:
    read it, never change it."""
    import ast

    return ast.parse(source)


@functools.cache
def walked(source: str) -> tuple:
    """Every node of :func:`parsed`'s tree of ``source`` in ``ast.walk``'s order, once per text
    and test process: each of the dozen tests that walk every module of urdftool walked them
    all again (0.26 s of CPU; through the kept nodes 0.03 s). Read them, never change them."""
    import ast

    return tuple(ast.walk(parsed(source)))


def corpus_or_skip() -> Path:
    if not CORPUS.is_dir():
        pytest.skip(f"corpus not found at {CORPUS}")
    return CORPUS


def load_text(folder: Path, text: str, name: str = "robot.urdf"):
    """The robot ``text`` written to ``folder`` (made the root of a repository, where relative
    meshes may be) and loaded."""
    from urdftool.description.load import load

    (folder / ".git").mkdir(parents=True, exist_ok=True)
    (folder / name).write_text(text)
    return load(folder / name)


@pytest.fixture
def corpus() -> Path:
    return corpus_or_skip()


@pytest.fixture(scope="session")
def analysis_imported():
    """The analysis commands' libraries imported once in this test process: a command runs
    in a worker forked from it (its budget), which would otherwise import them again for
    every command a test runs (1-3 s of CPU each)."""
    import importlib

    for name in ("numpy", "lxml.etree", "rich.console", "rich.table", "trimesh", "PIL.Image",
                 "pinocchio", "fcl", "yourdfpy", "urdftool.lint.engine",
                 "urdftool.kinematics.fk", "urdftool.kinematics.scene", "urdftool.report.picture"):
        try:
            importlib.import_module(name)
        except ImportError:  # a lint-only install: the test says what is missing
            pass


def one_piece_here(monkeypatch) -> None:
    """A budgeted command of one piece (one file checked, one robot analysed) done in this
    process, as ``--timeout 0 --max-memory 0`` does it, not in a worker forked from the test
    process: the fork of a pytest worker (hundreds of MB mapped) and its exit cost 0.05-0.1 s
    of CPU, most of it system time, for each of about 2,000 commands the tests run, and prove
    nothing the test is about. A MemoryError is still the budget's Stop (``pool._here``). The
    tests of budgets, and one command of each kind (test_cli, ``@pytest.mark.worker``), keep
    the forked worker; tests/lint/test_pool.py and test_budgets.py test it."""
    from urdftool.lint import pool

    forked = pool._run_pool

    def run_pool(work, queue, jobs, budget, stopped, results, finished, cancel=None):
        if len(queue) != 1 or cancel is not None:
            return forked(work, queue, jobs, budget, stopped, results, finished, cancel)
        [index] = queue
        results[index] = pool._here(index, work, budget, stopped)
        finished(1)
        return None

    monkeypatch.setattr(pool, "_run_pool", run_pool)


@pytest.fixture
def run_cli(analysis_imported, request, monkeypatch):
    """Invoke the CLI in-process with a fixed width and no colour; returns the Result. A
    command of one piece runs in this process too (:func:`one_piece_here`), unless the test
    is marked ``worker`` (what it proves needs the forked worker: a budget, a death)."""
    from typer.testing import CliRunner

    from urdftool.cli import app

    runner = CliRunner()
    forked = request.node.get_closest_marker("worker") is not None

    def run(*args, input=None):
        with monkeypatch.context() as patches:
            if not forked:
                one_piece_here(patches)
            return runner.invoke(app, [str(a) for a in args], input=input,
                                 env={"COLUMNS": "120", "NO_COLOR": "1", "TERM": "dumb",
                                      "GITHUB_ACTIONS": "", "CI": ""})  # CI: the full mode

    return run


def corpus_entry_points() -> list[tuple[str, dict[str, str]]]:
    """Every corpus robot: (path relative to the corpus, xacro args) — the plain URDFs and the
    xacro entry points with the args CHECKS.tsv records (``<corpus>`` replaced)."""
    if not CORPUS.is_dir():
        return []
    entries = []
    for line in (CORPUS / "MANIFEST.tsv").read_text().splitlines()[1:]:
        columns = line.split("\t")
        if columns[4] == "urdf":
            entries.append((columns[0], {}))
    plain = {path for path, _ in entries}
    for line in (CORPUS / "CHECKS.tsv").read_text().splitlines()[1:]:
        columns = line.split("\t")
        if columns[1] != "xacro":
            continue
        args = corpus_args(columns[2])
        if args or columns[0] not in plain:  # sam_bot's .urdf is in both lists: once is enough
            entries.append((columns[0], args))
    return entries


def corpus_args(text: str) -> dict[str, str]:
    """The xacro args of a CHECKS.tsv row (``name:=value ...``), ``<corpus>`` replaced."""
    pairs = (word.partition(":=") for word in text.split())
    return {name: value.replace("<corpus>", str(CORPUS)) for name, _, value in pairs}


def entry_id(entry) -> str:
    path, args = entry
    return path + ("[" + ",".join(f"{k}={Path(v).name}" for k, v in sorted(args.items())) + "]"
                   if args else "")


@pytest.fixture(scope="session")
def corpus_run() -> dict[str, tuple[tuple[str, dict[str, str]], object]]:
    """Every corpus entry point checked once per session, as ``urdftool check`` checks it (one
    run: the corpus repository's launch files, packages and settings looked up once, not once
    per robot), with the loaded robot kept: ``{entry_id: (entry, FileResult)}``. The
    integration modules that need the corpus robots or their findings read them here instead
    of loading them again."""
    from urdftool.description.run_memo import one_run
    from urdftool.lint.engine import CheckOptions, load_and_check

    corpus_or_skip()
    with one_run():
        run = {entry_id(entry): (entry, load_and_check(str(CORPUS / entry[0]),
                                                   CheckOptions(xacro_args=entry[1])))
               for entry in corpus_entry_points()}
    lasting()  # the robots live as long as the session
    return run


MESH_SUFFIXES = (".stl", ".dae", ".obj")


@pytest.fixture(scope="session")
def corpus_meshes() -> dict[Path, tuple | None]:
    """Every corpus mesh (STL, COLLADA, OBJ) read once per session by ``mesh_arrays.read``:
    ``{path: (vertices, faces) or None}``, sorted by path. The arrays are read-only: a test
    that wrote into one fails there rather than changing what the next test reads."""
    from urdftool.description import mesh_arrays

    corpus_or_skip()
    read = {}
    for path in sorted(p for p in CORPUS.rglob("*") if p.suffix.lower() in MESH_SUFFIXES):
        if path.is_file():
            arrays = read[path] = mesh_arrays.read(path, path.read_bytes())
            for array in arrays or ():
                array.setflags(write=False)
    return read


def lasting() -> None:
    """The objects alive now moved out of the cyclic collector's sight (``gc.freeze()``, after
    a collection): what the session keeps (modules, test items, the corpus run) is no longer
    walked by every full collection of a pytest worker, which held half a million objects.
    Objects made later are collected as before; a test that needs nothing frozen unfreezes."""
    import gc

    gc.collect()
    gc.freeze()


def pytest_configure(config):
    """urdftool, hypothesis and anyio imported by the tests as installed (compiled by ``make``),
    not rewritten: pytest marks every module of a distribution that ships a plugin for assertion
    rewriting, so each test process parsed and rewrote them all again in a fresh clone, where
    no rewritten copy is cached yet (urdftool's 185 modules 1 s of CPU per worker, hypothesis's
    and anyio's 0.7 s), for nothing: urdftool holds no ``assert``, and no test reads theirs.
    The tests' own asserts are rewritten as before (and pytest_lsp's checks); a plugin module,
    imported before this file, stays rewritten."""
    config.addinivalue_line("markers", "worker: the CLI's commands of one piece (run_cli) run in "
                            "a forked worker, as outside the tests (a budget, a death)")
    marked = getattr(getattr(config.pluginmanager, "rewrite_hook", None), "_must_rewrite", None)
    if isinstance(marked, set):  # (pytest's private set: without it, all is rewritten as before)
        marked.difference_update({"urdftool", "hypothesis", "anyio"})


@pytest.hookimpl(trylast=True)
def pytest_collection_finish(session):
    lasting()  # every module imported and every item collected lives as long as the session


def without_heavy_imports(code: str) -> str:
    """The output of ``code`` run in a fresh interpreter that then asserts neither trimesh nor
    pycollada was imported (what checking without them promises)."""
    script = (f"import sys\n{code}\nassert 'trimesh' not in sys.modules, 'trimesh imported'\n"
              "assert 'collada' not in sys.modules, 'pycollada imported'\n")
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return done.stdout



def guardian_and_child(setup: str = "", said: str = "") -> list[str]:
    """A fresh interpreter that runs ``setup``, then forks as a plain check does
    (:func:`urdftool.guardian.guarded`): the child writes ``[child]`` and ends as the door ends
    it, the guardian ``[guardian FOUND SAID]`` (``said``: an f-string part). What both wrote, one
    line each, sorted; the program's exit status 0 is asserted."""
    program = (f"import os\n{setup}\nfrom urdftool import guardian\nfound = guardian.guarded()\n"
               "if found is None:\n    os.write(2, b'[child]')\n"
               "    guardian.end_after(lambda: None)\n"
               f"os.write(2, f'[guardian {{found}}{said}]'.encode())\n")
    done = subprocess.run([sys.executable, "-c", program], capture_output=True, text=True,
                          timeout=60)
    assert done.returncode == 0, done.stderr
    return sorted(done.stderr.replace("][", "]\n[").splitlines())

# ---- synthetic robots of any size (benchmarks/generate.py, the one generator) ------------

@pytest.fixture
def attribute_reads(monkeypatch):
    """How many times each (element, attribute) of the robots loaded from now on is read
    through lxml's get (every parser lxml makes gives elements that count)."""
    from collections import Counter

    from lxml import etree

    reads = Counter()

    class Counted(etree.ElementBase):
        def get(self, key, default=None):
            reads[self, key] += 1
            return super().get(key, default)

    parser = etree.XMLParser

    def counting(**options):
        made = parser(**options)
        made.set_element_class_lookup(etree.ElementDefaultClassLookup(element=Counted))
        return made

    monkeypatch.setattr(etree, "XMLParser", counting)
    return reads


def synthetic_robot(folder: Path, links: int, shape: str = "chain") -> Path:
    """A ``shape`` ('chain' or 'star') URDF of ``links`` links written into ``folder``."""
    import importlib.util

    spec = importlib.util.spec_from_file_location("generate", ROOT / "benchmarks" / "generate.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.write(folder, links, shape)


def rigid_body_robot(links: int, mesh: str = "") -> str:
    """The URDF text of ``links`` links fixed together (one rigid body: each fixed to the base
    or to the link before, turned and offset its own way), each with a box, cylinder or
    sphere (or ``mesh``), and one more link on a revolute joint, not part of the body."""
    import random

    rng = random.Random(links)
    shapes = ['<box size="0.1 0.2 0.05"/>', '<cylinder radius="0.03" length="0.2"/>',
              '<sphere radius="0.04"/>', mesh or '<box size="0.02 0.02 0.3"/>']
    parts = ['<robot name="b">']
    for i in range(links + 1):
        rpy = " ".join(f"{rng.uniform(-3, 3):.3f}" for _ in range(3))
        xyz = " ".join(f"{rng.uniform(-1, 1):.3f}" for _ in range(3))
        parts.append(f'<link name="l{i}"><visual><origin xyz="{xyz}" rpy="{rpy}"/><geometry>'
                     f'{shapes[i % 4]}</geometry></visual></link>')
        if i:  # fixed to the base or to the link before, turned: a tree of fixed joints
            parent = 0 if i % 3 else i - 1
            kind = "revolute" if i == links else "fixed"
            parts.append(f'<joint name="j{i}" type="{kind}"><parent link="l{parent}"/>'
                         f'<child link="l{i}"/><origin xyz="{xyz}" rpy="{rpy}"/>'
                         '<axis xyz="0 0 1"/><limit lower="0" upper="1" effort="1" '
                         'velocity="1"/></joint>')
    return "".join(parts) + "</robot>"


# ---- urdfdom's check_urdf (shipped in the pin wheel), the reference parser -----------------

CHECK_URDF = shutil.which("check_urdf", path=str(Path(sys.executable).parent)) or \
    shutil.which("check_urdf")
# pin's check_urdf is a Python wrapper (cmeel) that sets LD_LIBRARY_PATH and runs the binary in
# its prefix: run the binary directly, saving a Python start-up per file.
_CMEEL = Path(sysconfig.get_paths()["purelib"]) / "cmeel.prefix"
if CHECK_URDF and (_CMEEL / "bin" / "check_urdf").is_file():
    CHECK_URDF = str(_CMEEL / "bin" / "check_urdf")
    _URDFDOM_ENV = {**os.environ, "LD_LIBRARY_PATH": os.pathsep.join(
        filter(None, [str(_CMEEL / "lib"), os.environ.get("LD_LIBRARY_PATH")]))}
else:
    _URDFDOM_ENV = None


CHECK_URDF_TIMEOUT = 20.0  # [s]: it takes 0.01-0.1 s a file; on a cycle below the root it loops


@functools.cache
def check_urdf(path: Path, timeout: float = CHECK_URDF_TIMEOUT) -> subprocess.CompletedProcess:
    """check_urdf's verdict on ``path``, run once per path and session (files do not change).
    urdfdom never returns on a kinematic cycle below the root (a self-joint, or ``b -> c -> b``
    under ``r -> b``: its tree walk loops); stopped after ``timeout``, it is a refusal (exit
    status -9, saying so on stderr), as robot_state_publisher never starts on such a file."""
    try:
        return subprocess.run([CHECK_URDF, str(path)], capture_output=True, text=True,
                              timeout=timeout, env=_URDFDOM_ENV)
    except subprocess.TimeoutExpired as stopped:
        return subprocess.CompletedProcess(
            stopped.cmd, -9, _text(stopped.stdout), _text(stopped.stderr)
            + f"check_urdf did not finish in {timeout:g} s (a kinematic cycle?)")


def _text(output) -> str:
    return output.decode("utf-8", "replace") if isinstance(output, bytes) else output or ""


# ---- case files (tests/cases): one per rule, offending lines marked `expect: CODE` ----------

MARK = re.compile(r"expect:\s*((?:U\d{3}[\s,]*)+)(?:is reported )?(?:at\s+([\w.\-]+):(\d+))?")
# ``expect: U604 warning``: the finding is reported at that severity (a conditional one)
SEVERITY_MARK = re.compile(r"expect:\s*(U\d{3})\s+(error|warning|info)\b")


def case_robot(case: Path) -> Path:
    if case.is_file():
        return case
    robots = sorted(p for p in case.iterdir() if p.name.endswith((".urdf", ".urdf.xacro")))
    assert len(robots) == 1, f"{case} must hold exactly one .urdf or .urdf.xacro, has {robots}"
    return robots[0]


def expected_marks(case: Path) -> set[tuple[str, int, str]]:
    files = [case] if case.is_file() else sorted(p for p in case.rglob("*") if p.is_file())
    marks = set()
    for path in files:
        for number, line in enumerate(path.read_text(errors="replace").splitlines(), start=1):
            for codes, elsewhere, at_line in MARK.findall(line):
                where = (elsewhere, int(at_line)) if elsewhere else (path.name, number)
                for code in re.findall(r"U\d{3}", codes):
                    marks.add((*where, code))
    return marks


def expected_severities(case: Path) -> dict[tuple[str, int, str], str]:
    """(file, line, code) -> severity, for the marks that say one (``expect: U604 warning``)."""
    files = [case] if case.is_file() else sorted(p for p in case.rglob("*") if p.is_file())
    return {(path.name, number, code): severity for path in files
            for number, line in enumerate(path.read_text(errors="replace").splitlines(), start=1)
            for code, severity in SEVERITY_MARK.findall(line)}


CASE_PATHS = sorted(p for p in CASES.iterdir() if re.match(r"U\d{3}_", p.name))


# The case files are checked as ``urdftool check tests/cases/...`` checks them: in one run, whose
# view of the file system (the repository's launch index, packages and settings) is made once,
# not once per case (two thirds of a case's check).
_CASES_RUN: dict = {}


@functools.cache
def case_result(case: Path, targets: tuple[str, ...] = ()):
    """The FileResult of checking ``case``'s robot (with the portability ``targets``), once per
    test process: tests/lint/test_cases.py and tests/integration/test_parity.py read the
    same check. Do not change it."""
    from urdftool.description.run_memo import one_run
    from urdftool.lint.engine import CheckOptions, load_and_check
    from urdftool.lint.options import Selection

    with one_run(_CASES_RUN):
        return load_and_check(str(case_robot(case)),
                              CheckOptions(selection=Selection(targets=targets)))


def case_targets(case: Path) -> tuple[str, ...]:
    """The ``--target`` a case is checked with: its code's own (a portability rule runs only for
    its target), none for the others."""
    from urdftool.lint.catalogue import TARGET_DECADES

    target = TARGET_DECADES.get(case.name[:3])
    return (target,) if target else ()


def in_corpus_group(nodeid: str) -> bool:
    """Whether the test ``nodeid`` runs in the worker that checks the corpus (``corpus_run``):
    its module or its name says corpus."""
    return "corpus" in nodeid.partition("[")[0]


def pytest_collection_modifyitems(config, items):
    """Everything under tests/integration/ is marked ``integration`` (``make test-fast``
    skips it). A test that reads the corpus run says so in its module or name (it must: the
    corpus group is found by the node ID, see pytest_xdist_make_scheduler)."""
    for item in items:
        if "integration" in item.path.relative_to(ROOT).parts[:2]:
            item.add_marker(pytest.mark.integration)
        if "corpus_run" in getattr(item, "fixturenames", ()) and not in_corpus_group(item.nodeid):
            raise pytest.UsageError(f"{item.nodeid} reads corpus_run: name its module or test "
                                    "for the corpus (tests/conftest.py, in_corpus_group)")


@pytest.hookimpl(optionalhook=True)
def pytest_xdist_make_scheduler(config, log):
    """``--dist loadgroup`` (``make test``) with the tests of the corpus in one group, run by
    one worker: the corpus is checked once per session (corpus_run, 6-8 s of CPU), not once
    per worker. The group is read from the node ID here, where xdist reads it; an
    ``xdist_group`` mark added at collection is lost under pytest 9.2, whose node IDs xdist
    can no longer rename (pytest-xdist#1386)."""
    if config.getvalue("dist") != "loadgroup":
        return None
    from xdist.scheduler import LoadGroupScheduling

    class CorpusGroup(LoadGroupScheduling):
        def _split_scope(self, nodeid: str) -> str:
            return "corpus" if in_corpus_group(nodeid) else super()._split_scope(nodeid)

    return CorpusGroup(config, log)


def counting_str(compared: list):
    """A ``str`` class whose equality tests append to ``compared``: how many comparisons a
    search of names made (a search of the names before each, quadratic, makes millions)."""

    class Name(str):
        def __eq__(self, other):
            compared.append(1)
            return str.__eq__(self, other)

        __hash__ = str.__hash__

    return Name


def another_users(path, monkeypatch) -> None:
    """Make ``path`` another user's file: chown it when root, else pretend to be someone else
    (``os.geteuid``, which :func:`urdftool.lint.settings.foreign` asks)."""
    if os.geteuid() == 0:
        os.chown(path, 54321, 54321)
    else:
        monkeypatch.setattr(os, "geteuid", lambda: os.stat(path).st_uid + 1)
