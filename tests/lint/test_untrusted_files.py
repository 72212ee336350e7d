"""Issue 12, classes 3, 4 and 6: a stranger's repository cannot make urdftool read or write
files outside it, nor make a folder walk take gigabytes.

An audit hook on "open" records every file this process opens while a test asks it to; the
commands run in this process (IN_PROCESS: no budget, so no forked worker) so that the hook sees
them.
"""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
import textwrap
from contextlib import contextmanager
from pathlib import Path

import pytest

from conftest import ROOT
from urdftool.errors import LoadError, PackageNotFound
from urdftool.lint.engine import load_error_findings
from urdftool.description.load import load
from urdftool.description.packages import PackageResolver

pytestmark = [pytest.mark.skipif(not hasattr(os, "symlink") or not hasattr(os, "mkfifo"),
                                 reason="needs symbolic links and FIFOs")]
# run_cli's commands in the forked worker (as outside the tests) where the command does its work
# and writes or refuses a file there; a refusal of the output path made before the work (exit
# 2) proves nothing more through a fork of the pytest worker (0.15 s of wall each, 60 tests)
WORKER = pytest.mark.worker

XACRO = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
BOX = '<geometry><box size="0.1 0.1 0.1"/></geometry>'
ROBOT = f"""<robot name="r">
  <link name="base"><inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0"
    izz="1"/></inertial><collision>{BOX}</collision></link>
  <link name="arm"><inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0"
    izz="1"/></inertial><collision><origin xyz="0 0 1"/>{BOX}</collision></link>
  <joint name="slide" type="prismatic"><parent link="base"/><child link="arm"/>
    <axis xyz="1 0 0"/><limit lower="0" upper="1" effort="1" velocity="1"/></joint>
</robot>
"""
IN_PROCESS = ("--timeout", "0", "--max-memory", "0")
MACROS = f'<robot {XACRO}><xacro:macro name="leg"><link name="leg"/></xacro:macro></robot>\n'

# --- every file opened, while recording -----------------------------------------------------

_OPENED: list[str] | None = None


def _audit(event, args):
    """Files opened, and folders listed (os.scandir, os.listdir: what glob uses)."""
    if event in ("open", "os.scandir", "os.listdir") and _OPENED is not None and args \
            and isinstance(args[0], (str, bytes, Path)):
        _OPENED.append(os.path.abspath(os.fsdecode(args[0])))


sys.addaudithook(_audit)  # cannot be removed; records only inside opened_files()


@contextmanager
def opened_files():
    global _OPENED
    _OPENED = []
    try:
        yield _OPENED
    finally:
        _OPENED = None


def _python_file(path: str) -> bool:
    """Python's own files (modules imported lazily while a command runs)."""
    places = {sys.prefix, sys.base_prefix, sys.exec_prefix, str(ROOT / "urdftool")}
    return any(path.startswith(place + os.sep) for place in places)


def outside_opened(opened: list[str], repo: Path) -> list[str]:
    """What was opened or listed outside ``repo`` (the repository folder itself is inside)."""
    real_repo = os.path.realpath(repo)
    return sorted({path for path in opened if not _python_file(path)
                   and not (os.path.realpath(path) + os.sep).startswith(real_repo + os.sep)
                   and not (path + os.sep).startswith(str(repo) + os.sep)})


# --- a repository with links leading out --------------------------------------------------

@pytest.fixture
def planted(tmp_path):
    """tmp_path/outside: files nobody may read; tmp_path/repo: a repository whose links lead
    there."""
    outside = tmp_path / "outside"
    (outside / "pkg").mkdir(parents=True)
    (outside / "folder").mkdir()
    (outside / "secret.urdf").write_text(ROBOT)
    (outside / "secret.xacro").write_text(MACROS)
    (outside / "folder" / "robot.urdf").write_text(ROBOT)
    (outside / "pkg" / "package.xml").write_text("<package><name>evil</name></package>")
    (outside / "pkg" / "parts.xacro").write_text(MACROS)
    (outside / "spec.yaml").write_text("unit: rad\njoints: {}\n")
    repo = tmp_path / "repo"
    (repo / ".git").mkdir(parents=True)
    robots = repo / "robots"
    (robots / "parts").mkdir(parents=True)
    (robots / "parts" / "leg.xacro").symlink_to(outside / "secret.xacro")
    (robots / "include.urdf.xacro").write_text(
        f'<robot name="r" {XACRO}>\n  <xacro:include filename="parts/leg.xacro"/>\n'
        '  <link name="base"/>\n</robot>\n')
    (robots / "link.urdf").symlink_to(outside / "secret.urdf")
    (robots / "linked_folder").symlink_to(outside / "folder", target_is_directory=True)
    (repo / "src").mkdir()
    (repo / "src" / "evil").symlink_to(outside / "pkg", target_is_directory=True)
    (robots / "find.urdf.xacro").write_text(
        f'<robot name="r" {XACRO}>\n  <xacro:include filename="$(find evil)/parts.xacro"/>\n'
        '  <link name="base"/>\n</robot>\n')
    (robots / "config").mkdir()
    (robots / "config" / "joint_limits.yaml").symlink_to(outside / "spec.yaml")
    return repo


def findings(run_cli, *args) -> tuple[int, list[tuple[str, int | None, str, str]]]:
    result = run_cli("check", *args, "--jobs", "1", *IN_PROCESS, "--format", "json")
    assert result.exit_code in (0, 1) or result.exit_code == 2 and \
        "not checked: a package" in result.output, result.output
    return result.exit_code, sorted((Path(d["file"]).name, d["line"], d["code"], d["message"])
                                    for d in json.loads(result.stdout)["diagnostics"])


def test_folder_walk_reports_links_out_and_opens_nothing_outside(run_cli, planted):
    with opened_files() as opened:
        code, found = findings(run_cli, planted / "robots")
    assert code == 2  # find.urdf.xacro not checked: its package (a link leading out) is not
    codes = {(name, line, code) for name, line, code, _ in found}  # followed, U006
    assert codes == {("link.urdf", None, "U017"), ("linked_folder", None, "U017"),
                     ("include.urdf.xacro", 2, "U017"), ("find.urdf.xacro", 2, "U006")}, found
    unresolved = next(message for name, _, _, message in found if name == "find.urdf.xacro")
    assert "src/evil (a symbolic link leading outside" in unresolved
    assert not outside_opened(opened, planted)
    assert opened  # the hook saw the files inside


def test_every_file_opened_by_the_commands_is_inside_the_repository(run_cli, planted):
    robots = planted / "robots"
    with opened_files() as opened:
        for path in ("link.urdf", "include.urdf.xacro", "find.urdf.xacro"):
            run_cli("check", robots / path, "--jobs", "1", *IN_PROCESS)
            for command in ("tree", "xacro", "fk", "inertia"):
                result = run_cli(command, robots / path, *IN_PROCESS)
                # find.urdf.xacro needs a package not installed here: not checked (exit 2)
                assert result.exit_code == (2 if path == "find.urdf.xacro" else 1) \
                    and "Traceback" not in result.output, result.output
    assert not outside_opened(opened, planted)
    assert str(robots / "find.urdf.xacro") in opened  # the hook saw the commands' reads


@WORKER
def test_robot_file_linked_out_is_u017_in_every_command(run_cli, planted):
    for command in ("check", "tree", "xacro", "fk", "graph", "dynamics", "collisions"):
        result = run_cli(command, planted / "robots" / "link.urdf")
        assert result.exit_code == 1 and "Traceback" not in result.output, result.output
        assert "U017" in result.output and "not followed" in result.output


def test_include_linked_out_is_refused_even_with_environment_access(planted):
    with pytest.raises(LoadError) as caught:
        load(planted / "robots" / "include.urdf.xacro", allow_env=True)
    [finding] = load_error_findings(caught.value)
    assert (finding.code, finding.line) == ("U017", 2) and "symbolic link" in finding.message


def test_links_inside_the_repository_still_work(tmp_path):
    repo = tmp_path / "repo"
    (repo / ".git").mkdir(parents=True)
    (repo / "models").mkdir()
    (repo / "models" / "real.urdf.xacro").write_text(
        f'<robot name="r" {XACRO}>\n  <xacro:include filename="leg.xacro"/>\n'
        '  <xacro:leg/>\n</robot>\n')
    (repo / "shared.xacro").write_text(MACROS)
    (repo / "models" / "leg.xacro").symlink_to(repo / "shared.xacro")
    (repo / "alias.urdf.xacro").symlink_to(repo / "models" / "real.urdf.xacro")
    robot = load(repo / "models" / "real.urdf.xacro")
    assert list(robot.links) == ["leg"]
    with pytest.raises(LoadError) as caught:  # the alias includes leg.xacro beside itself
        load(repo / "alias.urdf.xacro")
    assert load_error_findings(caught.value)[0].code == "U005"


def test_base_dir_is_where_the_link_is_not_where_it_leads(tmp_path):
    repo = tmp_path / "repo"
    (repo / ".git").mkdir(parents=True)
    (repo / "models").mkdir()
    (repo / "models" / "real.urdf").write_text(ROBOT)
    (repo / "alias.urdf").symlink_to(repo / "models" / "real.urdf")
    assert load(repo / "alias.urdf").base_dir == repo


def test_package_folder_linked_out_is_not_a_package(planted):
    start = planted / "robots"
    with opened_files() as opened, pytest.raises(PackageNotFound) as caught:
        PackageResolver(start=start, environ={}).find("evil")
    assert "symbolic link leading outside" in str(caught.value)
    assert not outside_opened(opened, planted)


def test_package_walk_up_stops_at_the_repository_root(tmp_path):
    (tmp_path / "above").mkdir()
    (tmp_path / "above" / "package.xml").write_text("<package><name>above</name></package>")
    repo = tmp_path / "repo"
    (repo / ".git").mkdir(parents=True)
    with opened_files() as opened, pytest.raises(PackageNotFound):
        PackageResolver(start=repo, environ={}).find("above")
    assert not outside_opened(opened, repo)
    # ROS_PACKAGE_PATH is the user's own choice: allowed.
    found = PackageResolver(start=repo, environ={"ROS_PACKAGE_PATH": str(tmp_path)}).find("above")
    assert found == tmp_path / "above"


# --- settings files name only files inside the repository ----------------------------------

@pytest.fixture
def project(tmp_path):
    repo = tmp_path / "repo"
    (repo / ".git").mkdir(parents=True)
    (repo / "robot.urdf").write_text(ROBOT)
    (tmp_path / "spec.yaml").write_text("unit: rad\njoints: {}\n")
    return repo


@pytest.mark.parametrize("setting", [
    'spec = "/dev/zero"', 'spec = "../spec.yaml"', 'srdf = "/etc/passwd"',
    'controllers = ["config/ok.yaml", "../../../../../../etc/hostname"]',
    '[tool.urdftool.packages]\nevil = "/"'])
def test_settings_naming_files_outside_are_a_usage_error(run_cli, project, setting):
    (project / "pyproject.toml").write_text(f"[tool.urdftool]\n{setting}\n")
    with opened_files() as opened:
        result = run_cli("check", project / "robot.urdf", "--jobs", "1", *IN_PROCESS)
    assert result.exit_code == 2, result.output
    assert "leads outside the repository" in result.stderr
    assert len(result.stderr.strip().splitlines()) == 1
    assert not outside_opened(opened, project)


def test_settings_file_linked_out_is_a_usage_error(run_cli, project, tmp_path):
    (tmp_path / "elsewhere.toml").write_text('ignore = ["U"]\n')
    (project / "urdftool.toml").symlink_to(tmp_path / "elsewhere.toml")
    with opened_files() as opened:
        result = run_cli("check", project / "robot.urdf", "--jobs", "1", *IN_PROCESS)
    assert result.exit_code == 2 and "leads outside the repository" in result.stderr
    assert not outside_opened(opened, project)


def test_settings_above_the_repository_are_not_read(run_cli, project, tmp_path):
    (tmp_path / "urdftool.toml").write_text('ignore = ["U"]\n')
    (project / "robot.urdf").write_text('<robot name="r"><link name="a"/><link name="a"/></robot>')
    with opened_files() as opened:
        result = run_cli("check", project / "robot.urdf", "--jobs", "1", *IN_PROCESS)
    assert result.exit_code == 1 and "U101" in result.output
    assert not outside_opened(opened, project)


def test_settings_inside_the_repository_still_work(run_cli, project):
    (project / "config").mkdir()
    (project / "config" / "spec.yaml").write_text("unit: rad\njoints: {}\n")
    (project / "pyproject.toml").write_text('[tool.urdftool]\nspec = "config/spec.yaml"\n')
    result = run_cli("check", project / "robot.urdf", "--jobs", "1", *IN_PROCESS)
    assert result.exit_code == 0, result.output


# --- only regular files under the size limit are read --------------------------------------

def _run(*args, cwd, timeout=60) -> subprocess.CompletedProcess:
    """urdftool in a child process with 1 GiB of address space and a time limit: a FIFO that
    blocks or /dev/zero read to the end fails the test instead of the machine."""
    import resource

    def limit():
        resource.setrlimit(resource.RLIMIT_AS, (1 << 30, 1 << 30))

    environment = {**os.environ, "PYTHONPATH": str(ROOT), "COLUMNS": "120", "NO_COLOR": "1",
                   "GITHUB_ACTIONS": ""}
    try:
        return subprocess.run([sys.executable, "-c", "from urdftool.cli import main; main()",
                               *map(str, args)], cwd=cwd,
                              env=environment, capture_output=True, text=True, timeout=timeout,
                              preexec_fn=limit)
    except subprocess.TimeoutExpired:
        pytest.fail(f"urdftool {' '.join(map(str, args))} hung")


@pytest.mark.parametrize("special", ["fifo", "/dev/zero"])
def test_q_file_must_be_a_regular_file(project, special):
    path = project / "q.csv"
    if special == "fifo":
        os.mkfifo(path)
    else:
        path = Path(special)
    done = _run("fk", project / "robot.urdf", "--q-file", path, cwd=project)
    assert done.returncode in (1, 2), done.stderr
    assert "not a regular file" in done.stderr and "Traceback" not in done.stderr


@pytest.mark.parametrize("command", [["fk", "robot.urdf", "--q-file", "q.csv"],
                                     ["fk", "robot.urdf", "--dh", "q.csv"]], ids=["q-file", "dh"])
def test_a_table_linked_out_of_the_repository_is_not_read(project, command):
    """A q-file or D-H table named in the repository that is a planted link to a file outside:
    not opened (its lines would be quoted in the parse error)."""
    (project.parent / "victim.csv").write_text("SECRET,LINE\n1,2\n")
    (project / "q.csv").symlink_to(project.parent / "victim.csv")
    done = _run(*command, cwd=project)
    assert done.returncode in (1, 2), done.stderr
    assert "symbolic link" in done.stderr and "outside the repository" in done.stderr
    assert "SECRET" not in done.stdout + done.stderr


def test_a_binary_file_in_a_walk_is_a_target_without_parsing(tmp_path, monkeypatch):
    """A file with NUL bytes is no xacro library: it is checked (U003 says why) without feeding
    megabytes of it to the XML parser (a folder of large sparse files took seconds each)."""
    from urdftool.lint import targets

    repo = tmp_path / "repo"
    (repo / ".git").mkdir(parents=True)
    path = repo / "big.urdf.xacro"
    path.write_text(f"<robot {XACRO}>")
    os.truncate(path, 1 << 20)
    monkeypatch.setattr(targets, "_defines_robot", lambda data: pytest.fail("parsed"))
    top, skipped = targets.split_top_level(targets.robot_files(repo),
                                           lambda p: PackageResolver(start=p))
    assert top == [path] and not skipped


def test_companion_fifo_is_a_finding_not_a_hang(project):
    (project / "config").mkdir()
    os.mkfifo(project / "config" / "spec.yaml")
    (project / "pyproject.toml").write_text('[tool.urdftool]\nspec = "config/spec.yaml"\n')
    done = _run("check", project / "robot.urdf", cwd=project)
    assert done.returncode == 1 and "not a regular file" in done.stdout, done.stdout + done.stderr


def test_one_bounded_reader():
    """Every file urdftool reads goes through urdftool.description.files.read_regular."""
    allowed = {  # paths under urdftool/; each must still read (a stale entry fails)
        "description/files.py": "the reader and the writer themselves",
        "docs.py": "regenerates docs/ from the rules (a developer command)",
        "origin.py": "pip's record of where urdftool came from (its own direct_url.json)",
        "budget.py": "a worker's own address space (/proc/self/statm)",
        "__main__.py": "urdftool's own help texts and command modules, read before anything is "
                       "imported (a fast --help)",
    }
    reading = re.compile(r"\bopen\(|\.read_text\(|\.read_bytes\(|\bload\(open")
    offenders, readers = [], set()
    for path in sorted((ROOT / "urdftool").rglob("*.py")):
        name = path.relative_to(ROOT / "urdftool").as_posix()
        for number, line in enumerate(path.read_text().splitlines(), start=1):
            code = line.split("#")[0]
            if reading.search(code) and "os.open" not in code:
                readers.add(name)
                if name not in allowed:
                    offenders.append(f"{path.relative_to(ROOT)}:{number}: {line.strip()}")
    assert not offenders, "\n".join(offenders)
    assert sorted(set(allowed) - readers) == [], "no longer reads: remove from allowed"


# --- nothing outside is written ------------------------------------------------------------

def _commands(robot: Path, out: Path):
    return {
        "check -o": ["check", robot, "-o", out, "--jobs", "1", "--timeout", "0"],
        "xacro -o": ["xacro", robot, "-o", out],
        "graph -o": ["graph", robot, "-o", out],
        "inertia --write": ["inertia", robot, "--write", out, "--all"],
        "collisions --write-srdf": ["collisions", robot, "--matrix", "--samples", "500",
                                    "--workers", "1", "--write-srdf", out],
        "collisions --plot": ["collisions", robot, "--matrix", "--samples", "500",
                              "--workers", "1", "--plot", out],
        "collisions --render": ["collisions", robot, "--render", out],
        "diff -o": ["diff", robot, robot, "-o", out, "--samples", "2"],
        "diff --render": ["diff", robot, robot, "--render", out, "--samples", "2"],
        "render -o": ["render", robot, "-o", out],
        "dynamics --plot": ["dynamics", robot, "--support", "base", "--plot", out],
        "workspace --plot": ["workspace", robot, "--tip", "arm", "--samples", "20",
                             "--plot", out],
    }


SUFFIX = {"graph -o": ".dot", "collisions --plot": ".svg", "collisions --write-srdf": ".srdf",
          "collisions --render": ".svg", "diff --render": ".svg", "render -o": ".svg",
          "dynamics --plot": ".svg", "workspace --plot": ".svg"}
WRITERS = list(_commands(Path(), Path()))


@WORKER
@pytest.mark.parametrize("writer", WRITERS)
def test_output_never_follows_a_planted_link(run_cli, tmp_path, writer):
    robot = tmp_path / "robot.urdf"
    robot.write_text(ROBOT)
    victim = tmp_path / "victim.txt"
    victim.write_text("precious\n")
    out = tmp_path / f"out{SUFFIX.get(writer, '.txt')}"
    out.symlink_to(victim)
    result = run_cli(*_commands(robot, out)[writer])
    assert result.exit_code in (0, 1), result.output
    assert victim.read_text() == "precious\n"
    assert not out.is_symlink() and out.is_file() and out.stat().st_size > 0


@pytest.mark.parametrize("writer", WRITERS)
@pytest.mark.parametrize("where", ["missing folder", "a folder"])
def test_output_in_a_missing_folder_or_onto_a_folder_is_a_usage_error(run_cli, tmp_path, writer,
                                                                      where):
    robot = tmp_path / "robot.urdf"
    robot.write_text(ROBOT)
    out = tmp_path / "missing" / f"out{SUFFIX.get(writer, '.txt')}" if where == "missing folder" \
        else tmp_path
    result = run_cli(*_commands(robot, out)[writer])
    assert result.exit_code == 2, result.output
    assert "Traceback" not in result.output and isinstance(result.exception, SystemExit)
    assert len(result.stderr.strip().splitlines()) == 1, result.stderr
    assert "cannot write" in result.stderr or (  # a folder's name has no picture suffix
        where == "a folder" and writer in SUFFIX and "must end in" in result.stderr)


@pytest.mark.parametrize("writer", WRITERS)
@pytest.mark.parametrize("how", ["reports", "reports/sub", "reports/sub/.."])
def test_output_never_goes_through_a_folder_linked_outside(run_cli, tmp_path, writer, how):
    """Issue 29, class 3: ``reports`` is a symbolic link committed in the repository, leading
    to a folder outside it; the output path names it, or a folder below it, or goes up from
    one (``reports/sub/..`` is the outside folder, as the system resolves it). Every command
    refuses before its work (exit 2, one line naming the link, not where it leads) and
    nothing is written outside."""
    repo = tmp_path / "repo"
    (repo / ".git").mkdir(parents=True)
    robot = repo / "robot.urdf"
    robot.write_text(ROBOT)
    outside = tmp_path / "outside"
    (outside / "sub").mkdir(parents=True)
    (repo / "reports").symlink_to(outside, target_is_directory=True)
    out = repo / how / f"out{SUFFIX.get(writer, '.txt')}"
    result = run_cli(*_commands(robot, out)[writer])
    assert result.exit_code == 2, result.output
    assert "symbolic link" in result.stderr and str(outside) not in result.stderr
    assert sorted(p.name for p in outside.rglob("*")) == ["sub"]
    assert sorted(p.name for p in repo.iterdir()) == [".git", "reports", "robot.urdf"]


@WORKER
def test_output_through_links_that_stay_inside_or_are_the_users_own(run_cli, tmp_path):
    """A link inside the repository to another folder of it is followed; so is a link outside
    any repository (the user's own: /tmp -> /private/tmp)."""
    repo = tmp_path / "repo"
    (repo / ".git").mkdir(parents=True)
    (repo / "real").mkdir()
    robot = repo / "robot.urdf"
    robot.write_text(ROBOT)
    (repo / "reports").symlink_to(repo / "real", target_is_directory=True)
    assert run_cli("xacro", robot, "-o", repo / "reports" / "a.urdf").exit_code == 0
    assert (repo / "real" / "a.urdf").is_file()
    mine = tmp_path / "mine"
    mine.symlink_to(repo / "real", target_is_directory=True)
    assert run_cli("xacro", robot, "-o", mine / "b.urdf").exit_code == 0
    assert (repo / "real" / "b.urdf").is_file()


@WORKER
def test_cache_folders_are_not_made_through_a_folder_linked_outside(run_cli, tmp_path):
    repo = tmp_path / "repo"
    (repo / ".git").mkdir(parents=True)
    robot = repo / "robot.urdf"
    robot.write_text(ROBOT)
    outside = tmp_path / "outside"
    outside.mkdir()
    (repo / "reports").symlink_to(outside, target_is_directory=True)
    result = run_cli("check", robot, "--cache-dir", repo / "reports" / "cache", "--jobs", "1")
    assert result.exit_code in (0, 1), result.output
    assert list(outside.iterdir()) == []


def test_write_keeps_the_permissions_of_a_file_it_replaces(tmp_path):
    from urdftool.description.files import write_file

    out = tmp_path / "report.txt"
    out.write_text("old")
    out.chmod(0o640)
    write_file(out, "new")
    assert out.read_text() == "new" and (out.stat().st_mode & 0o777) == 0o640
    assert [p.name for p in tmp_path.iterdir()] == ["report.txt"]  # no temporary left


# --- folder walks stay bounded -------------------------------------------------------------

def test_walk_does_not_open_files_over_the_size_limit(run_cli, tmp_path):
    repo = tmp_path / "repo"
    (repo / ".git").mkdir(parents=True)
    for index in range(5):
        path = repo / f"big{index}.urdf.xacro"
        path.write_text(f"<robot {XACRO}>")
        os.truncate(path, 32 << 20)  # sparse: no disk used
    from urdftool.lint.targets import robot_files, split_top_level

    with opened_files() as opened:
        top, skipped = split_top_level(robot_files(repo), lambda p: PackageResolver(start=p))
    assert not [p for p in opened if "big" in p]
    assert len(top) == 5 and not skipped  # checked, and reported
    code, found = findings(run_cli, repo)
    assert {c for _, _, c, _ in found} == {"U008"} and len(found) == 5


_MEASURE = """
import os, resource, sys
from pathlib import Path
from urdftool.lint.targets import robot_files, split_top_level
from urdftool.description.packages import PackageResolver

repo = Path(sys.argv[1])
for index in range(int(sys.argv[2])):
    path = repo / f"f{{index}}.urdf.xacro"
    path.write_text('<robot name="r" {xacro}>')
    os.truncate(path, int(sys.argv[3]))
before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
split_top_level(robot_files(repo), lambda p: PackageResolver(start=p.parent))
print((resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - before) // 1024)
"""


@pytest.mark.parametrize("count, size", [(40, 32 << 20), (20, 16 << 20)],
                         ids=["over the limit", "at the limit"])
def test_classifying_a_folder_keeps_one_file_in_memory(tmp_path, count, size):
    """Peak memory of classifying ``count`` sparse files of ``size`` bytes (before: every
    file's first 16 MiB kept at once: 640 MB and 320 MB here, 2.4 GB for 150 files)."""
    (tmp_path / ".git").mkdir()
    script = textwrap.dedent(_MEASURE).format(xacro=XACRO)
    done = subprocess.run([sys.executable, "-c", script, str(tmp_path), str(count), str(size)],
                          env={**os.environ, "PYTHONPATH": str(ROOT)}, capture_output=True,
                          text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    assert int(done.stdout) < 100, f"classifying took {done.stdout.strip()} MB more"


@pytest.mark.parametrize("unit", ["<xacro:include ", "<robot "])
def test_classifying_tags_without_an_end_takes_linear_time(tmp_path, unit):
    (tmp_path / ".git").mkdir()
    (tmp_path / "r.urdf.xacro").write_text(unit * ((1 << 20) // len(unit)))
    script = ("import sys; from pathlib import Path; from urdftool.lint import targets; "
              "p = Path(sys.argv[1]); "
              "print(targets.explicit_targets(p, targets.includers_below(p.parent, "
              "lambda f: None), p.parent))")
    try:
        done = subprocess.run([sys.executable, "-c", script, str(tmp_path / "r.urdf.xacro")],
                              env={**os.environ, "PYTHONPATH": str(ROOT)}, capture_output=True,
                              text=True, timeout=60)
    except subprocess.TimeoutExpired:
        pytest.fail("classifying 1 MiB took over a minute")
    assert done.returncode == 0, done.stderr


# --- include patterns: containment before expansion (issue 29, class 4) ---------------------

PATTERN = f"""<robot name="r" {XACRO}>
  <xacro:include filename="{{pattern}}"/>
  <link name="base"/>
</robot>
"""


@pytest.fixture
def patterns(tmp_path):
    """repo/parts/good/ok.xacro; repo/parts/evil and repo/linked lead to outside/, which holds
    secret_name.xacro."""
    outside = tmp_path / "outside"
    outside.mkdir()
    (outside / "secret_name.xacro").write_text(MACROS)
    repo = tmp_path / "repo"
    (repo / ".git").mkdir(parents=True)
    (repo / "parts" / "good").mkdir(parents=True)
    (repo / "parts" / "good" / "ok.xacro").write_text(MACROS)
    (repo / "parts" / "evil").symlink_to(outside, target_is_directory=True)
    (repo / "linked").symlink_to(outside, target_is_directory=True)
    return repo, outside


def _expand(run_cli, repo, pattern, *mode):
    (repo / "robot.urdf.xacro").write_text(PATTERN.format(pattern=pattern))
    with opened_files() as opened:
        result = run_cli("check", *mode, "--format", "json", repo / "robot.urdf.xacro",
                         *IN_PROCESS, "--jobs", "1")
    found = json.loads(result.stdout)["diagnostics"] if result.stdout.strip() else []
    return result, found, opened


@pytest.mark.parametrize("pattern, code", [
    ("{outside}/*.xacro", "U014"),
    ("{outside}/secret_*", "U014"),
    ("linked/*.xacro", "U017"),
    ("parts/*/../../linked/*.xacro", "U016"),
])
def test_a_pattern_is_refused_before_anything_is_listed(run_cli, patterns, pattern, code):
    """Before: glob.glob listed the outside folder, and the refusal named the file it found
    there ('secret_name.xacro'). Now the pattern's fixed folder is judged first: nothing
    outside is listed or opened, and no message names what is there."""
    repo, outside = patterns
    result, found, opened = _expand(run_cli, repo, pattern.format(outside=outside), "--no-env")
    assert [d["code"] for d in found] == [code], result.output
    assert "secret_name" not in result.output
    assert not outside_opened(opened, repo), outside_opened(opened, repo)


def test_a_pattern_never_enters_a_linked_folder_leading_out(run_cli, patterns):
    repo, _ = patterns
    for mode in ("--no-env", "--allow-env"):
        result, found, opened = _expand(run_cli, repo, "parts/*/*.xacro", mode)
        assert found == [] and result.exit_code == 0, result.output  # parts/good/ok.xacro
        assert not outside_opened(opened, repo)


def test_a_pattern_expands_as_glob_does(patterns, tmp_path):
    """The same files, in the same order, as xacro's sorted(glob.glob(spec)), hidden files,
    character classes and ** (one level, not recursive) included."""
    import glob

    from urdftool.description.xacro import _expand_pattern, _Session

    repo, _ = patterns
    for name in ("a1.xacro", "a2.xacro", "b.xacro", ".hidden.xacro", "sub/c.xacro",
                 "sub/deeper/d.xacro", "sub/.e.xacro", "x.txt"):
        (repo / "tree" / name).parent.mkdir(parents=True, exist_ok=True)
        (repo / "tree" / name).write_text(MACROS)
    session = _Session(None, True, None, [repo])
    session.file_index(str(repo / "robot.urdf.xacro"))
    for spec in ("tree/*.xacro", "tree/a[12].xacro", "tree/?.xacro", "tree/**/*.xacro",
                 "tree/*/*.xacro", "tree/.*", "tree/sub/*", "tree/*/deeper/*.xacro",
                 "tree/nothing*", "tree/s?b/c.xacro"):
        spec = f"{repo}/{spec}"
        assert _expand_pattern(session, spec) == sorted(glob.glob(spec)), spec


def test_a_pattern_looks_at_a_bounded_number_of_files(run_cli, patterns, monkeypatch):
    from urdftool.description import xacro

    repo, _ = patterns
    monkeypatch.setattr(xacro, "MAX_PATTERN_ENTRIES", 50)
    (repo / "many").mkdir()
    for index in range(60):
        (repo / "many" / f"{index}.txt").write_text("")
    result, found, _ = _expand(run_cli, repo, "many/*.xacro")
    assert [d["code"] for d in found] == ["U016"] and "over 50 files" in found[0]["message"]


def test_a_mesh_linked_out_is_refused_without_saying_where_it_leads(tmp_path):
    """Issue 29, class 4: a refusal names what the repository holds, never what exists
    outside (realpath follows links there: /etc/alternatives/... would be named)."""
    from urdftool.description.meshes import MeshProblem, load_mesh

    outside = tmp_path / "outside"
    (outside / "real").mkdir(parents=True)
    (outside / "real" / "hidden_name.stl").write_bytes(b"solid x\nendsolid x\n")
    (outside / "alias").symlink_to(outside / "real", target_is_directory=True)
    repo = tmp_path / "repo"
    (repo / ".git").mkdir(parents=True)
    (repo / "m.stl").symlink_to(outside / "alias" / "hidden_name.stl")
    (repo / "r.urdf").write_text('<robot name="r"><link name="a"/></robot>')
    with pytest.raises(MeshProblem) as refused:
        load_mesh(load(repo / "r.urdf"), "m.stl")
    assert "symbolic link" in str(refused.value) and "hidden_name" not in str(refused.value)
    assert str(outside) not in str(refused.value)
