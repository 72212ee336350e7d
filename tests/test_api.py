"""The public Python API: `import urdftool` is cheap, and what it offers does what check does."""

from __future__ import annotations

import importlib
import shutil
import subprocess
import sys

import pytest

import urdftool
from conftest import CASES, ROBOTS, ROOT

BROKEN = (CASES / "U204_inverted_limits.urdf").read_text()  # U204 at line 7


def test_import_loads_nothing_heavy():
    """``import urdftool`` (what every console script does first) loads no library."""
    code = ("import sys, urdftool; heavy = ('numpy', 'typer', 'click', 'rich', 'lxml', 'yaml', "
            "'trimesh', 'xacro'); print(sorted({m.split('.')[0] for m in sys.modules} & "
            "set(heavy)), sorted(m for m in sys.modules if m.startswith('urdftool')))")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          check=True, cwd=ROOT)
    assert done.stdout.split("\n")[0] == "[] ['urdftool']"


def test_every_public_name_is_its_owners():
    assert set(urdftool._LAZY) == set(urdftool.__all__) - {"__version__"}
    for name, owner in urdftool._LAZY.items():
        assert getattr(urdftool, name) is getattr(importlib.import_module(owner), name), name
    assert urdftool.__version__ and "check_paths" in dir(urdftool)
    with pytest.raises(AttributeError, match="no attribute 'nothing'"):
        urdftool.nothing  # noqa: B018


def test_check_paths_on_the_bundled_robots_is_clean(monkeypatch):
    monkeypatch.chdir(ROOT)
    run = urdftool.check_paths(["robots/"])
    assert run.exit_code == 0
    assert [r.path for r in run.results] == ["robots/diffbot/diffbot.urdf.xacro",
                                             "robots/humanoid/humanoid.urdf.xacro",
                                             "robots/r2d2/r2d2.urdf.xacro"]
    assert all(r.findings == [] for r in run.results)
    assert run.skipped["robots/diffbot/wheel.xacro"].startswith("included by")


@pytest.fixture
def broken(tmp_path, monkeypatch):
    """A copy of robots/ plus robots/broken.urdf, whose limits are inverted (U204 at line 7)."""
    shutil.copytree(ROBOTS, tmp_path / "robots")
    (tmp_path / "robots" / "broken.urdf").write_text(BROKEN)
    monkeypatch.chdir(tmp_path)
    return tmp_path / "robots" / "broken.urdf"


def test_check_paths_on_a_broken_copy(broken):
    run = urdftool.check_paths(["robots"], jobs=1, timeout=0)
    assert run.exit_code == 1
    found = [(f.code, str(f.location), f.severity) for r in run.results for f in r.findings]
    assert found == [("U204", "robots/broken.urdf:7", urdftool.Severity.ERROR)]
    assert urdftool.check_paths(["robots"], ignore=["U204"], jobs=1, timeout=0).exit_code == 0
    assert urdftool.check_paths("robots/broken.urdf").results[0].path == "robots/broken.urdf"


def test_check_file_of_an_unsaved_buffer(broken):
    """``data`` is what is checked (an editor's buffer), not the file on disk."""
    assert [(f.code, f.line) for f in urdftool.check_file(broken).findings] == [("U204", 7)]
    fixed = BROKEN.replace('lower="1.57"', 'lower="-1.57"').replace('upper="-1.57"', 'upper="1"')
    result = urdftool.check_file(broken, data=fixed)
    assert result.findings == [] and result.robot.joints["elbow"] is not None
    assert [f.code for f in urdftool.check_file(broken, data=fixed.encode()[:-12]).findings] \
        == ["U001"]
    path = "robots/diffbot/diffbot.urdf.xacro"  # xacro: the buffer is expanded, includes read
    text = (ROBOTS / "diffbot" / "diffbot.urdf.xacro").read_text()
    assert urdftool.check_file(path, data=text.replace('name="diffbot"', 'name="d2"', 1)
                               ).robot.name == "d2"


def test_check_file_honours_a_suppression_only_in_the_buffer(tmp_path):
    robot = tmp_path / "arm.urdf"
    robot.write_text(BROKEN)
    assert [(f.code, f.line) for f in urdftool.check_file(robot).findings] == [("U204", 7)]
    buffer = BROKEN.replace("    <limit", "    <!-- urdftool: ignore U204 -->\n    <limit")
    assert urdftool.check_file(robot, data=buffer).findings == []


def test_load_and_its_errors(tmp_path):
    robot = urdftool.load(ROBOTS / "diffbot" / "diffbot.urdf.xacro")
    assert isinstance(robot, urdftool.Robot) and robot.name == "diffbot"
    assert robot.locate(robot.joints["left_wheel_joint"]).line == 25
    (tmp_path / "bad.urdf").write_text("<robot>")
    with pytest.raises(urdftool.LoadError) as error:
        urdftool.load(tmp_path / "bad.urdf")
    assert isinstance(error.value, urdftool.UrdftoolError)
    assert error.value.kind == "syntax" and error.value.location.line == 1
    assert "malformed XML" in error.value.message



@pytest.mark.parametrize("ci", ["1", ""], ids=["CI", "no-CI"])
def test_load_takes_the_safe_mode_of_check_under_ci(tmp_path, monkeypatch, ci):
    """``load`` left unset reads what ``check`` reads (:func:`urdftool.description.files.
    env_allowed`, the one owner of the mode): under ``CI`` no environment variable a robot
    names. It read ``$(optenv SECRET tip)`` under CI (its default was True), a job's secret
    made a link's name; without CI, and with ``allow_env=True`` given, the variable is read."""
    robot = tmp_path / "r.urdf.xacro"
    robot.write_text('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
                     '<link name="$(optenv URDFTOOL_SECRET_30 tip)"/></robot>\n')
    (tmp_path / ".git").mkdir()
    monkeypatch.setenv("CI", ci)
    monkeypatch.setenv("URDFTOOL_SECRET_30", "s3cr3t")
    assert list(urdftool.load(robot).links) == ["tip" if ci else "s3cr3t"]
    assert list(urdftool.load(robot, allow_env=True).links) == ["s3cr3t"]
    assert list(urdftool.load(robot, allow_env=False).links) == ["tip"]
    assert [result.robot.links.keys() for result in [urdftool.check_file(robot)]] == [
        urdftool.load(robot).links.keys()]  # (check's own mode, the same)


@pytest.mark.parametrize("order", [("a", "b"), ("b", "a")], ids=["a-b", "b-a"])
def test_settings_apply_per_target(tmp_path, order):
    for name in "ab":
        (tmp_path / name).mkdir()
        (tmp_path / name / "arm.urdf").write_text(BROKEN)
    (tmp_path / "a" / "urdftool.toml").write_text('ignore = ["U204"]\n')
    run = urdftool.check_paths([tmp_path / name for name in order])
    assert [(r.path.split("/")[-2], [f.code for f in r.findings]) for r in run.results] == \
        [(name, [] if name == "a" else ["U204"]) for name in order]
    file = urdftool.check_file(tmp_path / "a" / "arm.urdf")
    assert file.findings == []  # check_file applies the settings above the file too
    assert [f.code for f in urdftool.check_file(tmp_path / "a" / "arm.urdf",
                                                use_settings=False).findings] == ["U204"]


def test_errors_are_urdftool_errors_without_flags(tmp_path):
    with pytest.raises(urdftool.TargetError, match="^path '.*nowhere' does not exist$"):
        urdftool.check_paths([tmp_path / "nowhere"])
    (tmp_path / "urdftool.toml").write_text("strict = true\nbad = 1\n")
    (tmp_path / "r.urdf").write_text(BROKEN)
    with pytest.raises(urdftool.SettingsError) as error:
        urdftool.check_file(tmp_path / "r.urdf")
    assert "--" not in str(error.value) and isinstance(error.value, urdftool.UrdftoolError)


def test_paths_in_bytes_are_paths_and_anything_else_is_refused_by_name(broken):
    """``check_paths(b"robots")`` checked the paths 114, 111, ... (bytes iterated), ``load`` and
    ``check_file`` failed each in its own way; a path in bytes is one as ``os`` takes it."""
    name = bytes(broken.relative_to(broken.parent.parent))
    for given in (name, [name]):
        found = [f.code for r in urdftool.check_paths(given, jobs=1).results for f in r.findings]
        assert found == ["U204"]
    assert [f.code for f in urdftool.check_file(bytes(broken)).findings] == ["U204"]
    assert urdftool.load(bytes(broken)).name
    for given in (5, [5], None):
        with pytest.raises(TypeError, match="a path must be str, bytes or os.PathLike, not"):
            urdftool.check_paths(given)
    with pytest.raises(TypeError, match="data must be the file's text"):
        urdftool.check_file(broken, data=5)  # was 5 NUL bytes: U003


def test_no_path_is_nothing_checked_not_a_pass():
    """``check_paths([])`` (a glob that matched nothing: ``urdftool_check(*glob("urdf/*"))``)
    returned a run of no result with exit 0, where the command line says "no PATH given"."""
    for given in ([], (), iter([])):
        with pytest.raises(urdftool.TargetError, match="nothing checked: no path given"):
            urdftool.check_paths(given)


@pytest.mark.parametrize("options, message", [
    ({"strict": "no"}, 'strict must be True or False, not "no"'),
    ({"timeout": float("nan")}, "timeout must be a finite number of seconds"),
    ({"timeout": float("inf")}, "timeout must be a finite number of seconds"),
    ({"timeout": 10 ** 400}, "timeout must be a finite number of seconds"),  # (OverflowError)
    ({"max_triangles": float("nan")}, "max_triangles must be a whole number"),
    ({"jobs": -5}, "jobs must be a whole number, 0 or more, not -5"),
    ({"xacro_args": "a:=1"}, "xacro_args must map names"),
    ({"packages": "x=/etc"}, "packages must map names"),
    ({"select": [5]}, "select must be words"),
    ({"use_settings": 0}, "use_settings must be True or False"),
    ({"cache_dir": 5}, "cache_dir must be a path"),
])
def test_a_request_is_held_to_what_the_command_line_takes(broken, options, message):
    """The API took what the command line and the settings refuse: ``strict="no"`` was strict,
    ``timeout=nan`` and ``max_triangles=nan`` no limit, ``xacro_args="a:=1"`` Python's error."""
    with pytest.raises(urdftool.UrdftoolError, match=message):
        urdftool.check_paths(["robots"], **options)


@pytest.mark.parametrize("options, message", [
    ({"xacro_args": ["a:=1"]}, r"xacro_args must map names \(str\) to values \(str\), not \["),
    ({"packages": "x"}, r'packages must map names \(str\) to values \(str\), not "x"'),
    ({"packages": {"a": 5}}, r"packages must map names .* not \{ a = 5 \}"),
    ({"allow_env": "no"}, 'allow_env must be True or False, not "no"'),
    ({"as_written": 1}, "as_written must be True or False, not 1"),
    ({"max_file_size": -1}, "max_file_size must be a whole number of bytes from 1 to"),
    ({"max_file_size": "1M"}, 'max_file_size must be a whole number of bytes .* not "1M"'),
])
def test_load_holds_its_options_by_the_one_guard_of_a_callers_options(options, message):
    """The same guard as ``check_paths``' (a size limit is SettingsError there, as here):
    ``load(packages="x")`` was Python's AttributeError from inside the resolver,
    ``xacro_args=["a:=1"]`` another, ``allow_env="no"`` and ``as_written=1`` true, ``max_file_size
    ="1M"`` a TypeError of a comparison: now the guard ``check_paths`` uses names the option, an
    error that is a TypeError, a ValueError and a UsageError at once."""
    with pytest.raises(urdftool.UrdftoolError, match=message) as caught:
        urdftool.load(ROBOTS / "r2d2" / "r2d2.urdf.xacro", **options)
    if "max_file_size" not in options:
        assert isinstance(caught.value, TypeError) and isinstance(caught.value, ValueError)
        assert caught.value.option == next(iter(options))


@pytest.mark.parametrize("call, message", [
    (lambda: urdftool.check_paths(["robots"], progress=5), "progress must be callable, not 5"),
    (lambda: urdftool.check_paths(["robots"], {"strict": True}),
     "request must be a CheckRequest, not dict"),
    (lambda: urdftool.check_paths(["robots"], companions=5),
     "companions must be a Companions or a map of its fields, not 5"),
    (lambda: urdftool.check_paths(["robots"], companions={"srfd": "x.srdf"}),
     "no option 'srfd'; did you mean 'srdf'"),
    (lambda: urdftool.check_file("robots/r2d2/r2d2.urdf.xacro", strictt=True),
     "no option 'strictt'; did you mean 'strict'"),
])
def test_the_api_names_an_option_it_does_not_take(broken, call, message):
    """Each was Python's error from inside (``'int' object is not callable`` after the targets
    were walked, ``'dict' object has no attribute 'companions'``, ``unexpected keyword
    argument``), now an OptionError naming the option (and the close one)."""
    with pytest.raises(urdftool.OptionError, match=message):
        call()
