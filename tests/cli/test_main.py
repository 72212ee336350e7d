"""``python -m urdftool`` is the command line, as the ``urdftool`` script is."""

from __future__ import annotations

import os
import re
import subprocess
import sys

import pytest

from conftest import ROOT
from slow_robots import slow_xacro
from urdftool.lint import engine
from urdftool.lint.engine import CheckOptions, load_and_check


def _module(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "urdftool", *args], capture_output=True,
                          text=True, cwd=ROOT, timeout=120)


def test_python_m_urdftool_runs_the_command_line():
    version = _module("--version")
    assert version.returncode == 0 and version.stdout.startswith("urdftool "), version.stderr
    assert "Usage: urdftool" in _module("--help").stdout
    broken = _module("check", "--timeout", "0", "tests/cases/U204_inverted_limits.urdf")
    assert broken.returncode == 1 and "U204" in broken.stdout, broken.stdout + broken.stderr


def test_python_m_urdftool_imports_nothing_from_the_folder_it_runs_in(tmp_path):
    """``python -m`` puts the current folder first on sys.path: a ``yaml.py``, ``numpy.py``
    or ``dataclasses.py`` committed in the folder being checked ran in place of the module.
    Every module this test process imported (urdftool's dependencies and the standard
    library's), but those Python imports before ``-m`` runs, is planted there; none runs,
    through the plain check nor through Typer."""
    started = subprocess.run([sys.executable, "-c", "import sys; print(*sys.modules)"],
                             capture_output=True, text=True, check=True).stdout.split()
    planted = {name.partition(".")[0] for name in sys.modules} - set(started) - {"urdftool"}
    marker = tmp_path / "ran"
    for name in planted:
        if not name.startswith("__"):
            (tmp_path / f"{name}.py").write_text(f"open({str(marker)!r}, 'a').write('{name} ')\n")
    (tmp_path / "r.urdf").write_text('<robot name="r"><link name="a"/></robot>\n')
    environment = {**os.environ, "PYTHONPATH": os.pathsep.join(
        [str(ROOT), *filter(None, [os.environ.get("PYTHONPATH")])])}
    for words in (["check", "--no-cache", "r.urdf"], ["fk", "r.urdf"]):
        done = subprocess.run([sys.executable, "-m", "urdftool", *words], capture_output=True,
                              text=True, cwd=tmp_path, env=environment, timeout=120)
        assert not marker.exists(), (words, marker.read_text())
        assert done.returncode == 0, (words, done.stderr)
    gone = tmp_path / "gone"  # a folder deleted under it has no name to compare (getcwd fails)
    gone.mkdir()
    done = subprocess.run(["sh", "-c", 'cd "$1" && rmdir "$1" && exec "$2" -m urdftool --version',
                           "sh", str(gone), sys.executable], capture_output=True, text=True,
                          env=environment, timeout=120)
    assert done.returncode == 0 and done.stdout.startswith("urdftool "), done.stderr


# ``urdftool check`` through the door, with the result cache
ROBOT = """<robot name="bot" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="parts.xacro"/>
  <link name="body"><inertial><mass value="${mass}"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
</robot>
"""
PARTS = """<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="mass" value="{mass}"/>
</robot>
"""
# the program as the urdftool script starts it, trusting the stamps of files written just now
PROGRAM = ("import sys; import urdftool.description.files as files; files.RACY_NS = 0; "
           "sys.argv = ['urdftool', *sys.argv[1:]]; from urdftool.__main__ import main; main()")


def _program(tmp_path, *args: str) -> subprocess.CompletedProcess:
    env = {**os.environ, "XDG_CACHE_HOME": str(tmp_path / "home-cache")}
    return subprocess.run([sys.executable, "-c", PROGRAM, *args], capture_output=True,
                          text=True, cwd=tmp_path, env=env, timeout=120)


@pytest.fixture
def bot(tmp_path):
    (tmp_path / "bot.urdf.xacro").write_text(ROBOT)
    (tmp_path / "parts.xacro").write_text(PARTS.format(mass=-1))
    return tmp_path


def test_an_edited_included_file_is_seen_by_the_same_words(bot):
    words = ["check", "--cache-dir", "cache", "--timeout", "0", "bot.urdf.xacro"]
    _program(bot, *words)
    assert "-1 kg" in _program(bot, *words).stdout
    (bot / "parts.xacro").write_text(PARTS.format(mass=-2.5))
    edited = _program(bot, *words)
    assert "-2.5 kg" in edited.stdout and "-1 kg" not in edited.stdout


def test_a_reader_that_leaves_ends_the_check_quietly(bot):
    words = ["check", "--cache-dir", "cache", "--timeout", "0", "bot.urdf.xacro"]
    _program(bot, *words)
    env = {**os.environ, "XDG_CACHE_HOME": str(bot / "home-cache")}
    reader = subprocess.Popen([sys.executable, "-c", PROGRAM, *words], stdout=subprocess.PIPE,
                              stderr=subprocess.PIPE, cwd=bot, env=env)
    reader.stdout.close()  # before anything is read
    assert reader.wait(timeout=120) == 1
    assert "Traceback" not in reader.stderr.read().decode()


def test_a_check_through_a_worker_prints_what_one_process_prints():
    """``urdftool check`` checks a file, or standard input, in a worker forked after the rules
    were imported, within its budget; without one, in this process."""
    case = "tests/cases/U204_inverted_limits.urdf"
    alone = ["--timeout", "0", "--max-memory", "0", "--jobs", "1"]
    for words in (["--no-cache", case], ["--no-cache", "--stdin-filename", case, "-"]):
        stdin = (ROOT / case).read_text() if "-" in words else None
        worker, here = (subprocess.run([sys.executable, "-m", "urdftool", "check", *extra, *words],
                                       capture_output=True, text=True, cwd=ROOT, timeout=120,
                                       input=stdin) for extra in ([], alone))
        assert worker.returncode == here.returncode == 1 and "U204" in worker.stdout, worker.stderr
        assert (worker.stdout, worker.stderr) == (here.stdout, here.stderr)


def test_check_runs_the_collector_as_the_door_says_and_other_commands_as_python_does(tmp_path):
    """The collector's rhythm for a check is installed by ``__main__`` (the door for speed
    tricks) into the engine; a library user's check keeps Python's."""
    (tmp_path / "a.urdf").write_text('<robot name="r"><link name="a"/></robot>\n')
    program = ("import atexit, sys; from urdftool.lint import engine; import urdftool.__main__ as d;"
               " atexit.register(lambda: print('[policy]', engine.COLLECTION =="
               " (d._fewer_collections, d._unexamined) and engine.LATEST is not None,"
               " file=sys.stderr)); "
               "sys.argv = ['urdftool', *sys.argv[1:]]; d.main()")
    for words, installed in ((["check", "--no-cache", "a.urdf"], True),
                             (["tree", "a.urdf"], False)):
        done = subprocess.run([sys.executable, "-c", program, *words], capture_output=True,
                              text=True, cwd=tmp_path, timeout=120)
        assert done.returncode == 0 and f"[policy] {installed}" in done.stderr, done.stderr
    from urdftool.lint import engine

    assert engine.COLLECTION[0] is engine.COLLECTION[1]  # nullcontext, unless installed
    assert engine.LATEST is None


def test_a_check_through_the_door_says_all_and_exits_as_the_command_does(tmp_path):
    """The exit status, a long report through a pipe, and the exit functions of a check run
    through the door (``__main__``) as through ``urdftool.cli.main``."""
    links = "".join(f'<link name="l{i}"/><joint name="j{i}" type="revolute"><parent link="l0"/>'
                    f'<child link="l{i}"/><limit lower="1" upper="-1" effort="1" velocity="1"/>'
                    "</joint>\n" for i in range(1, 400))
    (tmp_path / "many.urdf").write_text(f'<robot name="r"><link name="l0"/>\n{links}</robot>\n')
    (tmp_path / "clean.urdf").write_text('<robot name="r"><link name="a"/></robot>\n')
    program = ("import atexit, sys; atexit.register(lambda: print('[exit functions ran]', "
               "file=sys.stderr)); sys.argv = ['urdftool', *sys.argv[1:]]; from urdftool.{} "
               "import main; main()")
    for words, status in ((["many.urdf"], 1), (["clean.urdf"], 0), (["--format", "nope", "x"], 2),
                          (["many.urdf", "--format", "json", "--exit-zero"], 0)):
        ended, usual = (subprocess.run([sys.executable, "-c", program.format(module), "check",
                                        "--no-cache", *words], capture_output=True, text=True,
                                       cwd=tmp_path, timeout=120)
                        for module in ("__main__", "cli"))
        assert ended.returncode == usual.returncode == status, ended.stderr
        assert (ended.stdout, ended.stderr) == (usual.stdout, usual.stderr)
        assert ended.stderr.endswith("[exit functions ran]\n")
    assert ended.stdout.count('"U204"') == 399


def test_a_plain_check_ends_without_tearing_the_interpreter_down(tmp_path):
    """``__main__._end``: the door's check runs the exit functions and ends, not freeing its
    objects one by one (the finalizer of an object an exit function made does not run);
    through Typer, Python tears down as usual."""
    (tmp_path / "a.urdf").write_text('<robot name="r"><link name="a"/></robot>\n')
    program = ("import atexit, os, sys\nclass Kept:\n    def __del__(self, write=os.write):\n"
               "        write(2, b'[torn down]')\n"
               "atexit.register(lambda: setattr(sys, 'kept', Kept()))\n"
               "atexit.register(lambda: print('[exit functions ran]', file=sys.stderr))\n"
               "sys.argv = ['urdftool', *sys.argv[1:]]\nfrom urdftool.{} import main\nmain()")
    for module, torn_down in (("__main__", False), ("cli", True)):
        done = subprocess.run([sys.executable, "-c", program.format(module), "check",
                               "--no-cache", "a.urdf"], capture_output=True, text=True,
                              cwd=tmp_path, timeout=120)
        assert done.returncode == 0 and "[exit functions ran]" in done.stderr, done.stderr
        assert ("[torn down]" in done.stderr) == torn_down, (module, done.stderr)


def test_a_check_imports_no_module_its_robot_does_not_use(tmp_path):
    """The digests of what a check read are the result cache's: hashlib (which loads OpenSSL)
    is imported for a check that keeps its results, not for one without the cache; a
    setup.cfg's parser (configparser) only for a package that has one."""
    (tmp_path / "a.urdf").write_text('<robot name="r"><link name="a"/></robot>\n')
    program = ("import atexit, sys; atexit.register(lambda: sys.stderr.write(''.join("
               "f'[{m}]' for m in ('hashlib', 'configparser') if m in sys.modules))); "
               "sys.argv = ['urdftool', *sys.argv[1:]]; from urdftool.cli import main; main()")
    for words, loaded in ((["--no-cache"], ""), (["--cache-dir", "cache"], "[hashlib]")):
        done = subprocess.run([sys.executable, "-c", program, "check", "--timeout", "0",
                               "--max-memory", "0", *words, "a.urdf"], capture_output=True,
                              text=True, cwd=tmp_path, timeout=120)
        assert done.returncode == 0, done.stderr
        assert done.stderr.endswith("\n" + loaded) or done.stderr == loaded, (words, done.stderr)


# The collector's rhythm for a check, installed into the engine by the door (``__main__``)

@pytest.fixture
def door_collection(monkeypatch):
    import urdftool.__main__ as door

    monkeypatch.setattr(engine, "COLLECTION", (door._fewer_collections, door._unexamined))
    return door


def test_a_check_collects_garbage_less_often_and_restores_the_threshold(door_collection, monkeypatch, tmp_path):
    import gc

    seen = []
    real = engine.check_robot
    monkeypatch.setattr(engine, "check_robot", lambda *a: seen.append(gc.get_threshold()) or
                        real(*a))
    before = gc.get_threshold()
    robot = tmp_path / "r.urdf"
    robot.write_text('<robot name="r"><link name="a"/></robot>')
    load_and_check(str(robot), CheckOptions())
    assert seen[0][0] >= 100_000 and seen[0][1:] == before[1:]
    assert gc.get_threshold() == before


@pytest.fixture
def _nothing_frozen():
    """No object frozen while the test runs (a test before it in this process may have frozen
    its own, as the fuzz harness's parent does): they are frozen again afterwards."""
    import gc

    frozen = gc.get_freeze_count()
    gc.unfreeze()
    yield
    if frozen:
        gc.freeze()


def test_the_rules_run_unexamined_and_leave_the_collector_as_it_was(door_collection, monkeypatch,
                                                                    tmp_path, _nothing_frozen):
    import gc
    import weakref

    robot = tmp_path / "r.urdf"
    robot.write_text('<robot name="r"><link name="a"/></robot>')
    seen, left = [], []
    real = engine.check_robot

    def rules(*args):
        seen.append(gc.isenabled())
        left.append(weakref.ref(_Cycle()))  # garbage only the cyclic collector frees
        return real(*args)

    monkeypatch.setattr(engine, "check_robot", rules)
    load_and_check(str(robot), CheckOptions())
    assert seen == [False]  # paused while the rules ran
    assert gc.isenabled() and gc.get_freeze_count() == 0
    gc.collect()
    assert left[0]() is None  # what the rules left is still collected


def test_a_callers_frozen_objects_stay_frozen(door_collection, tmp_path, monkeypatch):
    import gc

    robot = tmp_path / "r.urdf"
    robot.write_text('<robot name="r"><link name="a"/></robot>')
    load_and_check(str(robot), CheckOptions())  # a first check frees objects made on import
    session = gc.get_freeze_count()  # (the test process's own, tests/conftest.py's lasting)
    gc.freeze()
    unfrozen = []
    monkeypatch.setattr(gc, "unfreeze", lambda: unfrozen.append(gc.get_freeze_count()))
    try:
        frozen = gc.get_freeze_count()
        load_and_check(str(robot), CheckOptions())
        # never unfrozen; a frozen object the check no longer holds may be freed (a load's run
        # sets its memory in the context, whose earlier mapping goes)
        assert unfrozen == [] and frozen - 10 < gc.get_freeze_count() <= frozen
    finally:
        monkeypatch.undo()
        gc.unfreeze()
        if session:
            gc.freeze()  # the test process's objects out of the collector's sight again


def test_a_full_collection_runs_once_enough_objects_went_unexamined(door_collection, monkeypatch,
                                                                   tmp_path, _nothing_frozen):
    import gc

    robot = tmp_path / "r.urdf"
    robot.write_text('<robot name="r"><link name="a"/></robot>')
    full = []
    real = gc.collect
    monkeypatch.setattr(gc, "collect", lambda *a: full.append(a) or real(*a))
    monkeypatch.setitem(door_collection._PROMOTED, "objects", door_collection.FULL_COLLECTION_AFTER + 1)
    load_and_check(str(robot), CheckOptions())
    assert full == [()] and door_collection._PROMOTED["objects"] < door_collection.FULL_COLLECTION_AFTER


def test_the_imports_of_a_check_are_frozen_and_the_rules_still_run_unexamined(tmp_path):
    """The door imports what a check needs with the collector off, then freezes it (a forked
    worker's collector no longer writes into every imported object's page); its own freeze
    does not turn the rhythm off: the rules still run with the collector paused, and what
    was frozen goes to the oldest generation after them."""
    (tmp_path / "a.urdf").write_text('<robot name="r"><link name="a"/></robot>\n')
    program = ("import gc; import urdftool.__main__ as d; d._collect_less(); "
               "from urdftool.lint import runner; runner.import_rules(); "
               "frozen = gc.get_freeze_count(); "
               "from urdftool.lint import engine; seen = []; real = engine.check_robot; "
               "engine.check_robot = lambda *a: seen.append(gc.isenabled()) or real(*a); "
               "engine.load_and_check('a.urdf', engine.CheckOptions()); "
               "print(frozen > 10000, 'urdftool.checking' in __import__('sys').modules, seen, "
               "gc.get_freeze_count(), gc.isenabled())")
    done = subprocess.run([sys.executable, "-c", program], capture_output=True, text=True,
                          cwd=tmp_path, timeout=120)
    assert done.stdout.split("\n")[0] == "True True [False] 0 True", done.stderr


def test_a_check_collects_nothing_before_its_imports_are_frozen(tmp_path):
    """The collector is off from a check's first step through the door (the kept code, the
    command's imports) until :func:`urdftool.__main__._collect_less` froze what they made,
    which it examined only to find it all alive; other commands collect as Python does."""
    (tmp_path / "a.urdf").write_text('<robot name="r"><link name="a"/></robot>\n')
    program = ("import atexit, gc, sys; import urdftool.__main__ as d; seen = []; "
               "gc.callbacks.append(lambda phase, info: phase == 'start' and "
               "seen.append('collected')); "
               "kept, frozen, command = d.kept_code, d._collect_less, d._command; "
               # as many young objects as the kept code and dataclasses' imports make
               "d.kept_code = lambda: (kept(), [[] for _ in range(5000)])[0]; "
               "d._collect_less = lambda: (seen.append('frozen'), frozen())[1]; "
               "d._command = lambda words: (seen.clear(), command(words))[1]; "
               "atexit.register(lambda: print('[seen]', *(seen + ['end'])[:2], file=sys.stderr)); "
               "sys.argv = ['urdftool', *sys.argv[1:]]; d.main()")
    for words, first in ((["check", "--no-cache", "--timeout", "0", "--max-memory", "0",
                           "a.urdf"], "frozen"), (["tree", "a.urdf"], "collected")):
        done = subprocess.run([sys.executable, "-c", program, *words], capture_output=True,
                              text=True, cwd=tmp_path, timeout=120)
        assert done.returncode == 0 and f"[seen] {first}" in done.stderr, done.stderr


def test_a_check_whose_rhythm_is_patched_out_runs_with_the_collector_on(tmp_path):
    """The pause ends after the freeze whoever froze (``make bench`` times the check without
    the rhythm: with Python's collector, not none)."""
    (tmp_path / "a.urdf").write_text('<robot name="r"><link name="a"/></robot>\n')
    program = ("import atexit, gc, sys; import urdftool.__main__ as d; "
               "d._collect_less = lambda: None; "
               "atexit.register(lambda: print('[on]', gc.isenabled(), file=sys.stderr)); "
               "sys.argv = ['urdftool', *sys.argv[1:]]; d.main()")
    done = subprocess.run([sys.executable, "-c", program, "check", "--no-cache", "--timeout",
                           "0", "--max-memory", "0", "a.urdf"], capture_output=True, text=True,
                          cwd=tmp_path, timeout=120)
    assert done.returncode == 0 and "[on] True" in done.stderr, done.stderr


def test_the_collector_is_on_again_when_a_check_fails_before_its_imports(monkeypatch):
    import gc

    from urdftool import __main__ as door

    def fails(path=None):
        raise RuntimeError("no kept code")

    monkeypatch.setattr(door, "kept_code", fails)
    assert gc.isenabled()
    with pytest.raises(RuntimeError):
        door._command(["check", "a.urdf"])
    assert gc.isenabled()


def test_a_run_the_result_cache_serves_imports_no_rule(tmp_path):
    """The door imports the rules when files are to be checked (``runner.import_rules``), not
    before: a re-run served whole from the result cache imported them for nothing (33-75 ms
    of the corpus's cached re-check, sessions 5 to 10)."""
    (tmp_path / "a.urdf").write_text('<robot name="r"><link name="a"/></robot>\n')
    words = [sys.executable, "-X", "importtime", "-m", "urdftool", "check", "--jobs", "1",
             "--cache-dir", str(tmp_path / "cache"), "a.urdf"]
    environment = {k: v for k, v in os.environ.items() if k not in ("CI", "URDFTOOL_NO_CACHE")}
    first, again = (subprocess.run(words, capture_output=True, text=True, cwd=tmp_path,
                                   env=environment, timeout=120) for _ in range(2))
    for done in (first, again):
        assert done.returncode == 0 and "no problems found" in done.stdout, done.stderr
    assert re.search(r"\|\s+urdftool\.lint\.engine$", first.stderr, re.M), first.stderr
    assert not re.search(r"\|\s+urdftool\.lint\.(engine|rules)$", again.stderr, re.M), again.stderr


def test_a_check_never_counts_the_objects_it_froze(tmp_path):
    """The door knows what it froze (the imports, :func:`urdftool.__main__._collect_less`)
    without counting it: ``gc.get_freeze_count()`` walks every frozen object (a millisecond
    each time after the imports), asked only where nothing of the door's is frozen."""
    (tmp_path / "a.urdf").write_text('<robot name="r"><link name="a"/></robot>\n')
    patch = ("import gc\ncount = gc.get_freeze_count\n"
             "def counted():\n    found = count()\n"
             "    if found: os.write(2, b'[counted]')\n    return found\n"
             "gc.get_freeze_count = counted")
    for budgets in ((), ("--timeout", "0", "--max-memory", "0")):  # guarded, and in one process
        done = _door(tmp_path, patch, "check", "--no-cache", *budgets, "a.urdf")
        assert done.returncode == 0 and "no problems found" in done.stdout, done.stderr
        assert "[counted]" not in done.stderr, (budgets, done.stderr)


class _Cycle:
    def __init__(self):
        self.me = self


# ---- check's plain words, parsed by the door without Typer ------------------------------------

def _typer_values(monkeypatch, words: list[str]):
    """The values Typer gives the check command for ``words``, or None when it gives none (a
    usage error, --help)."""
    import urdftool.checking
    from urdftool.cli import app

    seen = []
    monkeypatch.setattr(urdftool.checking, "run", lambda *a, **values: seen.append(values) or 0)
    try:
        app(["check", *words], prog_name="urdftool")
    except SystemExit:
        pass
    return seen[0] if seen else None


def _grammar():
    """Word lists: paths, xacro words, stdin, every option of check in each of its forms with
    values that convert, that do not, that look like options, and what is never plain (short
    options joined, --, --help, an unknown option, a flag given a value)."""
    import itertools

    import urdftool.__main__ as door

    values = {"text": ["json", "", "a b", "-x", "é"], "texts": ["U2", "-U2", "a=b"],
              "path": ["out.txt", "", "-", "./x"], "paths": ["c.yaml", "-c"],
              "int": ["3", "-1", "x", "0x1", "1_0", " 4 "], "float": ["2.5", "1e1", "nan", "x"],
              "int>=1": ["0", "1", "7", "x"]}
    forms = []
    for name, kind, names, negative, default in door.kept_words("check"):
        if kind == "words":
            continue
        for option in names.split(",") + [n for n in negative.split(",") if n]:
            if kind in ("flag", "switch"):
                forms += [[option], [option + "=1"] if option.startswith("--") else [option + "x"]]
                continue
            for value in values[kind]:
                forms.append([option, value])
                if option.startswith("--"):
                    forms.append([f"{option}={value}"])
                else:
                    forms.append([option + value])
            forms.append([option])  # no value
    odd = [["--"], ["--help"], ["-h"], ["-qv"], ["--nope"], ["-"], ["x:=1"], []]
    paths = [["robots/r2d2/r2d2.urdf.xacro"], ["a", "b"], []]
    found = []
    for form, before in itertools.product(forms + odd, paths):
        found.append(before + form)
        found.append(form + before)
    found += [["a", "--format", "json", "-f", "text"], ["a", "--notes", "--no-notes"],
              ["a", "--select", "U1", "--select", "U2", "--arg", "x=1", "b:=2"],
              ["--strict", "a", "--strict"], ["a", "-o", "o", "-j", "2", "-t", "mujoco"]]
    return found


def test_the_door_reads_checks_plain_words_as_typer_does_and_leaves_it_the_others(monkeypatch):
    """Over a grammar of words: where the door's parser gives values, Typer gives the same
    (same types); where it gives none, Typer runs the command (usage errors, help)."""
    import urdftool.__main__ as door

    parameters = door.kept_words("check")
    assert parameters, "stale help.txt: run python -m urdftool.help_text"
    plain = 0
    for words in _grammar():
        ours = door.plain_words(words, parameters)
        if ours is None:
            continue
        theirs = _typer_values(monkeypatch, words)
        assert repr(ours) == repr(theirs), words  # (nan is no nan)
        assert [type(v) for v in ours.values()] == [type(v) for v in theirs.values()], words
        assert all(type(a) is type(b) for key in ours if isinstance(ours[key], list)
                   for a, b in zip(ours[key], theirs[key])), words
        plain += 1
    assert plain > 300


def test_a_path_typer_refuses_is_not_plain(monkeypatch, tmp_path, capsys):
    """Typer refuses a path option naming a file that is present but unreadable (its usage
    error, exit 2): the door hands such words over instead of checking with them. (os.access
    is faked: the tests may run as root, who reads everything.)"""
    import os

    import urdftool.__main__ as door

    secret = tmp_path / "secret.yaml"
    secret.write_text("{}")
    real_access = os.access
    monkeypatch.setattr(os, "access", lambda path, mode, *a, **k: False
                        if os.fspath(path) == str(secret) else real_access(path, mode, *a, **k))
    parameters = door.kept_words("check")
    for option in ("--controllers", "--config", "--srdf", "--spec", "--output", "--cache-dir"):
        words = ["robots", option, str(secret)]
        assert _typer_values(monkeypatch, words) is None, option
        assert "is not readable" in capsys.readouterr().err
        assert door.plain_words(words, parameters) is None, option
        absent = ["robots", option, str(tmp_path / "absent")]
        assert door.plain_words(absent, parameters) is not None, option


def test_the_kept_parameters_are_the_commands():
    import urdftool.__main__ as door
    from urdftool import help_text

    assert ["\t".join(row) + "\n" for row in door.kept_words("check")] == \
        help_text.words("check").splitlines(True)


@pytest.mark.parametrize("words", [
    ["tests/cases/U204_inverted_limits.urdf"],
    ["tests/cases/U204_inverted_limits.urdf", "--format", "json", "--exit-zero", "-v"],
    ["tests/cases/U204_inverted_limits.urdf", "--statistics", "--strict"],
    ["tests/cases/U204_inverted_limits.urdf", "--diff"],
    ["tests/cases/U204_inverted_limits.urdf", "--format", "nope"],
    ["tests/cases/U204_inverted_limits.urdf", "--unsafe-fixes"],
    ["no/such/file.urdf"],
    ["robots", "--notes", "--select", "U1,U2", "--jobs", "2"],
])
def test_a_plain_check_prints_and_exits_as_typers_without_importing_it(words):
    program = ("import atexit, sys; import urdftool.__main__ as door; {}; "
               "atexit.register(lambda: sys.stderr.write('[typer]' * ('typer' in sys.modules)));"
               " sys.argv = ['urdftool', *sys.argv[1:]]; door.main()")
    plain, typer = (subprocess.run([sys.executable, "-c", program.format(patch), "check",
                                    "--no-cache", *words], capture_output=True, text=True,
                                   cwd=ROOT, timeout=120)
                    for patch in ("pass", "door._check = lambda words: None"))
    assert (plain.returncode, plain.stdout, plain.stderr + "[typer]") == \
        (typer.returncode, typer.stdout, typer.stderr)


# One file checked under a guardian (``__main__._guarded``, ``urdftool.guardian``): forked
# before the rules are imported, the budgets kept against hostile files



def _door(tmp_path, patch: str, *words: str) -> subprocess.CompletedProcess:
    """``urdftool WORDS`` as the script runs it, after ``patch`` (Python run first)."""
    program = (f"import os, sys, signal\n{patch}\nsys.argv = ['urdftool', *sys.argv[1:]]\n"
               "from urdftool.__main__ import main\nmain()")
    return subprocess.run([sys.executable, "-c", program, *words], capture_output=True,
                          text=True, cwd=tmp_path, timeout=120)


def test_a_plain_check_of_one_file_forks_before_the_rules_are_imported(tmp_path):
    """The one process forked for a budgeted check of one file is forked small, before the
    rules and before any class is made (the kept code): the check runs in it, not in a worker
    forked after them, which copied their pages."""
    (tmp_path / "a.urdf").write_text('<robot name="r"><link name="a"/></robot>\n')
    patch = ("fork = os.fork\ndef counted():\n"
             "    big = {'urdftool.lint.engine', 'dataclasses'} & set(sys.modules)\n"
             "    pid = fork()\n"
             "    if pid: os.write(2, b'[fork after rules]' if big else b'[fork before rules]')\n"
             "    return pid\nos.fork = counted")
    done = _door(tmp_path, patch, "check", "--no-cache", "--timeout", "30", "a.urdf")
    assert done.returncode == 0 and "no problems found" in done.stdout, done.stderr
    # (the guardian's child, and where the system cannot signal the guardian's end, the
    # child's watcher: urdftool.guardian.watched_by)
    watcher = not sys.platform.startswith("linux")
    assert done.stderr == "[fork before rules]" * (2 if watcher else 1), done.stderr


def test_a_check_without_budgets_forks_nothing(tmp_path):
    """``--timeout 0 --max-memory 0`` (the command line wins over settings files): no budget
    to keep, so no guardian and no worker: the check runs in the one process."""
    (tmp_path / "a.urdf").write_text('<robot name="r"><link name="a"/></robot>\n')
    patch = ("fork = os.fork\ndef counted():\n    os.write(2, b'[fork]')\n    return fork()\n"
             "os.fork = counted")
    done = _door(tmp_path, patch, "check", "--no-cache", "--timeout", "0", "--max-memory", "0",
                 "a.urdf")
    assert done.returncode == 0 and "no problems found" in done.stdout, done.stderr
    assert "[fork]" not in done.stderr, done.stderr


def test_a_hostile_file_checked_under_the_guardian_is_stopped_at_its_time(tmp_path):
    """Work the sandbox lets through but that would run for minutes: stopped at --timeout by
    the guardian, reported where it was (U015), as a worker's was; the exit status the
    command's."""
    import json
    import time

    (tmp_path / "slow.urdf.xacro").write_text(slow_xacro())
    start = time.monotonic()
    done = _door(tmp_path, "", "check", "--no-cache", "--timeout", "1", "--format", "json",
                 "slow.urdf.xacro")
    assert time.monotonic() - start < 30
    assert done.returncode == 1, done.stderr
    finding, = json.loads(done.stdout)["diagnostics"]
    assert finding["code"] == "U015" and finding["line"] >= 2, finding
    assert "took longer than 1 s" in finding["message"]


def test_a_check_that_dies_under_the_guardian_is_an_internal_error(tmp_path):
    (tmp_path / "a.urdf").write_text('<robot name="r"><link name="a"/></robot>\n')
    patch = ("from urdftool.lint import engine\n"
             "engine.load_and_check = lambda *a, **k: os.kill(os.getpid(), signal.SIGKILL)")
    done = _door(tmp_path, patch, "check", "--no-cache", "a.urdf")
    assert done.returncode == 1, done.stderr
    assert "U900" in done.stdout and "died: killed by SIGKILL" in done.stdout, done.stdout


def test_a_check_over_its_memory_under_the_guardian_is_stopped_and_reported(tmp_path):
    """The memory budget caps the process that checks (a MemoryError there is U018), and is
    lifted again for the report."""
    (tmp_path / "a.urdf").write_text('<robot name="r"><link name="a"/></robot>\n')
    patch = ("from urdftool.lint import engine\n"
             "def hungry(*a, **k):\n    return bytearray(1 << 30)\n"
             "engine.load_and_check = hungry")
    done = _door(tmp_path, patch, "check", "--no-cache", "--max-memory", "700M", "a.urdf")
    assert done.returncode == 1, done.stderr
    assert "U018" in done.stdout and "700 MiB" in done.stdout, done.stdout + done.stderr


@pytest.mark.parametrize("started", [
    "import threading\nthreading.Thread(target=__import__('time').sleep, args=(60,), "
    "daemon=True).start()",
    # a thread threading does not count (execnet's, in every pytest-xdist worker)
    "import _thread\n_thread.start_new_thread(__import__('time').sleep, (60,))"])
def test_a_check_in_a_process_running_other_threads_forks_no_guardian(tmp_path, started):
    """A process forked from one where other threads run may find a lock one of them held
    forever: there the check's file goes to a budgeted worker, as before the guardian. Threads
    as the system counts them."""
    (tmp_path / "a.urdf").write_text('<robot name="r"><link name="a"/></robot>\n')
    patch = (f"{started}\nfork = os.fork\ndef counted():\n"
             "    big = {'urdftool.lint.engine', 'dataclasses'} & set(sys.modules)\n"
             "    pid = fork()\n"
             "    if pid: os.write(2, b'[fork after rules]' if big else b'[fork before rules]')\n"
             "    return pid\nos.fork = counted")
    done = _door(tmp_path, patch, "check", "--no-cache", "--timeout", "30", "a.urdf")
    assert "no problems found" in done.stdout, done.stderr
    assert "[fork before rules]" not in done.stderr, done.stderr


def test_the_door_run_inside_another_program_neither_forks_nor_ends_it(monkeypatch, tmp_path,
                                                                      capsys):
    """``main()`` called by a program of its own (a test runner, an embedding tool), not as
    the program's top level: the door forks no guardian from that program's process (the copy
    would hold the caller's state, its threads' locks and pipes, and the guardian would end
    the caller as the child ended), and does not end it with ``os._exit`` (before, this very
    test ended pytest's process, silently): it raises SystemExit, and the file goes to a
    budgeted worker, as before the guardian. Decided once, by the first call
    (``door.PROGRAM``)."""
    import urdftool.__main__ as door
    from urdftool import guardian

    forked = []
    monkeypatch.setattr(guardian, "guarded", lambda: forked.append("guardian"))
    monkeypatch.setattr(door, "kept_code", lambda path=None: None)
    monkeypatch.setattr(door, "_collect_less", lambda: None)
    monkeypatch.setattr(door, "PROGRAM", {"entry": None})
    (tmp_path / "a.urdf").write_text('<robot name="r"><link name="a"/></robot>\n')
    monkeypatch.setattr(sys, "argv", ["urdftool", "check", "--no-cache",
                                      str(tmp_path / "a.urdf")])
    with pytest.raises(SystemExit) as ended:
        door.main()
    assert ended.value.code == 0 and "no problems found" in capsys.readouterr().out
    assert forked == [] and door.PROGRAM == {"entry": False}
